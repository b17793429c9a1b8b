// The raster engine's device side (see raster_device.h and the method in raster_engine.cpp).
#include "bluetile/raster/raster_device.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <iterator>
#include <utility>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/gpu/context.h"
#include "bluetile/gpu/pipelines.h"
#include "bluetile/raster/raster_reference.h"

namespace bluetile {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

gpu::uvec2 double_bits(double v) {
  const auto bits = std::bit_cast<std::uint64_t>(v);
  return {static_cast<std::uint32_t>(bits), static_cast<std::uint32_t>(bits >> 32)};
}

// A device buffer the host fills or reads. Where its memory is host-visible (lavapipe,
// integrated GPUs) the host uses it directly; elsewhere through a staging buffer and a copy in
// the pass's command buffer.
struct HostBuffer {
  gpu::Buffer device, staging;
  void* host() const { return device.mapped ? device.mapped : staging.mapped; }
  bool staged() const { return device.mapped == nullptr; }
};

// Bytes per atlas sample of one pass: ID and depth images, boundary and overflow lists (8 bytes
// per entry, room for every pixel), masks; with slack for the per-site buffers.
constexpr double kBytesPerSample = 32.0;
// Atlas samples of one pass at most, whatever the memory: bounds one submission's latency.
constexpr double kMaxPassSamples = 256.0 * 1024 * 1024;
// Device timestamps of a pass: before the cones, after the cones, classify, split and readback.
constexpr std::uint32_t kTimestamps = 5;
// The bindings read as uniform texel buffers (by split_lane_f64.comp): views over the storage buffers.
constexpr std::uint32_t texel_bindings[] = {BLUETILE_BINDING_POSITION_TEXELS, BLUETILE_BINDING_GRID_TEXELS,
                                            BLUETILE_BINDING_SCENE_TEXELS, BLUETILE_BINDING_SITE_TEXELS,
                                            BLUETILE_BINDING_LIST_POSITION_TEXELS};

}  // namespace

struct RasterDevice::Impl {
  RasterDeviceSettings settings;
  std::unique_ptr<gpu::Context> gpu;
  bool float64 = false;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  VkRenderPass render_pass = VK_NULL_HANDLE;
  VkPipeline cone_pipeline = VK_NULL_HANDLE, classify_pipeline = VK_NULL_HANDLE, split_pipeline = VK_NULL_HANDLE;
  VkPipeline beyond_texels_pipeline = VK_NULL_HANDLE;  // split_for
  // split_lane_f64.comp (positions, positions in list order, grid words and records as texels,
  // at most BLUETILE_MAX_PIECES candidates a pixel; split_lane5_f64.comp with
  // BLUETILE_MAX_PIECES_GPU), else split_f64.comp or, without shaderFloat64, split_f32.comp.
  bool lane_split = false;
  std::uint32_t lane_pieces = 0;  // the lane split's candidate slots
  // ConeDraw::points: the point pipeline (cone_pipeline is then the triangles it falls back to).
  VkPipeline point_pipeline = VK_NULL_HANDLE;
  // ConeDraw::indexed: 0 1 2 2 1 3 per cone, offset by 4 per cone, for this many cones.
  HostBuffer cone_indices;
  std::size_t indexed_cones = 0;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  VkQueryPool timestamps = VK_NULL_HANDLE;  // per-stage device times (where the device has them)
  gpu::Image id_image, depth_image;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  HostBuffer instances, scenes, sites, positions, masks, grid, list_positions, sums, counters, overflow;
  gpu::Buffer boundary;
  gpu::Buffer id_readback;
  VkBufferView position_texels = VK_NULL_HANDLE, grid_texels = VK_NULL_HANDLE, scene_texels = VK_NULL_HANDLE,
               site_texels = VK_NULL_HANDLE, list_position_texels = VK_NULL_HANDLE;
  bool descriptors_dirty = true;

  // The last pass.
  std::uint32_t atlas_width = 0, atlas_height = 0;
  std::size_t group_size = 0;
  bool ids_read = false;
  std::vector<gpu::uvec2> overflow_copy;
  RasterPassTiming timing;

  explicit Impl(const RasterDeviceSettings& s) : settings(s) {
    gpu = std::make_unique<gpu::Context>(s.device);
    float64 = gpu->float64() && !s.force_float32;
    lane_split = float64 && s.split_kernel != SplitKernel::pixel;
    // Three on a CPU device (lavapipe runs every slot's code for every pixel), five elsewhere.
    const bool five = s.split_kernel == SplitKernel::lane_five || (s.split_kernel == SplitKernel::lane && gpu->info().type != "cpu");
    if (lane_split) lane_pieces = five ? BLUETILE_MAX_PIECES_GPU : BLUETILE_MAX_PIECES;
    try {
      create_pipelines();
    } catch (...) {
      release();
      throw;
    }
  }

  ~Impl() { release(); }

