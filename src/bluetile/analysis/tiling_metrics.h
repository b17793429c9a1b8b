// Figures of merit of a tiled plane, defined so that they compare with the literature (the
// definitions of docs/RESULTS.md, "Wang tiles"; periodogram conventions of psa, docs/DESIGN.md
// section 5). For N points on the unit torus:
//  - rho: the global minimum nearest-neighbour distance over the hexagonal spacing
//    sqrt(2 / (sqrt(3) N)) (Lagae and Dutré's relative radius, psa's global mindist);
//  - LF: the mean periodogram over integer k with 0 < |k| < 0.5 sqrt(N) (white noise 1);
//  - lattice coherence of an M x M tiling of a T-tile set, at the tile lattice frequencies
//    k = M m: C_LF = max over 0 < |m|^2 <= 5 of P(M m) / (M^2 / T), and C_mid = max of the same
//    over 0.5 sqrt(N) <= |k| < 1.5 sqrt(N) (P(M m) M^2 / T is |sum over the T tiles' points of
//    exp(-2 pi i m.x)|^2 / (T n) when every tile occurs equally often);
//  - tile-lattice peak: the mean of P(M m) over 0 < |M m| < sqrt(N) (untiled sets about 1);
//  - diffuse anisotropy: the mean over width-1 annuli with 0.5 sqrt(N) <= |k| < 1.6 sqrt(N) of the
//    annulus anisotropy in dB, the lattice frequencies left out (annuli of fewer than two
//    frequencies, or of no variance, too).
// Each is NaN (undefined, not 0: an empty band has no mean or maximum) where its band holds no
// frequency: LF for N <= 4; C_LF, C_mid and the peak for an untiled set, the peak for one point a
// tile (|m| < 1 holds no m); the anisotropy when every annulus is left out (a 1 x 1 tiling: every
// frequency is a lattice one).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "bluetile/analysis/periodogram.h"
#include "bluetile/core/torus.h"

namespace bluetile {

// The bands above, for frequencies k with |k|^2 = k2 and N = count points, in integers, so that
// a frequency on a band's edge falls on the same side for every user. The Wang loop's lattice
// objective (relax/wang_lattice.h) aims at the same bands in tile units (k = M m and N = n M^2,
// so k2 / N = m2 / n): its points per tile n and |m|^2 serve as count and k2.
inline bool in_low_band(std::int64_t k2, std::size_t count) {  // 0 < |k| < 0.5 sqrt(N)
  return k2 > 0 && 4 * k2 < static_cast<std::int64_t>(count);
}
inline bool in_mid_band(std::int64_t k2, std::size_t count) {  // 0.5 sqrt(N) <= |k| < 1.5 sqrt(N)
  return 4 * k2 >= static_cast<std::int64_t>(count) && 4 * k2 < 9 * static_cast<std::int64_t>(count);
}
inline bool in_coherence_low_band(std::int64_t m2) { return m2 > 0 && m2 <= 5; }  // C_LF's 0 < |m|^2 <= 5

struct TilingMetrics {
  std::size_t count = 0;  // N
  double rho = 0.0;
  // NaN where the band is empty (above): LF for N <= 4, the lattice measures of an untiled set.
  double low_frequency = 0.0;       // LF
  double coherence_low = 0.0;       // C_LF
  double coherence_mid = 0.0;       // C_mid
  double lattice_peak = 0.0;        // mean P over k = M m, 0 < |k| < sqrt(N)
  double diffuse_anisotropy_db = 0.0;
};

// The periodogram (periodogram.h's conventions) of a period x period torus tiling scaled to the
// unit torus: cell (i, j) holds tile cell_tiles[j * period + i], whose points tile_points[t] are
// tile-local in [0,1)^2. Computed per tile, S(k) = sum over tiles t of F_t(k / M) G_t(k), with
// F_t(q) = sum over the tile's points of exp(-2 pi i q.x) and G_t(k) = sum over the cells holding
// t of exp(-2 pi i k.c / M): about T n F^2 operations instead of M^2 n F^2 for the direct sum,
// the same values to rounding. Throws Error on bad arguments.
Periodogram tiled_periodogram(std::span<const std::vector<Point>> tile_points, std::span<const int> cell_tiles,
                              int period, int size);

// The smallest periodogram size that holds every frequency the metrics use.
int tiling_metrics_periodogram_size(std::size_t count);

// Metrics of `points` (N >= 2, unit torus) from their periodogram (at least
// tiling_metrics_periodogram_size(N) wide). `period` M and `tile_count` T describe the tiling;
// period 0 means an untiled set (no lattice frequencies: C_LF, C_mid and the peak NaN). Throws
// Error when the periodogram is too small.
TilingMetrics measure_tiling(std::span<const Point> points, const Periodogram& periodogram, int period, int tile_count);

// The same, computing the periodogram: by the direct sum for an untiled set (period 0).
TilingMetrics measure_tiling(std::span<const Point> points, int period, int tile_count);

// The periodogram size measure_tiling uses for N points and a period M.
int tiling_periodogram_size(std::size_t count, int period);

// The prefix sweep of a progressive tile set of `top` points per tile (docs/RESULTS.md, "Every prefix"): k at 1/16, 3/32,
// 1/8, 3/16, 1/4, 3/8, 1/2, 3/4 and 1 of the top count, rounded, and every level boundary in
// `boundaries`; sorted, distinct, each at least 1.
std::vector<std::size_t> prefix_sweep(std::size_t top, std::span<const std::size_t> boundaries);

// rho alone (minimum nearest-neighbour distance on the torus / hexagonal spacing).
double relative_min_distance(std::span<const Point> points);

}  // namespace bluetile
