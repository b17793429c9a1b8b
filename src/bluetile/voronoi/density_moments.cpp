// Weighted polygon moments over a texel grid, by Green's theorem.
//
// For any integrand g, the integral over a counter-clockwise polygon P is -(contour integral of
// G du) with G(u, v) = integral of g(u, t) dt from a reference height up to v (Green's theorem
// with L = G, M = 0). The reference may change from one texel column to the next: split P into
// column strips, and the strips' vertical sides have du = 0. Everything runs in a frame of
// texel units whose origin is the lower-left corner of the polygon's bounding box of texels,
// the reference being that box's bottom, so within box texel (c, r)
//   G(u, v) = K(c, r) + rho(c, r) * integral of g from r up to v,
// where K(c, r) sums the full texels of column c below row r. One pass over the box's rows
// (the grid's storage order) builds K; then each edge is cut at the column and row lines it
// crosses, and along a piece inside one texel G is a polynomial of degree at most 3 in u for
// g in {1, u, v, u^2, v^2}: its integral is a closed form of the piece's two ends. The cost is
// the box's texels once plus a constant per edge piece; coordinates relative to the box keep
// precision independent of where the polygon lies, and the moments are moved to `origin` at
// the end.
#include "bluetile/voronoi/density_moments.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "bluetile/core/error.h"
#include "bluetile/core/text.h"
#include "bluetile/voronoi/engine.h"

namespace bluetile {
namespace {

// Contour integrals of G du for g = 1, u, v, u^2 and v^2 (texel units).
struct Sums {
  double s0 = 0.0, su = 0.0, sv = 0.0, suu = 0.0, svv = 0.0;
};

// A texel of the box: its density and K for g = 1, v, v^2 (the full texels below it).
struct BoxTexel {
  double rho, k0, k1, k2;
};

// The box of texels is processed in bands of columns so that its table stays small however
// large a cell is (a cell of a few sites can span the whole grid).
constexpr long kBandTexels = 1L << 16;

// A texel index of the grid: wrapped on a torus (the box reaches at most one period beyond
// it), clamped (against rounding) in a rectangle.
long grid_index(long i, int size, bool periodic) {
  if (!periodic) return std::clamp<long>(i, 0, size - 1);
  const long m = i % size;
  return m < 0 ? m + size : m;
}

// Adds the piece (u1, r + d1) -> (u2, r + d2), inside a texel of row r (0 <= d <= 1 up to
// rounding): the exact integrals of G du along it.
inline void add_piece(const BoxTexel& t, double r, double u1, double d1, double u2, double d2, Sums& s) {
  const double du = u2 - u1;
  const double g1 = t.k0 + t.rho * d1, g2 = t.k0 + t.rho * d2;  // G for g = 1 at the ends
  const double d_mean = 0.5 * (d1 + d2);
  const double d2_mean = (d1 * d1 + d1 * d2 + d2 * d2) * (1.0 / 3.0);
  const double d3_mean = 0.25 * (d1 + d2) * (d1 * d1 + d2 * d2);
  const double u_mid = 0.5 * (u1 + u2);
  s.s0 += du * (t.k0 + t.rho * d_mean);
  s.su += du * (1.0 / 6.0) * (u1 * (2.0 * g1 + g2) + u2 * (g1 + 2.0 * g2));
  s.sv += du * (t.k1 + t.rho * (r * d_mean + 0.5 * d2_mean));
  s.svv += du * (t.k2 + t.rho * (r * (r * d_mean + d2_mean) + d3_mean * (1.0 / 3.0)));
  s.suu += du * (1.0 / 6.0) * (u1 * u1 * g1 + 2.0 * u_mid * u_mid * (g1 + g2) + u2 * u2 * g2);  // Simpson
}

}  // namespace

TexelFrame texel_frame(std::span<const Point> polygon, Point origin, const DensityGrid& density, Point domain_size,
                       std::vector<Point>& vertices) {
  TexelFrame f;
  f.texel = {domain_size.x / density.width, domain_size.y / density.height};
  Point lo = polygon[0];
  for (const Point& p : polygon) lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
  f.column = static_cast<long>(std::floor((origin.x + lo.x) / f.texel.x));
  f.row = static_cast<long>(std::floor((origin.y + lo.y) / f.texel.y));
  f.site = {origin.x - static_cast<double>(f.column) * f.texel.x, origin.y - static_cast<double>(f.row) * f.texel.y};
  vertices.resize(polygon.size());
  Point hi{0.0, 0.0};
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    vertices[k] = {(f.site.x + polygon[k].x) / f.texel.x, (f.site.y + polygon[k].y) / f.texel.y};
    hi = {std::max(hi.x, vertices[k].x), std::max(hi.y, vertices[k].y)};
  }
  f.columns = static_cast<long>(hi.x) + 1;
  f.rows = static_cast<long>(hi.y) + 1;
  return f;
}

