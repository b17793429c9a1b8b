// The exact engine's state between calls for one scene of a batch (exact_engine.h, "Topology
// kept between calls"): the periodic Delaunay triangulation of its sites (periodic_delaunay.h).
//
// A call on a scene of the same shape as the last one (site count, wanted range, domain) moves
// the triangulation's vertices to the new sites, sweeps every triangle (orientation,
// circumcentre, in-circle tests) and flips the edges that fail; the cells are then read off the
// triangles (delaunay_cells.h). Triangles a large move folded over are repaired (their vertices
// removed where they were and inserted where they are, PeriodicDelaunay::repair). The
// triangulation is built from the search (the cells' neighbours, in order, are the vertices'
// stars) on the first call, and again when more than one vertex in 16 would be repaired or the
// flips could not finish. Stars that do not fit together (the roundings of the clipping near a
// tie) are computed again with the exact predicates.
//
// Which path measures a cell is a function of the sites alone: the triangulation a set of sites
// reaches is unique (the perturbation breaks ties alike everywhere), its cells' arithmetic is
// canonical, and a scene goes to the search as a whole only for properties of its sites (too
// few, coincident ones, a circumcircle of a tenth of a period or more, coordinates the predicates
// cannot take exactly, most of a fixed sample of the sites sharing their x and their y with other
// samples: a grid of rows and columns, cocircular at nearly every vertex, whose cells would all be
// ties); cells on a cocircular tie are searched one by one. So results never depend on the calls
// before, nor on the thread count. A scene searched whole drops the kept triangulation; the next
// one that suits a triangulation builds it again.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "bluetile/voronoi/cell_measure.h"
#include "bluetile/voronoi/delaunay_cells.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/voronoi/periodic_delaunay.h"

namespace bluetile {

class KeptDelaunay {
 public:
  // Scenes with fewer sites are searched: their triangulation would cost more than it saves, and
  // the Wang loop's crops (a few dozen sites, new ones every step) are all below it.
  static constexpr std::size_t kMinSites = 256;
  // Triangles are named by 30 bits (PeriodicDelaunay::link): 2 N of them must fit.
  static constexpr std::size_t kMaxSites = std::size_t{1} << 28;

  // Whether the scene can be measured through a triangulation at all (periodic, kMinSites to
  // kMaxSites sites, a domain whose sides lie between 2^-20 and 2^20, inside the predicates'
  // exact range).
  static bool suits(const Scene& scene);

  // `lanes`: the sweep and the cell walks in SIMD lanes where the processor has them
  // (DelaunayCells::sweep, DelaunayCells::measure_four).
  explicit KeptDelaunay(bool lanes = true) : lanes_(lanes) {}

  // How many measured cells have each status that SceneCells counts.
  struct StatusCounts {
    std::size_t coincident = 0, zero_density = 0;
    void add(const Cell& cell) {
      coincident += cell.status == CellStatus::coincident;
      zero_density += cell.status == CellStatus::zero_density;
    }
    StatusCounts& operator+=(const StatusCounts& other) {
      coincident += other.coincident;
      zero_density += other.zero_density;
      return *this;
    }
  };

  // Measures the wanted cells of `scene` (which suits()) into cells[site - wanted_begin]:
  // through the triangulation, kept or built now, or by the search where the scene or a cell
  // asks for it. Adds what it did to `stats`. Returns true when the cells came from the
  // triangulation (ties searched one by one) and their statuses are counted in `counts`, while
  // each cell is still in its thread's cache; false when the scene was searched whole (the
  // caller counts them).
  bool compute(const Scene& scene, const Weighting& weighting, std::span<Cell> cells, bool parallel,
               KeptTopologyStats& stats, StatusCounts& counts);

  std::size_t bytes() const;

 private:
  bool matches(const Scene& scene) const;
  // Moves the kept triangulation's vertices to the scene's sites (wraps across the border
  // followed); false when a coordinate is outside the predicates' range.
  bool move_vertices(const Scene& scene);
  // One sweep over the triangles, flips to Delaunay and the circumcentres of what they changed:
  // delaunay; or folded (triangles folded over, listed in `folded`: to repair); or failed (the
  // flips could not finish: to build again). Sets fits_: whether the triangulation can stand for
  // the diagram (no circumcircle of a tenth of a period or more, the triangles cover the domain
  // once).
  enum class Settled { delaunay, folded, failed };
  Settled settle(KeptTopologyStats& stats, std::vector<std::uint32_t>& folded);
  bool settle(KeptTopologyStats& stats);  // true when delaunay
  // Searches every cell and builds the triangulation from the cells' stars, then settles it;
  // false when the scene cannot be triangulated. The search's results go into the wanted
  // `cells` only when they stand: when it returns false or the triangulation does not fit
  // (fits_); otherwise the triangulation measures them.
  bool rebuild(const Scene& scene, const Weighting& weighting, std::span<Cell> cells, bool parallel,
               KeptTopologyStats& stats);

  bool lanes_ = true;
  bool valid_ = false;
  bool fits_ = false;
  double scene_area_ = 0.0;
  Domain domain_;
  std::size_t site_count_ = 0, wanted_begin_ = 0, wanted_end_ = 0;
  std::vector<std::uint32_t> site_of_vertex_;
  std::vector<Point> previous_;  // each vertex's position at the last call
  std::vector<PeriodicDelaunay::Wrap> wraps_;  // the vertices that wrapped since
  PeriodicDelaunay triangulation_;
  DelaunayCells cells_;
};

}  // namespace bluetile
