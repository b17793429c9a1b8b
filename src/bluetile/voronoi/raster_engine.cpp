// The raster centroid engine.
//
// Method. Hoff, Keyser, Lin, Manocha, Culver: "Fast computation of generalized Voronoi
// diagrams using graphics hardware" (SIGGRAPH 1999), as the paper (Hiller, Deussen, Keller
// 2001, section 2) uses it for Lloyd relaxation: every site draws a distance cone into a depth
// buffer with the test LESS, and an ID buffer then holds, at each pixel centre, the site
// nearest to it. Here:
//  - Cones are bounded (radius R per site) and drawn as screen-aligned squares whose fragment
//    shader writes the exact float distance as depth; a site near a border also draws its
//    periodic replicas. The classic tessellated fan is kept as an option.
//  - Pixel (i, j) of a scene at resolution rx x ry has its centre at ((i+0.5) W/rx, (j+0.5) H/ry).
//  - A compute pass sums, per site, integer pixel offsets from the site's own pixel, wrapped on
//    the torus, with 64-bit integer atomics: exact, so the same in any order and with any
//    thread count. The host turns them into domain units in double.
//  - Coverage check. A bounded cone can miss pixels of its own cell, which then show a wrong
//    site. Every pass is checked and redone with larger radii if it fails, never accepted:
//    no pixel may be uncovered, and for every site s whose farthest owned pixel centre lies at
//    distance F_s, every site t within 2 F_s of s must have R_t >= F_s (then every site closer
//    to any pixel than its owner drew that pixel, so the ID buffer is the nearest-site diagram
//    at pixel centres, ties to the lower index). The next radii come from the last F and the
//    sites' motion, so relaxed sets draw small cones.
//  - `point` coverage: a pixel counts wholly for the site its centre shows.
//  - `area` coverage: a pixel whose 3x3 neighbourhood shows only its own ID lies wholly in that
//    cell (any other cell reaching into the pixel would own one of those nine centres) and is
//    summed on the GPU. Every other pixel is split exactly on the host, in double precision:
//    the pixel square is clipped by the bisectors between its candidate sites and each piece's
//    area, first and second moments go to its site. Candidates are the IDs of the 3x3
//    neighbourhood, their neighbours in the ID buffer (cells owning no pixel near here are
//    missed otherwise), the sites' own periodic images when cells are as wide as the domain,
//    and, for cells that own no pixel at all, their neighbours from the exact engine. Only
//    candidates within (nearest distance + pixel diagonal) of the pixel centre can own part of
//    it or cut a piece, so the others are dropped before clipping. The sums are then those of
//    the exact Voronoi cells up to double rounding: resolution becomes a speed knob.
//  - A cell that owns no pixel centre gets its values from the exact engine (exact_fallback);
//    a site coinciding with a lower-index site is not drawn (coincident), as in ExactEngine.
//  - Batches: the scenes of one compute() call are packed as tiles into one atlas and drawn,
//    reduced and read back in one submission.
#include "bluetile/voronoi/raster_engine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <numeric>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/gpu/context.h"
#include "bluetile/gpu/embedded_shaders.h"
#include "bluetile/gpu/raster_layout.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/voronoi/polygon.h"
#include "bluetile/voronoi/site_grid.h"

namespace bluetile {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Rows of pixels per host work item in the area split: fixed, so the summation order (and the
// result) does not depend on the thread count.
constexpr int kRowsPerChunk = 8;
// Coverage-check failures before every cone of the scene covers the whole domain.
constexpr int kMaxRedos = 6;

struct Piece {
  std::uint32_t site;
  double area, mx, my, m2;
};

// Per scene of a batch during one compute().
struct Job {
  std::size_t index = 0;  // in the batch
  const Scene* scene = nullptr;
  std::vector<Point> sites;  // wrapped into the domain
  std::vector<std::uint8_t> coincident;
  std::vector<double> radius;  // cone radius per site, domain units
  int rx = 0, ry = 0;
  double hx = 0.0, hy = 0.0;
  double radius_cap = 0.0;  // a cone this large covers the whole torus
  int redos = 0;
  bool done = false;
  std::uint64_t boundary_pixels = 0;  // split on the host in the accepted pass
  std::vector<std::uint8_t> split;  // per site: split all its pixels on the host
  std::vector<std::pair<std::uint32_t, std::uint32_t>> close_pairs;
  std::vector<double> need;  // per site: the largest F_s of sites s within 2 F_s (coverage check)
  // Placement in the current pass.
  int origin_x = 0, origin_y = 0;
  std::uint32_t site_begin = 0;
  std::uint32_t boundary_offset = 0;

  double pixel_diagonal() const { return std::sqrt(hx * hx + hy * hy); }
};

// What the engine remembers of a batch slot to pick the next radii.
struct Slot {
  std::vector<Point> sites;
  std::vector<double> farthest;
  Point domain;
  int rx = 0;
};

}  // namespace

int default_resolution(std::size_t sites, Coverage coverage) {
  double n = static_cast<double>(std::max<std::size_t>(sites, 1));
  // area: ~16 pixels per cell keeps candidate lists short; point: ~1000 pixels per cell.
  double side = coverage == Coverage::area ? 4.0 * std::sqrt(n) : 32.0 * std::sqrt(n);
  int lo = coverage == Coverage::area ? 16 : 64;
  int rounded = static_cast<int>(std::ceil(side / 16.0)) * 16;
  return std::clamp(rounded, lo, 8192);
}

struct RasterEngine::Impl {
  RasterOptions options;
  std::unique_ptr<gpu::Context> gpu;
  RasterStats stats;
  std::vector<Slot> slots;
  std::vector<IdImage> id_images;

  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineLayout graphics_layout = VK_NULL_HANDLE;
  VkPipelineLayout compute_layout = VK_NULL_HANDLE;
  VkDescriptorPool descriptor_pool = VK_NULL_HANDLE;
  VkDescriptorSet descriptor_set = VK_NULL_HANDLE;
  VkRenderPass render_pass = VK_NULL_HANDLE;
  VkPipeline cone_pipeline = VK_NULL_HANDLE;
  VkPipeline reduce_pipeline = VK_NULL_HANDLE;
  VkCommandBuffer commands = VK_NULL_HANDLE;

  gpu::Image id_image, depth_image;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  gpu::Buffer instances, scenes, sites, ids, sums, counters, boundary;
  bool descriptors_dirty = true;
  bool gpu_reduction = true;

