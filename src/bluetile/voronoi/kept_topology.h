// The state ExactEngine keeps between calls for one scene of a batch (exact_engine.h, "Topology
// kept between calls"): where the sites were when each wanted cell's list of nearby sites was
// made, and the lists. Internal to the engine.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "bluetile/voronoi/exact_engine.h"

namespace bluetile {

struct ExactEngine::Topology {
  // Scenes with fewer sites are always searched (their lists would cost more than they save).
  static constexpr std::size_t kMinSites = 1024;
  // A list holds the sites within kListFactor times the cell's radius: twice the radius is the
  // reach the cell needs, the rest is the room the sites have to move before the list is stale.
  static constexpr double kListFactor = 2.6;
  // Lists are made on a searched call only when no site moved farther than this many mean site
  // spacings since the call before (otherwise they would be stale at once: a random start).
  static constexpr double kListMove = 0.08;
  // When more than one cell in this many fails its certificate, the lists are dropped and the
  // next call searches every cell (and makes new lists if the sites now move little).
  static constexpr std::size_t kFailShare = 16;
  // The sites that moved the most since the lists were made, at most one in this many, are
  // checked one by one against each cell (exact_engine.cpp, kept_scene), so that a few fast
  // sites do not make every certificate fail.
  static constexpr std::size_t kFastShare = 1024;

  // One periodic copy of a site: its index and the copy's shift in periods (0, 0 when bounded).
  struct Entry {
    std::uint32_t site;
    std::int16_t wx, wy;
  };

  // The scene the state belongs to.
  Domain domain;
  Boundary boundary = Boundary::periodic;
  std::size_t site_count = 0, wanted_begin = 0, wanted_end = 0;

  // Every site's position at the call the lists were made, in the order below (without lists:
  // at the last call, in site order).
  std::vector<Point> reference;
  bool has_reference = false;
  bool has_lists = false;
  // Every site in the order the cells are computed (the grid's bucket order when the lists were
  // made, so that neighbouring cells are computed together and read nearby memory), and each
  // wanted one's list: entries[start[q], start[q + 1]) for order[q], nearest first, each entry
  // naming its site by its place q in this order (positions are gathered in this order per call).
  std::vector<std::uint32_t> order;
  std::vector<std::uint32_t> start;
  std::vector<Entry> entries;
  // How many of a list's first entries carry the cell's edges, counter-clockwise (0: none kept;
  // the cell is then clipped against its list rather than built from its edges).
  std::vector<std::uint8_t> edges;
  std::vector<double> reach;  // the list's radius; negative: no list (searched, or a fixed site)

  bool matches(const Scene& scene) const {
    return has_reference && scene.sites.size() == site_count && scene.wanted_begin == wanted_begin &&
           scene.wanted_end == wanted_end && scene.boundary == boundary && scene.domain.size == domain.size;
  }
  void reset(const Scene& scene) {
    domain = scene.domain;
    boundary = scene.boundary;
    site_count = scene.sites.size();
    wanted_begin = scene.wanted_begin;
    wanted_end = scene.wanted_end;
    has_reference = false;
    drop_lists();
  }
  void drop_lists() {
    has_lists = false;
    order.clear();
    start.clear();
    entries.clear();
    edges.clear();
    reach.clear();
  }
  std::size_t bytes() const {
    return reference.capacity() * sizeof(Point) + order.capacity() * sizeof(std::uint32_t) +
           start.capacity() * sizeof(std::uint32_t) + entries.capacity() * sizeof(Entry) + edges.capacity() +
           reach.capacity() * sizeof(double);
  }
};

}  // namespace bluetile
