// Weighted polygon moments over a texel grid, by Green's theorem.
//
// For any integrand g, the integral over a counter-clockwise polygon P is -(contour integral of
// G du) with G(u, v) = integral of g(u, t) dt from a reference height up to v (Green's theorem
// with L = G, M = 0). The reference may change from one texel column to the next: split P into
// column strips, and the strips' vertical sides have du = 0. Here the reference is the bottom of
// the lowest texel row the polygon reaches, so within texel (i, r)
//   G(u, v) = C_i(r)(u) + rho(i, r) * integral of g from V_r up to v,
// where C_i(r) sums the full texels of column i below row r, per column in one pass. Along a
// piece of an edge inside one texel, G is a polynomial of degree at most 3 in u for
// g in {1, u, v, u^2 + v^2}, so Simpson's rule integrates it exactly. The cost is one pass over
// the texels of the polygon's bounding box plus a constant per edge piece, instead of clipping
// the polygon by every texel; all coordinates are relative to `origin`, so precision does not
// depend on where the polygon lies.
#include "bluetile/voronoi/density_moments.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "bluetile/core/error.h"
#include "bluetile/voronoi/engine.h"

namespace bluetile {
namespace {

struct Sums {
  double s0 = 0.0, sx = 0.0, sy = 0.0, s2 = 0.0;
};

// What one row of texels of the polygon's bounding box contributes, the same for every column:
// its bottom line V (relative to the origin), where its texels start in the grid, and the
// integrals over its height h of 1, v and v^2 (h, h (V0 + V1) / 2, h (V0^2 + V0 V1 + V1^2) / 3).
struct Row {
  double line;
  std::size_t offset;
  double k0, k1, k2;
};

// The texel columns of the polygon's bounding box while its edges are integrated.
class ColumnIntegrator {
 public:
  ColumnIntegrator(const DensityGrid& density, Point origin, Point texel, long row_begin, long row_end, bool periodic,
                   std::vector<Row>& rows, std::vector<double>& below)
      : density_(density), origin_(origin), texel_(texel), row_begin_(row_begin), row_end_(row_end),
        periodic_(periodic), rows_(rows), below_(below) {
    const std::size_t count = static_cast<std::size_t>(row_end - row_begin + 1);
    rows_.resize(count + 1);
    for (std::size_t r = 0; r <= count; ++r) {
      const long row = row_begin + static_cast<long>(r);
      rows_[r].line = static_cast<double>(row) * texel.y - origin.y;
      rows_[r].offset = static_cast<std::size_t>(index(row, density.height)) * static_cast<std::size_t>(density.width);
    }
    for (std::size_t r = 0; r < count; ++r) {
      const double v0 = rows_[r].line, v1 = rows_[r + 1].line, h = v1 - v0;
      rows_[r].k0 = h;
      rows_[r].k1 = h * 0.5 * (v0 + v1);
      rows_[r].k2 = h * (v0 * v0 + v0 * v1 + v1 * v1) * kThird;
    }
    below_.resize(3 * count);
  }

  // Prepares the full-texel sums of column i below each row of the box.
  void start_column(long i) {
    column_ = density_.texels.data() + index(i, density_.width);
    double k0 = 0.0, k1 = 0.0, k2 = 0.0;
    double* below = below_.data();
    for (std::size_t r = 0; r + 1 < rows_.size(); ++r) {
      below[3 * r] = k0;
      below[3 * r + 1] = k1;
      below[3 * r + 2] = k2;
      const double rho = column_[rows_[r].offset];
      k0 += rho * rows_[r].k0;
      k1 += rho * rows_[r].k1;
      k2 += rho * rows_[r].k2;
    }
  }

  // Adds the integral of G du along the segment (u1, v1) -> (u2, v2), which lies in the column.
  void segment(double u1, double v1, double u2, double v2, Sums& sums) const {
    const long r1 = row_of(v1), r2 = row_of(v2);
    if (r1 == r2) {
      piece(u1, v1, u2, v2, r1, sums);
      return;
    }
    const long step = r2 > r1 ? 1 : -1;
    const double du_dv = (u2 - u1) / (v2 - v1);
    double pu = u1, pv = v1;
    for (long r = r1; r != r2; r += step) {
      const double line = rows_[static_cast<std::size_t>(step > 0 ? r + 1 : r)].line;
      const double qu = u1 + (line - v1) * du_dv;
      piece(pu, pv, qu, line, r, sums);
      pu = qu;
      pv = line;
    }
    piece(pu, pv, u2, v2, r2, sums);
  }

 private:
  static constexpr double kThird = 1.0 / 3.0;

  // A texel index of the grid: wrapped on a torus (the box reaches at most one period beyond
  // it), clamped (against rounding) in a rectangle.
  int index(long i, int size) const {
    if (!periodic_) return static_cast<int>(std::clamp<long>(i, 0, size - 1));
    long m = i % size;
    return static_cast<int>(m < 0 ? m + size : m);
  }