  explicit Impl(const RasterOptions& o) : options(o) {
    gpu = std::make_unique<gpu::Context>(o.device);
    gpu_reduction = o.reduction == Reduction::gpu || (o.reduction == Reduction::automatic && gpu->info().type != "cpu");
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
    for (gpu::Buffer* b : {&instances, &scenes, &sites, &ids, &sums, &counters, &boundary}) gpu->destroy(*b);
    if (framebuffer) vkDestroyFramebuffer(d, framebuffer, nullptr);
    gpu->destroy(id_image);
    gpu->destroy(depth_image);
    if (commands) vkFreeCommandBuffers(d, gpu->command_pool(), 1, &commands);
    if (cone_pipeline) vkDestroyPipeline(d, cone_pipeline, nullptr);
    if (reduce_pipeline) vkDestroyPipeline(d, reduce_pipeline, nullptr);
    if (render_pass) vkDestroyRenderPass(d, render_pass, nullptr);
    if (descriptor_pool) vkDestroyDescriptorPool(d, descriptor_pool, nullptr);
    if (graphics_layout) vkDestroyPipelineLayout(d, graphics_layout, nullptr);
    if (compute_layout) vkDestroyPipelineLayout(d, compute_layout, nullptr);
    if (set_layout) vkDestroyDescriptorSetLayout(d, set_layout, nullptr);
    gpu.reset();
  }

  void create_pipelines() {
    VkDevice d = gpu->device();
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    for (std::uint32_t b = 0; b <= BLUETILE_BINDING_BOUNDARY; ++b)
      bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
                          VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
    VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    set_info.bindingCount = static_cast<std::uint32_t>(bindings.size());
    set_info.pBindings = bindings.data();
    BLUETILE_VK_CHECK(vkCreateDescriptorSetLayout(d, &set_info, nullptr, &set_layout));

    VkPushConstantRange graphics_push{VK_SHADER_STAGE_VERTEX_BIT, 0, 8};
    VkPushConstantRange compute_push{VK_SHADER_STAGE_COMPUTE_BIT, 0, 4};
    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout;
    layout_info.pushConstantRangeCount = 1;
    layout_info.pPushConstantRanges = &graphics_push;
    BLUETILE_VK_CHECK(vkCreatePipelineLayout(d, &layout_info, nullptr, &graphics_layout));
    layout_info.pPushConstantRanges = &compute_push;
    BLUETILE_VK_CHECK(vkCreatePipelineLayout(d, &layout_info, nullptr, &compute_layout));

    VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, static_cast<std::uint32_t>(bindings.size())};
    VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = 1;
    pool_info.pPoolSizes = &pool_size;
    BLUETILE_VK_CHECK(vkCreateDescriptorPool(d, &pool_info, nullptr, &descriptor_pool));
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = descriptor_pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &set_layout;
    BLUETILE_VK_CHECK(vkAllocateDescriptorSets(d, &alloc, &descriptor_set));

