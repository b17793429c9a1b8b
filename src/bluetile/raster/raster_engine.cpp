// The raster centroid engine: the batch driver.
//
// Method. Hoff, Keyser, Lin, Manocha, Culver: "Fast computation of generalized Voronoi
// diagrams using graphics hardware" (SIGGRAPH 1999), as the paper (Hiller, Deussen, Keller
// 2001, section 2) uses it for Lloyd relaxation: every site draws a distance cone into a depth
// buffer with the test LESS, and an ID image then holds, at each sample, the nearest site.
// The parts, one file each:
//  - raster_scene.cpp: a scene's sites wrapped, coincident sites set aside (the lower index
//    owns the cell, as in ExactEngine), sites too close for float depths flagged, cone radii
//    (remembered per site position from the last call), fixed-point scales.
//  - raster_device.cpp: one pass over a batch packed into an atlas, one submission: cones are
//    bounded squares whose fragment shader writes the exact distance as depth (replicas for
//    sites near a border; the tessellated fan as an option); samples sit at pixel corners.
//    classify.comp sums every sample (point coverage: a sample is a pixel) and, in area
//    coverage, every whole pixel (four corners of one cell and no other site inside: convex
//    cells make it wholly that cell's) in exact integer runs; split_f64.comp (or split_f32.comp)
//    splits every other pixel exactly among the sites within reach, found in the scene's site
//    grid, into fixed-point piece sums. 64-bit integer atomics make every sum independent of
//    order and thread count.
//  - raster_coverage.cpp: a bounded cone can miss samples of its own cell; every pass is
//    checked and redone with larger radii when it fails, never accepted.
//  - raster_reference.cpp: the same sums on the host, without Vulkan: the tests' reference for
//    the device, and the split of the few pixels the device leaves to the host.
//  - raster_cells.cpp: sums to cells. A cell with no area (point coverage: no sample) comes from
//    the exact engine (exact_fallback).
// In area coverage the results are those of the exact Voronoi cells up to rounding, at any
// resolution: resolution only sets the speed. A bounded domain draws no replicas and wraps
// nothing; a varying density weighs whole pixels by their moments under the texels they cover
// (a table per map and resolution) and pieces by density_moments, into fixed-point sums (Secord
// 2002's weighted centroids, exact to rounding). Both run on the host per-pixel path only.
#include "bluetile/raster/raster_engine.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>

#include "bluetile/core/error.h"
#include "bluetile/core/field_checks.h"
#include "bluetile/core/text.h"
#include "bluetile/core/parallel.h"
#include "bluetile/raster/engine_choice.h"
#include "bluetile/raster/raster_cells.h"
#include "bluetile/raster/raster_coverage.h"
#include "bluetile/raster/raster_device.h"
#include "bluetile/raster/raster_reference.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/voronoi/scene.h"

namespace bluetile {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Coverage-check failures before every cone of the scene covers the whole domain.
constexpr int kMaxRedos = 6;

// The nearest site to `p` (not coincident), by the grid's buckets in rings.
double nearest_site_distance(const RasterScene& scene, Point p) {
  const SiteGrid& grid = scene.grid();
  const Domain& domain = scene.scene->domain;
  double best = HUGE_VAL;
  const Point cell = grid.cell_size();
  for (double reach = std::max(cell.x, cell.y);; reach *= 2.0) {
    if (reach > 8.0 * std::max(cell.x, cell.y)) {
      // Far from every site (sites on a line): the rings would visit O(N) sites; the tree finds
      // the few within a hair of the nearest, and the same distance is their least.
      const RasterSearch& search = raster_search(scene);
      const SiteTree::Disk near{p, std::sqrt(search.tree.nearest_squared(p)) * (1.0 + 1e-9) + 1e-9 * std::max(domain.size.x, domain.size.y)};
      std::vector<SiteTree::Copy> copies;
      search.tree.copies_in_disks(std::span<const SiteTree::Disk>(&near, 1), copies);
      for (const SiteTree::Copy& c : copies)
        if (!scene.coincident[c.index]) best = std::min(best, raster_distance(scene, p, scene.sites[c.index]));
      return best;
    }
    grid.for_each_near(p, reach, [&](std::uint32_t t) {
      if (!scene.coincident[t]) best = std::min(best, raster_distance(scene, p, scene.sites[t]));
    });
    if (best <= reach || reach > 2.0 * (domain.size.x + domain.size.y)) return best;
  }
}

// How many times the scene's cones cover its domain on average: each cone's disk, at most the
// domain, over the domain's area (RasterOptions::max_cone_overlap).
double cone_overlap(const RasterScene& job) {
  const Point size = job.scene->domain.size;
  const double area = size.x * size.y, pi = 3.141592653589793;
  double sum = 0.0;
  for (std::size_t i = 0; i < job.size(); ++i)
    if (!job.coincident[i]) sum += std::min(pi * job.radius[i] * job.radius[i], area);
  return sum / area;
}

}  // namespace

