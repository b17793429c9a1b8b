// Figures of merit of tiled planes (see tiling_metrics.h for the definitions).
#include "bluetile/analysis/tiling_metrics.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"

namespace bluetile {
namespace {

// The end of the anisotropy's band, in units of sqrt(N) (the LF and mid bands: tiling_metrics.h).
constexpr double kAnisotropyBandEnd = 1.6;

}  // namespace

int tiling_metrics_periodogram_size(std::size_t count) {
  const double root = std::sqrt(static_cast<double>(count));
  return 2 * (static_cast<int>(std::ceil(kAnisotropyBandEnd * root)) + 2);
}

std::vector<std::size_t> prefix_sweep(std::size_t top, std::span<const std::size_t> boundaries) {
  std::vector<std::size_t> sweep;
  for (int in_32nds : {2, 3, 4, 6, 8, 12, 16, 24, 32}) {
    const auto k = static_cast<std::size_t>(std::llround(static_cast<double>(top) * in_32nds / 32.0));
    if (k >= 1) sweep.push_back(k);
  }
  for (std::size_t b : boundaries)
    if (b >= 1 && b <= top) sweep.push_back(b);
  std::sort(sweep.begin(), sweep.end());
  sweep.erase(std::unique(sweep.begin(), sweep.end()), sweep.end());
  return sweep;
}

double relative_min_distance(std::span<const Point> points) {
  NearestNeighbourStats nn = nearest_neighbour_stats(std::vector<Point>(points.begin(), points.end()));
  return nn.min / nn.hexagonal_spacing;
}

TilingMetrics measure_tiling(std::span<const Point> points, const Periodogram& periodogram, int period, int tile_count) {
  if (points.size() < 2) throw Error("tiling metrics need at least 2 points");
  const double n = static_cast<double>(points.size());
  const double root = std::sqrt(n);
  const int half = periodogram.half();
  const int needed = tiling_metrics_periodogram_size(points.size());
  if (periodogram.size < needed || (period > 0 && 2 * period >= half))
    throw Error("periodogram of size " + std::to_string(periodogram.size) + " too small for the tiling metrics of " +
                std::to_string(points.size()) + " points");
  TilingMetrics m;
  m.count = points.size();
  m.rho = relative_min_distance(points);

  auto lattice = [&](int kx, int ky) { return period > 0 && kx % period == 0 && ky % period == 0; };
  // Mean tile-lattice power of a set whose T tiles each occur M^2 / T times.
  const double lattice_scale = period > 0 ? static_cast<double>(period) * period / tile_count : 1.0;

  double low_sum = 0.0, lattice_sum = 0.0;
  std::size_t low_count = 0, lattice_count = 0;
  // A maximum over an empty band is undefined (NaN), not 0; fmax keeps the first value met.
  constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();
  m.coherence_low = m.coherence_mid = kUndefined;
  const int first_annulus = static_cast<int>(std::ceil(0.5 * root));  // the mid band's start
  const int end_annulus = static_cast<int>(std::floor(kAnisotropyBandEnd * root));  // annuli [i, i+1) below it
  const std::size_t annuli = static_cast<std::size_t>(std::max(0, end_annulus - first_annulus));
  std::vector<double> sum(annuli, 0.0), sum_squares(annuli, 0.0);
  std::vector<std::size_t> count(annuli, 0);
  for (int ky = -half; ky < half; ++ky) {
    for (int kx = -half; kx < half; ++kx) {
      const std::int64_t k2 = static_cast<std::int64_t>(kx) * kx + static_cast<std::int64_t>(ky) * ky;
      const double p = periodogram.at(kx, ky);
      if (in_low_band(k2, points.size())) {
        low_sum += p;
        ++low_count;
      }
      if (lattice(kx, ky) && k2 > 0) {
        if (k2 < static_cast<std::int64_t>(points.size())) {
          lattice_sum += p;
          ++lattice_count;
        }
        const std::int64_t mx = kx / period, my = ky / period;
        if (in_coherence_low_band(mx * mx + my * my)) m.coherence_low = std::fmax(m.coherence_low, p / lattice_scale);
        if (in_mid_band(k2, points.size()))
          m.coherence_mid = std::fmax(m.coherence_mid, p / lattice_scale);
        continue;  // lattice frequencies stay out of the diffuse anisotropy
      }
      const int annulus = static_cast<int>(std::floor(std::sqrt(static_cast<double>(k2))));
      if (annulus >= first_annulus && annulus < end_annulus) {
        const std::size_t i = static_cast<std::size_t>(annulus - first_annulus);
        sum[i] += p;
        sum_squares[i] += p * p;
        ++count[i];
      }
    }
  }
  m.low_frequency = low_count ? low_sum / static_cast<double>(low_count) : kUndefined;
  m.lattice_peak = lattice_count ? lattice_sum / static_cast<double>(lattice_count) : kUndefined;
  double db_sum = 0.0;
  std::size_t db_count = 0;
  for (std::size_t i = 0; i < annuli; ++i) {
    if (count[i] < 2) continue;
    const double c = static_cast<double>(count[i]);
    const double mean = sum[i] / c;
    const double variance = std::max(0.0, (sum_squares[i] - c * mean * mean) / (c - 1.0));
    if (mean <= 0.0 || variance <= 0.0) continue;
    db_sum += 10.0 * std::log10(variance / (mean * mean));
    ++db_count;
  }
  m.diffuse_anisotropy_db = db_count ? db_sum / static_cast<double>(db_count) : kUndefined;
  return m;
}

int tiling_periodogram_size(std::size_t count, int period) {
  int size = tiling_metrics_periodogram_size(count);
  return period > 0 ? std::max(size, 4 * period + 2) : size;
}

TilingMetrics measure_tiling(std::span<const Point> points, int period, int tile_count) {
  return measure_tiling(points, compute_periodogram(points, tiling_periodogram_size(points.size(), period)), period,
                        tile_count);
}

Periodogram tiled_periodogram(std::span<const std::vector<Point>> tile_points, std::span<const int> cell_tiles,
                              int period, int size) {
  if (period < 1) throw Error("tiled periodogram: period must be at least 1");
  check_periodogram_size(size);
  const std::size_t cells = static_cast<std::size_t>(period) * static_cast<std::size_t>(period);
  if (cell_tiles.size() != cells) throw Error("tiled periodogram: cell list does not match the period");
  const std::size_t tiles = tile_points.size();
  std::size_t count = 0;
  for (int t : cell_tiles) {
    if (t < 0 || static_cast<std::size_t>(t) >= tiles) throw Error("tiled periodogram: unknown tile id");
    count += tile_points[static_cast<std::size_t>(t)].size();
  }
  if (count == 0) throw Error("periodogram of an empty point set");
  const int half = size / 2;
  const std::size_t f = static_cast<std::size_t>(size);
  const double m = static_cast<double>(period);
  auto unit = [](double phase) {  // exp(-2 pi i phase), the phase reduced first for accuracy
    phase -= std::nearbyint(phase);
    const double angle = -2.0 * std::numbers::pi * phase;
    return std::complex<double>(std::cos(angle), std::sin(angle));
  };
  // G_t(q) for q in [0, M)^2: the cells' phases depend on k modulo M only.
  std::vector<std::complex<double>> cell_sums(tiles * cells);
  parallel_for(cells, 16, [&](std::size_t begin, std::size_t end) {
    for (std::size_t q = begin; q < end; ++q) {
      const double qx = static_cast<double>(q % static_cast<std::size_t>(period)),
                   qy = static_cast<double>(q / static_cast<std::size_t>(period));
      for (std::size_t c = 0; c < cells; ++c) {
        const double cx = static_cast<double>(c % static_cast<std::size_t>(period)),
                     cy = static_cast<double>(c / static_cast<std::size_t>(period));
        cell_sums[static_cast<std::size_t>(cell_tiles[c]) * cells + q] += unit((qx * cx + qy * cy) / m);
      }
    }
  });
  // Rows ky in [-F/2, 0] are summed, the others mirrored (P(-k) = P(k)). Along a row the
  // exponentials of a point follow a recurrence, re-anchored by sin/cos every kAnchor steps
  // (about kAnchor ulps lost at most).
  constexpr std::size_t kAnchor = 64;
  const std::size_t columns = f + 1;
  const std::size_t rows = static_cast<std::size_t>(half) + 1;
  std::vector<double> summed(rows * columns);
  parallel_for(rows, 1, [&](std::size_t begin, std::size_t end) {
    std::vector<std::complex<double>> row(columns);
    std::vector<double> tile_re(columns), tile_im(columns);
    for (std::size_t r = begin; r < end; ++r) {
      const int ky = static_cast<int>(r) - half;
      const std::size_t qy = static_cast<std::size_t>(((ky % period) + period) % period);
      std::fill(row.begin(), row.end(), std::complex<double>{});
      for (std::size_t t = 0; t < tiles; ++t) {
        std::fill(tile_re.begin(), tile_re.end(), 0.0);
        std::fill(tile_im.begin(), tile_im.end(), 0.0);
        for (const Point& p : tile_points[t]) {
          const std::complex<double> y = unit(static_cast<double>(ky) * p.y / m);
          const std::complex<double> step = unit(p.x / m);
          for (std::size_t i0 = 0; i0 < columns; i0 += kAnchor) {
            // Plain doubles: std::complex products check for NaN on every step.
            const std::complex<double> anchor = unit(static_cast<double>(static_cast<int>(i0) - half) * p.x / m) * y;
            double xr = anchor.real(), xi = anchor.imag();
            const double sr = step.real(), si = step.imag();
            const std::size_t i1 = std::min(columns, i0 + kAnchor);
            for (std::size_t i = i0; i < i1; ++i) {
              tile_re[i] += xr;
              tile_im[i] += xi;
              const double nr = xr * sr - xi * si;
              xi = xr * si + xi * sr;
              xr = nr;
            }
          }
        }
        for (std::size_t i = 0; i < columns; ++i) {
          const int kx = static_cast<int>(i) - half;
          const std::size_t qx = static_cast<std::size_t>(((kx % period) + period) % period);
          const std::complex<double> g = cell_sums[t * cells + qy * static_cast<std::size_t>(period) + qx];
          row[i] += std::complex<double>(tile_re[i] * g.real() - tile_im[i] * g.imag(),
                                         tile_re[i] * g.imag() + tile_im[i] * g.real());
        }
      }
      for (std::size_t i = 0; i < columns; ++i) summed[r * columns + i] = std::norm(row[i]) / static_cast<double>(count);
    }
  });
  Periodogram result;
  result.size = size;
  result.power.resize(f * f);
  for (int ky = -half; ky < half; ++ky) {
    for (int kx = -half; kx < half; ++kx) {
      const int sx = ky <= 0 ? kx : -kx, sy = ky <= 0 ? ky : -ky;
      result.power[static_cast<std::size_t>(ky + half) * f + static_cast<std::size_t>(kx + half)] =
          summed[static_cast<std::size_t>(sy + half) * columns + static_cast<std::size_t>(sx + half)];
    }
  }
  // k = 0 exactly N, as the direct sum gives it.
  result.power[static_cast<std::size_t>(half) * f + static_cast<std::size_t>(half)] = static_cast<double>(count);
  return result;
}

}  // namespace bluetile