  void release() {
    if (!gpu) return;
    VkDevice d = gpu->device();
    vkDeviceWaitIdle(d);
    for (HostBuffer* b : {&instances, &scenes, &sites, &positions, &masks, &grid, &list_positions, &sums, &counters, &overflow,
                          &cone_indices}) {
      gpu->destroy(b->device);
      gpu->destroy(b->staging);
    }
    for (VkBufferView v : {position_texels, grid_texels, scene_texels, site_texels, list_position_texels})
      if (v) vkDestroyBufferView(d, v, nullptr);
    gpu->destroy(boundary);
    gpu->destroy(id_readback);
    if (framebuffer) vkDestroyFramebuffer(d, framebuffer, nullptr);
    gpu->destroy(id_image);
    gpu->destroy(depth_image);
    if (commands) vkFreeCommandBuffers(d, gpu->command_pool(), 1, &commands);
    for (VkPipeline p : {cone_pipeline, point_pipeline, classify_pipeline, split_pipeline, beyond_texels_pipeline})
      if (p) vkDestroyPipeline(d, p, nullptr);
    if (render_pass) vkDestroyRenderPass(d, render_pass, nullptr);
    if (timestamps) vkDestroyQueryPool(d, timestamps, nullptr);
    if (pool) vkDestroyDescriptorPool(d, pool, nullptr);
    if (layout) vkDestroyPipelineLayout(d, layout, nullptr);
    if (set_layout) vkDestroyDescriptorSetLayout(d, set_layout, nullptr);
    gpu.reset();
  }

  void create_pipelines() {
    VkDevice d = gpu->device();
    VkDescriptorType types[BLUETILE_BINDING_COUNT];
    std::fill(std::begin(types), std::end(types), VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    types[BLUETILE_BINDING_ID_IMAGE] = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    for (std::uint32_t b : texel_bindings) types[b] = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    set_layout = gpu::create_set_layout(d, types);
    layout = gpu::create_pipeline_layout(d, set_layout, VK_SHADER_STAGE_VERTEX_BIT, 16);

    constexpr std::uint32_t texel_count = std::size(texel_bindings);
    VkDescriptorPoolSize sizes[3] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, BLUETILE_BINDING_COUNT - 1 - texel_count},
                                     {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1},
                                     {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, texel_count}};
    VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = 3;
    pool_info.pPoolSizes = sizes;
    BLUETILE_VK_CHECK(vkCreateDescriptorPool(d, &pool_info, nullptr, &pool));
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &set_layout;
    BLUETILE_VK_CHECK(vkAllocateDescriptorSets(d, &alloc, &set));

    gpu::GraphicsPipelineDesc cones;
    cones.vertex_shader = "cone_quad.vert";
    cones.fragment_shader = "cone_quad.frag";
    cones.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    if (settings.fan) {
      cones.vertex_shader = "cone_fan.vert";
      cones.fragment_shader = "cone_fan.frag";
    } else if (settings.cone_draw == ConeDraw::indexed) {
      cones.vertex_shader = "cone_quad_indexed.vert";
    } else if (settings.cone_draw == ConeDraw::instanced) {
      cones.vertex_shader = "cone_quad_instanced.vert";
      cones.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
    }
    render_pass = gpu::create_render_pass(d, cones);
    cone_pipeline = gpu::create_graphics_pipeline(*gpu, layout, render_pass, cones);
    if (!settings.fan && settings.cone_draw == ConeDraw::points) {
      gpu::GraphicsPipelineDesc points = cones;
      points.vertex_shader = "cone_point.vert";
      points.fragment_shader = "cone_point.frag";
      points.topology = VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
      point_pipeline = gpu::create_graphics_pipeline(*gpu, layout, render_pass, points);
    }

    VkCommandBufferAllocateInfo command_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    command_info.commandPool = gpu->command_pool();
    command_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    command_info.commandBufferCount = 1;
    BLUETILE_VK_CHECK(vkAllocateCommandBuffers(d, &command_info, &commands));

