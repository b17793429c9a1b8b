// CGAL reference engines (see cgal_reference.h). GPL code: benchmark only, never in bluetile_lib.
#include "cgal_reference.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Periodic_2_Delaunay_triangulation_2.h>
#include <CGAL/Periodic_2_Delaunay_triangulation_traits_2.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>
#include <CGAL/version.h>

#include "bluetile/core/error.h"

namespace bluetile::bench {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using KPoint = K::Point_2;

using PGt = CGAL::Periodic_2_Delaunay_triangulation_traits_2<K>;
using PVb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, PGt,
                                                         CGAL::Periodic_2_triangulation_vertex_base_2<PGt>>;
using PFb = CGAL::Periodic_2_triangulation_face_base_2<PGt>;
using PeriodicDelaunay = CGAL::Periodic_2_Delaunay_triangulation_2<PGt, CGAL::Triangulation_data_structure_2<PVb, PFb>>;

using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;
using PlainDelaunay = CGAL::Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb>>;

void check_scene(const Scene& scene) {
  if (scene.domain.size != Point{1.0, 1.0}) throw Error("CGAL reference engines support only the unit torus");
  if (scene.sites.size() >= std::numeric_limits<std::uint32_t>::max() / 16) throw Error("too many sites for the CGAL reference");
}

// Site indices in CGAL's spatial (Hilbert) order, so each insertion starts near the last one.
// (The property-map adapter keys on std::size_t, so the indices are that type.)
std::vector<std::size_t> spatial_order(const std::vector<KPoint>& points) {
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  using Traits = CGAL::Spatial_sort_traits_adapter_2<K, CGAL::Pointer_property_map<KPoint>::const_type>;
  CGAL::spatial_sort(order.begin(), order.end(), Traits(CGAL::make_property_map(points)));
  return order;
}

// Circumcentre of triangle a, b, c. Computed relative to the vertex opposite the longest edge:
// the two short edges then carry the digits, which keeps near-coincident sites accurate
// (DESIGN section 4).
Point circumcentre(Point a, Point b, Point c) {
  auto len2 = [](Point d) { return d.x * d.x + d.y * d.y; };
  double la = len2(b - c), lb = len2(c - a), lc = len2(a - b);
  Point o = a, p = b, q = c;
  if (lb >= la && lb >= lc) {
    o = b, p = c, q = a;
  } else if (lc >= la && lc >= lb) {
    o = c, p = a, q = b;
  }
  Point u = p - o, w = q - o;
  double d = 2.0 * (u.x * w.y - u.y * w.x);
  double uu = len2(u), ww = len2(w);
  return o + Point{(w.y * uu - u.y * ww) / d, (u.x * ww - w.x * uu) / d};
}

// Area, centroid and second moment of a polygon given relative to its site, counter-clockwise.
Cell measure_polygon(const std::vector<Point>& polygon, Point site) {
  double a2 = 0.0, cx = 0.0, cy = 0.0, moment = 0.0;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    Point p = polygon[i], q = polygon[i + 1 == n ? 0 : i + 1];
    double cross = p.x * q.y - q.x * p.y;
    a2 += cross;
    cx += (p.x + q.x) * cross;
    cy += (p.y + q.y) * cross;
    moment += (p.x * p.x + p.x * q.x + q.x * q.x + p.y * p.y + p.y * q.y + q.y * q.y) * cross;
  }
  Cell cell;
  cell.area = 0.5 * a2;
  cell.mass = cell.area;
  Point offset = a2 > 0.0 ? Point{cx / (3.0 * a2), cy / (3.0 * a2)} : Point{0.0, 0.0};
  cell.centroid = wrap_point(site + offset, Domain{});
  cell.second_moment = moment / 12.0;
  return cell;
}

