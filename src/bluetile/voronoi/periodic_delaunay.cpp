// The periodic Delaunay triangulation and its flips: see periodic_delaunay.h.
#include "bluetile/voronoi/periodic_delaunay.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "bluetile/core/parallel.h"

namespace bluetile {
namespace {

// Chunks of the parallel passes: large enough that a chunk's bookkeeping is noise, small enough
// that a build of 10^4 sites has twenty of them, not five split 3:2 between two threads
// (docs/BENCHMARKS.md, "Two threads at 10^4: smaller move chunks and grid order from 8192 sites").
constexpr std::size_t kVertexGrain = 512;
constexpr std::size_t kTriangleGrain = 1024;
// Flips split into strips (make_delaunay) only where there are enough of both to share.
constexpr double kMinStripVertices = 2048;
constexpr std::size_t kMinStripSuspects = 256;

}  // namespace

void PeriodicDelaunay::reset(const Domain& domain, std::vector<Point> positions, std::vector<std::uint32_t> sites) {
  domain_ = domain;
  positions_ = std::move(positions);
  sites_ = std::move(sites);
  triangles_.clear();
  corners_.clear();
  ties_.clear();
  free_.clear();
  tie_edges_ = 0;
  flips_ = 0;
}

bool PeriodicDelaunay::short_edge(const PeriodicPoint& a, const PeriodicPoint& b) const {
  const double dx = detail::rounded_difference(b.p.x, b.shift.x, a.p.x, a.shift.x);
  const double dy = detail::rounded_difference(b.p.y, b.shift.y, a.p.y, a.shift.y);
  return std::abs(dx) < 0.25 * domain_.size.x && std::abs(dy) < 0.25 * domain_.size.y;
}

void PeriodicDelaunay::normalise(Triangle& t) const {
  const std::int8_t x = t.shift_x[0], y = t.shift_y[0];
  for (int k = 0; k < 3; ++k) {
    t.shift_x[k] = static_cast<std::int8_t>(t.shift_x[k] - x);
    t.shift_y[k] = static_cast<std::int8_t>(t.shift_y[k] - y);
  }
}

bool PeriodicDelaunay::build(std::span<const std::uint32_t> star_start, std::span<const StarEntry> stars) {
  const std::size_t n = vertex_count();
  assert(star_start.size() == n + 1);
  triangles_.clear();
  corners_.clear();
  ties_.clear();
  tie_edges_ = 0;
  flips_ = 0;
  auto star = [&](std::uint32_t v) { return stars.subspan(star_start[v], star_start[v + 1] - star_start[v]); };
  auto owns = [&](std::uint32_t v, std::size_t k, std::span<const StarEntry> s) {
    return v < s[k].vertex && v < s[k + 1 == s.size() ? 0 : k + 1].vertex;
  };
  // A triangle of the torus has 2 V faces (Euler: V - E + F = 0 and 3 F = 2 E).
  if (star_start[n] != 6 * n) return false;

  // Every star well formed; each corner's twin, the entry of its vertex in the star of the
  // corner's neighbour (copies shifted alike: v at -(shift) in the star of s[k]); the corners
  // whose vertex owns their triangle (the lowest index of the three): a triangle is written once,
  // by its owner, so triangles are numbered in vertex order. Corner (v, k) is the triangle
  // (v, s[k], s[k + 1]) of v's star s, numbered star_start[v] + k. And each vertex's canonical
  // corner (corner_of()): the one whose s[k + 1] has the lowest site, read off the star.
  const std::size_t corners = star_start[n];
  // The large arrays are written whole by the passes below before they are read (where a star
  // is bad, the build stops first): their pages are first touched on all threads.
  const auto number = default_init_array<std::uint32_t>(corners + 1);
  number[0] = 0;
  const auto twin = default_init_array<std::uint32_t>(corners);
  const auto canonical = default_init_array<std::uint32_t>(n);
  std::vector<std::uint8_t> bad(n, 0);
  // Where v is in star s (no duplicates there once checked): a scan without an early exit, whose
  // compare the compiler turns into a select (an exit at a varying place mispredicts).
  auto position_of = [&](std::span<const StarEntry> s, std::uint32_t v, int sx, int sy) -> long {
    std::size_t at = s.size();
    for (std::size_t j = 0; j < s.size(); ++j) at = s[j].vertex == v ? j : at;
    if (at == s.size() || s[at].shift_x != sx || s[at].shift_y != sy) return -1;
    return static_cast<long>(at);
  };
  parallel_for(n, kVertexGrain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t vi = begin; vi < end; ++vi) {
      const auto v = static_cast<std::uint32_t>(vi);
      const auto s = star(v);
      if (s.size() < 3) {
        bad[v] = 1;
        continue;
      }
      std::size_t lowest = 0;
      for (std::size_t k = 0; k < s.size(); ++k) {
        const StarEntry& b = s[k];
        number[star_start[v] + k + 1] = owns(v, k, s);
        if (b.vertex == v || b.vertex >= n) {
          bad[v] = 1;
          break;
        }
        for (std::size_t j = 0; j < k; ++j) bad[v] |= s[j].vertex == b.vertex;
        const long at = position_of(star(b.vertex), v, -b.shift_x, -b.shift_y);
        if (at < 0) {
          bad[v] = 1;
          break;
        }
        twin[star_start[v] + k] = star_start[b.vertex] + static_cast<std::uint32_t>(at);
        if (sites_[b.vertex] < sites_[s[lowest].vertex]) lowest = k;
      }
      canonical[v] = star_start[v] + static_cast<std::uint32_t>(lowest == 0 ? s.size() - 1 : lowest - 1);
    }
  });
  if (std::find(bad.begin(), bad.end(), 1) != bad.end()) return false;
  for (std::size_t c = 0; c < corners; ++c) number[c + 1] += number[c];
  if (number[corners] != 2 * n) return false;

  // Each corner's triangle, found in the stars of its other two vertices through the twins:
  // (v, b, c) is (b, c, v) in b's star (c just before v there) and (c, v, b) in c's star (b just
  // after v). Its number is its owner's corner's. The owner writes the triangle, and the corners
  // whose triangles lie across its edges (turned into triangles below, once every corner has one).
  const auto triangle_at = default_init_array<std::uint32_t>(corners);  // the triangle of each corner
  triangles_.resize(2 * n);
  const auto across = default_init_array<std::uint32_t>(3 * triangles_.size());
  parallel_for(n, kVertexGrain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t vi = begin; vi < end; ++vi) {
      const auto v = static_cast<std::uint32_t>(vi);
      const auto s = star(v);
      const std::size_t d = s.size();
      const std::uint32_t first = star_start[v];
      for (std::size_t k = 0; k < d; ++k) {
        const std::size_t k1 = k + 1 == d ? 0 : k + 1;
        const StarEntry& b = s[k];
        const StarEntry& c = s[k1];
        const std::uint32_t at_b = twin[first + k], at_c = twin[first + k1];  // v in b's star, in c's
        const std::uint32_t before_v = at_b == star_start[b.vertex] ? star_start[b.vertex + 1] - 1 : at_b - 1;
        const std::uint32_t after_v = at_c + 1 == star_start[c.vertex + 1] ? star_start[c.vertex] : at_c + 1;
        const StarEntry& c_in_b = stars[before_v];
        const StarEntry& b_in_c = stars[after_v];
        if (c_in_b.vertex != c.vertex || c_in_b.shift_x != c.shift_x - b.shift_x || c_in_b.shift_y != c.shift_y - b.shift_y ||
            b_in_c.vertex != b.vertex || b_in_c.shift_x != b.shift_x - c.shift_x || b_in_c.shift_y != b.shift_y - c.shift_y) {
          bad[v] = 1;
          continue;
        }
        const std::uint32_t owner = std::min({v, b.vertex, c.vertex});
        const std::uint32_t owner_corner = owner == v ? first + static_cast<std::uint32_t>(k) : owner == b.vertex ? before_v : at_c;
        const std::uint32_t id = number[owner_corner];
        triangle_at[first + k] = id;
        if (owner != v) continue;
        Triangle& t = triangles_[id];
        t.vertex[0] = v;
        t.vertex[1] = b.vertex;
        t.vertex[2] = c.vertex;
        t.shift_x[0] = t.shift_y[0] = 0;
        t.shift_x[1] = b.shift_x;
        t.shift_y[1] = b.shift_y;
        t.shift_x[2] = c.shift_x;
        t.shift_y[2] = c.shift_y;
        // Opposite v: the edge b-c, whose other triangle comes before (b, c, v) around b.
        across[3 * id + 0] = before_v == star_start[b.vertex] ? star_start[b.vertex + 1] - 1 : before_v - 1;
        across[3 * id + 1] = first + static_cast<std::uint32_t>(k1);                   // opposite b: edge c-v
        across[3 * id + 2] = first + static_cast<std::uint32_t>(k == 0 ? d - 1 : k - 1);  // opposite c: edge v-b
      }
    }
  });
  if (std::find(bad.begin(), bad.end(), 1) != bad.end()) {
    triangles_.clear();
    return false;
  }
  // Each neighbour as a link: the edge of the neighbour that is not at either end of the shared edge.
  std::vector<std::uint8_t> broken(triangles_.size(), 0);
  parallel_for(triangles_.size(), kTriangleGrain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) {
      Triangle& tri = triangles_[t];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t u = triangle_at[across[3 * t + static_cast<std::size_t>(k)]];
        const Triangle& other = triangles_[u];
        const std::uint32_t a = tri.vertex[next(k)], b = tri.vertex[previous(k)];
        int e = -1;
        for (int j = 0; j < 3; ++j)
          if (other.vertex[j] != a && other.vertex[j] != b) e = e < 0 ? j : 3;
        if (e < 0 || e > 2 || triangle_at[across[3 * u + static_cast<std::size_t>(e)]] != t) {
          broken[t] = 1;
          e = 0;
        }
        tri.neighbour[k] = link(u, e);
      }
    }
  });
  if (std::find(broken.begin(), broken.end(), 1) != broken.end()) {
    triangles_.clear();
    return false;
  }
  corners_.resize(n);
  parallel_for(n, kVertexGrain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const std::uint32_t t = triangle_at[canonical[v]];
      const Triangle& tri = triangles_[t];
      corners_[v] = link(t, tri.vertex[0] == v ? 0 : tri.vertex[1] == v ? 1 : 2);
    }
  });
  ties_.assign(triangles_.size(), 0);
  tie_edges_ = 0;
  return true;
}