    if (gpu->properties().limits.timestampComputeAndGraphics) {
      VkQueryPoolCreateInfo query_info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
      query_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
      query_info.queryCount = kTimestamps;
      BLUETILE_VK_CHECK(vkCreateQueryPool(d, &query_info, nullptr, &timestamps));
    }
  }

  // The compute pipelines on first use: a run with the per-pixel work on the host never pays
  // for their compilation (the split's is the largest shader).
  void create_compute_pipelines() {
    if (classify_pipeline) return;
    classify_pipeline = gpu::create_compute_pipeline(*gpu, layout, "classify.comp");
    const char* split = !lane_split ? (float64 ? "split_f64.comp" : "split_f32.comp")
                        : lane_pieces == BLUETILE_MAX_PIECES_GPU ? "split_lane5_f64.comp" : "split_lane_f64.comp";
    split_pipeline = gpu::create_compute_pipeline(*gpu, layout, split);
  }

  // The split of a pass whose sites or grid words reach beyond the texel views
  // (maxTexelBufferElements: 2^27 on lavapipe, 2^16 on some GPUs) is split_f64.comp.
  VkPipeline split_for(std::size_t scene_count, std::size_t site_total, std::size_t grid_words) {
    const std::size_t texels = gpu->properties().limits.maxTexelBufferElements;
    if (!lane_split || (scene_count * BLUETILE_SCENE_TEXELS <= texels && site_total * BLUETILE_SITE_TEXELS <= texels &&
                        grid_words <= texels))
      return split_pipeline;
    if (!beyond_texels_pipeline) beyond_texels_pipeline = gpu::create_compute_pipeline(*gpu, layout, "split_f64.comp");
    return beyond_texels_pipeline;
  }

  // ---- resources -------------------------------------------------------------------------------

  void reserve(HostBuffer& b, std::size_t bytes, VkBufferUsageFlags usage) {
    bytes = std::max<std::size_t>(bytes, 64);
    if (b.device.size >= bytes) return;
    gpu->destroy(b.device);
    gpu->destroy(b.staging);
    const std::size_t size = std::min<std::size_t>(bytes + bytes / 2, gpu->properties().limits.maxStorageBufferRange);
    gpu::check_address_space(2 * size, "the raster engine's buffers");
    b.device = gpu->create_buffer(std::max(size, bytes), usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    if (!b.device.mapped)
      b.staging = gpu->create_buffer(b.device.size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                     gpu::MemoryUse::staging);
    descriptors_dirty = true;
  }

  void reserve(gpu::Buffer& b, std::size_t bytes, VkBufferUsageFlags usage, gpu::MemoryUse use) {
    bytes = std::max<std::size_t>(bytes, 64);
    if (b.size >= bytes) return;
    gpu->destroy(b);
    const std::size_t size = std::min<std::size_t>(bytes + bytes / 2, gpu->properties().limits.maxStorageBufferRange);
    gpu::check_address_space(size, "the raster engine's buffers");
    b = gpu->create_buffer(std::max(size, bytes), usage, use);
    descriptors_dirty = true;
  }

  void reserve_atlas(std::uint32_t width, std::uint32_t height) {
    if (id_image.width >= width && id_image.height >= height) return;
    width = std::max(width, id_image.width);
    height = std::max(height, id_image.height);
    gpu::check_address_space(std::size_t{8} * width * height, "the raster engine's images");
    VkDevice d = gpu->device();
    if (framebuffer) vkDestroyFramebuffer(d, framebuffer, nullptr);
    framebuffer = VK_NULL_HANDLE;
    gpu->destroy(id_image);
    gpu->destroy(depth_image);
    id_image = gpu->create_image(width, height, VK_FORMAT_R32_UINT,
                                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                 VK_IMAGE_ASPECT_COLOR_BIT);
    depth_image = gpu->create_image(width, height, VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                    VK_IMAGE_ASPECT_DEPTH_BIT);
    VkImageView views[2] = {id_image.view, depth_image.view};
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = render_pass;
    info.attachmentCount = 2;
    info.pAttachments = views;
    info.width = width;
    info.height = height;
    info.layers = 1;
    BLUETILE_VK_CHECK(vkCreateFramebuffer(d, &info, nullptr, &framebuffer));
    descriptors_dirty = true;
  }

  void update_descriptors() {
    if (!descriptors_dirty) return;
    const VkBuffer buffers[BLUETILE_BINDING_COUNT] = {
        instances.device.buffer, scenes.device.buffer, sites.device.buffer, positions.device.buffer,
        sums.device.buffer,      counters.device.buffer, boundary.buffer,   masks.device.buffer,
        grid.device.buffer,      overflow.device.buffer, VK_NULL_HANDLE, VK_NULL_HANDLE, VK_NULL_HANDLE,
        VK_NULL_HANDLE,          VK_NULL_HANDLE,         VK_NULL_HANDLE};
    VkDescriptorBufferInfo infos[BLUETILE_BINDING_COUNT];
    VkWriteDescriptorSet writes[BLUETILE_BINDING_COUNT];
    for (std::uint32_t b = 0; b < BLUETILE_BINDING_COUNT; ++b) {
      writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      writes[b].dstSet = set;
      writes[b].dstBinding = b;
      writes[b].descriptorCount = 1;
      if (b == BLUETILE_BINDING_ID_IMAGE || std::find(std::begin(texel_bindings), std::end(texel_bindings), b) != std::end(texel_bindings))
        continue;
      infos[b] = {buffers[b], 0, VK_WHOLE_SIZE};
      writes[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      writes[b].pBufferInfo = &infos[b];
    }
    VkDescriptorImageInfo image_info{VK_NULL_HANDLE, id_image.view, VK_IMAGE_LAYOUT_GENERAL};
    writes[BLUETILE_BINDING_ID_IMAGE].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    writes[BLUETILE_BINDING_ID_IMAGE].pImageInfo = &image_info;
    // Texel views over as much of each buffer as the device's texel limit allows (a pass beyond
    // it splits with split_f64.comp: split_for).
    VkDevice d = gpu->device();
    for (VkBufferView* v : {&position_texels, &grid_texels, &scene_texels, &site_texels, &list_position_texels})
      if (*v) vkDestroyBufferView(d, *v, nullptr);
    auto view = [&](const gpu::Buffer& b, VkFormat format, std::size_t texel_bytes) {
      VkBufferViewCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
      info.buffer = b.buffer;
      info.format = format;
      info.range = std::min<std::size_t>(b.size / texel_bytes, gpu->properties().limits.maxTexelBufferElements) * texel_bytes;
      VkBufferView v;
      BLUETILE_VK_CHECK(vkCreateBufferView(d, &info, nullptr, &v));
      return v;
    };
    position_texels = view(positions.device, VK_FORMAT_R32G32B32A32_UINT, 16);
    grid_texels = view(grid.device, VK_FORMAT_R32_UINT, 4);
    scene_texels = view(scenes.device, VK_FORMAT_R32G32B32A32_UINT, 16);
    site_texels = view(sites.device, VK_FORMAT_R32G32B32A32_UINT, 16);
    list_position_texels = view(list_positions.device, VK_FORMAT_R32G32B32A32_UINT, 16);
    const std::pair<std::uint32_t, const VkBufferView*> texel_views[] = {
        {BLUETILE_BINDING_POSITION_TEXELS, &position_texels}, {BLUETILE_BINDING_GRID_TEXELS, &grid_texels},
        {BLUETILE_BINDING_SCENE_TEXELS, &scene_texels},       {BLUETILE_BINDING_SITE_TEXELS, &site_texels},
        {BLUETILE_BINDING_LIST_POSITION_TEXELS, &list_position_texels}};
    for (const auto& [binding, texel_view] : texel_views) {
      writes[binding].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
      writes[binding].pTexelBufferView = texel_view;
    }
    vkUpdateDescriptorSets(gpu->device(), BLUETILE_BINDING_COUNT, writes, 0, nullptr);
    descriptors_dirty = false;
  }

  // ---- one pass --------------------------------------------------------------------------------

  struct Layout {  // where each scene's data go in the pass's buffers
    std::size_t site_begin = 0, instance_begin = 0, mask_begin = 0, grid_begin = 0;
  };

  void fill_scene(const RasterScene& job, std::size_t k, const Layout& at, bool pixel_work, std::uint32_t& instance_count) {
    const std::size_t n = job.size();
    const Point size = job.scene->domain.size;
    auto* scene_data = static_cast<gpu::SceneInfo*>(scenes.host());
    auto* site_data = static_cast<gpu::SiteInfo*>(sites.host()) + at.site_begin;
    auto* position_data = static_cast<gpu::uvec2*>(positions.host()) + 2 * at.site_begin;
    auto* instance_data = static_cast<gpu::ConeInstance*>(instances.host()) + at.instance_begin;
    const SiteGrid& site_grid = job.grid();

    gpu::SceneInfo& info = scene_data[k];
    info = {};
    info.origin = {job.origin_x, job.origin_y};
    info.size = {job.rx, job.ry};
    info.pixel_size = {static_cast<float>(job.hx), static_cast<float>(job.hy)};
    info.domain_size = {static_cast<float>(size.x), static_cast<float>(size.y)};
    info.depth_scale = static_cast<float>(1.0 / (2.0 * job.radius_cap));
    info.site_begin = static_cast<std::uint32_t>(at.site_begin);
    info.flags = job.area ? BLUETILE_SCENE_AREA : 0u;
    info.mask_offset = static_cast<std::uint32_t>(at.mask_begin);
    info.grid_size = {static_cast<std::int32_t>(site_grid.columns()), static_cast<std::int32_t>(site_grid.rows())};
    info.grid_offset = static_cast<std::uint32_t>(at.grid_begin);
    info.bucket_size = {static_cast<float>(site_grid.cell_size().x), static_cast<float>(site_grid.cell_size().y)};
    info.reach_limit = static_cast<float>(job.reach_limit);
    info.pixel_size64[0] = double_bits(job.hx);
    info.pixel_size64[1] = double_bits(job.hy);
    info.domain_size64[0] = double_bits(size.x);
    info.domain_size64[1] = double_bits(size.y);
    info.bucket_size64[0] = double_bits(site_grid.cell_size().x);
    info.bucket_size64[1] = double_bits(site_grid.cell_size().y);
    info.reach_limit64 = double_bits(job.reach_limit);
    // The kernel's bound (a pass beyond the texel views runs split_f64.comp under it too); the
    // engine splits the pixels it leaves as the host reference does.
    info.max_pieces = lane_split ? lane_pieces : BLUETILE_MAX_CANDIDATES;
    info.guard_test = settings.split_guard_test;
    info.scale64[0] = double_bits(job.scale_area);
    info.scale64[1] = double_bits(job.scale_first);
    info.scale64[2] = double_bits(job.scale_second);
    info.scale32 = {static_cast<float>(job.scale_area), static_cast<float>(job.scale_first)};
    info.scale32_second = static_cast<float>(job.scale_second);

    std::uint32_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
      int px, py;
      double fx, fy;
      job.site_pixel(i, px, py, fx, fy);
      gpu::SiteInfo& si = site_data[i];
      si = {};
      si.pixel = {px, py};
      si.fraction = {static_cast<float>(fx), static_cast<float>(fy)};
      si.scene = static_cast<std::uint32_t>(k);
      si.flags = (job.split[i] ? BLUETILE_SITE_SPLIT : 0u) | (job.wanted(i) ? BLUETILE_SITE_WANTED : 0u);
      position_data[2 * i] = double_bits(job.sites[i].x);
      position_data[2 * i + 1] = double_bits(job.sites[i].y);
      if (job.coincident[i]) continue;
      const double r = job.radius[i];
      const auto id = static_cast<std::uint32_t>(at.site_begin + i + 1);
      // Replicas one period away on a torus; a bounded domain has none.
      const int copies = job.periodic ? 1 : 0;
      for (int ky = -copies; ky <= copies; ++ky)
        for (int kx = -copies; kx <= copies; ++kx) {
          const Point p{job.sites[i].x + kx * size.x, job.sites[i].y + ky * size.y};
          if (p.x + r <= -job.hx || p.x - r >= size.x || p.y + r <= -job.hy || p.y - r >= size.y) continue;
          instance_data[count++] = {{px + kx * job.rx, py + ky * job.ry}, static_cast<float>(r), id};
        }
    }
    instance_count = count;
    if (!pixel_work) return;  // the host does the rest

    if (job.area) {
      const std::vector<std::uint32_t> scene_masks = raster_site_masks(job);
      std::memcpy(static_cast<std::uint32_t*>(masks.host()) + at.mask_begin, scene_masks.data(), scene_masks.size() * 4);
    }
    // The grid without coincident sites (the split never considers them).
    auto* g = static_cast<std::uint32_t*>(grid.host()) + at.grid_begin;
    const std::size_t buckets = site_grid.bucket_count();
    std::uint32_t* starts = g;
    std::uint32_t* indices = g + buckets + 1;
    auto* list_position_data = static_cast<gpu::uvec2*>(list_positions.host()) + 2 * (at.grid_begin + buckets + 1);
    std::uint32_t filled = 0;
    for (std::size_t b = 0; b < buckets; ++b) {
      starts[b] = filled;
      for (std::uint32_t s : site_grid.sites_in_bucket(b)) {
        if (job.coincident[s]) continue;
        if (lane_split) {
          list_position_data[2 * filled] = position_data[2 * s];
          list_position_data[2 * filled + 1] = position_data[2 * s + 1];
        }
        indices[filled++] = s;
      }
    }
    starts[buckets] = filled;
  }

  // The widest cone square of a pass in samples (with a pixel of margin for float rounding).
  static double widest_cone_pixels(std::span<RasterScene* const> group) {
    double widest = 0.0;
    for (const RasterScene* job : group) {
      double radius = 0.0;
      for (std::size_t i = 0; i < job->size(); ++i)
        if (!job->coincident[i]) radius = std::max(radius, job->radius[i]);
      widest = std::max(widest, 2.0 * radius / std::min(job->hx, job->hy) + 1.0);
    }
    return widest;
  }

  void run(std::span<RasterScene* const> group, std::uint32_t width, std::uint32_t height, bool read_ids, bool pixel_work) {
    // The lane kernel's pixels left to the host are split there from the corners' owners.
    read_ids = read_ids || !pixel_work || (lane_split && std::any_of(group.begin(), group.end(), [](const RasterScene* job) { return job->area; }));
    if (pixel_work) create_compute_pipelines();
    auto upload_start = Clock::now();
    group_size = group.size();
    atlas_width = width;
    atlas_height = height;
    ids_read = read_ids;
    // Buffer layout of the pass.
    std::vector<Layout> at(group.size());
    std::size_t site_total = 0, instance_total = 0, mask_words = 0, grid_words = 0, pixel_total = 0;
    std::uint32_t max_rx = 0, max_ry = 0;
    bool any_area = false;
    for (std::size_t k = 0; k < group.size(); ++k) {
      RasterScene& job = *group[k];
      at[k] = {site_total, instance_total, mask_words, grid_words};
      job.site_begin = static_cast<std::uint32_t>(site_total);
      site_total += job.size();
      instance_total += 9 * job.size();
      if (job.area) mask_words += static_cast<std::size_t>((job.rx + 15) / 16) * job.ry;
      const std::size_t buckets = static_cast<std::size_t>(job.grid().bucket_count());
      grid_words += buckets + 1 + job.size();
      pixel_total += static_cast<std::size_t>(job.rx) * job.ry;
      max_rx = std::max<std::uint32_t>(max_rx, job.rx);
      max_ry = std::max<std::uint32_t>(max_ry, job.ry);
      any_area |= job.area;
    }
    if (site_total >= 0xffffffffu) throw Error("raster engine: too many sites in one pass");
    reserve_atlas(width, height);
    const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    reserve(instances, instance_total * sizeof(gpu::ConeInstance), storage);
    const VkBufferUsageFlags texels = storage | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
    reserve(scenes, group.size() * sizeof(gpu::SceneInfo), texels);
    reserve(sites, site_total * sizeof(gpu::SiteInfo), texels);
    reserve(positions, site_total * 16, texels);
    reserve(masks, mask_words * 4, storage);
    reserve(grid, grid_words * 4, texels);
    reserve(list_positions, lane_split ? grid_words * 16 : 0, texels);
    reserve(sums, site_total * sizeof(gpu::SiteSums), storage);
    reserve(counters, (BLUETILE_COUNTER_UNCOVERED + group.size()) * 4, storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    reserve(overflow, pixel_total * sizeof(gpu::uvec2), storage);
    reserve(boundary, pixel_total * sizeof(gpu::uvec2), storage, gpu::MemoryUse::device);
    const bool indexed = !settings.fan && settings.cone_draw == ConeDraw::indexed;
    if (indexed && indexed_cones < instance_total) {
      reserve(cone_indices, instance_total * 6 * sizeof(std::uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
      indexed_cones = cone_indices.device.size / (6 * sizeof(std::uint32_t));
      auto* index = static_cast<std::uint32_t*>(cone_indices.host());
      const std::uint32_t pattern[6] = {0, 1, 2, 2, 1, 3};
      for (std::size_t c = 0; c < indexed_cones; ++c)
        for (int v = 0; v < 6; ++v) index[6 * c + v] = static_cast<std::uint32_t>(4 * c) + pattern[v];
    }
    if (read_ids)
      reserve(id_readback, std::size_t{width} * height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryUse::staging);
    update_descriptors();

    // Fill the inputs, scenes in parallel (each writes its own ranges).
    std::vector<std::uint32_t> instance_counts(group.size(), 0);
    parallel_for(group.size(), 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) fill_scene(*group[k], k, at[k], pixel_work, instance_counts[k]);
    });
    // Instances packed in scene order (site order within a scene: ties in depth go to the
    // lower index, since the first drawn wins).
    auto* instance_data = static_cast<gpu::ConeInstance*>(instances.host());
    std::size_t instance_count = 0;
    for (std::size_t k = 0; k < group.size(); ++k) {
      if (at[k].instance_begin != instance_count)
        std::memmove(instance_data + instance_count, instance_data + at[k].instance_begin, instance_counts[k] * sizeof(gpu::ConeInstance));
      instance_count += instance_counts[k];
    }
    timing.upload = seconds_since(upload_start);

    auto device_start = Clock::now();
    VkCommandBuffer cb = commands;
    BLUETILE_VK_CHECK(vkResetCommandBuffer(cb, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    BLUETILE_VK_CHECK(vkBeginCommandBuffer(cb, &begin));
    if (timestamps) vkCmdResetQueryPool(cb, timestamps, 0, kTimestamps);
    auto stamp = [&](std::uint32_t q) {
      if (timestamps) vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps, q);
    };
    auto upload = [&](HostBuffer& b, std::size_t bytes) {
      if (!b.staged() || bytes == 0) return;
      VkBufferCopy region{0, 0, bytes};
      vkCmdCopyBuffer(cb, b.staging.buffer, b.device.buffer, 1, &region);
    };
    upload(instances, instance_count * sizeof(gpu::ConeInstance));
    if (indexed) upload(cone_indices, instance_count * 6 * sizeof(std::uint32_t));
    upload(scenes, group.size() * sizeof(gpu::SceneInfo));
    upload(sites, site_total * sizeof(gpu::SiteInfo));
    upload(positions, site_total * 16);
    upload(masks, mask_words * 4);
    upload(grid, grid_words * 4);
    if (lane_split) upload(list_positions, grid_words * 16);
    vkCmdFillBuffer(cb, sums.device.buffer, 0, std::max<std::size_t>(site_total * sizeof(gpu::SiteSums), 4), 0u);
    vkCmdFillBuffer(cb, counters.device.buffer, 0, (BLUETILE_COUNTER_UNCOVERED + group.size()) * 4, 0u);
    const std::uint32_t dispatch_yz[2] = {1u, 1u};
    vkCmdUpdateBuffer(cb, counters.device.buffer, 4, sizeof dispatch_yz, dispatch_yz);
    VkMemoryBarrier to_shaders{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    to_shaders.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_HOST_WRITE_BIT;
    to_shaders.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_HOST_BIT,
                         VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                         0, 1, &to_shaders, 0, nullptr, 0, nullptr);

    stamp(0);
    VkClearValue clears[2];
    clears[0].color.uint32[0] = clears[0].color.uint32[1] = clears[0].color.uint32[2] = clears[0].color.uint32[3] = 0;
    clears[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    pass.renderPass = render_pass;
    pass.framebuffer = framebuffer;
    pass.renderArea = {{0, 0}, {width, height}};
    pass.clearValueCount = 2;
    pass.pClearValues = clears;
    vkCmdBeginRenderPass(cb, &pass, VK_SUBPASS_CONTENTS_INLINE);
    // Point cones: a point whose centre leaves the clip volume may be dropped whole, and a
    // replica's centre lies up to half its side outside the atlas; so the viewport reaches that
    // far past the atlas on every side (the scissor stays the atlas).
    const float point_margin = std::ceil(0.5f * gpu->max_point_size());
    const VkPhysicalDeviceLimits& limits = gpu->properties().limits;
    const bool points = point_pipeline && widest_cone_pixels(group) <= gpu->max_point_size() &&
                        static_cast<float>(std::max(width, height)) + 2.0f * point_margin <=
                            static_cast<float>(std::min(limits.maxViewportDimensions[0], limits.maxViewportDimensions[1])) &&
                        -point_margin >= limits.viewportBoundsRange[0] &&
                        static_cast<float>(std::max(width, height)) + point_margin <= limits.viewportBoundsRange[1];
    const float margin = points ? point_margin : 0.0f;
    const float push[4] = {static_cast<float>(width) + 2.0f * margin, static_cast<float>(height) + 2.0f * margin, margin, margin};
    VkViewport viewport{-margin, -margin, push[0], push[1], 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {width, height}};
    vkCmdSetViewport(cb, 0, 1, &viewport);
    vkCmdSetScissor(cb, 0, 1, &scissor);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, points ? point_pipeline : cone_pipeline);
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
    vkCmdPushConstants(cb, layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof push, push);
    const auto cones = static_cast<std::uint32_t>(instance_count);
    if (cones == 0) {
    } else if (settings.fan) {
      vkCmdDraw(cb, 3 * BLUETILE_FAN_SEGMENTS, cones, 0, 0);
    } else if (points) {
      vkCmdDraw(cb, cones, 1, 0, 0);
    } else if (indexed) {
      vkCmdBindIndexBuffer(cb, cone_indices.device.buffer, 0, VK_INDEX_TYPE_UINT32);
      vkCmdDrawIndexed(cb, 6 * cones, 1, 0, 0, 0);
    } else if (settings.cone_draw == ConeDraw::instanced) {
      vkCmdDraw(cb, 4, cones, 0, 0);
    } else {
      vkCmdDraw(cb, 6 * cones, 1, 0, 0);
    }
    vkCmdEndRenderPass(cb);
    stamp(1);

    if (pixel_work) {
      vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, classify_pipeline);
      vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
      vkCmdDispatch(cb, (max_rx + BLUETILE_CLASSIFY_GROUP - 1) / BLUETILE_CLASSIFY_GROUP,
                    (max_ry + BLUETILE_CLASSIFY_ROWS - 1) / BLUETILE_CLASSIFY_ROWS, static_cast<std::uint32_t>(group.size()));
    }
    stamp(2);
    VkMemoryBarrier compute_to_compute{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    compute_to_compute.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    compute_to_compute.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
    if (pixel_work && any_area) {
      vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                           VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT, 0, 1, &compute_to_compute, 0,
                           nullptr, 0, nullptr);
      vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, split_for(group.size(), site_total, grid_words));
      vkCmdDispatchIndirect(cb, counters.device.buffer, 4 * BLUETILE_COUNTER_DISPATCH);
    }
    stamp(3);
    VkMemoryBarrier to_transfer{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    to_transfer.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    to_transfer.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                         &to_transfer, 0, nullptr, 0, nullptr);
    auto download = [&](HostBuffer& b, std::size_t bytes) {
      if (!b.staged() || bytes == 0) return;
      VkBufferCopy region{0, 0, bytes};
      vkCmdCopyBuffer(cb, b.device.buffer, b.staging.buffer, 1, &region);
    };
    download(sums, site_total * sizeof(gpu::SiteSums));
    download(counters, (BLUETILE_COUNTER_UNCOVERED + group.size()) * 4);
    if (read_ids) {
      VkBufferImageCopy copy{};
      copy.bufferRowLength = width;
      copy.bufferImageHeight = height;
      copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      copy.imageExtent = {width, height, 1};
      vkCmdCopyImageToBuffer(cb, id_image.image, VK_IMAGE_LAYOUT_GENERAL, id_readback.buffer, 1, &copy);
    }
    stamp(4);
    VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                         &to_host, 0, nullptr, 0, nullptr);
    BLUETILE_VK_CHECK(vkEndCommandBuffer(cb));
    gpu->submit_and_wait(cb);
    timing.cones = timing.classify = timing.split = timing.readback = 0.0;
    timing.cones_drawn = instance_count;
    timing.point_cones = points;
    if (timestamps) {
      std::uint64_t t[kTimestamps] = {};
      if (vkGetQueryPoolResults(gpu->device(), timestamps, 0, kTimestamps, sizeof t, t, sizeof t[0],
                                VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT) == VK_SUCCESS) {
        const double period = 1e-9 * static_cast<double>(gpu->properties().limits.timestampPeriod);
        timing.cones = static_cast<double>(t[1] - t[0]) * period;
        timing.classify = static_cast<double>(t[2] - t[1]) * period;
        timing.split = static_cast<double>(t[3] - t[2]) * period;
        timing.readback = static_cast<double>(t[4] - t[3]) * period;
      }
    }

    // The overflow list is read only as far as it was filled (rarely at all).
    const std::uint32_t overflowed = static_cast<const std::uint32_t*>(counters.host())[BLUETILE_COUNTER_OVERFLOW];
    overflow_copy.clear();
    if (overflowed) {
      if (overflow.staged()) {
        BLUETILE_VK_CHECK(vkResetCommandBuffer(cb, 0));
        BLUETILE_VK_CHECK(vkBeginCommandBuffer(cb, &begin));
        VkBufferCopy region{0, 0, std::size_t{overflowed} * sizeof(gpu::uvec2)};
        vkCmdCopyBuffer(cb, overflow.device.buffer, overflow.staging.buffer, 1, &region);
        vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, nullptr, 0, nullptr);
        BLUETILE_VK_CHECK(vkEndCommandBuffer(cb));
        gpu->submit_and_wait(cb);
      }
      const auto* entries = static_cast<const gpu::uvec2*>(overflow.host());
      overflow_copy.assign(entries, entries + overflowed);
      // Atomic appends come in any order: sort, so the host splits them in a fixed one.
      std::sort(overflow_copy.begin(), overflow_copy.end(),
                [](const gpu::uvec2& a, const gpu::uvec2& b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
    }
    timing.device = seconds_since(device_start);
  }
};