    VkAttachmentDescription attachments[2] = {};
    attachments[0].format = VK_FORMAT_R32_UINT;
    attachments[0].samples = VK_SAMPLE_COUNT_1_BIT;
    attachments[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    attachments[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachments[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachments[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachments[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    attachments[0].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    attachments[1] = attachments[0];
    attachments[1].format = VK_FORMAT_D32_SFLOAT;
    attachments[1].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachments[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    VkAttachmentReference color_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkAttachmentReference depth_ref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &color_ref;
    subpass.pDepthStencilAttachment = &depth_ref;
    VkSubpassDependency dependencies[2] = {};
    dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[0].dstSubpass = 0;
    dependencies[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dependencies[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                   VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dependencies[0].srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dependencies[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
    dependencies[1].srcSubpass = 0;
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    VkRenderPassCreateInfo pass_info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    pass_info.attachmentCount = 2;
    pass_info.pAttachments = attachments;
    pass_info.subpassCount = 1;
    pass_info.pSubpasses = &subpass;
    pass_info.dependencyCount = 2;
    pass_info.pDependencies = dependencies;
    BLUETILE_VK_CHECK(vkCreateRenderPass(d, &pass_info, nullptr, &render_pass));

    bool fan = options.cone == ConeShape::fan;
    VkShaderModule vert = gpu->create_shader(embedded_shader(fan ? "cone_fan.vert" : "cone_quad.vert"));
    VkShaderModule frag = VK_NULL_HANDLE, comp = VK_NULL_HANDLE;
    try {
      frag = gpu->create_shader(embedded_shader(fan ? "cone_fan.frag" : "cone_quad.frag"));
      comp = gpu->create_shader(embedded_shader("reduce.comp"));
      VkPipelineShaderStageCreateInfo stages[2] = {};
      stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vert, "main", nullptr};
      stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, frag, "main", nullptr};
      VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
      VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
      assembly.topology = fan ? VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
      VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
      viewport.viewportCount = 1;
      viewport.scissorCount = 1;
      VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
      raster.polygonMode = VK_POLYGON_MODE_FILL;
      raster.cullMode = VK_CULL_MODE_NONE;
      raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
      raster.lineWidth = 1.0f;
      VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
      multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
      VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
      depth.depthTestEnable = VK_TRUE;
      depth.depthWriteEnable = VK_TRUE;
      depth.depthCompareOp = VK_COMPARE_OP_LESS;
      VkPipelineColorBlendAttachmentState blend_attachment{};
      blend_attachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT;
      VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
      blend.attachmentCount = 1;
      blend.pAttachments = &blend_attachment;
      VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
      VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
      dynamic.dynamicStateCount = 2;
      dynamic.pDynamicStates = dynamic_states;
      VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
      info.stageCount = 2;
      info.pStages = stages;
      info.pVertexInputState = &vertex_input;
      info.pInputAssemblyState = &assembly;
      info.pViewportState = &viewport;
      info.pRasterizationState = &raster;
      info.pMultisampleState = &multisample;
      info.pDepthStencilState = &depth;
      info.pColorBlendState = &blend;
      info.pDynamicState = &dynamic;
      info.layout = graphics_layout;
      info.renderPass = render_pass;
      BLUETILE_VK_CHECK(vkCreateGraphicsPipelines(d, VK_NULL_HANDLE, 1, &info, nullptr, &cone_pipeline));

      VkComputePipelineCreateInfo compute_info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
      compute_info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, comp, "main", nullptr};
      compute_info.layout = compute_layout;
      BLUETILE_VK_CHECK(vkCreateComputePipelines(d, VK_NULL_HANDLE, 1, &compute_info, nullptr, &reduce_pipeline));
    } catch (...) {
      vkDestroyShaderModule(d, vert, nullptr);
      if (frag) vkDestroyShaderModule(d, frag, nullptr);
      if (comp) vkDestroyShaderModule(d, comp, nullptr);
      throw;
    }
    vkDestroyShaderModule(d, vert, nullptr);
    vkDestroyShaderModule(d, frag, nullptr);
    vkDestroyShaderModule(d, comp, nullptr);

    VkCommandBufferAllocateInfo command_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    command_info.commandPool = gpu->command_pool();
    command_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    command_info.commandBufferCount = 1;
    BLUETILE_VK_CHECK(vkAllocateCommandBuffers(d, &command_info, &commands));
  }

  void ensure_buffer(gpu::Buffer& buffer, std::size_t bytes, VkBufferUsageFlags usage) {
    bytes = std::max<std::size_t>(bytes, 256);
    if (buffer.size >= bytes) return;
    gpu->destroy(buffer);
    buffer = gpu->create_buffer(static_cast<VkDeviceSize>(bytes + bytes / 2), usage);
    descriptors_dirty = true;
  }

  void ensure_atlas(std::uint32_t width, std::uint32_t height) {
    if (id_image.width >= width && id_image.height >= height) return;
    width = std::max(width, id_image.width);
    height = std::max(height, id_image.height);
    VkDevice d = gpu->device();
    if (framebuffer) vkDestroyFramebuffer(d, framebuffer, nullptr);
    framebuffer = VK_NULL_HANDLE;
    gpu->destroy(id_image);
    gpu->destroy(depth_image);
    id_image = gpu->create_image(width, height, VK_FORMAT_R32_UINT,
                                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
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
  }

  void update_descriptors() {
    if (!descriptors_dirty) return;
    gpu::Buffer* buffers[] = {&instances, &scenes, &sites, &ids, &sums, &counters, &boundary};
    VkDescriptorBufferInfo infos[7];
    VkWriteDescriptorSet writes[7];
    for (std::uint32_t b = 0; b < 7; ++b) {
      infos[b] = {buffers[b]->buffer, 0, VK_WHOLE_SIZE};
      writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      writes[b].dstSet = descriptor_set;
      writes[b].dstBinding = b;
      writes[b].descriptorCount = 1;
      writes[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      writes[b].pBufferInfo = &infos[b];
    }
    vkUpdateDescriptorSets(gpu->device(), 7, writes, 0, nullptr);
    descriptors_dirty = false;
  }

  // ---- scene preparation -------------------------------------------------------------------

  int resolution_for(const Scene& scene) const {
    if (!(scene.domain.size.x > 0.0 && scene.domain.size.y > 0.0)) throw Error("raster engine: domain size must be positive");
    int rx = options.resolution > 0 ? options.resolution : default_resolution(scene.sites.size(), options.coverage);
    int ry = std::max(1, static_cast<int>(std::lround(rx * scene.domain.size.y / scene.domain.size.x)));
    std::uint32_t limit = gpu->properties().limits.maxImageDimension2D;
    if (static_cast<std::uint32_t>(std::max(rx, ry)) > limit) {
      throw Error("resolution " + std::to_string(rx) + " x " + std::to_string(ry) + " exceeds the device's limit of " +
                  std::to_string(limit) + " pixels per side (" + gpu->info().name + ")");
    }
    double bytes = 16.0 * rx * ry;  // ID, depth, readback, bit mask and slack
    if (bytes > static_cast<double>(gpu->memory_budget())) {
      throw Error("resolution " + std::to_string(rx) + " x " + std::to_string(ry) + " needs " +
                  std::to_string(static_cast<long long>(bytes / 1048576.0)) + " MiB, more than the device's " +
                  std::to_string(static_cast<long long>(gpu->memory_budget() / 1048576)) + " MiB budget");
    }
    return rx;
  }

  Job prepare(const Scene& scene, std::size_t index) {
    if (scene.wanted_begin > scene.wanted_end || scene.wanted_end > scene.sites.size())
      throw Error("raster engine: scene's wanted range lies outside its sites");
    Job job;
    job.index = index;
    job.scene = &scene;
    job.rx = resolution_for(scene);
    job.ry = std::max(1, static_cast<int>(std::lround(job.rx * scene.domain.size.y / scene.domain.size.x)));
    job.hx = scene.domain.size.x / job.rx;
    job.hy = scene.domain.size.y / job.ry;
    job.radius_cap = 0.5 * std::sqrt(scene.domain.size.x * scene.domain.size.x + scene.domain.size.y * scene.domain.size.y);
    const std::size_t n = scene.sites.size();
    job.sites.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      Point p = scene.sites[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw Error("raster engine: site " + std::to_string(i) + " is not finite");
      job.sites[i] = wrap_point(p, scene.domain);
    }
    job.coincident.assign(n, 0);
    std::vector<std::uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      const Point &p = job.sites[a], &q = job.sites[b];
      if (p.x != q.x) return p.x < q.x;
      if (p.y != q.y) return p.y < q.y;
      return a < b;
    });
    for (std::size_t k = 1; k < n; ++k)
      if (job.sites[order[k]] == job.sites[order[k - 1]]) job.coincident[order[k]] = 1;

    // Float depths rank two sites correctly only where their distances differ by more than a
    // few float ulps. Seen from an interior pixel's 3x3 neighbourhood, sites closer together
    // than `fragile` may differ by less; their cells are split on the host whole, with each
    // other as candidates.
    job.split.assign(n, 0);
    if (options.coverage == Coverage::area && n > 1) {
      const double extent = std::max(scene.domain.size.x, scene.domain.size.y);
      const double fragile = 16.0 * std::ldexp(1.0, -24) * extent * extent / std::min(job.hx, job.hy);
      SiteGrid grid(job.sites, scene.domain, 1.0);
      for (std::size_t s = 0; s < n; ++s) {
        if (job.coincident[s]) continue;
        grid.for_each_near(job.sites[s], fragile, [&](std::uint32_t t) {
          if (t <= s || job.coincident[t] || torus_distance(job.sites[s], job.sites[t], scene.domain) > fragile) return;
          job.split[s] = job.split[t] = 1;
          job.close_pairs.push_back({static_cast<std::uint32_t>(s), t});
        });
      }
    }

    // Radii: from the slot's last pass when it is the same batch moving on, else the start value.
    double start = options.radius_factor * std::sqrt(scene.domain.area() / static_cast<double>(std::max<std::size_t>(n, 1)));
    job.radius.assign(n, std::min(start, job.radius_cap));
    if (options.adapt_radius && index < slots.size()) {
      const Slot& slot = slots[index];
      if (slot.sites.size() == n && slot.domain == scene.domain.size && slot.rx == job.rx) {
        std::vector<double> motion(n);
        double max_motion = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
          motion[i] = torus_distance(slot.sites[i], job.sites[i], scene.domain);
          max_motion = std::max(max_motion, motion[i]);
        }
        // A cell's radius grows by at most about its site's and its neighbours' motion; the
        // coverage check catches the rest.
        double slack = 2.0 * job.pixel_diagonal();
        for (std::size_t i = 0; i < n; ++i)
          job.radius[i] = std::min(job.radius_cap, 1.1 * slot.farthest[i] + motion[i] + max_motion + slack);
      }
    }
    return job;
  }

  // ---- one pass over a group of jobs -------------------------------------------------------

  void run_pass(std::vector<Job*>& group, std::uint32_t atlas_width, std::uint32_t atlas_height) {
    auto start = Clock::now();
    ensure_atlas(atlas_width, atlas_height);
    std::size_t site_total = 0, instance_total = 0, mask_words = 0;
    for (Job* job : group) {
      job->site_begin = static_cast<std::uint32_t>(site_total);
      job->boundary_offset = static_cast<std::uint32_t>(mask_words);
      site_total += job->sites.size();
      mask_words += static_cast<std::size_t>((job->rx + 31) / 32) * job->ry;
      instance_total += 9 * job->sites.size();
    }
    ensure_buffer(instances, instance_total * sizeof(gpu::ConeInstance), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    ensure_buffer(scenes, group.size() * sizeof(gpu::SceneInfo), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    ensure_buffer(sites, site_total * sizeof(gpu::SiteInfo), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    ensure_buffer(ids, std::size_t{atlas_width} * atlas_height * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    ensure_buffer(sums, site_total * sizeof(gpu::SiteSums), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    ensure_buffer(counters, group.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    ensure_buffer(boundary, mask_words * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    update_descriptors();

    auto* scene_data = static_cast<gpu::SceneInfo*>(scenes.mapped);
    auto* site_data = static_cast<gpu::SiteInfo*>(sites.mapped);
    auto* instance_data = static_cast<gpu::ConeInstance*>(instances.mapped);
    std::size_t instance_count = 0;
    int max_rx = 0, max_ry = 0;
    for (std::size_t k = 0; k < group.size(); ++k) {
      const Job& job = *group[k];
      const Point size = job.scene->domain.size;
      max_rx = std::max(max_rx, job.rx);
      max_ry = std::max(max_ry, job.ry);
      gpu::SceneInfo& info = scene_data[k];
      info.origin = {job.origin_x, job.origin_y};
      info.size = {job.rx, job.ry};
      info.pixel_size = {static_cast<float>(job.hx), static_cast<float>(job.hy)};
      info.domain_size = {static_cast<float>(size.x), static_cast<float>(size.y)};
      info.depth_scale = static_cast<float>(1.0 / (2.0 * job.radius_cap));
      info.site_begin = job.site_begin;
      info.boundary_offset = job.boundary_offset;
      info.flags = options.coverage == Coverage::area ? BLUETILE_SCENE_AREA : 0u;
      for (std::size_t i = 0; i < job.sites.size(); ++i) {
        const Point s = job.sites[i];
        int px = std::clamp(static_cast<int>(std::floor(s.x / job.hx)), 0, job.rx - 1);
        int py = std::clamp(static_cast<int>(std::floor(s.y / job.hy)), 0, job.ry - 1);
        gpu::SiteInfo& si = site_data[job.site_begin + i];
        si = {};
        si.pixel = {px, py};
        si.fraction = {static_cast<float>((px + 0.5) * job.hx - s.x), static_cast<float>((py + 0.5) * job.hy - s.y)};
        si.scene = static_cast<std::uint32_t>(k);
        si.flags = job.split[i] ? BLUETILE_SITE_SPLIT : 0u;
        if (job.coincident[i]) continue;
        const double r = job.radius[i];
        const auto id = static_cast<std::uint32_t>(job.site_begin + i + 1);
        for (int ky = -1; ky <= 1; ++ky)
          for (int kx = -1; kx <= 1; ++kx) {
            Point p{s.x + kx * size.x, s.y + ky * size.y};
            if (p.x + r <= 0.0 || p.x - r >= size.x || p.y + r <= 0.0 || p.y - r >= size.y) continue;
            instance_data[instance_count++] = {{static_cast<float>(p.x), static_cast<float>(p.y)}, static_cast<float>(r), id};
          }
      }
    }
    std::memset(sums.mapped, 0, site_total * sizeof(gpu::SiteSums));
    std::memset(counters.mapped, 0, group.size() * 4);
    std::memset(boundary.mapped, 0, std::max<std::size_t>(mask_words, 1) * 4);

    VkCommandBuffer cb = commands;
    BLUETILE_VK_CHECK(vkResetCommandBuffer(cb, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    BLUETILE_VK_CHECK(vkBeginCommandBuffer(cb, &begin));
    VkClearValue clears[2];
    clears[0].color.uint32[0] = 0;
    clears[0].color.uint32[1] = clears[0].color.uint32[2] = clears[0].color.uint32[3] = 0;
    clears[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    pass.renderPass = render_pass;
    pass.framebuffer = framebuffer;
    pass.renderArea = {{0, 0}, {atlas_width, atlas_height}};
    pass.clearValueCount = 2;
    pass.pClearValues = clears;
    vkCmdBeginRenderPass(cb, &pass, VK_SUBPASS_CONTENTS_INLINE);
    VkViewport viewport{0.0f, 0.0f, static_cast<float>(atlas_width), static_cast<float>(atlas_height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {atlas_width, atlas_height}};
    vkCmdSetViewport(cb, 0, 1, &viewport);
    vkCmdSetScissor(cb, 0, 1, &scissor);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, cone_pipeline);
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, graphics_layout, 0, 1, &descriptor_set, 0, nullptr);
    float atlas_size[2] = {static_cast<float>(atlas_width), static_cast<float>(atlas_height)};
    vkCmdPushConstants(cb, graphics_layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof atlas_size, atlas_size);
    std::uint32_t vertices = options.cone == ConeShape::fan ? 3 * BLUETILE_FAN_SEGMENTS : 4;
    if (instance_count) vkCmdDraw(cb, vertices, static_cast<std::uint32_t>(instance_count), 0, 0);
    vkCmdEndRenderPass(cb);

    VkBufferImageCopy copy{};
    copy.bufferRowLength = atlas_width;
    copy.bufferImageHeight = atlas_height;
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {atlas_width, atlas_height, 1};
    vkCmdCopyImageToBuffer(cb, id_image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, ids.buffer, 1, &copy);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_HOST_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_HOST_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1,
                         &barrier, 0, nullptr, 0, nullptr);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, reduce_pipeline);
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, compute_layout, 0, 1, &descriptor_set, 0, nullptr);
    vkCmdPushConstants(cb, compute_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, 4, &atlas_width);
    if (gpu_reduction) {
      vkCmdDispatch(cb, static_cast<std::uint32_t>((max_rx + BLUETILE_REDUCE_GROUP_X - 1) / BLUETILE_REDUCE_GROUP_X),
                    static_cast<std::uint32_t>((max_ry + BLUETILE_REDUCE_GROUP_Y - 1) / BLUETILE_REDUCE_GROUP_Y),
                    static_cast<std::uint32_t>(group.size()));
    }
    VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                         &to_host, 0, nullptr, 0, nullptr);
    BLUETILE_VK_CHECK(vkEndCommandBuffer(cb));
    gpu->submit_and_wait(cb);
    if (!gpu_reduction) host_reduce(group, atlas_width);
    ++stats.submits;
    stats.scene_passes += group.size();
    stats.gpu_seconds += seconds_since(start);
  }

  // The reduction of reduce.comp on the host, for CPU devices: lavapipe runs that compute
  // shader single-threaded at about 150 ns per pixel, while this loop takes about 1 ns. Runs of
  // equal IDs along a row are summed first; integer sums make the order irrelevant, so the
  // result is bit-identical to the shader's. The farthest distance uses the same float formula.
  void host_reduce(const std::vector<Job*>& group, std::uint32_t atlas_width) {
    struct Run {
      std::uint32_t site, owned, count;
      float farthest;
      std::int64_t sx, sy, sxx, syy;
    };
    struct Item {
      std::size_t scene;
      int row_begin, row_end;
    };
    std::vector<Item> items;
    for (std::size_t k = 0; k < group.size(); ++k)
      for (int j = 0; j < group[k]->ry; j += kRowsPerChunk)
        items.push_back({k, j, std::min(group[k]->ry, j + kRowsPerChunk)});
    std::vector<std::vector<Run>> runs(items.size());
    std::vector<std::uint32_t> uncovered(items.size(), 0);
    const auto* pixels = static_cast<const std::uint32_t*>(ids.mapped);
    const auto* site_data = static_cast<const gpu::SiteInfo*>(sites.mapped);
    auto* mask = static_cast<std::uint32_t*>(boundary.mapped);
    const bool area = options.coverage == Coverage::area;
    parallel_for(items.size(), 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t t = begin; t < end; ++t) {
        const Job& job = *group[items[t].scene];
        const int rx = job.rx, ry = job.ry, half_x = rx / 2, half_y = ry / 2;
        const float hx = static_cast<float>(job.hx), hy = static_cast<float>(job.hy);
        const std::size_t words_per_row = static_cast<std::size_t>((rx + 31) / 32);
        auto row_of = [&](int j) {
          j = j < 0 ? j + ry : (j >= ry ? j - ry : j);
          return pixels + static_cast<std::size_t>(job.origin_y + j) * atlas_width + job.origin_x;
        };
        std::vector<Run>& out = runs[t];
        Run run{0, 0, 0, 0.0f, 0, 0, 0, 0};
        for (int j = items[t].row_begin; j < items[t].row_end; ++j) {
          const std::uint32_t* above = row_of(j + 1);
          const std::uint32_t* row = row_of(j);
          const std::uint32_t* below = row_of(j - 1);
          std::uint32_t* mask_row = mask + job.boundary_offset + static_cast<std::size_t>(j) * words_per_row;
          for (int i = 0; i < rx; ++i) {
            const std::uint32_t id = row[i];
            if (id == 0) {
              ++uncovered[t];
              continue;
            }
            const std::uint32_t s = id - 1;
            if (s != run.site || run.owned == 0) {
              if (run.owned) out.push_back(run);
              run = Run{s, 0, 0, 0.0f, 0, 0, 0, 0};
            }
            const gpu::SiteInfo& site = site_data[s];
            int dx = i - site.pixel.x, dy = j - site.pixel.y;
            dx = dx < -half_x ? dx + rx : dx;
            dx = dx >= rx - half_x ? dx - rx : dx;
            dy = dy < -half_y ? dy + ry : dy;
            dy = dy >= ry - half_y ? dy - ry : dy;
            const float ox = static_cast<float>(dx) * hx + site.fraction.x;
            const float oy = static_cast<float>(dy) * hy + site.fraction.y;
            run.farthest = std::max(run.farthest, ox * ox + oy * oy);
            ++run.owned;
            if (area) {
              bool whole = std::abs(dx) < half_x - 1 && std::abs(dy) < half_y - 1 && !(site.flags & BLUETILE_SITE_SPLIT);
              if (whole) {
                const int il = i == 0 ? rx - 1 : i - 1, ir = i == rx - 1 ? 0 : i + 1;
                whole = row[il] == id && row[ir] == id && above[il] == id && above[i] == id && above[ir] == id &&
                        below[il] == id && below[i] == id && below[ir] == id;
              }
              if (!whole) {
                mask_row[i / 32] |= 1u << (i % 32);
                continue;
              }
            }
            ++run.count;
            run.sx += dx;
            run.sy += dy;
            run.sxx += static_cast<std::int64_t>(dx) * dx;
            run.syy += static_cast<std::int64_t>(dy) * dy;
          }
        }
        if (run.owned) out.push_back(run);
      }
    });
    auto* sum_data = static_cast<gpu::SiteSums*>(sums.mapped);
    auto* counter_data = static_cast<std::uint32_t*>(counters.mapped);
    for (std::size_t t = 0; t < items.size(); ++t) {
      counter_data[items[t].scene] += uncovered[t];
      for (const Run& r : runs[t]) {
        gpu::SiteSums& sum = sum_data[r.site];
        float previous;
        std::memcpy(&previous, &sum.farthest, sizeof previous);
        float farthest = std::max(previous, r.farthest);
        std::memcpy(&sum.farthest, &farthest, sizeof farthest);
        sum.owned += r.owned;
        sum.count += r.count;
        sum.sum_x += r.sx;
        sum.sum_y += r.sy;
        sum.sum_xx += r.sxx;
        sum.sum_yy += r.syy;
      }
    }
  }

  // ---- after a pass ------------------------------------------------------------------------

  const gpu::SiteSums& sums_of(const Job& job, std::size_t i) const {
    return static_cast<const gpu::SiteSums*>(sums.mapped)[job.site_begin + i];
  }

  static double farthest_of(const gpu::SiteSums& s) {
    float f;
    std::memcpy(&f, &s.farthest, sizeof f);
    return std::sqrt(static_cast<double>(f));
  }

  // The coverage check (see the top of the file). On failure, grows the radii that caused it.
  bool certify(Job& job, std::uint32_t uncovered) {
    const std::size_t n = job.sites.size();
    if (uncovered) {
      stats.uncovered_pixels += uncovered;
      for (double& r : job.radius) r = std::min(job.radius_cap, 2.0 * r);
      return false;
    }
    // A cone at the cap covers the torus; slack for float positions and edge rasterization.
    auto effective = [&](double r) {
      return r >= job.radius_cap ? HUGE_VAL : r * (1.0 - 1e-6) - 1e-3 * std::max(job.hx, job.hy);
    };
    std::vector<double> farthest(n, 0.0);
    double max_farthest = 0.0, min_radius = HUGE_VAL;
    for (std::size_t i = 0; i < n; ++i) {
      if (job.coincident[i]) continue;
      farthest[i] = farthest_of(sums_of(job, i));
      max_farthest = std::max(max_farthest, farthest[i]);
      min_radius = std::min(min_radius, effective(job.radius[i]));
    }
    // need[t]: the radius t must reach for this diagram to pass; the next pass starts from it.
    job.need = farthest;
    const bool all_reach = min_radius >= max_farthest;
    SiteGrid grid(job.sites, job.scene->domain, 1.0);
    bool ok = true;
    std::vector<double> grown = job.radius;
    for (std::size_t s = 0; s < n; ++s) {
      if (job.coincident[s] || farthest[s] == 0.0) continue;
      const double f = farthest[s];
      grid.for_each_near(job.sites[s], 2.0 * f, [&](std::uint32_t t) {
        if (job.coincident[t] || job.need[t] >= f) return;
        if (torus_distance(job.sites[s], job.sites[t], job.scene->domain) > 2.0 * f) return;
        job.need[t] = f;
        if (all_reach || effective(job.radius[t]) >= f) return;
        ok = false;
        grown[t] = std::max(grown[t], std::min(job.radius_cap, std::max(1.5 * job.radius[t], 1.25 * f + job.pixel_diagonal())));
      });
    }
    if (!ok) job.radius = std::move(grown);
    return ok;
  }

  std::uint32_t id_at(const Job& job, const std::uint32_t* pixels, std::uint32_t atlas_width, int i, int j) const {
    i = i < 0 ? i + job.rx : (i >= job.rx ? i - job.rx : i);  // |i|, |j| stay within one period
    j = j < 0 ? j + job.ry : (j >= job.ry ? j - job.ry : j);
    return pixels[static_cast<std::size_t>(job.origin_y + j) * atlas_width + static_cast<std::size_t>(job.origin_x + i)] - 1u -
           job.site_begin;
  }

  // Splits the boundary pixels of `job` exactly; returns per-site sums of the pieces.
  void split_boundary(Job& job, const std::uint32_t* pixels, std::uint32_t atlas_width,
                      const std::vector<std::uint8_t>& pixelless, std::vector<std::vector<std::uint32_t>>& adjacency,
                      std::vector<Piece>& totals) {
    const std::size_t n = job.sites.size();
    const Scene& scene = *job.scene;
    const auto* mask = static_cast<const std::uint32_t*>(boundary.mapped) + job.boundary_offset;
    const std::size_t words_per_row = static_cast<std::size_t>((job.rx + 31) / 32);
    auto is_boundary = [&](int i, int j) {
      return (mask[static_cast<std::size_t>(j) * words_per_row + static_cast<std::size_t>(i / 32)] >> (i % 32)) & 1u;
    };
    auto neighbourhood = [&](int i, int j, std::uint32_t* key) {
      int count = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          std::uint32_t id = id_at(job, pixels, atlas_width, i + dx, j + dy);
          if (std::find(key, key + count, id) == key + count) key[count++] = id;
        }
      for (int a = 1; a < count; ++a)  // insertion sort: at most nine IDs
        for (int b = a; b > 0 && key[b - 1] > key[b]; --b) std::swap(key[b - 1], key[b]);
      return count;
    };
    auto add_unique = [](std::vector<std::uint32_t>& list, std::uint32_t v) {
      if (std::find(list.begin(), list.end(), v) == list.end()) list.push_back(v);
    };

    // Adjacency of cells in the ID buffer: IDs that meet in some pixel's 3x3 neighbourhood.
    std::uint64_t boundary_count = 0;
    std::uint32_t previous[9];
    int previous_count = -1;
    for (int j = 0; j < job.ry; ++j)
      for (int i = 0; i < job.rx; ++i) {
        if (!is_boundary(i, j)) continue;
        ++boundary_count;
        std::uint32_t key[9];
        int count = neighbourhood(i, j, key);
        if (count == previous_count && std::equal(key, key + count, previous)) continue;
        std::copy(key, key + count, previous);
        previous_count = count;
        for (int a = 0; a < count; ++a)
          for (int b = 0; b < count; ++b)
            if (a != b) add_unique(adjacency[key[a]], key[b]);
      }
    job.boundary_pixels = boundary_count;
    for (auto [a, b] : job.close_pairs) {
      add_unique(adjacency[a], b);
      add_unique(adjacency[b], a);
    }
    // Cells with no pixel: only the exact engine knows their neighbours.
    for (std::size_t t = 0; t < n; ++t) {
      if (!pixelless[t]) continue;
      for (std::size_t u : exact_cell_neighbours(scene, t)) {
        if (u == t || job.coincident[u]) continue;
        add_unique(adjacency[t], static_cast<std::uint32_t>(u));
        add_unique(adjacency[u], static_cast<std::uint32_t>(t));
      }
    }

    const int chunks = (job.ry + kRowsPerChunk - 1) / kRowsPerChunk;
    std::vector<std::vector<Piece>> chunk_pieces(static_cast<std::size_t>(chunks));
    const Point size = scene.domain.size;
    const Point half = 0.5 * size;
    const double diagonal = job.pixel_diagonal();
    parallel_for(static_cast<std::size_t>(chunks), 1, [&](std::size_t chunk_begin, std::size_t chunk_end) {
      std::vector<std::uint32_t> candidates;
      struct Entry {
        std::uint32_t site;
        Point offset;  // from the pixel centre to this image of the site
        double distance;  // squared
      };
      std::vector<std::uint32_t> stamp(n, 0u);
      std::uint32_t generation = 0;
      std::vector<Entry> all, near;
      ConvexPolygon polygon;
      std::uint32_t last_key[9];
      int last_count = -1;
      for (std::size_t chunk = chunk_begin; chunk < chunk_end; ++chunk) {
        std::vector<Piece>& pieces = chunk_pieces[chunk];
        int j_end = std::min(job.ry, static_cast<int>(chunk + 1) * kRowsPerChunk);
        for (int j = static_cast<int>(chunk) * kRowsPerChunk; j < j_end; ++j)
          for (int i = 0; i < job.rx; ++i) {
            if (!is_boundary(i, j)) continue;
            std::uint32_t key[9];
            int count = neighbourhood(i, j, key);
            if (count != last_count || !std::equal(key, key + count, last_key)) {
              // A stamp per site makes building the candidate set linear in its size.
              if (++generation == 0) std::fill(stamp.begin(), stamp.end(), 0u), generation = 1;
              candidates.clear();
              auto add = [&](std::uint32_t v) {
                if (stamp[v] != generation) stamp[v] = generation, candidates.push_back(v);
              };
              for (int a = 0; a < count; ++a) add(key[a]);
              for (int a = 0; a < count; ++a)
                for (std::uint32_t v : adjacency[key[a]]) add(v);
              for (std::size_t c = 0; c < candidates.size(); ++c)
                if (pixelless[candidates[c]])
                  for (std::uint32_t v : adjacency[candidates[c]]) add(v);
              std::copy(key, key + count, last_key);
              last_count = count;
            }
            const Point centre{(i + 0.5) * job.hx, (j + 0.5) * job.hy};
            all.clear();
            double nearest2 = HUGE_VAL;
            for (std::uint32_t c : candidates) {
              Point o{job.sites[c].x - centre.x, job.sites[c].y - centre.y};
              if (o.x < -half.x) o.x += size.x; else if (o.x >= half.x) o.x -= size.x;
              if (o.y < -half.y) o.y += size.y; else if (o.y >= half.y) o.y -= size.y;
              double d2 = o.x * o.x + o.y * o.y;
              all.push_back({c, o, d2});
              nearest2 = std::min(nearest2, d2);
            }
            // Only sites within nearest + diagonal of the centre can be nearest somewhere in
            // the pixel; the others cannot own a piece nor cut one.
            const double reach = std::sqrt(nearest2) + diagonal * (1.0 + 1e-9);
            const double reach2 = reach * reach;
            near.clear();
            for (const Entry& e : all)
              if (e.distance <= reach2) near.push_back(e);
            if (reach >= 0.5 * std::min(size.x, size.y)) {
              // Cells as wide as the domain: the sites' other periodic images count too.
              for (const Entry& e : all)
                for (int ky = -1; ky <= 1; ++ky)
                  for (int kx = -1; kx <= 1; ++kx) {
                    if (kx == 0 && ky == 0) continue;
                    Point o{e.offset.x + kx * size.x, e.offset.y + ky * size.y};
                    double d2 = o.x * o.x + o.y * o.y;
                    if (d2 <= reach2) near.push_back({e.site, o, d2});
                  }
            }
            for (std::size_t a = 0; a < near.size(); ++a) {
              const Entry& owner = near[a];
              if (owner.site < scene.wanted_begin || owner.site >= scene.wanted_end) continue;
              // The pixel square relative to this image of the site.
              const Point c = -owner.offset;
              polygon.reset_rectangle({c.x - 0.5 * job.hx, c.y - 0.5 * job.hy}, {c.x + 0.5 * job.hx, c.y + 0.5 * job.hy});
              for (std::size_t b = 0; b < near.size() && !polygon.empty(); ++b) {
                if (b == a) continue;
                Point d = near[b].offset - owner.offset;
                if (d.x == 0.0 && d.y == 0.0) continue;
                polygon.clip_by_bisector(d, near[b].site);
              }
              if (polygon.empty()) continue;
              const PolygonMoments m = polygon.moments();
              Piece piece{owner.site, m.area(), m.first_moment().x, m.first_moment().y, m.second_moment()};
              if (piece.area > 0.0) pieces.push_back(piece);
            }
          }
      }
    });
    for (const auto& list : chunk_pieces)
      for (const Piece& p : list) {
        Piece& t = totals[p.site];
        t.area += p.area;
        t.mx += p.mx;
        t.my += p.my;
        t.m2 += p.m2;
      }
  }

  void finish(Job& job, const std::uint32_t* pixels, std::uint32_t atlas_width, SceneCells& out) {
    const Scene& scene = *job.scene;
    const std::size_t n = job.sites.size();
    std::vector<std::uint8_t> pixelless(n, 0);
    for (std::size_t i = 0; i < n; ++i) pixelless[i] = !job.coincident[i] && sums_of(job, i).owned == 0;

    std::vector<Piece> pieces(n, Piece{0, 0, 0, 0, 0});
    if (options.coverage == Coverage::area) {
      std::vector<std::vector<std::uint32_t>> adjacency(n);
      split_boundary(job, pixels, atlas_width, pixelless, adjacency, pieces);
    }

    out.cells.assign(scene.wanted_count(), Cell{});
    out.coincident_count = 0;
    out.fallback_count = 0;
    const double pixel_area = job.hx * job.hy;
    for (std::size_t i = scene.wanted_begin; i < scene.wanted_end; ++i) {
      Cell& cell = out.cells[i - scene.wanted_begin];
      const Point site = job.sites[i];
      if (job.coincident[i]) {
        cell.centroid = site;
        cell.status = CellStatus::coincident;
        ++out.coincident_count;
        continue;
      }
      const gpu::SiteSums& s = sums_of(job, i);
      int px = std::clamp(static_cast<int>(std::floor(site.x / job.hx)), 0, job.rx - 1);
      int py = std::clamp(static_cast<int>(std::floor(site.y / job.hy)), 0, job.ry - 1);
      const double ax = (px + 0.5) * job.hx - site.x, ay = (py + 0.5) * job.hy - site.y;
      const double count = s.count;
      const double sx = static_cast<double>(s.sum_x), sy = static_cast<double>(s.sum_y);
      const double sxx = static_cast<double>(s.sum_xx), syy = static_cast<double>(s.sum_yy);
      double area = count * pixel_area + pieces[i].area;
      double mx = pixel_area * (job.hx * sx + count * ax) + pieces[i].mx;
      double my = pixel_area * (job.hy * sy + count * ay) + pieces[i].my;
      double m2 = pixel_area * (job.hx * job.hx * sxx + 2.0 * ax * job.hx * sx + count * ax * ax + job.hy * job.hy * syy +
                                2.0 * ay * job.hy * sy + count * ay * ay + count * (job.hx * job.hx + job.hy * job.hy) / 12.0) +
                  pieces[i].m2;
      if (pixelless[i] || !(area > 0.0)) {
        const PolygonMoments m = polygon_moments(exact_cell_polygon(scene, i));
        area = m.area();
        mx = m.first_moment().x;
        my = m.first_moment().y;
        m2 = m.second_moment();
        cell.status = CellStatus::exact_fallback;
        ++out.fallback_count;
      }
      cell.area = area;
      cell.mass = area;
      cell.second_moment = m2;
      cell.centroid = area > 0.0 ? wrap_point(site + Point{mx / area, my / area}, scene.domain) : site;
    }

    Slot& slot = slots[job.index];
    slot.sites = job.sites;
    slot.domain = scene.domain.size;
    slot.rx = job.rx;
    slot.farthest = job.need;

    if (options.keep_id_images) {
      IdImage& image = id_images[job.index];
      image.width = job.rx;
      image.height = job.ry;
      image.ids.resize(static_cast<std::size_t>(job.rx) * job.ry);
      for (int j = 0; j < job.ry; ++j)
        for (int i = 0; i < job.rx; ++i) {
          std::uint32_t raw = pixels[static_cast<std::size_t>(job.origin_y + j) * atlas_width + job.origin_x + i];
          image.ids[static_cast<std::size_t>(j) * job.rx + i] =
              raw == 0 ? -1 : static_cast<std::int32_t>(raw - 1 - job.site_begin);
        }
    }
  }

  // ---- the batch -------------------------------------------------------------------------

  void compute(std::span<const Scene> batch, std::span<SceneCells> out) {
    if (batch.size() != out.size()) throw Error("raster engine: scenes and results differ in number");
    ++stats.computes;
    if (slots.size() != batch.size()) slots.assign(batch.size(), Slot{});
    if (options.keep_id_images) id_images.assign(batch.size(), IdImage{});
    std::vector<Job> jobs;
    jobs.reserve(batch.size());
    for (std::size_t k = 0; k < batch.size(); ++k) {
      jobs.push_back(prepare(batch[k], k));
      if (batch[k].sites.empty()) {
        jobs.back().done = true;
        out[k] = SceneCells{};
      }
    }

    const auto& limits = gpu->properties().limits;
    const std::uint32_t max_side = limits.maxImageDimension2D;
    const std::size_t max_scenes = std::min<std::size_t>(limits.maxComputeWorkGroupCount[2], 65535);
    const double pixel_budget = std::min(static_cast<double>(gpu->memory_budget()) / 16.0, 256.0 * 1024 * 1024);

    for (;;) {
      std::vector<Job*> pending;
      for (Job& job : jobs)
        if (!job.done) pending.push_back(&job);
      if (pending.empty()) break;

      // Shelf packing into an atlas about as wide as it is tall.
      double total = 0.0;
      for (Job* job : pending) total += static_cast<double>(job->rx) * job->ry;
      std::uint32_t width = static_cast<std::uint32_t>(std::ceil(std::sqrt(std::min(total, pixel_budget))));
      for (Job* job : pending) width = std::max(width, static_cast<std::uint32_t>(job->rx));
      width = std::min(width, max_side);
      std::vector<Job*> group;
      std::uint32_t x = 0, y = 0, shelf = 0;
      double used = 0.0;
      for (Job* job : pending) {
        auto w = static_cast<std::uint32_t>(job->rx), h = static_cast<std::uint32_t>(job->ry);
        if (x + w > width) {
          x = 0;
          y += shelf;
          shelf = 0;
        }
        if (!group.empty() && (y + h > max_side || used + double(w) * h > pixel_budget || group.size() >= max_scenes)) break;
        job->origin_x = static_cast<int>(x);
        job->origin_y = static_cast<int>(y);
        x += w;
        shelf = std::max(shelf, h);
        used += double(w) * h;
        group.push_back(job);
      }
      std::uint32_t height = y + shelf;
      run_pass(group, width, height);

      auto host_start = Clock::now();
      const auto* pixels = static_cast<const std::uint32_t*>(ids.mapped);
      const auto* uncovered = static_cast<const std::uint32_t*>(counters.mapped);
      std::vector<std::uint8_t> accepted(group.size(), 0);
      for (std::size_t k = 0; k < group.size(); ++k) {
        Job& job = *group[k];
        accepted[k] = certify(job, uncovered[k]);
        if (!accepted[k]) {
          ++stats.redone_scenes;
          ++job.redos;
          if (job.redos > kMaxRedos + 1)
            throw Error("raster engine: pixels stay uncovered even with cones covering the whole domain (device problem?)");
          if (job.redos >= kMaxRedos) std::fill(job.radius.begin(), job.radius.end(), job.radius_cap);
        }
      }
      // Scenes one per thread; a lone scene splits its rows across threads instead.
      parallel_for(group.size(), 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k)
          if (accepted[k]) finish(*group[k], pixels, width, out[group[k]->index]);
      });
      for (std::size_t k = 0; k < group.size(); ++k) {
        if (!accepted[k]) continue;
        group[k]->done = true;
        stats.boundary_pixels += group[k]->boundary_pixels;
        stats.fallback_cells += out[group[k]->index].fallback_count;
      }
      stats.host_seconds += seconds_since(host_start);
    }
  }
};

RasterEngine::RasterEngine(const RasterOptions& options) : impl_(std::make_unique<Impl>(options)) {}
RasterEngine::~RasterEngine() = default;

void RasterEngine::compute(std::span<const Scene> scenes, std::span<SceneCells> out) {
  for (const Scene& scene : scenes)
    if (scene.density || !scene.periodic())
      throw Error("raster engine: densities and bounded domains are not supported yet (use --engine exact)");
  impl_->compute(scenes, out);
}
const RasterOptions& RasterEngine::options() const { return impl_->options; }
const RasterStats& RasterEngine::stats() const { return impl_->stats; }
std::string RasterEngine::device_name() const { return impl_->gpu->info().name; }
int RasterEngine::resolution_for(const Scene& scene) const { return impl_->resolution_for(scene); }

const IdImage& RasterEngine::id_image(std::size_t scene) const {
  if (scene >= impl_->id_images.size()) throw Error("raster engine: no ID image kept for that scene (keep_id_images)");
  return impl_->id_images[scene];
}

}  // namespace bluetile