void PeriodicDelaunay::canonical_corner(std::uint32_t vertex) {
  const std::uint32_t start = corners_[vertex];
  std::uint32_t corner = start, best = start, lowest = 0;
  bool found = false;
  do {
    const Triangle& t = triangles_[triangle_of(corner)];
    const std::uint32_t site = sites_[t.vertex[previous(edge_of(corner))]];
    if (!found || site < lowest) {
      best = corner;
      lowest = site;
      found = true;
    }
    corner = next_around(corner);
  } while (corner != start);
  corners_[vertex] = best;
}

void PeriodicDelaunay::wrap(std::uint32_t vertex, int kx, int ky) {
  const std::uint32_t start = corners_[vertex];
  std::uint32_t corner = start;
  do {
    Triangle& t = triangles_[triangle_of(corner)];
    const int k = edge_of(corner);
    t.shift_x[k] = static_cast<std::int8_t>(t.shift_x[k] + kx);
    t.shift_y[k] = static_cast<std::int8_t>(t.shift_y[k] + ky);
    normalise(t);
    corner = next_around(corner);
  } while (corner != start);
}

void PeriodicDelaunay::frame_offset(const Triangle& t, int edge, const Triangle& across, int across_edge, int& dx,
                                    int& dy) const {
  // Corner next(edge) of t is corner previous(across_edge) of the other triangle (the shared edge
  // runs the other way there).
  dx = t.shift_x[next(edge)] - across.shift_x[previous(across_edge)];
  dy = t.shift_y[next(edge)] - across.shift_y[previous(across_edge)];
}

