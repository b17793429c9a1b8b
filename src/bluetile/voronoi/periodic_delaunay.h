// A Delaunay triangulation of sites on the torus W x H, kept while the sites move and repaired by
// edge flips (Lawson, "Software for C1 surface interpolation", 1977): a triangulation whose edges
// all pass the in-circle test is the Delaunay triangulation. Periodicity as in CGAL's periodic
// triangulations (Caroli and Teillaud 2009): a triangle names its three sites and, per corner,
// the periodic copy of the site it uses (whole periods in x and y); the triangles cover the
// torus once.
//
// Every decision is an exact predicate (predicates.h). Cocircular ties are broken by a symbolic
// perturbation keyed on the site index, so the triangulation a set of sites reaches is unique
// whatever the triangulation it started from, and so is everything read off it; the edges where
// the unperturbed test is exactly 0 are marked (ties()): their cells belong to no single
// triangulation.
//
// Large moves that fold triangles over are repaired by removing the vertices concerned where the
// triangulation was still valid and inserting them again (repair()); a point is located by a
// stochastic walk (Devillers, Pion and Teillaud, "Walking in a triangulation", 2002).
//
// Precondition the callers keep (delaunay_cells.h's sweep checks it, every flip too): an edge
// between copies in different periods is shorter than a quarter period along each axis, so that
// the differences between the points of a test stay below half a period (predicates.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "bluetile/core/default_init.h"
#include "bluetile/core/torus.h"
#include "bluetile/voronoi/predicates.h"

namespace bluetile {

class PeriodicDelaunay {
 public:
  // Corner k uses the copy of site `vertex[k]` at position + (shift_x[k] W, shift_y[k] H);
  // corners counter-clockwise, corner 0 at shift 0. `neighbour[k]` is the triangle across the
  // edge opposite corner k, as link(triangle, that edge's index in it).
  struct Triangle {
    std::uint32_t vertex[3];
    std::uint32_t neighbour[3];
    std::int8_t shift_x[3], shift_y[3];
  };
  static constexpr std::uint32_t link(std::uint32_t triangle, int edge) { return triangle << 2 | static_cast<std::uint32_t>(edge); }
  static constexpr std::uint32_t triangle_of(std::uint32_t link) { return link >> 2; }
  static constexpr int edge_of(std::uint32_t link) { return static_cast<int>(link & 3u); }
  static constexpr int next(int k) { return k == 2 ? 0 : k + 1; }
  static constexpr int previous(int k) { return k == 0 ? 2 : k - 1; }

  // A neighbour in a vertex's star: its vertex and the whole periods of the copy, relative to
  // the star's vertex.
  struct StarEntry {
    std::uint32_t vertex;
    std::int8_t shift_x, shift_y;
  };

  // Vertices are 0..count-1 at `positions` (inside the domain); `sites` names each vertex's site
  // (the perturbation's key and every tie-break, so that nothing depends on the vertex order).
  void reset(const Domain& domain, std::vector<Point> positions, std::vector<std::uint32_t> sites);

  // The triangulation from every vertex's star (the neighbours of its Voronoi cell, counter-
  // clockwise): stars[star_start[v], star_start[v + 1]) for vertex v. Returns false when the
  // stars do not fit together into a triangulation of the torus (they came from roundings near a
  // tie, a vertex sees the same site twice); the object is then empty. Whether the triangles are
  // counter-clockwise with short edges is for a sweep to tell (DelaunayCells::sweep). On all
  // threads; the same result for any count.
  bool build(std::span<const std::uint32_t> star_start, std::span<const StarEntry> stars);
  bool empty() const { return triangles_.empty(); }

