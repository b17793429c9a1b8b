// The centroid engine interface shared by the exact CPU engine and the raster (Vulkan) engine.
// A scene is a set of sites in a rectangle, periodic (a torus, the default) or bounded (cells end
// at its border); every site takes part in the Voronoi diagram, but only a contiguous range of
// them (the "wanted" sites) needs its cell measured. Sites outside that range are fixed sites
// (earlier levels of a hierarchy) or context sites (neighbouring Wang tiles): they shape the
// cells of the wanted sites and are not moved. A scene may carry a density (a grid of texels over
// the domain, constant per texel): cells are then measured weighted by it, so Lloyd moves each
// site to its cell's centre of mass under the density (weighted Voronoi stippling, Secord 2002).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "bluetile/core/density_grid.h"
#include "bluetile/core/torus.h"

namespace bluetile {

// Boundary (core/torus.h): periodic (cells wrap around) or bounded (cells clipped by the border).

struct Scene {
  Domain domain;
  Boundary boundary = Boundary::periodic;
  // The density over the domain (texel (i, j) covers [i W/width, (i+1) W/width) x
  // [j H/height, (j+1) H/height), density_grid.h), shared because scenes of a batch often share
  // one map. Null: density 1 everywhere, and every result is bit for bit that of a scene without
  // this field. A density constant over the grid gives the unweighted centroids bit for bit.
  std::shared_ptr<const DensityGrid> density;
  // Every site of the diagram, inside [0,W) x [0,H).
  std::vector<Point> sites;
  // Sites [wanted_begin, wanted_end) get a cell measured; the rest only shape the diagram.
  std::size_t wanted_begin = 0;
  std::size_t wanted_end = 0;

  // Whether the cells' second moments (Cell::second_moment, the Lloyd energy) are wanted. When
  // false an engine may skip them (the exact engine leaves them 0 on the kept triangulation,
  // 1-3 ns of about 150 per site: docs/BENCHMARKS.md) and their values are unspecified; every
  // other field is bit for bit what it is when they are wanted.
  bool second_moments = true;

  std::size_t wanted_count() const { return wanted_end - wanted_begin; }
  bool periodic() const { return boundary == Boundary::periodic; }
};

// A scene in which every site is wanted.
Scene make_scene(std::vector<Point> sites, Domain domain = {});

// The offset from a to b in the scene's domain: the shortest periodic offset on a torus, b - a in
// a bounded rectangle; and its length (how far a site moved).
inline Point scene_offset(const Scene& scene, Point a, Point b) {
  return scene.periodic() ? torus_offset(a, b, scene.domain) : b - a;
}
inline double scene_distance(const Scene& scene, Point a, Point b) {
  Point d = scene_offset(scene, a, b);
  return std::sqrt(d.x * d.x + d.y * d.y);
}

// A point of the domain placed back inside [0,W) x [0,H): wrapped on a torus, clamped in a
// bounded rectangle (a centroid lies inside its cell; only rounding can put it on the far edge).
Point scene_point(const Scene& scene, Point p);

enum class CellStatus : std::uint8_t {
  ok,
  // The site coincides exactly with a site of lower index, which owns the shared cell; this
  // one has area 0 and its centroid is the site itself, so Lloyd leaves it in place.
  coincident,
  // (raster engine) the cell covered no pixel; its values came from the exact engine.
  exact_fallback,
  // The density is zero over the whole cell (mass 0): the centroid is the site itself, so Lloyd
  // leaves it in place.
  zero_density,
};

// The cell of one wanted site. Units are domain units; rho is the scene's density (1 without).
struct Cell {
  Point centroid{0.0, 0.0};    // centre of mass under rho, inside the domain
  double area = 0.0;           // cell area (geometric, whatever the density)
  double mass = 0.0;           // integral of rho over the cell (the area when there is no density)
  double second_moment = 0.0;  // integral of rho |x - site|^2 over the cell (its Lloyd energy)
  // Distance from the site to the farthest point of its cell (exact engine: exactly; raster
  // engine: its farthest owned sample plus a pixel diagonal); 0 when unknown. No site farther
  // than 2 radius from the site can touch the cell, which is how a cropped scene proves a cell
  // complete (Wang-tile loop); loops may also pass it on as a hint.
  double radius = 0.0;
  CellStatus status = CellStatus::ok;
};

struct SceneCells {
  // One entry per wanted site, in site order.
  std::vector<Cell> cells;
  std::size_t coincident_count = 0;
  std::size_t fallback_count = 0;
  std::size_t zero_density_count = 0;
};

class CentroidEngine {
 public:
  virtual ~CentroidEngine() = default;
  virtual std::string_view name() const = 0;

  // Measures the wanted cells of every scene; out[i] belongs to scenes[i]. Scenes are
  // independent: an engine may process them in any order or all at once, and results do not
  // depend on the batch they came in. Throws Error on failure.
  virtual void compute(std::span<const Scene> scenes, std::span<SceneCells> out) = 0;

  SceneCells compute(const Scene& scene) {
    SceneCells cells;
    compute(std::span<const Scene>(&scene, 1), std::span<SceneCells>(&cells, 1));
    return cells;
  }
};

}  // namespace bluetile