PeriodicPoint PeriodicDelaunay::across_point(const Triangle& t, int edge) const {
  const std::uint32_t l = t.neighbour[edge];
  const Triangle& u = triangles_[triangle_of(l)];
  const int e = edge_of(l);
  int dx = 0, dy = 0;
  frame_offset(t, edge, u, e, dx, dy);
  return {positions_[u.vertex[e]], {(u.shift_x[e] + dx) * domain_.size.x, (u.shift_y[e] + dy) * domain_.size.y}};
}

PeriodicDelaunay::Test PeriodicDelaunay::test_edge(std::uint32_t triangle, int edge) const {
  const Triangle& t = triangles_[triangle];
  const PeriodicPoint d = across_point(t, edge);
  // incircle(a, b, c, d) for any rotation of the corners: the edge's own order does not matter.
  Test r{};
  r.perturbed = incircle_perturbed(corner_point(t, 0), corner_point(t, 1), corner_point(t, 2), d, sites_[t.vertex[0]],
                                   sites_[t.vertex[1]], sites_[t.vertex[2]], across_site(t, edge), r.exact);
  return r;
}

void PeriodicDelaunay::add(const Tally& tally) {
  flips_ += tally.flips;
  tie_edges_ = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(tie_edges_) + tally.tie_edges);
}

void PeriodicDelaunay::set_tie(std::uint32_t triangle, int edge, bool tie, Tally& tally) {
  const std::uint32_t l = triangles_[triangle].neighbour[edge];
  const auto bit = static_cast<std::uint8_t>(1u << edge), other = static_cast<std::uint8_t>(1u << edge_of(l));
  const bool was = (ties_[triangle] & bit) != 0;
  if (was == tie) return;
  tally.tie_edges += tie ? 1 : -1;
  ties_[triangle] = static_cast<std::uint8_t>(tie ? ties_[triangle] | bit : ties_[triangle] & ~bit);
  std::uint8_t& o = ties_[triangle_of(l)];
  o = static_cast<std::uint8_t>(tie ? o | other : o & ~other);
}

