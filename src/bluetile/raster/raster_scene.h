// One scene as the raster engine draws it: sites wrapped into the domain, coincident sites set
// aside, sites too close for float depths flagged, cone radii, the sample lattice and the
// fixed-point scales of the boundary sums. Pure host code (no Vulkan): the device pass, the host
// reference and the coverage check all read it. Method: raster_engine.cpp and docs/RASTER.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "bluetile/gpu/raster_layout.h"
#include "bluetile/voronoi/density_moments.h"
#include "bluetile/voronoi/engine.h"
#include "bluetile/voronoi/site_grid.h"

namespace bluetile {

// How the exact-depth cones (squares) are drawn; every choice gives the same ID image (the
// fragment shader computes each sample's depth), so it changes speed only. Measured on lavapipe:
// docs/BENCHMARKS.md, "The cone pass per cone".
enum class ConeDraw {
  triangles,  // six vertices per cone, one non-indexed triangle list
  indexed,    // four vertices per cone and an index buffer
  instanced,  // one instance of a four-vertex strip per cone
  points,     // one point per cone, its size the square's side (passes with a cone wider than the
              // device's largest point fall back to triangles)
};

// Which float64 split kernel the device runs. All give the same bits: the lane kernels leave
// pixels with more candidates than their slots to the host, which splits them as the host
// reference does. Measured on lavapipe: docs/BENCHMARKS.md, "The split with candidates in
// registers" and "The lane kernel for three".
enum class SplitKernel {
  lane,        // lane_three on a CPU device, lane_five on others
  lane_three,  // split_lane_f64.comp: one pixel per invocation, candidates and pieces in
               // registers, BLUETILE_MAX_PIECES (3) candidates
  lane_five,   // split_lane5_f64.comp: the same with BLUETILE_MAX_PIECES_GPU (5)
  pixel,       // split_f64.comp: one pixel per invocation, candidates and pieces in shared memory
};

struct RasterScene {
  const Scene* scene = nullptr;
  std::uint64_t serial = 0;  // unique per prepared scene (copies share it): keys per-scene caches
  std::size_t index = 0;  // in the batch
  bool area = true;       // area coverage (else point)
  // A periodic domain (the scene's boundary): cones drawn with replicas, offsets and windows
  // wrapped. Bounded: the raster covers exactly the domain, nothing wraps, and the pixels of the
  // last column and row (whose far corners are no samples) are always split.
  bool periodic = true;
  int rx = 0, ry = 0;     // samples along x and y
  double hx = 0.0, hy = 0.0;  // pixel size
  double radius_cap = 0.0;    // a cone this large covers the whole domain
  std::vector<Point> sites;   // wrapped into the domain
  std::vector<std::uint8_t> coincident;  // equal to a site of lower index: not drawn
  std::vector<std::uint8_t> split;       // has a site too close for float depths: all its pixels are split
  std::vector<double> radius;            // cone radius per site
  // Pieces may lie at most this far from their site (else the pixel goes to the host), which
  // bounds each site's piece sums; the fixed-point scales follow (powers of two).
  double reach_limit = 0.0;
  double scale_area = 1.0, scale_first = 1.0, scale_second = 1.0;
  // The scene's density, when it varies (else null: a uniform density only scales mass and
  // second moment). Whole pixels are weighted by their moments in `pixel_density`, pieces by
  // density_moments; weighted sums are fixed point at the scales above times density_scale
  // (1 / the least power of two above the largest texel), so the same bounds hold.
  const DensityGrid* density = nullptr;
  double density_constant = 1.0;  // the density of a uniform one (1 without)
  double density_scale = 1.0;
  std::shared_ptr<const std::vector<WeightedMoments>> pixel_density;

  // Per pass.
  int origin_x = 0, origin_y = 0;  // tile corner in the atlas
  std::uint32_t site_begin = 0;    // global index of site 0 in the pass
  int redos = 0;
  bool done = false;
  // From the coverage check: per site, the radius its cone must reach for the last diagram to
  // pass (the largest farthest-sample distance of the sites within twice that distance).
  std::vector<double> need;

  std::size_t size() const { return sites.size(); }
  double pixel_diagonal() const;
  bool wanted(std::size_t i) const { return i >= scene->wanted_begin && i < scene->wanted_end; }
  // floor(site / pixel size), clamped to the lattice, and the fraction left over in [0, 1).
  void site_pixel(std::size_t i, int& px, int& py, double& fx, double& fy) const;
  // The scene's site grid (coincident sites are skipped by its users).
  const SiteGrid& grid() const { return *grid_; }
  std::shared_ptr<const SiteGrid> grid_;  // set by prepare_raster_scene
  // The k-d tree of the split's wide windows, built on first use (raster_reference.h).
  std::shared_ptr<struct RasterSearchCache> search_cache_;  // set by prepare_raster_scene
  // Recomputes the fixed-point scales from the current radii.
  void update_scales();
};

// Remembers each site's last cell radius under its position, so that the next call, which
// gets the sites at their centroids, draws small cones however the caller rebuilt or reordered
// its scenes. Only the last call's entries are kept.
class RadiusMemory {
 public:
  // Radii for `scene`'s sites where they are known; returns how many were found.
  std::size_t recall(RasterScene& scene) const;
  // Records the last pass: `next_position[i]` is where site i will be next time (its centroid
  // for a wanted site), `radius[i]` its cell radius.
  void remember(const RasterScene& scene, const std::vector<Point>& next_position, const std::vector<double>& radius);
  // Forgets entries of earlier calls (call once per compute, before remembering).
  void start_call();

 private:
  struct Entry {
    std::uint64_t key = 0;
    double radius = 0.0, motion = 0.0;
  };
  static std::uint64_t key_of(Point p, Point domain);
  void insert(const Entry& e);
  const Entry* find(std::uint64_t key) const;
  void grow();

  std::vector<Entry> table_;  // open addressing, linear probing; key 0 = empty
  std::vector<Entry> pending_;  // this call's entries, inserted at the next start_call
  std::size_t used_ = 0;
};

struct RasterSettings {
  bool area = true;
  int resolution = 0;          // 0: default_resolution
  double radius_factor = 2.5;  // start radius: factor * sqrt(area / N)
  std::uint32_t max_side = 16384;  // device limit on the atlas side
};

// Prepares `scene` (index `index` in its batch). Throws Error on a bad scene (non-finite site,
// wanted range outside the sites, non-positive domain) or a resolution beyond `max_side`.
RasterScene prepare_raster_scene(const Scene& scene, std::size_t index, const RasterSettings& settings);
// The prepared scene keeps a pointer to `scene`: a temporary would dangle.
RasterScene prepare_raster_scene(Scene&& scene, std::size_t index, const RasterSettings& settings) = delete;

// The weighted moments of every pixel of an rx x ry raster over `scene`'s domain under its
// density, relative to each pixel's centre, row by row (the table of RasterScene::pixel_density).
std::vector<WeightedMoments> pixel_density_moments(const Scene& scene, int rx, int ry);

// The distance from a to b in the scene's domain (on a torus the shortest).
double raster_distance(const RasterScene& scene, Point a, Point b);

// Flags sites whose nearest other site is closer than float depths can tell apart (see
// raster_scene.cpp); the radii must be set.
void flag_close_sites(RasterScene& scene);

}  // namespace bluetile