int default_resolution(std::size_t sites, Coverage coverage) {
  double n = static_cast<double>(std::max<std::size_t>(sites, 1));
  // area: ~4 pixels per cell, tied fastest with 1 (boundary pixels grow as the square root of
  // the pixels per cell, their candidates as its inverse: 1, 2, 4, 8, 16 pixels per cell cost 4.9,
  // 5.7, 5.0, 6.3, 7.1 ms of CPU per iteration at N = 1000, docs/BENCHMARKS.md; at 1 some pixels
  // are left to the host fallback); point: ~1000 pixels per cell (error ~ 0.05
  // pixel).
  double side = coverage == Coverage::area ? 2.0 * std::sqrt(n) : 32.0 * std::sqrt(n);
  int lo = coverage == Coverage::area ? 16 : 64;
  int rounded = static_cast<int>(std::ceil(side / 16.0)) * 16;
  return std::clamp(rounded, lo, 8192);
}

bool runs_pixel_work_on_device(PixelWork work, Coverage coverage, bool cpu_device) {
  if (work != PixelWork::automatic) return work == PixelWork::device;
  // On lavapipe the device path is within 1.2x of the host path for point coverage (classify.comp
  // against the host's classification and ID readback) and 1.6-1.7x for area coverage (the split):
  // docs/BENCHMARKS.md, "Point coverage and `auto`" and "The lane kernel, texels for the set-up".
  return !cpu_device || coverage == Coverage::point;
}

struct RasterEngine::Impl {
  RasterOptions options;
  RasterDevice device;
  RasterStats stats;
  RadiusMemory memory;
  std::vector<IdImage> id_images;
  std::vector<PassData> pass_data;

  bool on_device = true;
  // Measures the scenes whose cones would overlap past max_cone_overlap.
  ExactEngine exact;

  explicit Impl(const RasterOptions& o)
      : options(o),
        device(RasterDeviceSettings{o.device, o.cone == ConeShape::fan, o.cone_draw, o.force_float32, o.split_kernel,
                                    o.split_guard_test}) {
    on_device = runs_pixel_work_on_device(o.pixel_work, o.coverage, device.is_cpu());
    // Asked for by name, the device path is the exact one or none: never moved to the host, and
    // never the float32 split unless that is asked for too.
    if (o.pixel_work == PixelWork::device) {
      const std::string refusal = device_pixel_work_refusal(device.device_name(), device.float64_split(), o.force_float32);
      if (!refusal.empty()) throw Error(refusal);
    }
  }

  RasterSettings settings() const {
    RasterSettings s;
    s.area = options.coverage == Coverage::area;
    s.resolution = options.resolution;
    s.radius_factor = options.radius_factor;
    s.max_side = device.max_side();
    return s;
  }

  int resolution_for(const Scene& scene) const {
    RasterScene job = prepare_raster_scene(scene, 0, settings());
    return job.rx;
  }