bool PeriodicDelaunay::flip(std::uint32_t ti, int k, Tally& tally, bool walk_corners) {
  // t = (a, b, c) with a at corner k; across b-c lies u = (d, c, b) with d at corner e. The
  // quadrilateral a, b, d, c is convex (d lies inside the circle through a, b, c, beyond b-c),
  // so the diagonal a-d replaces b-c: t becomes (a, b, d), u becomes (a, d, c).
  Triangle t = triangles_[ti];
  const std::uint32_t ui = triangle_of(t.neighbour[k]);
  const int e = edge_of(t.neighbour[k]);
  Triangle u = triangles_[ui];
  if (ui == ti) return false;
  int dx = 0, dy = 0;
  frame_offset(t, k, u, e, dx, dy);
  const int kb = next(k), kc = previous(k);
  struct Corner {
    std::uint32_t vertex;
    int sx, sy;
  };
  const Corner a{t.vertex[k], t.shift_x[k], t.shift_y[k]};
  const Corner b{t.vertex[kb], t.shift_x[kb], t.shift_y[kb]};
  const Corner c{t.vertex[kc], t.shift_x[kc], t.shift_y[kc]};
  const Corner d{u.vertex[e], u.shift_x[e] + dx, u.shift_y[e] + dy};
  const PeriodicPoint pa{positions_[a.vertex], {a.sx * domain_.size.x, a.sy * domain_.size.y}};
  const PeriodicPoint pd{positions_[d.vertex], {d.sx * domain_.size.x, d.sy * domain_.size.y}};
  if (!short_edge(pa, pd)) return false;
  const std::uint32_t n_ab = t.neighbour[kc], n_ca = t.neighbour[kb];
  const std::uint32_t n_bd = u.neighbour[next(e)], n_dc = u.neighbour[previous(e)];
  for (std::uint32_t l : {n_ab, n_ca, n_bd, n_dc})
    if (triangle_of(l) == ti || triangle_of(l) == ui) return false;  // a triangulation too small to flip in
  // The corners before the flip, and the neighbour each of a's and d's is associated with.
  const std::uint32_t corner_a = corners_[a.vertex], corner_b = corners_[b.vertex], corner_c = corners_[c.vertex],
                      corner_d = corners_[d.vertex];
  auto associated = [&](std::uint32_t corner) {
    const Triangle& owner = triangles_[triangle_of(corner)];
    return sites_[owner.vertex[previous(edge_of(corner))]];
  };
  const std::uint32_t lowest_a = walk_corners ? 0 : associated(corner_a);
  const std::uint32_t lowest_d = walk_corners ? 0 : associated(corner_d);
  auto make = [&](Triangle& out, const Corner& p, const Corner& q, const Corner& r) {
    out.vertex[0] = p.vertex;
    out.vertex[1] = q.vertex;
    out.vertex[2] = r.vertex;
    const int x[3] = {p.sx, q.sx, r.sx}, y[3] = {p.sy, q.sy, r.sy};
    for (int j = 0; j < 3; ++j) {
      out.shift_x[j] = static_cast<std::int8_t>(x[j] - p.sx);
      out.shift_y[j] = static_cast<std::int8_t>(y[j] - p.sy);
    }
  };
  Triangle& nt = triangles_[ti];
  Triangle& nu = triangles_[ui];
  make(nt, a, b, d);
  make(nu, a, d, c);
  nt.neighbour[0] = n_bd;
  nt.neighbour[1] = link(ui, 2);
  nt.neighbour[2] = n_ab;
  nu.neighbour[0] = n_dc;
  nu.neighbour[1] = n_ca;
  nu.neighbour[2] = link(ti, 1);
  triangles_[triangle_of(n_bd)].neighbour[edge_of(n_bd)] = link(ti, 0);
  triangles_[triangle_of(n_ab)].neighbour[edge_of(n_ab)] = link(ti, 2);
  triangles_[triangle_of(n_dc)].neighbour[edge_of(n_dc)] = link(ui, 0);
  triangles_[triangle_of(n_ca)].neighbour[edge_of(n_ca)] = link(ui, 1);
  if (walk_corners) {
    corners_[a.vertex] = link(ti, 0);
    corners_[b.vertex] = link(ti, 1);
    corners_[d.vertex] = link(ti, 2);
    corners_[c.vertex] = link(ui, 2);
    for (std::uint32_t v : {a.vertex, b.vertex, c.vertex, d.vertex}) canonical_corner(v);
  } else {
    // Each vertex's canonical corner from the one it had (corner_a and the others, read before
    // the rewrite), without walking its star: a gains the neighbour d, d gains a, b loses c and
    // c loses b; a corner's triangle moves only where it was t or u. Only a vertex that lost its
    // lowest neighbour walks. (A corner is associated with the neighbour before it, as in
    // canonical_corner; the sites of a star are distinct.)
    const std::uint32_t sa = sites_[a.vertex], sb = sites_[b.vertex], sc = sites_[c.vertex], sd = sites_[d.vertex];
    corners_[a.vertex] = corner_a == link(ti, k) ? (sd < sc ? link(ti, 0) : link(ui, 0))
                                                 : (sd < lowest_a ? link(ti, 0) : corner_a);
    corners_[d.vertex] = corner_d == link(ui, e) ? (sa < sb ? link(ui, 1) : link(ti, 2))
                                                 : (sa < lowest_d ? link(ui, 1) : corner_d);
    if (corner_b == link(ti, kb)) {
      corners_[b.vertex] = link(ti, 1);
    } else if (corner_b == link(ui, previous(e))) {
      corners_[b.vertex] = link(ti, 1);
      canonical_corner(b.vertex);
    }
    if (corner_c == link(ui, next(e))) {
      corners_[c.vertex] = link(ui, 2);
    } else if (corner_c == link(ti, kc)) {
      corners_[c.vertex] = link(ui, 2);
      canonical_corner(c.vertex);
    }
  }
  // The tie marks of the two triangles start afresh; the outer edges are tested again by the
  // caller, and set them on both sides.
  auto clear_side = [&](std::uint32_t l) {
    std::uint8_t& o = ties_[triangle_of(l)];
    const auto bit = static_cast<std::uint8_t>(1u << edge_of(l));
    if (o & bit) {
      o = static_cast<std::uint8_t>(o & ~bit);
      --tally.tie_edges;
    }
  };
  for (std::uint32_t l : {n_ab, n_ca, n_bd, n_dc}) clear_side(l);
  if (ties_[ti] & (1u << k)) --tally.tie_edges;  // the old diagonal
  ties_[ti] = ties_[ui] = 0;
  ++tally.flips;
  return true;
}