// Every wanted cell starts as "coincident" (centroid = site); owners are overwritten later.
void init_cells(const Scene& scene, SceneCells& out) {
  out.cells.assign(scene.wanted_count(), Cell{});
  for (std::size_t i = 0; i < scene.wanted_count(); ++i) {
    out.cells[i].centroid = scene.sites[scene.wanted_begin + i];
    out.cells[i].status = CellStatus::coincident;
  }
  out.fallback_count = 0;
}

void count_coincident(SceneCells& out) {
  out.coincident_count = 0;
  for (const Cell& c : out.cells) out.coincident_count += c.status == CellStatus::coincident;
}

void compute_periodic(const Scene& scene, SceneCells& out) {
  check_scene(scene);
  init_cells(scene, out);
  const std::size_t n = scene.sites.size();
  if (n == 0) return;
  std::vector<KPoint> points(n);
  for (std::size_t i = 0; i < n; ++i) points[i] = KPoint(scene.sites[i].x, scene.sites[i].y);

  PeriodicDelaunay tri;
  // One insert per point (DESIGN section 4: CGAL 5.5's range insert with info can drop points
  // silently); a coincident point returns the existing vertex, whose owner is the lowest index.
  PeriodicDelaunay::Face_handle hint;
  for (std::size_t k : spatial_order(points)) {
    const auto i = static_cast<std::uint32_t>(k);
    std::size_t before = tri.number_of_vertices();
    PeriodicDelaunay::Vertex_handle v = tri.insert(points[i], hint);
    if (tri.number_of_vertices() > before) {
      v->info() = i;
    } else {
      v = tri.get_original_vertex(v);
      v->info() = std::min(v->info(), i);
    }
    hint = v->face();
  }

  std::vector<Point> polygon;
  for (auto vit = tri.unique_vertices_begin(); vit != tri.unique_vertices_end(); ++vit) {
    PeriodicDelaunay::Vertex_handle v = vit;
    const std::uint32_t site = v->info();
    if (site < scene.wanted_begin || site >= scene.wanted_end) continue;
    if (n == 1) {  // CGAL's lone vertex has no faces: its cell is the whole torus
      out.cells[0] = measure_polygon({{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}}, scene.sites[0]);
      continue;
    }
    polygon.clear();
    auto fc = tri.incident_faces(v), done = fc;
    do {
      int k = fc->index(v);
      // This face's copy of v can carry an offset: take every vertex relative to it.
      KPoint pv = tri.point(fc, k);
      Point origin{pv.x(), pv.y()};
      Point corner[3];
      for (int j = 0; j < 3; ++j) {
        KPoint p = tri.point(fc, j);
        corner[j] = Point{p.x(), p.y()} - origin;
      }
      polygon.push_back(circumcentre(corner[0], corner[1], corner[2]));
    } while (++fc != done);
    out.cells[site - scene.wanted_begin] = measure_polygon(polygon, scene.sites[site]);
  }
  count_coincident(out);
}

// Periodic copies of the sites that lie in the box [-w, 1+w)^2 but not in [-inner, 1+inner)^2.
void add_replicas(const Scene& scene, double inner, double w, std::vector<KPoint>& points) {
  auto inside = [](Point c, double b) { return c.x >= -b && c.x < 1.0 + b && c.y >= -b && c.y < 1.0 + b; };
  for (const Point s : scene.sites)
    for (int oy = -1; oy <= 1; ++oy)
      for (int ox = -1; ox <= 1; ++ox) {
        Point c{s.x + ox, s.y + oy};
        if ((ox != 0 || oy != 0) && inside(c, w) && !inside(c, inner)) points.emplace_back(c.x, c.y);
      }
}