  // Shelf packing of pending scenes into one atlas about as wide as it is tall, within the
  // device's limits. Returns the group; sets each scene's origin.
  std::vector<RasterScene*> pack(std::vector<RasterScene*>& pending, std::uint32_t& width, std::uint32_t& height) const {
    const std::uint32_t max_side = device.max_side();
    const double pixel_budget = static_cast<double>(device.max_pass_pixels());
    const std::size_t max_scenes = device.max_scenes_per_pass();
    const std::size_t max_sites = device.max_pass_sites();
    double total = 0.0;
    for (RasterScene* job : pending) total += static_cast<double>(job->rx) * job->ry;
    width = static_cast<std::uint32_t>(std::ceil(std::sqrt(std::min(total, pixel_budget))));
    for (RasterScene* job : pending) width = std::max(width, static_cast<std::uint32_t>(job->rx));
    width = std::min(width, max_side);
    std::vector<RasterScene*> group;
    std::uint32_t x = 0, y = 0, shelf = 0;
    double used = 0.0;
    std::size_t sites = 0;
    for (RasterScene* job : pending) {
      const auto w = static_cast<std::uint32_t>(job->rx), h = static_cast<std::uint32_t>(job->ry);
      if (x + w > width) {
        x = 0;
        y += shelf;
        shelf = 0;
      }
      if (!group.empty() && (y + h > max_side || used + double(w) * h > pixel_budget || group.size() >= max_scenes ||
                             sites + job->size() > max_sites))
        break;
      if (job->size() > max_sites)
        throw Error("raster engine: a scene of " + std::to_string(job->size()) +
                    " sites exceeds what the device's largest storage buffer holds; use the exact engine");
      if (double(w) * h > pixel_budget)
        throw Error("raster engine: a scene of " + std::to_string(w) + " x " + std::to_string(h) +
                    " pixels exceeds the device's memory budget of " + count_text(pixel_budget) +
                    " pixels a pass (a side of " + std::to_string(static_cast<long>(std::sqrt(pixel_budget))) +
                    "); use a smaller resolution");
      job->origin_x = static_cast<int>(x);
      job->origin_y = static_cast<int>(y);
      x += w;
      shelf = std::max(shelf, h);
      used += double(w) * h;
      sites += job->size();
      group.push_back(job);
    }
    height = y + shelf;
    return group;
  }

  // Pixel work asked for on the device is not moved to the host: scenes that need the host
  // (a varying density, a bounded domain) are refused before any work.
  static void refuse_host_only_scenes(std::span<const Scene* const> batch) {
    for (const Scene* scene : batch) {
      const char* what = nullptr;
      if (!scene->periodic()) {
        what = "a bounded domain";
      } else if (scene->density) {
        const std::vector<float>& t = scene->density->texels;
        if (std::adjacent_find(t.begin(), t.end(), std::not_equal_to<>()) != t.end()) what = "a varying density";
      }
      if (what)
        throw Error(std::string("raster engine: pixel work 'device' cannot take a scene with ") + what +
                    " (the shaders neither weigh pixels nor know a border); use pixel work 'host' or 'auto'");
    }
  }

  void compute(std::span<const Scene* const> batch, std::span<SceneCells> out) {
    if (options.pixel_work == PixelWork::device) refuse_host_only_scenes(batch);
    auto host_start = Clock::now();
    ++stats.computes;
    if (options.keep_id_images) id_images.assign(batch.size(), IdImage{});
    if (options.keep_pass_data) pass_data.assign(batch.size(), PassData{});
    memory.start_call();
    const RasterSettings s = settings();
    std::vector<RasterScene> jobs(batch.size());
    std::vector<std::size_t> remembered(batch.size(), 0);
    parallel_for(batch.size(), 16, [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        jobs[k] = prepare_raster_scene(*batch[k], k, s);
        if (options.adapt_radius) remembered[k] = memory.recall(jobs[k]);
      }
    });
    // Densities and bounded domains are weighed and clipped by the host's per-pixel work only
    // (the shaders know neither): a batch holding one runs wholly on the host.
    bool pixel_work_here = on_device;
    for (std::size_t k = 0; k < batch.size(); ++k) {
      if (jobs[k].density) jobs[k].pixel_density = pixel_density_for(*batch[k], jobs[k].rx, jobs[k].ry);
      if (jobs[k].density || !jobs[k].periodic) pixel_work_here = false;
    }
    // Sliver cells (sites on lines) make the pixel method quadratic; the cones' overlap tells,
    // from the radii remembered or grown by failed passes. Those scenes go to the exact engine.
    const bool may_hand_over = options.max_cone_overlap > 0.0 && !options.keep_id_images && !options.keep_pass_data;
    std::vector<std::uint8_t> to_exact(batch.size(), 0);
    auto hand_over_if_slivers = [&](RasterScene& job) {
      if (!may_hand_over || cone_overlap(job) <= options.max_cone_overlap) return;
      to_exact[job.index] = 1;
      job.done = true;
    };
    for (std::size_t k = 0; k < batch.size(); ++k) {
      stats.remembered_radii += remembered[k];
      if (jobs[k].size() == 0) {
        jobs[k].done = true;
        out[k] = SceneCells{};
      } else {
        hand_over_if_slivers(jobs[k]);
      }
    }
    stats.host_seconds += seconds_since(host_start);
    stats.prepare_seconds += seconds_since(host_start);