  std::size_t vertex_count() const { return positions_.size(); }
  const Domain& domain() const { return domain_; }
  std::span<const Triangle> triangles() const { return triangles_; }
  std::span<Point> positions() { return positions_; }
  // Exchanges the positions with `other` (of the same size, or the triangulation is unusable).
  void swap_positions(std::vector<Point>& other) { positions_.swap(other); }
  std::span<const Point> positions() const { return positions_; }
  std::span<const std::uint32_t> sites() const { return sites_; }
  // The vertex's canonical corner, as link(triangle, corner): the one whose triangle comes just
  // before the edge to the vertex's neighbour of lowest site index, going counter-clockwise
  // around the vertex (where its cell's sums start, delaunay_cells.h). Every change to the
  // triangulation keeps it so.
  std::uint32_t corner_of(std::uint32_t vertex) const { return corners_[vertex]; }
  // Bit k: the edge opposite corner k is a cocircular tie (exact in-circle 0).
  std::uint8_t ties(std::uint32_t triangle) const { return ties_[triangle]; }
  std::size_t tie_edges() const { return tie_edges_; }

  // The copy a corner uses, for the predicates.
  PeriodicPoint corner_point(const Triangle& t, int k) const {
    return {positions_[t.vertex[k]], {t.shift_x[k] * domain_.size.x, t.shift_y[k] * domain_.size.y}};
  }
  // The corner after `corner` counter-clockwise around its vertex: the triangle across the edge
  // from the vertex to the corner's previous corner.
  std::uint32_t next_around(std::uint32_t corner) const {
    const Triangle& t = triangles_[triangle_of(corner)];
    const std::uint32_t across = t.neighbour[next(edge_of(corner))];
    return link(triangle_of(across), next(edge_of(across)));
  }

  // Vertex `vertex` wrapped across the domain's border: its new position plus (kx W, ky H) is
  // where it was, so every corner that used a copy of it uses the copy kx, ky periods further.
  void wrap(std::uint32_t vertex, int kx, int ky);

  // A vertex that wrapped across the border since the positions before (see wrap()).
  struct Wrap {
    std::uint32_t vertex;
    std::int8_t kx, ky;
  };
  // Repairs a triangulation that the last move folded over (`invalid`: the triangles not valid at
  // the current positions; `old_positions`: where the vertices were, where it was valid;
  // `wraps`: the vertices that wrapped since, already applied): the vertices of the folded
  // triangles are removed at their old positions (their edges flipped away until three are left,
  // then the three triangles merged), with the vertices of any triangle the removals fold, then
  // inserted again at their new positions (a stochastic walk to the triangle that holds each,
  // split in three). The result is valid, not yet Delaunay (make_delaunay follows). Returns false
  // when more than `limit` vertices would go or a step meets a degenerate case (a point on an
  // edge, no flippable edge): the triangulation is then unusable. Serial; `repaired` receives
  // how many vertices went and came back.
  bool repair(std::span<const std::uint32_t> invalid, std::vector<Point>& old_positions, std::span<const Wrap> wraps,
              std::size_t limit, std::size_t& repaired);

  // Flips until every edge passes the perturbed in-circle test (the Delaunay triangulation),
  // starting from the edges in `suspects` (links; the edges a test found failing), and marks the
  // edges in `tie_edges` as ties: together they must hold every edge that fails or ties now (every
  // other edge passes strictly). Adds the triangles it rewrote to `changed`. Precondition: every
  // triangle valid (counter-clockwise, edges below a quarter period). Returns false when a flip
  // would make an edge of a quarter period or more or the flips do not end (roundings of an input
  // the predicates cannot hold): the triangulation is then unusable. Flips in a fixed order,
  // the same for any thread count: with many suspects, first inside strips of vertices on all
  // threads (Strip), then what the strips left on the calling thread.
  bool make_delaunay(std::span<const std::uint32_t> suspects, std::span<const std::uint32_t> tie_edges,
                     std::vector<std::uint32_t>& changed);
  std::size_t flips() const { return flips_; }
  // Of those, the flips made inside strips (on all threads), for tests.
  std::size_t strip_flips() const { return strip_flips_; }
  // The perturbed and exact in-circle signs of edge `edge` of triangle `t`: positive when the
  // vertex across it lies inside t's circumcircle (the edge must flip).
  struct Test {
    int perturbed, exact;
  };
  Test test_edge(std::uint32_t triangle, int edge) const;
  // The copy of the vertex across edge `edge` of `t`, in t's frame.
  PeriodicPoint across_point(const Triangle& t, int edge) const;
  std::uint32_t across_site(const Triangle& t, int edge) const {
    const std::uint32_t l = t.neighbour[edge];
    return sites_[triangles_[triangle_of(l)].vertex[edge_of(l)]];
  }