std::string device_pixel_work_refusal(const std::string& name, bool has_float64, bool force_float32) {
  if (has_float64 || force_float32) return "";
  return "raster engine: pixel work 'device' needs shaderFloat64 for the exact split, which '" + name +
         "' lacks; use pixel work 'host' or 'auto'";
}

RasterDevice::RasterDevice(const RasterDeviceSettings& settings) : impl_(std::make_unique<Impl>(settings)) {}
RasterDevice::~RasterDevice() = default;

std::string RasterDevice::device_name() const { return impl_->gpu->info().name; }
bool RasterDevice::float64_split() const { return impl_->float64; }
bool RasterDevice::lane_split() const { return impl_->lane_split; }
std::uint32_t RasterDevice::max_side() const { return impl_->gpu->properties().limits.maxImageDimension2D; }
std::uint32_t RasterDevice::max_scenes_per_pass() const {
  return std::min<std::uint32_t>(impl_->gpu->properties().limits.maxComputeWorkGroupCount[2], 65535);
}
std::size_t RasterDevice::max_pass_pixels() const {
  const double range = static_cast<double>(impl_->gpu->properties().limits.maxStorageBufferRange);
  return static_cast<std::size_t>(std::min({static_cast<double>(impl_->gpu->memory_budget()) / kBytesPerSample,
                                            kMaxPassSamples, range / sizeof(gpu::uvec2)}));
}
std::size_t RasterDevice::max_pass_sites() const {
  const std::size_t per_site = std::max({9 * sizeof(gpu::ConeInstance), sizeof(gpu::SiteSums), sizeof(gpu::SiteInfo)});
  return impl_->gpu->properties().limits.maxStorageBufferRange / per_site;
}

