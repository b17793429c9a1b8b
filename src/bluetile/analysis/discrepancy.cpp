// L2 discrepancies by their closed forms (Hickernell 1998, sections 3 and 5; Zhou, Fang and Ning
// 2013, equation 3.8 for the mixture discrepancy; scipy.stats.qmc.discrepancy's documented
// conventions), in dimension 2:
//   CD^2 = (13/12)^2 - 2/N sum_i prod_k (1 + |z_ik|/2 - z_ik^2/2)
//          + 1/N^2 sum_ij prod_k (1 + |z_ik|/2 + |z_jk|/2 - |x_ik - x_jk|/2),   z = x - 1/2
//   WD^2 = -(4/3)^2 + 1/N^2 sum_ij prod_k (3/2 - |d| (1 - |d|)),                 d = x_ik - x_jk
//   MD^2 = (19/12)^2 - 2/N sum_i prod_k (5/3 - |z_ik|/4 - z_ik^2/4)
//          + 1/N^2 sum_ij prod_k (15/8 - |z_ik|/4 - |z_jk|/4 - 3|d|/4 + d^2/2)
//   L2*^2 = 3^-2 - 2^-1/N sum_i prod_k (1 - x_ik^2) + 1/N^2 sum_ij prod_k (1 - max(x_ik, x_jk))
#include "bluetile/analysis/discrepancy.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace {

struct Sums {
  double centred = 0.0, wrap_around = 0.0, mixture = 0.0, l2_star = 0.0;
};

}  // namespace

double discrepancy_pairs(std::size_t count) {
  const double n = static_cast<double>(count);
  return n * (n + 1.0) / 2.0;
}

Discrepancies discrepancies(std::span<const Point> points) {
  if (points.empty()) throw Error("discrepancy of an empty point set");
  const std::size_t n = points.size();
  // The closed forms hold for [0, 1]^2: a NaN made every figure NaN, a point outside gave figures
  // of no set.
  check_finite_points(points, "discrepancies");
  for (std::size_t i = 0; i < n; ++i) {
    const Point p = points[i];
    if (!(p.x >= 0.0 && p.x <= 1.0 && p.y >= 0.0 && p.y <= 1.0))
      throw Error("discrepancies: point " + std::to_string(i) + " (" + shortest_text(p.x) + ", " + shortest_text(p.y) +
                  ") lies outside [0, 1]^2");
  }
  // Coordinates apart, so that the inner loop streams through plain arrays.
  std::vector<double> x(n), y(n), zx(n), zy(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = points[i].x;
    y[i] = points[i].y;
    zx[i] = std::abs(x[i] - 0.5);
    zy[i] = std::abs(y[i] - 0.5);
  }
  // Row i's sum over j >= i (the pairs j > i twice, by symmetry), written only by the chunk that
  // owns row i, in kLanes interleaved partial sums (independent chains the processor overlaps)
  // added in a fixed order; the rows are added in order afterwards.
  constexpr std::size_t kLanes = 4;
  std::vector<Sums> rows(n);
  parallel_for(n, 16, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const double xa = x[i], ya = y[i];
      const double ca = 1.0 + 0.5 * zx[i], cb = 1.0 + 0.5 * zy[i];
      const double ma = 15.0 / 8.0 - 0.25 * zx[i], mb = 15.0 / 8.0 - 0.25 * zy[i];
      double c[kLanes] = {}, w[kLanes] = {}, m[kLanes] = {}, l[kLanes] = {};
      auto add = [&](std::size_t lane, std::size_t j) {
        const double dx = std::abs(xa - x[j]), dy = std::abs(ya - y[j]);
        c[lane] += (ca + 0.5 * zx[j] - 0.5 * dx) * (cb + 0.5 * zy[j] - 0.5 * dy);
        w[lane] += (1.5 - dx * (1.0 - dx)) * (1.5 - dy * (1.0 - dy));
        m[lane] += (ma - 0.25 * zx[j] - 0.75 * dx + 0.5 * dx * dx) * (mb - 0.25 * zy[j] - 0.75 * dy + 0.5 * dy * dy);
        l[lane] += (1.0 - std::max(xa, x[j])) * (1.0 - std::max(ya, y[j]));
      };
      std::size_t j = i + 1;
      for (; j + kLanes <= n; j += kLanes)
        for (std::size_t lane = 0; lane < kLanes; ++lane) add(lane, j + lane);
      for (std::size_t lane = 0; j < n; ++j, ++lane) add(lane, j);
      auto total = [](const double* v) { return (v[0] + v[1]) + (v[2] + v[3]); };
      Sums row;
      row.centred = 2.0 * total(c);
      row.wrap_around = 2.0 * total(w);
      row.mixture = 2.0 * total(m);
      row.l2_star = 2.0 * total(l);
      // The pair (i, i): d = 0.
      row.centred += (ca + 0.5 * zx[i]) * (cb + 0.5 * zy[i]);
      row.wrap_around += 1.5 * 1.5;
      row.mixture += (ma - 0.25 * zx[i]) * (mb - 0.25 * zy[i]);
      row.l2_star += (1.0 - xa) * (1.0 - ya);
      rows[i] = row;
    }
  });
  Sums pairs, single;
  for (std::size_t i = 0; i < n; ++i) {
    pairs.centred += rows[i].centred;
    pairs.wrap_around += rows[i].wrap_around;
    pairs.mixture += rows[i].mixture;
    pairs.l2_star += rows[i].l2_star;
    single.centred += (1.0 + 0.5 * zx[i] - 0.5 * zx[i] * zx[i]) * (1.0 + 0.5 * zy[i] - 0.5 * zy[i] * zy[i]);
    single.mixture += (5.0 / 3.0 - 0.25 * zx[i] - 0.25 * zx[i] * zx[i]) * (5.0 / 3.0 - 0.25 * zy[i] - 0.25 * zy[i] * zy[i]);
    single.l2_star += (1.0 - x[i] * x[i]) * (1.0 - y[i] * y[i]);
  }
  const double count = static_cast<double>(n), n2 = count * count;
  Discrepancies d;
  d.centred = (13.0 / 12.0) * (13.0 / 12.0) - 2.0 / count * single.centred + pairs.centred / n2;
  d.wrap_around = -(4.0 / 3.0) * (4.0 / 3.0) + pairs.wrap_around / n2;
  d.mixture = (19.0 / 12.0) * (19.0 / 12.0) - 2.0 / count * single.mixture + pairs.mixture / n2;
  // Rounding can take a discrepancy of a near-perfect set a hair below 0: it is 0.
  d.l2_star = std::sqrt(std::max(0.0, 1.0 / 9.0 - 0.5 / count * single.l2_star + pairs.l2_star / n2));
  return d;
}

}  // namespace bluetile