bool PeriodicDelaunay::flip_until_delaunay(std::vector<std::uint32_t>& stack, const Strip& strip, std::size_t cap,
                                           Tally& tally, std::vector<std::uint32_t>& changed,
                                           std::vector<std::uint32_t>& deferred) {
  while (!stack.empty()) {
    const std::uint32_t l = stack.back();
    stack.pop_back();
    const std::uint32_t ti = triangle_of(l);
    const int k = edge_of(l);
    const Triangle& t = triangles_[ti];
    const std::uint32_t across = t.neighbour[k];
    const Triangle& u = triangles_[triangle_of(across)];
    if (!strip.holds(t) || !strip.holds(u)) {
      deferred.push_back(l);
      continue;
    }
    const Test r = test_edge(ti, k);
    if (r.perturbed <= 0) {
      set_tie(ti, k, r.exact == 0, tally);
      continue;
    }
    // A flip rewrites the two triangles and the links and tie marks of the four around them,
    // and walks around vertices of the two: all of it held by the strip when the four are.
    if (!strip.whole()) {
      const int e = edge_of(across);
      if (!strip.holds(triangles_[triangle_of(t.neighbour[next(k)])]) ||
          !strip.holds(triangles_[triangle_of(t.neighbour[previous(k)])]) ||
          !strip.holds(triangles_[triangle_of(u.neighbour[next(e)])]) ||
          !strip.holds(triangles_[triangle_of(u.neighbour[previous(e)])])) {
        deferred.push_back(l);
        continue;
      }
    }
    if (tally.flips >= cap || !flip(ti, k, tally)) return false;
    const std::uint32_t ui = triangle_of(triangles_[ti].neighbour[1]);
    changed.push_back(ti);
    changed.push_back(ui);
    // The new diagonal passes (the flip made it Delaunay); it is a tie when the old one was.
    set_tie(ti, 1, r.exact == 0, tally);
    stack.push_back(link(ui, 1));
    stack.push_back(link(ui, 0));
    stack.push_back(link(ti, 2));
    stack.push_back(link(ti, 0));
  }
  return true;
}

bool PeriodicDelaunay::make_delaunay(std::span<const std::uint32_t> suspects, std::span<const std::uint32_t> tie_edges,
                                     std::vector<std::uint32_t>& changed) {
  flips_ = strip_flips_ = 0;
  if (tie_edges_ > 0) {
    ties_.assign(triangles_.size(), 0);
    tie_edges_ = 0;
  }
  Tally tally;
  for (std::uint32_t l : tie_edges) set_tie(triangle_of(l), edge_of(l), true, tally);
  // Lawson's flips reach the (perturbed) Delaunay triangulation from any triangulation in
  // O(V^2) flips; after a Lloyd step a few per site at most. A cap far above that stops a run
  // that roundings of an input outside the predicates' range would make endless.
  const std::size_t cap = 64 * triangles_.size() + 1024;
  auto finish = [&](bool delaunay) {
    add(tally);
    return delaunay;
  };
  // Vertices are numbered in rows of the plane, so a range of them is a strip about 32 rows of
  // sites high: most flips lie inside one, and strips flip at once. The strips depend on the
  // count only, so the flips' order does too, not on threads. (The Delaunay triangulation reached
  // is unique whatever the order; the order fixes which slot holds which triangle.)
  const std::size_t n = vertex_count();
  const double wanted_size = std::max<double>(kMinStripVertices, 32.0 * std::ceil(std::sqrt(static_cast<double>(n))));
  const auto strips = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(static_cast<double>(n) / wanted_size)));
  const std::size_t strip_size = (n + strips - 1) / strips;  // strips alike, for the threads' shares
  std::vector<std::uint32_t> stack;
  if (strips >= 2 && suspects.size() >= kMinStripSuspects) {
    struct StripRun {
      std::vector<std::uint32_t> stack, changed, deferred;
      Tally tally;
      bool ok = true;
    };
    std::vector<StripRun> runs(strips);
    // Each suspect to the strip of its triangle's first vertex (a strip the triangle has no
    // vertex in could not even read it).
    for (auto it = suspects.rbegin(); it != suspects.rend(); ++it)
      runs[triangles_[triangle_of(*it)].vertex[0] / strip_size].stack.push_back(*it);
    parallel_for(strips, 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        StripRun& run = runs[i];
        const Strip strip{static_cast<std::uint32_t>(i * strip_size),
                          static_cast<std::uint32_t>(std::min(n, (i + 1) * strip_size))};
        run.ok = flip_until_delaunay(run.stack, strip, cap, run.tally, run.changed, run.deferred);
      }
    });
    // What the strips left, on this thread, the first strip's first.
    for (const StripRun& run : runs) {
      if (!run.ok) return finish(false);
      tally += run.tally;
      strip_flips_ += run.tally.flips;
      changed.insert(changed.end(), run.changed.begin(), run.changed.end());
      stack.insert(stack.end(), run.deferred.begin(), run.deferred.end());
    }
    std::reverse(stack.begin(), stack.end());
  } else {
    stack.assign(suspects.rbegin(), suspects.rend());  // the first suspect first
  }
  std::vector<std::uint32_t> none;
  return finish(flip_until_delaunay(stack, Strip{}, cap, tally, changed, none));
}