    for (;;) {
      std::vector<RasterScene*> pending;
      for (RasterScene& job : jobs)
        if (!job.done) pending.push_back(&job);
      if (pending.empty()) break;
      host_start = Clock::now();
      std::uint32_t width = 0, height = 0;
      std::vector<RasterScene*> group = pack(pending, width, height);
      parallel_for(group.size(), 16, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
          flag_close_sites(*group[k]);
          // Tessellated cones make the ID image only close to the diagram (depth between the
          // fan's edges is too low): area coverage then splits every pixel.
          if (options.cone == ConeShape::fan) std::fill(group[k]->split.begin(), group[k]->split.end(), 1);
          group[k]->update_scales();
        }
      });
      for (RasterScene* job : group)
        for (std::size_t i = 0; i < job->size(); ++i)
          if (!job->coincident[i]) stats.drawn_radius_sum += job->radius[i];
      stats.host_seconds += seconds_since(host_start);
      stats.prepare_seconds += seconds_since(host_start);

      const bool read_ids = options.keep_id_images || options.keep_pass_data;
      device.run(group, width, height, read_ids, pixel_work_here);
      ++stats.submits;
      stats.scene_passes += group.size();
      stats.upload_seconds += device.timing().upload;
      stats.device_seconds += device.timing().device;
      stats.cone_seconds += device.timing().cones;
      stats.classify_seconds += device.timing().classify;
      stats.split_seconds += device.timing().split;
      stats.readback_seconds += device.timing().readback;
      stats.cones_drawn += device.timing().cones_drawn;
      stats.point_cone_submits += device.timing().point_cones ? 1 : 0;

      host_start = Clock::now();
      // Pixels left to the host, per scene of the group (in increasing order).
      std::vector<std::vector<std::uint32_t>> host_pixels(group.size());
      for (const gpu::uvec2& e : device.overflow()) host_pixels[e.x].push_back(e.y);
      std::vector<std::size_t> left(group.size(), 0);  // pixels the per-pixel pass left to the host
      std::vector<std::uint8_t> accepted(group.size(), 0);
      std::vector<std::uint32_t> uncovered(group.size(), 0);
      std::vector<std::uint64_t> boundary(group.size(), 0);
      std::vector<std::vector<gpu::SiteSums>> host_sums(group.size());
      std::vector<std::vector<WeightedSums>> weighted_sums(group.size());
      // Many scenes: one per thread; a few: each threaded over its rows.
      const bool across_scenes = group.size() >= 2 * thread_count();
      // Per scene stage times (the profile's): ID image readback, the per-pixel work, cells.
      struct FinishTiming {
        double readback = 0.0, cells = 0.0;
        ReferenceTiming pixels;
      };
      std::vector<FinishTiming> finish_timing(group.size());
      auto finish = [&](std::size_t k) {
        RasterScene& job = *group[k];
        FinishTiming& timing = finish_timing[k];
        std::span<const gpu::SiteSums> sums;
        std::vector<std::uint32_t> ids;
        if (pixel_work_here) {
          sums = device.sums(job);
          uncovered[k] = device.uncovered(k);
          // split_lane_f64.comp keeps fewer candidates than the host reference: the pixels it
          // left are split here into the same integer sums as on the host path (the same bits
          // whatever the kernel); only those the reference leaves too stay for host_split.
          left[k] = host_pixels[k].size();
          if (device.lane_split() && !host_pixels[k].empty() && uncovered[k] == 0) {
            ids = device.ids(job);
            host_sums[k].assign(sums.begin(), sums.end());
            std::erase_if(host_pixels[k], [&](std::uint32_t pixel) { return reference_split(job, ids, pixel, host_sums[k]); });
            sums = host_sums[k];
          }
        } else {
          const auto readback_start = Clock::now();
          ids = device.ids(job);
          timing.readback = seconds_since(readback_start);
          host_sums[k].assign(job.size(), gpu::SiteSums{});
          if (job.density) weighted_sums[k].assign(job.size(), WeightedSums{});
          uncovered[k] = reference_pass(job, ids, host_sums[k], true, !across_scenes, host_pixels[k], boundary[k], weighted_sums[k],
                                        &timing.pixels);
          sums = host_sums[k];
          left[k] = host_pixels[k].size();
        }
        const auto cells_start = Clock::now();
        accepted[k] = check_coverage(job, sums, uncovered[k]);
        if (!accepted[k]) {
          timing.cells = seconds_since(cells_start);
          return;
        }
        std::vector<PieceSums> pieces;
        if (!host_pixels[k].empty()) {
          pieces.assign(job.size(), PieceSums{});
          for (std::uint32_t pixel : host_pixels[k]) {
            const int i = static_cast<int>(pixel % static_cast<std::uint32_t>(job.rx));
            const int j = static_cast<int>(pixel / static_cast<std::uint32_t>(job.rx));
            const Point centre{(i + 0.5) * job.hx, (j + 0.5) * job.hy};
            host_split(job, nearest_site_distance(job, centre), pixel, pieces);
          }
        }
        SceneCells& cells = out[job.index];
        assemble_cells(job, sums, pieces, cells, weighted_sums[k]);
        finish_scene(job, sums, cells, host_pixels[k], std::move(ids));
        timing.cells = seconds_since(cells_start);
      };
      if (across_scenes) {
        parallel_for(group.size(), 1, [&](std::size_t begin, std::size_t end) {
          for (std::size_t k = begin; k < end; ++k) finish(k);
        });
      } else {
        for (std::size_t k = 0; k < group.size(); ++k) finish(k);
      }
      add_finish_timing(finish_timing, across_scenes ? seconds_since(host_start) : 0.0);
      if (pixel_work_here) {
        stats.boundary_pixels += device.boundary_pixels();
        stats.guard_pixels += device.guard_pixels();
      } else {
        for (std::uint64_t b : boundary) stats.boundary_pixels += b;
      }
      for (std::size_t k = 0; k < group.size(); ++k) {
        RasterScene& job = *group[k];
        stats.split_sites_examined += job.search_cache_->sites_examined.exchange(0);
        if (accepted[k]) {
          job.done = true;
          stats.host_split_pixels += left[k];
          stats.fallback_cells += out[job.index].fallback_count;
          continue;
        }
        ++stats.redone_scenes;
        stats.uncovered_pixels += uncovered[k];
        ++job.redos;
        if (job.redos > kMaxRedos + 1)
          throw Error("raster engine: samples stay uncovered even with cones covering the whole domain (device problem?)");
        if (job.redos >= kMaxRedos) std::fill(job.radius.begin(), job.radius.end(), job.radius_cap);
        hand_over_if_slivers(job);
      }
      stats.host_seconds += seconds_since(host_start);
    }
    measure_exactly(batch, jobs, to_exact, out);
  }

  // The scenes handed over to the exact engine, in one batch; their cell radii are remembered
  // like a pass's, so the next call on the moved sites decides without a pass.
  void measure_exactly(std::span<const Scene* const> batch, std::vector<RasterScene>& jobs, const std::vector<std::uint8_t>& to_exact,
                       std::span<SceneCells> out) {
    std::vector<std::size_t> which;
    for (std::size_t k = 0; k < batch.size(); ++k)
      if (to_exact[k]) which.push_back(k);
    if (which.empty()) return;
    const auto start = Clock::now();
    std::vector<Scene> scenes;
    scenes.reserve(which.size());
    for (std::size_t k : which) scenes.push_back(*batch[k]);
    std::vector<SceneCells> cells(which.size());
    exact.compute(scenes, cells);
    for (std::size_t w = 0; w < which.size(); ++w) {
      RasterScene& job = jobs[which[w]];
      out[job.index] = std::move(cells[w]);
      ++stats.exact_scenes;
      if (!options.adapt_radius) continue;
      const Scene& scene = *job.scene;
      std::vector<Point> next = job.sites;
      std::vector<double> radius = job.radius;  // sites not wanted: the cones they had
      for (std::size_t i = scene.wanted_begin; i < scene.wanted_end; ++i) {
        const Cell& cell = out[job.index].cells[i - scene.wanted_begin];
        next[i] = cell.centroid;
        radius[i] = cell.radius;
      }
      remember(job, next, radius);
    }
    stats.exact_seconds += seconds_since(start);
    stats.host_seconds += seconds_since(start);
  }

  // Adds the finish stages to the stats; `parallel_wall` > 0: the scenes ran in parallel for
  // that long, and their summed stage times are scaled to it.
  template <class Timing>
  void add_finish_timing(const std::vector<Timing>& timing, double parallel_wall) {
    double readback = 0.0, classify = 0.0, split = 0.0, reduce = 0.0, cells = 0.0;
    for (const Timing& t : timing) {
      readback += t.readback;
      classify += t.pixels.classify;
      split += t.pixels.split;
      reduce += t.pixels.reduce;
      cells += t.cells;
    }
    const double total = readback + classify + split + reduce + cells;
    const double scale = parallel_wall > 0.0 && total > 0.0 ? parallel_wall / total : 1.0;
    stats.host_readback_seconds += scale * readback;
    stats.host_classify_seconds += scale * classify;
    stats.host_split_seconds += scale * split;
    stats.host_reduce_seconds += scale * reduce;
    stats.cells_seconds += scale * cells;
  }

  // What an accepted pass leaves behind: the radius memory, ID images, pass data.
  void finish_scene(const RasterScene& job, std::span<const gpu::SiteSums> sums, const SceneCells& cells,
                    const std::vector<std::uint32_t>& host_pixels, std::vector<std::uint32_t> ids) {
    if (options.adapt_radius) {
      std::vector<Point> next = job.sites;
      const Scene& scene = *job.scene;
      for (std::size_t i = scene.wanted_begin; i < scene.wanted_end; ++i) next[i] = cells.cells[i - scene.wanted_begin].centroid;
      remember(job, next, job.need);
    }
    if (options.keep_id_images || options.keep_pass_data) {
      if (ids.empty()) ids = device.ids(job);
      if (options.keep_id_images) {
        IdImage& image = id_images[job.index];
        image.width = job.rx;
        image.height = job.ry;
        image.ids.resize(ids.size());
        for (std::size_t p = 0; p < ids.size(); ++p) image.ids[p] = static_cast<std::int32_t>(ids[p]) - 1;
      }
      if (options.keep_pass_data) {
        PassData& data = pass_data[job.index];
        data.scene = job;
        data.ids = std::move(ids);
        data.sums.assign(sums.begin(), sums.end());
        data.host_split = host_pixels;
      }
    }
  }

  // The moments of every pixel under a scene's density, kept for the next calls (a relaxation
  // measures the same map at the same resolution every iteration). Holding the density keeps its
  // address from naming another grid; the hash of its texels catches a grid changed in place.
  struct PixelDensityEntry {
    std::shared_ptr<const DensityGrid> density;
    std::uint64_t texel_hash = 0;
    int rx = 0, ry = 0;
    Point size;
    Boundary boundary = Boundary::periodic;
    std::shared_ptr<const std::vector<WeightedMoments>> table;
  };
  std::vector<PixelDensityEntry> pixel_density_cache;
  // Tables kept: a batch of scenes rarely holds more than a few maps.
  static constexpr std::size_t kPixelDensityTables = 4;

  static std::uint64_t hash_texels(const DensityGrid& density) {
    std::uint64_t h = 0xcbf29ce484222325ull ^ (static_cast<std::uint64_t>(density.width) << 32 | static_cast<std::uint32_t>(density.height));
    for (float t : density.texels) h = (h ^ std::bit_cast<std::uint32_t>(t)) * 0x100000001b3ull;  // FNV-1a, per texel
    return h;
  }

  std::shared_ptr<const std::vector<WeightedMoments>> pixel_density_for(const Scene& scene, int rx, int ry) {
    const std::uint64_t texel_hash = hash_texels(*scene.density);
    for (const PixelDensityEntry& e : pixel_density_cache)
      if (e.density == scene.density && e.texel_hash == texel_hash && e.rx == rx && e.ry == ry && e.size == scene.domain.size &&
          e.boundary == scene.boundary)
        return e.table;
    if (pixel_density_cache.size() >= kPixelDensityTables) pixel_density_cache.erase(pixel_density_cache.begin());
    auto table = std::make_shared<const std::vector<WeightedMoments>>(pixel_density_moments(scene, rx, ry));
    pixel_density_cache.push_back({scene.density, texel_hash, rx, ry, scene.domain.size, scene.boundary, table});
    return table;
  }

  void remember(const RasterScene& job, const std::vector<Point>& next, const std::vector<double>& radius) {
    // Guarded: scenes of a group finish in parallel.
    std::lock_guard<std::mutex> lock(memory_mutex);
    memory.remember(job, next, radius);
  }
  std::mutex memory_mutex;
};

