// The raster centroid engine (Vulkan): Hoff et al. 1999's distance cones, bounded, in an ID
// image sampled at pixel corners, reduced by compute shaders to exact integer sums; in `area`
// coverage the pixels on cell boundaries are split exactly on the device, in double precision
// where it has shaderFloat64. The method, its guarantees and measured figures: raster_engine.cpp
// and docs/RASTER.md.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bluetile/core/output_file.h"
#include "bluetile/gpu/raster_layout.h"
#include "bluetile/voronoi/engine.h"
#include "bluetile/raster/raster_scene.h"

namespace bluetile {

enum class Coverage {
  point,  // a pixel belongs wholly to the site whose ID its centre shows (the classic method)
  area,   // boundary pixels are split exactly among the sites whose cells cross them
};

enum class ConeShape {
  quad,  // a square per cone; the fragment shader writes the exact distance as depth
  fan,   // the classic tessellated cone (triangle fan), depth interpolated: biased
};

// Where the per-pixel work (classification, sums, boundary split) runs; every choice gives the
// same bits. Scenes with a varying density or a bounded domain need the host (the shaders
// neither weigh pixels nor know a border).
enum class PixelWork {
  automatic,  // the device on GPUs; on CPU devices the device for point coverage and the host for
              // area coverage (as measured on lavapipe: docs/RASTER.md); a batch holding a
              // weighted or bounded scene runs on the host
  device,     // classify.comp and split_f64.comp: RasterEngine throws Error on a device without
              // shaderFloat64 (unless force_float32) and compute() on a weighted or bounded scene
  host,       // the host reference (raster_reference.cpp), threaded
};

// Whether `work` puts the per-pixel work of periodic unweighted scenes of `coverage` on the
// device, on a device that is (`cpu_device`) or is not a CPU implementation such as lavapipe.
bool runs_pixel_work_on_device(PixelWork work, Coverage coverage, bool cpu_device);

struct RasterOptions {
  // Pixels along the domain's x side (y follows the aspect ratio); 0 picks one from the
  // number of sites (default_resolution).
  int resolution = 0;
  Coverage coverage = Coverage::area;
  ConeShape cone = ConeShape::quad;
  // How quad cones are drawn (speed only: every choice gives the same bits); for measurements.
  ConeDraw cone_draw = ConeDraw::points;
  // First pass of a scene: every cone has radius radius_factor * sqrt(area / N). Later passes
  // on the same batch use per-site radii from the last cell radius and the sites' motion.
  double radius_factor = 2.5;
  // Remember each site's cell radius under its position, so the next call (sites moved to
  // their centroids) draws cones just large enough, however the caller rebuilds its scenes.
  bool adapt_radius = true;
  // Split boundary pixels in single precision even where the device has shaderFloat64 (the
  // path of devices without it; for tests and measurements).
  bool force_float32 = false;
  // Which float64 split kernel the device runs (SplitKernel); the others are for tests and
  // measurements.
  SplitKernel split_kernel = SplitKernel::lane;
  // Tests only: nonzero makes the lane split's clip guard (a clip needing more than one new
  // vertex, which no known input reaches) trip on the last piece of boundary pixels whose index
  // i + j * resolution has every bit of this mask set, so they go to the host whole.
  std::uint32_t split_guard_test = 0;
  PixelWork pixel_work = PixelWork::automatic;
  // Vulkan device: empty (CPU/lavapipe first), an index or a name substring.
  std::string device{};
  // Sites on lines (or a few parallel lines) have sliver cells that reach across the domain:
  // every cone covers most of it and every pixel it crosses is split among O(N) strips, so a
  // pass costs about N^2 (docs/RASTER.md, "Sliver cells"). A scene whose cones would overlap more
  // than this many times on average (the sum of their areas, each at most the domain's, over the
  // domain's area: about 2 for a relaxed set, 20 on a first pass, 0.8 N for sites on one line)
  // is measured by the exact engine instead (RasterStats::exact_scenes): the same cells to
  // rounding. 0: never (the raster path at any cost). Never while ID images or pass data are kept.
  double max_cone_overlap = 64.0;
  // Keep a copy of every scene's ID buffer from the last compute (for id_image()).
  bool keep_id_images = false;
  // Keep every scene's last accepted pass (ID image, device sums, overflow) for pass_data().
  bool keep_pass_data = false;
};

// Counters over the engine's life, to see what the passes cost and how often the coverage
// check forced a redo.
struct RasterStats {
  std::uint64_t computes = 0;         // compute() calls
  std::uint64_t submits = 0;          // device submissions (one per atlas pass)
  std::uint64_t scene_passes = 0;     // scenes drawn, redos included
  std::uint64_t redone_scenes = 0;    // scene passes rejected by the coverage check and redone
  std::uint64_t uncovered_pixels = 0;  // samples no cone reached, in rejected passes
  std::uint64_t boundary_pixels = 0;   // pixels split on the device (area coverage)
  std::uint64_t host_split_pixels = 0;  // boundary pixels the per-pixel pass left to the host
  // Of those, pixels the lane split's clip guard left (a clip needing more than one new vertex),
  // accepted passes and rejected ones alike.
  std::uint64_t guard_pixels = 0;
  std::uint64_t fallback_cells = 0;    // cells measured by the exact engine (point coverage, no sample)
  std::uint64_t exact_scenes = 0;      // scenes measured by the exact engine (max_cone_overlap)
  std::uint64_t split_sites_examined = 0;  // sites the host split's candidate searches examined
  std::uint64_t remembered_radii = 0;  // sites whose cone radius came from the radius memory
  double drawn_radius_sum = 0.0;       // sum of the cone radii of every site drawn (domain units)
  double upload_seconds = 0.0;  // filling the device's input buffers
  double device_seconds = 0.0;  // recording, submission and wait
  // Parts of device_seconds from device timestamps (0 where the device has none): the cone
  // pass, classify.comp, the split, the copies back (the ID image with host pixel work).
  double cone_seconds = 0.0, classify_seconds = 0.0, split_seconds = 0.0, readback_seconds = 0.0;
  std::uint64_t cones_drawn = 0;  // cone instances drawn (sites and periodic replicas), redos included
  std::uint64_t point_cone_submits = 0;  // submissions whose cones were drawn as points (ConeDraw::points)
  double host_seconds = 0.0;    // scene preparation, coverage check, host splits, assembling cells
  // Parts of host_seconds (wall; where scenes finish in parallel, their stage times are scaled to
  // the wall time of that loop): scenes prepared (wrapping, radii, close-site flags, scales); the
  // ID image taken out of the atlas; the host's per-pixel work (classification and sums, split,
  // the threads' sums merged); the coverage check, pixels left to the host and cells assembled.
  double prepare_seconds = 0.0, host_readback_seconds = 0.0;
  double host_classify_seconds = 0.0, host_split_seconds = 0.0, host_reduce_seconds = 0.0;
  double cells_seconds = 0.0;
  double exact_seconds = 0.0;  // part of host_seconds: scenes measured by the exact engine
};

// One scene's ID buffer: ids[j * width + i] is the index of the site that owns pixel (i, j)'s
// centre within the scene, or -1 for none.
struct IdImage {
  int width = 0, height = 0;
  std::vector<std::int32_t> ids;
};

// A resolution for `sites` sites: in area coverage (where resolution only sets speed) about
// 4 pixels per cell, in point coverage about 1000 (point error ~ 0.05 pixel).
int default_resolution(std::size_t sites, Coverage coverage);

class RasterEngine final : public CentroidEngine {
 public:
  // Creates the Vulkan context and pipelines; throws Error when there is no usable device.
  explicit RasterEngine(const RasterOptions& options = {});
  ~RasterEngine() override;