bool PeriodicDelaunay::valid_at(const Triangle& t, std::span<const Point> positions, std::span<const std::int8_t> shift_x,
                                std::span<const std::int8_t> shift_y) const {
  PeriodicPoint p[3];
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t v = t.vertex[k];
    p[k] = {positions[v], {(t.shift_x[k] + shift_x[v]) * domain_.size.x, (t.shift_y[k] + shift_y[v]) * domain_.size.y}};
  }
  return short_edge(p[0], p[1]) && short_edge(p[1], p[2]) && short_edge(p[2], p[0]) && orientation(p[0], p[1], p[2]) > 0;
}

std::uint32_t PeriodicDelaunay::take_free_triangle() {
  const std::uint32_t t = free_.back();
  free_.pop_back();
  return t;
}

bool PeriodicDelaunay::remove_vertex(std::uint32_t vertex, std::vector<std::uint32_t>& rewritten) {
  std::vector<std::uint32_t> star;
  // Each round flips one edge away from the vertex: its degree falls by one.
  for (int round = 0; round < 1024; ++round) {
    star.clear();
    const std::uint32_t start = corners_[vertex];
    std::uint32_t corner = start;
    do {
      star.push_back(corner);
      corner = next_around(corner);
      if (star.size() > 1024) return false;
    } while (corner != start);
    const std::size_t d = star.size();
    if (d < 3) return false;
    if (d == 3) {
      // The three triangles (v, u0, u1), (v, u1, u2), (v, u2, u0) become (u0, u1, u2).
      std::uint32_t ti[3];
      int j[3];
      Triangle t[3];
      for (int k = 0; k < 3; ++k) {
        ti[k] = triangle_of(star[static_cast<std::size_t>(k)]);
        j[k] = edge_of(star[static_cast<std::size_t>(k)]);
        t[k] = triangles_[ti[k]];
      }
      const std::uint32_t outer[3] = {t[1].neighbour[j[1]], t[2].neighbour[j[2]], t[0].neighbour[j[0]]};
      for (std::uint32_t l : outer)
        if (triangle_of(l) == ti[0] || triangle_of(l) == ti[1] || triangle_of(l) == ti[2]) return false;
      // u2 into t0's frame through the vertex both hold.
      const int dx = t[0].shift_x[j[0]] - t[1].shift_x[j[1]], dy = t[0].shift_y[j[0]] - t[1].shift_y[j[1]];
      Triangle& merged = triangles_[ti[0]];
      merged.vertex[0] = t[0].vertex[next(j[0])];
      merged.vertex[1] = t[0].vertex[previous(j[0])];
      merged.vertex[2] = t[1].vertex[previous(j[1])];
      merged.shift_x[0] = t[0].shift_x[next(j[0])];
      merged.shift_y[0] = t[0].shift_y[next(j[0])];
      merged.shift_x[1] = t[0].shift_x[previous(j[0])];
      merged.shift_y[1] = t[0].shift_y[previous(j[0])];
      merged.shift_x[2] = static_cast<std::int8_t>(t[1].shift_x[previous(j[1])] + dx);
      merged.shift_y[2] = static_cast<std::int8_t>(t[1].shift_y[previous(j[1])] + dy);
      normalise(merged);
      for (int k = 0; k < 3; ++k) {
        merged.neighbour[k] = outer[k];
        triangles_[triangle_of(outer[k])].neighbour[edge_of(outer[k])] = link(ti[0], k);
        corners_[merged.vertex[k]] = link(ti[0], k);
      }
      corners_[vertex] = kNoCorner;
      for (int k = 1; k < 3; ++k) {
        triangles_[ti[k]].vertex[0] = kNoCorner;  // a free slot
        free_.push_back(ti[k]);
      }
      rewritten.push_back(ti[0]);
      return true;
    }
    bool flipped = false;
    for (std::size_t k = 0; k < d && !flipped; ++k) {
      // Triangle (v, u[k-1], u[k]): the edge v-u[k] is opposite u[k-1], u[k+1] lies across it.
      // Flippable when the quadrilateral u[k-1], u[k], u[k+1], v is convex.
      const std::uint32_t corner_before = star[(k + d - 1) % d];
      const std::uint32_t t = triangle_of(corner_before);
      const int jv = edge_of(corner_before);
      const Triangle& tri = triangles_[t];
      const PeriodicPoint v = corner_point(tri, jv), before = corner_point(tri, next(jv)), at = corner_point(tri, previous(jv));
      const PeriodicPoint after = across_point(tri, next(jv));
      if (!short_edge(before, after) || !short_edge(v, after)) continue;
      if (orientation(before, at, after) <= 0 || orientation(v, before, after) <= 0) continue;
      const std::uint32_t other = triangle_of(tri.neighbour[next(jv)]);
      Tally tally;
      if (!flip(t, next(jv), tally, true)) return false;
      add(tally);
      rewritten.push_back(t);
      rewritten.push_back(other);
      flipped = true;
    }
    if (!flipped) return false;
  }
  return false;
}