  // The row of the box (0-based) holding height v.
  long row_of(double v) const {
    const long r = static_cast<long>(std::floor((origin_.y + v) / texel_.y));
    return std::clamp(r, row_begin_, row_end_) - row_begin_;
  }

  // Simpson's rule on a piece inside the box's texel row r: exact for G's cubic along a straight piece.
  void piece(double pu, double pv, double qu, double qv, long r, Sums& sums) const {
    const Row& row = rows_[static_cast<std::size_t>(r)];
    const double rho = column_[row.offset];
    const double base = row.line;
    const double* k = below_.data() + 3 * r;
    auto add = [&](double u, double v, double weight) {
      const double d = v - base;
      const double g0 = k[0] + rho * d;
      sums.s0 += weight * g0;
      sums.sx += weight * u * g0;
      sums.sy += weight * (k[1] + rho * d * 0.5 * (v + base));
      sums.s2 += weight * (u * u * g0 + k[2] + rho * d * (v * v + v * base + base * base) * kThird);
    };
    const double w = (qu - pu) / 6.0;
    add(pu, pv, w);
    add(0.5 * (pu + qu), 0.5 * (pv + qv), 4.0 * w);
    add(qu, qv, w);
  }

  const DensityGrid& density_;
  Point origin_, texel_;
  long row_begin_, row_end_;
  bool periodic_;
  std::vector<Row>& rows_;      // the box's rows and the line above its last
  std::vector<double>& below_;  // per row of the current column: the sums of its full texels below
  const float* column_ = nullptr;
};

}  // namespace

WeightedMoments density_moments(std::span<const Point> polygon, Point origin, const DensityGrid& density,
                                Point domain_size, bool periodic) {
  WeightedMoments moments;
  const std::size_t n = polygon.size();
  if (n < 3 || density.empty()) return moments;
  const Point texel{domain_size.x / density.width, domain_size.y / density.height};
  Point lo = polygon[0], hi = polygon[0];
  for (const Point& p : polygon) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  auto texel_of = [](double x, double size) { return static_cast<long>(std::floor(x / size)); };
  const long column_begin = texel_of(origin.x + lo.x, texel.x), column_end = texel_of(origin.x + hi.x, texel.x);
  const long row_begin = texel_of(origin.y + lo.y, texel.y), row_end = texel_of(origin.y + hi.y, texel.y);

  thread_local std::vector<Row> rows;
  thread_local std::vector<double> below;
  ColumnIntegrator integrator(density, origin, texel, row_begin, row_end, periodic, rows, below);
  Sums sums;
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  for (long i = column_begin; i <= column_end; ++i) {
    // The outer columns reach to infinity, so rounding at the box's edge loses no part of an edge.
    const double left = i == column_begin ? -kInfinity : static_cast<double>(i) * texel.x - origin.x;
    const double right = i == column_end ? kInfinity : static_cast<double>(i + 1) * texel.x - origin.x;
    bool started = false;
    for (std::size_t e = 0; e < n; ++e) {
      const Point a = polygon[e], b = polygon[e + 1 == n ? 0 : e + 1];
      if (a.x == b.x) continue;  // du = 0
      const double from = std::max(std::min(a.x, b.x), left), to = std::min(std::max(a.x, b.x), right);
      if (!(from < to)) continue;
      if (!started) {
        integrator.start_column(i);
        started = true;
      }
      const bool rightwards = a.x < b.x;
      const double u1 = rightwards ? from : to, u2 = rightwards ? to : from;
      const double slope = (b.y - a.y) / (b.x - a.x);
      auto height_at = [&](double u) { return u == a.x ? a.y : u == b.x ? b.y : a.y + (u - a.x) * slope; };
      integrator.segment(u1, height_at(u1), u2, height_at(u2), sums);
    }
  }
  moments.mass = -sums.s0;
  moments.first = {-sums.sx, -sums.sy};
  moments.second = -sums.s2;
  return moments;
}

void check_density(const Scene& scene) {
  if (!scene.density) return;
  const DensityGrid& d = *scene.density;
  if (d.width <= 0 || d.height <= 0 || d.texels.size() != static_cast<std::size_t>(d.width) * static_cast<std::size_t>(d.height))
    throw Error("density grid of " + std::to_string(d.width) + " x " + std::to_string(d.height) + " texels holds " +
                std::to_string(d.texels.size()) + " values");
  bool any_positive = false;
  for (std::size_t k = 0; k < d.texels.size(); ++k) {
    const float t = d.texels[k];
    if (!std::isfinite(t) || t < 0.0f)
      throw Error("density texel (" + std::to_string(k % static_cast<std::size_t>(d.width)) + ", " +
                  std::to_string(k / static_cast<std::size_t>(d.width)) + ") is " + std::to_string(t) +
                  ": densities must be finite and non-negative");
    any_positive |= t > 0.0f;
  }
  if (!any_positive) throw Error("the density is zero everywhere: no cell has a centre of mass");
}

bool is_uniform(const DensityGrid& density) {
  return std::all_of(density.texels.begin(), density.texels.end(),
                     [&](float t) { return t == density.texels.front(); });
}

}  // namespace bluetile