namespace {

// The options a caller of the library may set wrong (the front ends check theirs through
// EngineChoice): a resolution of -5 or a NaN radius factor ran as if given sensibly.
const RasterOptions& checked(const RasterOptions& options) {
  if (options.resolution != 0 && (options.resolution < kMinResolution || options.resolution > kMaxResolution))
    throw Error("resolution: expected 0 (from N) or " + std::to_string(kMinResolution) + " to " +
                std::to_string(kMaxResolution) + ", got " + std::to_string(options.resolution));
  check_real_field("radius_factor", options.radius_factor, 1e-3, 1e3);
  check_real_field("max_cone_overlap", options.max_cone_overlap, 0.0, std::numeric_limits<double>::infinity());
  return options;
}

}  // namespace

RasterEngine::RasterEngine(const RasterOptions& options) : impl_(std::make_unique<Impl>(checked(options))) {}
RasterEngine::~RasterEngine() = default;

void RasterEngine::compute(std::span<const Scene> scenes, std::span<SceneCells> out) {
  check_batch(name(), scenes.size(), out.size());
  // The contract, checked once per scene; wrapped copies only of scenes that need them.
  std::vector<Scene> wrapped(scenes.size());
  std::vector<const Scene*> checked(scenes.size());
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    checked[i] = &validated_scene(scenes[i], wrapped[i]);
    if (scenes[i].density && impl_->options.coverage == Coverage::point && !is_uniform(*scenes[i].density))
      throw Error("raster engine: a density weights cells only in area coverage");
  }
  impl_->compute(checked, out);
}
const RasterOptions& RasterEngine::options() const { return impl_->options; }
const RasterStats& RasterEngine::stats() const { return impl_->stats; }
std::string RasterEngine::device_name() const { return impl_->device.device_name(); }
int RasterEngine::resolution_for(const Scene& scene) const { return impl_->resolution_for(scene); }
bool RasterEngine::float64_split() const { return impl_->device.float64_split(); }
bool RasterEngine::pixel_work_on_device() const { return impl_->on_device; }
bool RasterEngine::cpu_device() const { return impl_->device.is_cpu(); }

const IdImage& RasterEngine::id_image(std::size_t scene) const {
  if (scene >= impl_->id_images.size()) throw Error("raster engine: no ID image kept for that scene (keep_id_images)");
  return impl_->id_images[scene];
}

const RasterEngine::PassData& RasterEngine::pass_data(std::size_t scene) const {
  if (scene >= impl_->pass_data.size()) throw Error("raster engine: no pass data kept for that scene (keep_pass_data)");
  return impl_->pass_data[scene];
}

}  // namespace bluetile