  // Bytes held.
  std::size_t bytes() const;

 private:
  // The shift that takes the frame of the triangle across edge `edge` of `t` into t's frame.
  void frame_offset(const Triangle& t, int edge, const Triangle& across, int across_edge, int& dx, int& dy) const;
  bool short_edge(const PeriodicPoint& a, const PeriodicPoint& b) const;
  // What flips and tie marks change, counted apart so that strips can flip at once.
  struct Tally {
    std::size_t flips = 0;
    std::ptrdiff_t tie_edges = 0;
    Tally& operator+=(const Tally& other) {
      flips += other.flips;
      tie_edges += other.tie_edges;
      return *this;
    }
  };
  // Flips the edge; the four vertices' canonical corners follow from the ones they had (which
  // must be canonical for the result to be), or with `walk_corners` from a walk around each
  // (the repair's removals, where some are not yet).
  bool flip(std::uint32_t triangle, int edge, Tally& tally, bool walk_corners = false);
  // Adds what a tally counted to flips() and tie_edges().
  void add(const Tally& tally);
  void set_tie(std::uint32_t triangle, int edge, bool tie, Tally& tally);
  // Vertices [begin, end) of a strip (rows of the plane, as vertices are numbered); the whole
  // triangulation when begin == end. A strip writes only triangles whose three vertices it holds
  // (and those vertices' corners), and reads only triangles with a vertex of its own: strips never
  // touch what another writes, so they flip at once without locks.
  struct Strip {
    std::uint32_t begin = 0, end = 0;
    bool whole() const { return begin == end; }
    bool holds(const Triangle& t) const {
      return whole() || (in(t.vertex[0]) && in(t.vertex[1]) && in(t.vertex[2]));
    }
    bool in(std::uint32_t vertex) const { return vertex >= begin && vertex < end; }
  };
  // Lawson's flips from the links on `stack` (the last first) until it is empty. Inside a strip,
  // an edge whose test or flip would touch a triangle the strip does not hold goes to `deferred`
  // instead. False when a flip fails or the flips pass `cap`.
  bool flip_until_delaunay(std::vector<std::uint32_t>& stack, const Strip& strip, std::size_t cap, Tally& tally,
                           std::vector<std::uint32_t>& changed, std::vector<std::uint32_t>& deferred);
  void normalise(Triangle& t) const;
  // Whether t is valid (counter-clockwise, short edges) with its vertices at `positions`, vertex
  // w's copies shifted by shift[w] periods more.
  bool valid_at(const Triangle& t, std::span<const Point> positions, std::span<const std::int8_t> shift_x,
                std::span<const std::int8_t> shift_y) const;
  bool remove_vertex(std::uint32_t vertex, std::vector<std::uint32_t>& rewritten);
  void canonical_corner(std::uint32_t vertex);
  bool insert_vertex(std::uint32_t vertex, std::uint32_t hint);
  std::uint32_t take_free_triangle();

  static constexpr std::uint32_t kNoCorner = 0xffffffffu;  // corners_ of a removed vertex

  Domain domain_;
  std::vector<Point> positions_;
  std::vector<std::uint32_t> sites_;
  std::vector<Triangle, DefaultInitAllocator<Triangle>> triangles_;  // build() writes every triangle on all threads
  std::vector<std::uint32_t, DefaultInitAllocator<std::uint32_t>> corners_;  // build() writes every corner on all threads
  std::vector<std::uint8_t> ties_;
  std::vector<std::uint32_t> free_;  // triangle slots freed by removals, taken by insertions
  std::size_t tie_edges_ = 0;
  std::size_t flips_ = 0;
  std::size_t strip_flips_ = 0;
};

}  // namespace bluetile