  std::string_view name() const override { return "raster"; }
  using CentroidEngine::compute;
  void compute(std::span<const Scene> scenes, std::span<SceneCells> out) override;

  const RasterOptions& options() const;
  const RasterStats& stats() const;
  std::string device_name() const;
  // Whether the Vulkan device is a CPU implementation (lavapipe).
  bool cpu_device() const;
  // The ID buffer of scene `scene` of the last compute (needs keep_id_images).
  const IdImage& id_image(std::size_t scene) const;
  // The scene resolution the engine uses for a scene (x side, pixels); throws Error when it
  // exceeds the device's limits.
  int resolution_for(const Scene& scene) const;
  // Whether boundary pixels are split in double precision (the device has shaderFloat64 and
  // force_float32 is off).
  bool float64_split() const;
  // Whether the per-pixel work runs on the device (see PixelWork) for periodic unweighted scenes.
  bool pixel_work_on_device() const;

  // Scene `scene`'s last accepted pass in the last compute (needs keep_pass_data).
  struct PassData {
    RasterScene scene;                  // as drawn: radii, flags, scales, grid
    std::vector<std::uint32_t> ids;     // ID image: scene-local site index + 1, 0 for none
    std::vector<gpu::SiteSums> sums;    // the device's sums, one per site
    std::vector<std::uint32_t> host_split;  // boundary pixels the device left to the host
  };
  const PassData& pass_data(std::size_t scene) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes `image` as a PNG (or any format OpenImageIO knows by the extension) with one colour
// per cell and the sites drawn as dots, through output_file.h. Throws Error on failure.
void write_id_image(const IdImage& image, const Scene& scene, OutputFile& out);
void write_id_image(const IdImage& image, const Scene& scene, const std::string& path);

}  // namespace bluetile
