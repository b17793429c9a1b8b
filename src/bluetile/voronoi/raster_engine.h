// The raster centroid engine (Vulkan): Hoff et al. 1999's distance cones, bounded, in an ID
// buffer, reduced by a compute shader to exact integer sums; in `area` coverage the pixels on
// cell boundaries are split exactly among their candidate sites on the host. The method, its
// guarantees and measured figures: raster_engine.cpp and docs/RASTER.md.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bluetile/core/output_file.h"
#include "bluetile/voronoi/engine.h"

namespace bluetile {

enum class Coverage {
  point,  // a pixel belongs wholly to the site whose ID its centre shows (the classic method)
  area,   // boundary pixels are split exactly among the sites whose cells cross them
};

enum class ConeShape {
  quad,  // a square per cone; the fragment shader writes the exact distance as depth
  fan,   // the classic tessellated cone (triangle fan), depth interpolated: biased
};

enum class Reduction {
  automatic,  // host on CPU devices (lavapipe), the compute shader on GPUs
  gpu,        // compute shader with 64-bit integer atomics
  host,       // the same integer sums on the host, threaded
};

struct RasterOptions {
  // Pixels along the domain's x side (y follows the aspect ratio); 0 picks one from the
  // number of sites (default_resolution).
  int resolution = 0;
  Coverage coverage = Coverage::area;
  ConeShape cone = ConeShape::quad;
  // First pass of a scene: every cone has radius radius_factor * sqrt(area / N). Later passes
  // on the same batch use per-site radii from the last cell radius and the sites' motion.
  double radius_factor = 2.5;
  bool adapt_radius = true;
  Reduction reduction = Reduction::automatic;
  // Vulkan device: empty (CPU/lavapipe first), an index or a name substring.
  std::string device;
  // Keep a copy of every scene's ID buffer from the last compute (for id_image()).
  bool keep_id_images = false;
};

// Counters over the engine's life, to see what the passes cost and how often the coverage
// check forced a redo.
struct RasterStats {
  std::uint64_t computes = 0;        // compute() calls
  std::uint64_t submits = 0;         // GPU submissions (one per atlas pass)
  std::uint64_t scene_passes = 0;    // scenes rendered, redos included
  std::uint64_t redone_scenes = 0;   // scene passes rejected by the coverage check and redone
  std::uint64_t uncovered_pixels = 0;  // pixels no cone reached, in rejected passes
  std::uint64_t boundary_pixels = 0;   // pixels split on the host (area coverage)
  std::uint64_t fallback_cells = 0;    // cells that owned no pixel (values from the exact engine)
  double gpu_seconds = 0.0;          // recording, submit and wait
  double host_seconds = 0.0;         // coverage check, boundary split, assembling cells
};

// One scene's ID buffer: ids[j * width + i] is the index of the site that owns pixel (i, j)'s
// centre within the scene, or -1 for none.
struct IdImage {
  int width = 0, height = 0;
  std::vector<std::int32_t> ids;
};

// A resolution for `sites` sites: in area coverage (where resolution only sets speed) about
// 16 pixels per cell, in point coverage about 1000 (point error ~ 0.05 pixel).
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
  // The ID buffer of scene `scene` of the last compute (needs keep_id_images).
  const IdImage& id_image(std::size_t scene) const;
  // The scene resolution the engine uses for a scene (x side, pixels); throws Error when it
  // exceeds the device's limits.
  int resolution_for(const Scene& scene) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes `image` as a PNG (or any format OpenImageIO knows by the extension) with one colour
// per cell and the sites drawn as dots, through output_file.h. Throws Error on failure.
void write_id_image(const IdImage& image, const Scene& scene, OutputFile& out);
void write_id_image(const IdImage& image, const Scene& scene, const std::string& path);

}  // namespace bluetile
