// Exact reference engines built on CGAL, for the benchmark only.
//
// LICENCE: CGAL's triangulation packages are GPL-3.0-or-later. This code is compiled into the
// optional `bluetile_cgal_reference` target, which only `bluetile_bench` links; it must never be
// linked into `bluetile_lib` or the `bluetile` tool, so the library stays free of the GPL.
//
// Both engines compute the periodic Voronoi cells on the unit torus as duals of a Delaunay
// triangulation (CGAL has no periodic Lloyd function): a cell's vertices are the circumcentres
// of the triangles around its site, in counter-clockwise order.
// - CgalPeriodicEngine: CGAL::Periodic_2_Delaunay_triangulation_2 over the sites.
// - CgalBandEngine: a plain CGAL::Delaunay_triangulation_2 over the sites plus their periodic
//   copies in a border band of width w around the unit square. w starts at 4/sqrt(N) and is
//   doubled (inserting the new ring of copies) until every circumcircle around an original
//   site lies inside the replicated region, which certifies that those triangles are Delaunay
//   on the torus.
// Coincident sites: the lowest index owns the cell, the others are reported as coincident,
// as in the exact engine. Only the unit torus is supported; other domains throw Error.
#pragma once

#include <string>

#include "bluetile/voronoi/engine.h"

namespace bluetile::bench {

class CgalPeriodicEngine final : public CentroidEngine {
 public:
  std::string_view name() const override { return "cgal-periodic"; }
  using CentroidEngine::compute;
  void compute(std::span<const Scene> scenes, std::span<SceneCells> out) override;
};

class CgalBandEngine final : public CentroidEngine {
 public:
  std::string_view name() const override { return "cgal-band"; }
  using CentroidEngine::compute;
  void compute(std::span<const Scene> scenes, std::span<SceneCells> out) override;

  // Band width of the last scene computed (domain units) and how often it was doubled.
  double last_band_width() const { return last_band_width_; }
  int last_widenings() const { return last_widenings_; }

 private:
  double last_band_width_ = 0.0;
  int last_widenings_ = 0;
};

// "5.5.1" etc.
std::string cgal_version();

}  // namespace bluetile::bench