WeightedMoments density_moments(std::span<const Point> polygon, Point origin, const DensityGrid& density,
                                Point domain_size, bool periodic) {
  WeightedMoments moments;
  const std::size_t n = polygon.size();
  if (n < 3 || density.empty()) return moments;
  thread_local std::vector<Point> frame;
  const TexelFrame box = texel_frame(polygon, origin, density, domain_size, frame);
  const Point texel = box.texel, site = box.site;
  const long c0 = box.column, r0 = box.row, columns = box.columns, rows = box.rows;
  const long band_columns = std::max(1L, kBandTexels / rows);

  thread_local std::vector<std::size_t> row_start;
  thread_local std::vector<BoxTexel> table;  // column by column, `rows` texels each
  row_start.resize(static_cast<std::size_t>(rows));
  for (long r = 0; r < rows; ++r)
    row_start[static_cast<std::size_t>(r)] =
        static_cast<std::size_t>(grid_index(r0 + r, density.height, periodic)) * static_cast<std::size_t>(density.width);
  Sums sums;
  for (long band = 0; band < columns; band += band_columns) {
    const long band_end = std::min(columns, band + band_columns);
    const long width = band_end - band;
    // K for the band's columns, row by row as the grid is stored.
    table.resize(static_cast<std::size_t>(width * rows));
    for (long c = 0; c < width; ++c) {
      const long column = grid_index(c0 + band + c, density.width, periodic);
      double k0 = 0.0, k1 = 0.0, k2 = 0.0;
      BoxTexel* t = table.data() + c * rows;
      for (long r = 0; r < rows; ++r) {
        const double rho = density.texels[row_start[static_cast<std::size_t>(r)] + static_cast<std::size_t>(column)];
        const double rd = static_cast<double>(r);
        t[r] = {rho, k0, k1, k2};
        k0 += rho;
        k1 += rho * (rd + 0.5);
        k2 += rho * (rd * rd + rd + 1.0 / 3.0);
      }
    }
    // Each edge, cut by the band's column lines, then by the row lines.
    constexpr double kFar = std::numeric_limits<double>::infinity();
    for (std::size_t e = 0; e < n; ++e) {
      const Point a = frame[e], b = frame[e + 1 == n ? 0 : e + 1];
      if (a.x == b.x) continue;  // du = 0
      const bool rightwards = a.x < b.x;
      const Point left_end = rightwards ? a : b, right_end = rightwards ? b : a;
      const long c_first = std::max(band, std::min(static_cast<long>(left_end.x), columns - 1));
      const long c_last = std::min(band_end - 1, std::max(0L, static_cast<long>(right_end.x)));
      if (c_first > c_last) continue;
      const double slope = (right_end.y - left_end.y) / (right_end.x - left_end.x);
      const double du_dv = (right_end.x - left_end.x) / (right_end.y - left_end.y);  // where it crosses rows
      auto height_at = [&](double u) { return left_end.y + (u - left_end.x) * slope; };
      for (long c = c_first; c <= c_last; ++c) {
        // The box's outer columns reach to infinity, so rounding loses no part of an edge.
        const double lu = c == 0 ? -kFar : static_cast<double>(c), ru = c == columns - 1 ? kFar : static_cast<double>(c + 1);
        const double from = std::max(left_end.x, lu), to = std::min(right_end.x, ru);
        if (!(from < to)) continue;
        const double pu = from == left_end.x ? left_end.x : from, pv = from == left_end.x ? left_end.y : height_at(from);
        const double qu = to == right_end.x ? right_end.x : to, qv = to == right_end.x ? right_end.y : height_at(to);
        // From (pu, pv) to (qu, qv), rows split; pieces oriented as the polygon runs. A piece
        // ending exactly on a row line has length 0 in the next row.
        const BoxTexel* column = table.data() + (c - band) * rows;
        long r = std::clamp(static_cast<long>(pv), 0L, rows - 1);
        const long r_end = std::clamp(static_cast<long>(qv), 0L, rows - 1);
        auto piece = [&](double u1, double v1, double u2, double v2, long row) {
          const double base = static_cast<double>(row);
          if (rightwards) {
            add_piece(column[row], base, u1, v1 - base, u2, v2 - base, sums);
          } else {
            add_piece(column[row], base, u2, v2 - base, u1, v1 - base, sums);
          }
        };
        double su = pu, sv = pv;
        const long step = r_end > r ? 1 : -1;
        for (; r != r_end; r += step) {
          const double line = static_cast<double>(step > 0 ? r + 1 : r);
          const double u = left_end.x + (line - left_end.y) * du_dv;
          piece(su, sv, u, line, r);
          su = u;
          sv = line;
        }
        piece(su, sv, qu, qv, r);
      }
    }
  }
  // Back to domain units, moments about the box's corner, then about `origin` (x - site).
  const double area = texel.x * texel.y;
  moments.mass = -sums.s0 * area;
  const Point first{-sums.su * area * texel.x, -sums.sv * area * texel.y};
  const double second = -(sums.suu * texel.x * texel.x + sums.svv * texel.y * texel.y) * area;
  moments.first = first - moments.mass * site;
  moments.second = second - 2.0 * (first.x * site.x + first.y * site.y) + moments.mass * (site.x * site.x + site.y * site.y);
  return moments;
}

void check_density(const Scene& scene) {
  if (!scene.density) return;
  if (!check_density_grid(*scene.density)) throw Error("the density is zero everywhere: no cell has a centre of mass");
}

bool is_uniform(const DensityGrid& density) {
  return std::all_of(density.texels.begin(), density.texels.end(),
                     [&](float t) { return t == density.texels.front(); });
}

}  // namespace bluetile