bool PeriodicDelaunay::insert_vertex(std::uint32_t vertex, std::uint32_t hint) {
  const Point p = positions_[vertex];
  const Point size = domain_.size;
  std::uint32_t t = triangle_of(corners_[hint]);
  // A stochastic walk (Devillers, Pion and Teillaud, "Walking in a triangulation", 2002): the
  // edge tried first is drawn, so the walk ends in any triangulation, not only a Delaunay one.
  // The draws come from a generator seeded with the vertex: the same walk every run.
  std::uint64_t state = 0x9e3779b97f4a7c15ull * (vertex + 1ull);
  int kx = 0, ky = 0;
  for (std::size_t step = 0; step < 4 * triangles_.size() + 64; ++step) {
    const Triangle& tri = triangles_[t];
    // The copy of the vertex nearest to the triangle's first corner (at shift 0), in the
    // triangle's frame. Near all three corners the exact tests decide; farther away (a site
    // that jumped) the walk only needs a direction, which the floating-point turn gives.
    const Point d = positions_[tri.vertex[0]] - p;
    kx = d.x > 0.5 * size.x ? 1 : d.x < -0.5 * size.x ? -1 : 0;
    ky = d.y > 0.5 * size.y ? 1 : d.y < -0.5 * size.y ? -1 : 0;
    const PeriodicPoint q{p, {kx * size.x, ky * size.y}};
    bool near = true;
    for (int k = 0; k < 3; ++k) near &= short_edge(corner_point(tri, k), q);
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const int first = static_cast<int>((state >> 33) % 3);
    int zeros = 0;
    bool moved = false;
    for (int i = 0; i < 3 && !moved; ++i) {
      const int e = (first + i) % 3;
      const PeriodicPoint a = corner_point(tri, next(e)), b = corner_point(tri, previous(e));
      int turn = 0;
      if (near) {
        turn = orientation(a, b, q);
      } else {
        const Point ab = (b.p + b.shift) - (a.p + a.shift), aq = (q.p + q.shift) - (a.p + a.shift);
        const double det = ab.x * aq.y - ab.y * aq.x;
        turn = det > 0.0 ? 1 : det < 0.0 ? -1 : 0;
      }
      zeros += turn == 0;
      if (turn >= 0) continue;
      t = triangle_of(tri.neighbour[e]);
      moved = true;
    }
    if (moved) continue;
    if (zeros > 0 || !near) return false;  // on an edge: left to a rebuild
    // Split t = (a, b, c) into (v, a, b), (v, b, c), (v, c, a).
    const Triangle old = tri;
    const std::uint32_t t1 = take_free_triangle(), t2 = take_free_triangle();
    const std::uint32_t n_ab = old.neighbour[2], n_bc = old.neighbour[0], n_ca = old.neighbour[1];
    for (std::uint32_t l : {n_ab, n_bc, n_ca})
      if (triangle_of(l) == t) return false;
    const std::uint32_t slot[3] = {t, t1, t2};
    const std::uint32_t outer[3] = {n_ab, n_bc, n_ca};
    for (int k = 0; k < 3; ++k) {
      // Triangle k: (v, corner k, corner k + 1) of the old one.
      Triangle& out = triangles_[slot[k]];
      out.vertex[0] = vertex;
      out.vertex[1] = old.vertex[k];
      out.vertex[2] = old.vertex[next(k)];
      out.shift_x[0] = static_cast<std::int8_t>(kx);
      out.shift_y[0] = static_cast<std::int8_t>(ky);
      out.shift_x[1] = old.shift_x[k];
      out.shift_y[1] = old.shift_y[k];
      out.shift_x[2] = old.shift_x[next(k)];
      out.shift_y[2] = old.shift_y[next(k)];
      normalise(out);
      out.neighbour[0] = outer[k];
      out.neighbour[1] = link(slot[next(k)], 2);
      out.neighbour[2] = link(slot[previous(k)], 1);
      triangles_[triangle_of(outer[k])].neighbour[edge_of(outer[k])] = link(slot[k], 0);
      corners_[old.vertex[k]] = link(slot[k], 1);
    }
    corners_[vertex] = link(t, 0);
    return true;
  }
  return false;
}

