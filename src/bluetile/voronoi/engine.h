// The centroid engine interface shared by the exact CPU engine and the raster (Vulkan) engine.
// A scene is a set of sites in a periodic rectangle; every site takes part in the Voronoi
// diagram, but only a contiguous range of them (the "wanted" sites) needs its cell measured.
// Sites outside that range are fixed sites (earlier levels of a hierarchy) or context sites
// (neighbouring Wang tiles): they shape the cells of the wanted sites and are not moved.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile {

struct Scene {
  Domain domain;
  // Every site of the diagram, inside [0,W) x [0,H).
  std::vector<Point> sites;
  // Sites [wanted_begin, wanted_end) get a cell measured; the rest only shape the diagram.
  std::size_t wanted_begin = 0;
  std::size_t wanted_end = 0;

  std::size_t wanted_count() const { return wanted_end - wanted_begin; }
};

// A scene in which every site is wanted.
Scene make_scene(std::vector<Point> sites, Domain domain = {});

enum class CellStatus : std::uint8_t {
  ok,
  // The site coincides exactly with a site of lower index, which owns the shared cell; this
  // one has area 0 and its centroid is the site itself, so Lloyd leaves it in place.
  coincident,
  // (raster engine) the cell covered no pixel; its values came from the exact engine.
  exact_fallback,
};

// The cell of one wanted site. Units are domain units.
struct Cell {
  Point centroid;            // inside the domain, wrapped
  double area = 0.0;         // cell area
  double second_moment = 0.0;  // integral of |x - site|^2 over the cell (its Lloyd energy)
  // Distance from the site to the farthest point of its cell (exact engine: exactly; raster
  // engine: its farthest owned sample plus a pixel diagonal). Loops may pass it on as a hint.
  double radius = 0.0;
  CellStatus status = CellStatus::ok;
};

struct SceneCells {
  // One entry per wanted site, in site order.
  std::vector<Cell> cells;
  std::size_t coincident_count = 0;
  std::size_t fallback_count = 0;
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