// The band method. Starts with width `w`; while some circumcircle around a wanted site leaves
// the replicated box (a site outside it, never inserted, could lie inside that circle), doubles
// w and inserts the new ring of copies into the same triangulation. Returns false when even
// w = 1 (all eight neighbouring copies) cannot certify the cells: only tiny N.
bool compute_band(const Scene& scene, SceneCells& out, double& w, int& widenings) {
  const std::size_t n = scene.sites.size();
  PlainDelaunay tri;
  std::vector<KPoint> points;
  points.reserve(n);
  for (const Point s : scene.sites) points.emplace_back(s.x, s.y);
  add_replicas(scene, -1.0, w, points);  // inner = -1: every copy in the box is new

  PlainDelaunay::Face_handle hint;
  auto insert_all = [&](bool with_originals) {
    for (std::size_t k : spatial_order(points)) {
      std::size_t before = tri.number_of_vertices();
      PlainDelaunay::Vertex_handle v = tri.insert(points[k], hint);
      const bool original = with_originals && k < n;
      if (tri.number_of_vertices() > before) {
        v->info() = original ? static_cast<std::uint32_t>(k) : std::numeric_limits<std::uint32_t>::max();
      } else if (original) {
        v->info() = std::min(v->info(), static_cast<std::uint32_t>(k));  // copies never meet originals
      }
      hint = v->face();
    }
  };
  insert_all(true);

  std::vector<Point> polygon;
  for (;;) {
    const double lo = -w, hi = 1.0 + w;
    bool certified = n > 1;  // a lone site has no triangles; the caller falls back
    // Vertices in storage (spatial) order: site order would miss the cache at large N.
    for (auto vit = tri.finite_vertices_begin(); certified && vit != tri.finite_vertices_end(); ++vit) {
      PlainDelaunay::Vertex_handle v = vit;
      const std::size_t site = v->info();  // the lowest index among coincident sites
      if (site < scene.wanted_begin || site >= scene.wanted_end) continue;  // copies are max()
      const Point origin = scene.sites[site];
      polygon.clear();
      auto fc = tri.incident_faces(v), done = fc;
      do {
        if (tri.is_infinite(fc)) {
          certified = false;
          break;
        }
        Point corner[3];
        for (int j = 0; j < 3; ++j) {
          const KPoint& p = fc->vertex(j)->point();
          corner[j] = Point{p.x(), p.y()} - origin;
        }
        Point c = circumcentre(corner[0], corner[1], corner[2]);
        Point to_corner = corner[0] - c;
        double r = std::sqrt(to_corner.x * to_corner.x + to_corner.y * to_corner.y);
        Point ca = origin + c;
        if (ca.x - r < lo || ca.x + r > hi || ca.y - r < lo || ca.y + r > hi) {
          certified = false;
          break;
        }
        polygon.push_back(c);
      } while (++fc != done);
      if (certified) out.cells[site - scene.wanted_begin] = measure_polygon(polygon, origin);
    }
    if (certified) return true;
    if (w >= 1.0) return false;
    const double wider = std::min(1.0, 2.0 * w);
    points.clear();
    add_replicas(scene, w, wider, points);
    insert_all(false);
    w = wider;
    ++widenings;
  }
}

}  // namespace

void CgalPeriodicEngine::compute(std::span<const Scene> scenes, std::span<SceneCells> out) {
  for (std::size_t i = 0; i < scenes.size(); ++i) compute_periodic(scenes[i], out[i]);
}

void CgalBandEngine::compute(std::span<const Scene> scenes, std::span<SceneCells> out) {
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const Scene& scene = scenes[i];
    check_scene(scene);
    init_cells(scene, out[i]);
    if (scene.sites.empty()) continue;
    // 4/sqrt(N) is about twice the largest circumradius of uniform random sites up to 10^6, so
    // one pass usually certifies; the copies cost about 16 sqrt(N) extra points.
    double w = std::min(1.0, 4.0 / std::sqrt(static_cast<double>(scene.sites.size())));
    int widenings = 0;
    if (!compute_band(scene, out[i], w, widenings)) {
      // Only tiny N get here (a full ring of copies cannot certify them): use the periodic
      // triangulation instead, which handles any N.
      compute_periodic(scene, out[i]);
    }
    count_coincident(out[i]);
    last_band_width_ = w;
    last_widenings_ = widenings;
  }
}

std::string cgal_version() { return CGAL_VERSION_STR; }

}  // namespace bluetile::bench