void RasterDevice::run(std::span<RasterScene* const> group, std::uint32_t width, std::uint32_t height, bool read_ids,
                       bool pixel_work) {
  impl_->run(group, width, height, read_ids, pixel_work);
}

bool RasterDevice::is_cpu() const { return impl_->gpu->info().type == "cpu"; }

std::span<const gpu::SiteSums> RasterDevice::sums(const RasterScene& scene) const {
  return {static_cast<const gpu::SiteSums*>(impl_->sums.host()) + scene.site_begin, scene.size()};
}

std::uint32_t RasterDevice::uncovered(std::size_t group_index) const {
  return static_cast<const std::uint32_t*>(impl_->counters.host())[BLUETILE_COUNTER_UNCOVERED + group_index];
}

std::uint32_t RasterDevice::boundary_pixels() const {
  return static_cast<const std::uint32_t*>(impl_->counters.host())[BLUETILE_COUNTER_BOUNDARY];
}

std::uint32_t RasterDevice::guard_pixels() const {
  return static_cast<const std::uint32_t*>(impl_->counters.host())[BLUETILE_COUNTER_GUARD];
}

std::span<const gpu::uvec2> RasterDevice::overflow() const { return impl_->overflow_copy; }

std::vector<std::uint32_t> RasterDevice::ids(const RasterScene& scene) const {
  if (!impl_->ids_read) throw Error("raster engine: the ID image was not read back");
  const auto* atlas = static_cast<const std::uint32_t*>(impl_->id_readback.mapped);
  std::vector<std::uint32_t> out(static_cast<std::size_t>(scene.rx) * scene.ry);
  for (int j = 0; j < scene.ry; ++j)
    for (int i = 0; i < scene.rx; ++i) {
      const std::uint32_t raw = atlas[static_cast<std::size_t>(scene.origin_y + j) * impl_->atlas_width + scene.origin_x + i];
      out[static_cast<std::size_t>(j) * scene.rx + i] = raw == 0 ? 0 : raw - scene.site_begin;
    }
  return out;
}

const RasterPassTiming& RasterDevice::timing() const { return impl_->timing; }

}  // namespace bluetile