bool PeriodicDelaunay::repair(std::span<const std::uint32_t> invalid, std::vector<Point>& old_positions,
                              std::span<const Wrap> wraps, std::size_t limit, std::size_t& repaired) {
  const std::size_t n = vertex_count();
  std::vector<std::int8_t> wrap_x(n, 0), wrap_y(n, 0);
  for (const Wrap& w : wraps) {
    wrap_x[w.vertex] = w.kx;
    wrap_y[w.vertex] = w.ky;
  }
  // Back to where the triangulation was valid: the old positions, the copies before the wraps.
  positions_.swap(old_positions);
  for (const Wrap& w : wraps) wrap(w.vertex, -w.kx, -w.ky);
  std::vector<std::uint8_t> removed(n, 0);
  std::vector<std::uint32_t> order, hints, pending, rewritten, written;
  auto take = [&](std::uint32_t v) {
    if (!removed[v]) {
      removed[v] = 1;
      pending.push_back(v);
    }
  };
  for (std::uint32_t t : invalid)
    for (std::uint32_t v : triangles_[t].vertex) take(v);
  while (!pending.empty()) {
    if (order.size() + pending.size() > limit) return false;
    rewritten.clear();
    for (std::uint32_t v : pending) {
      const std::uint32_t c = corners_[v];
      hints.push_back(triangles_[triangle_of(c)].vertex[next(edge_of(c))]);
      if (!remove_vertex(v, rewritten)) return false;
      order.push_back(v);
    }
    pending.clear();
    // The triangles the removals wrote, at the new positions: the vertices of those that fold
    // there go too.
    std::sort(rewritten.begin(), rewritten.end());
    rewritten.erase(std::unique(rewritten.begin(), rewritten.end()), rewritten.end());
    written.insert(written.end(), rewritten.begin(), rewritten.end());
    for (std::uint32_t t : rewritten) {
      const Triangle& tri = triangles_[t];
      if (tri.vertex[0] == kNoCorner) continue;  // freed by a later removal
      if (!valid_at(tri, old_positions, wrap_x, wrap_y))
        for (std::uint32_t v : tri.vertex) take(v);
    }
  }
  // Forward to the new positions, then the removed vertices back in, in the order they went.
  positions_.swap(old_positions);
  for (const Wrap& w : wraps)
    if (!removed[w.vertex]) wrap(w.vertex, w.kx, w.ky);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::uint32_t v = order[i];
    std::uint32_t hint = hints[i];
    // A neighbour that is back already, else the nearest vertex in vertex order that is.
    for (std::size_t step = 1; removed[hint] && step <= 2 * n; ++step) {
      const std::size_t k = (step + 1) / 2;
      hint = static_cast<std::uint32_t>(step % 2 ? (v + k) % n : (v + n - k % n) % n);
    }
    if (removed[hint] || !insert_vertex(v, hint)) return false;
    removed[v] = 0;
    // The three triangles the insertion made (around v).
    std::uint32_t corner = corners_[v];
    for (int k = 0; k < 3; ++k, corner = next_around(corner)) written.push_back(triangle_of(corner));
  }
  ties_.assign(triangles_.size(), 0);
  tie_edges_ = 0;
  // Canonical corners again where a merge or an insertion set them (the removals' flips walk
  // theirs): the vertices of every triangle the repair wrote that is still in use. The others'
  // stars did not change.
  std::vector<std::uint32_t> vertices;
  for (std::uint32_t t : written) {
    const Triangle& tri = triangles_[t];
    if (tri.vertex[0] == kNoCorner) continue;  // a free slot
    vertices.insert(vertices.end(), tri.vertex, tri.vertex + 3);
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  for (std::uint32_t v : vertices) canonical_corner(v);
  repaired = order.size();
  return true;
}

std::size_t PeriodicDelaunay::bytes() const {
  return positions_.capacity() * sizeof(Point) + sites_.capacity() * sizeof(std::uint32_t) +
         triangles_.capacity() * sizeof(Triangle) + corners_.capacity() * sizeof(std::uint32_t) + ties_.capacity();
}

}  // namespace bluetile
