// Periodogram by the direct sum (DESIGN section 5; psa, Heck & Schlömer; the paper's R_f,
// section 1.2).
//
// exp(-2 pi i k.x) = exp(-2 pi i kx x) exp(-2 pi i ky y), so the sums S(kx, ky) over the points
// form the matrix product S = A^T B with A[j][kx] = exp(-2 pi i kx x_j) and B[j][ky] likewise.
// It is computed like a blocked matrix product: each task owns a tile of frequencies, builds
// the exponentials of a block of points for its tile (a recurrence along the tile, re-anchored
// by sin/cos at its start and exactly at k = 0), and accumulates the block into the tile with a
// vectorised kernel. Every S(k) is summed over the points in index order whatever the thread
// count. P(-k) = P(k) for real points, so only ky <= 0 is summed and the rest mirrored.
#include "bluetile/analysis/periodogram.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"

namespace bluetile {
namespace {

// Tile of frequencies one task accumulates: kx along the vector lanes.
constexpr int tile_x = 128;
constexpr int tile_y = 128;
// Points per block: the block's exponentials (1 MB) and the tile (256 KB) stay in the L2 cache.
constexpr int block_points = 256;
constexpr int lanes = 8;  // kx per vector (one AVX-512 register; split on smaller targets)
constexpr int rows = 4;   // ky per register tile

using Lane = double __attribute__((vector_size(lanes * sizeof(double))));

// acc[ty][tx] += sum over j < count of a[j][tx] * b[j][ty] (complex; re and im apart).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
void accumulate_block(int count, const double* a_re, const double* a_im, const double* b_re,
                      const double* b_im, double* acc_re, double* acc_im) {
  for (int y0 = 0; y0 < tile_y; y0 += rows) {
    for (int x0 = 0; x0 < tile_x; x0 += lanes) {
      // Four products kept apart: every accumulator takes one FMA per point, so the loop is
      // bound by FMA throughput rather than by the latency of a chain of two.
      Lane rr[rows], ii[rows], ri[rows], ir[rows];
      for (int r = 0; r < rows; ++r) {
        __builtin_memcpy(&rr[r], acc_re + (y0 + r) * tile_x + x0, sizeof(Lane));
        __builtin_memcpy(&ri[r], acc_im + (y0 + r) * tile_x + x0, sizeof(Lane));
        ii[r] = Lane{};
        ir[r] = Lane{};
      }
      for (int j = 0; j < count; ++j) {
        Lane ar, ai;
        __builtin_memcpy(&ar, a_re + (x0 / lanes * block_points + j) * lanes, sizeof(Lane));
        __builtin_memcpy(&ai, a_im + (x0 / lanes * block_points + j) * lanes, sizeof(Lane));
        const double* br = b_re + (y0 / rows * block_points + j) * rows;
        const double* bi = b_im + (y0 / rows * block_points + j) * rows;
        for (int r = 0; r < rows; ++r) {
          rr[r] += ar * br[r];
          ii[r] += ai * bi[r];
          ri[r] += ar * bi[r];
          ir[r] += ai * br[r];
        }
      }
      for (int r = 0; r < rows; ++r) {
        Lane re = rr[r] - ii[r], im = ri[r] + ir[r];
        __builtin_memcpy(acc_re + (y0 + r) * tile_x + x0, &re, sizeof(Lane));
        __builtin_memcpy(acc_im + (y0 + r) * tile_x + x0, &im, sizeof(Lane));
      }
    }
  }
}

// exp(-2 pi i k c) for k = first .. first + count - 1 (count a multiple of G), packed as the
// kernel reads them: group g of G consecutive k goes to re + g * group_stride. The first group
// comes from sin/cos and a short recurrence, later groups from it times exp(-2 pi i G c), G
// independent recurrences of count / G steps each (about one ulp lost per step). k = 0 is then
// set exactly to 1 so that P(0) = N holds exactly.
template <int G>
void fill_exponentials(double c, int first, int count, double* re, double* im, int group_stride) {
  auto unit = [&](long long k, double& r, double& i) {
    double phase = static_cast<double>(k) * c;
    phase -= std::nearbyint(phase);
    const double angle = -2.0 * std::numbers::pi * phase;
    r = std::cos(angle), i = std::sin(angle);
  };
  double gr[G], gi[G], sr, si, step_r, step_i;
  unit(first, gr[0], gi[0]);
  unit(1, sr, si);
  for (int t = 1; t < G; ++t) {
    gr[t] = gr[t - 1] * sr - gi[t - 1] * si;
    gi[t] = gr[t - 1] * si + gi[t - 1] * sr;
  }
  unit(G, step_r, step_i);
  for (int g = 0; g < count / G; ++g) {
    for (int t = 0; t < G; ++t) {
      re[g * group_stride + t] = gr[t];
      im[g * group_stride + t] = gi[t];
    }
    for (int t = 0; t < G; ++t) {
      const double nr = gr[t] * step_r - gi[t] * step_i;
      gi[t] = gr[t] * step_i + gi[t] * step_r;
      gr[t] = nr;
    }
  }
  if (first <= 0 && 0 < first + count) {
    const int at = -first / G * group_stride + -first % G;
    re[at] = 1.0, im[at] = 0.0;
  }
}

}  // namespace

int default_periodogram_size(std::size_t count) {
  const double half = std::floor(5.0 * std::sqrt(static_cast<double>(count)));
  // Past 4.6e16 points the size passed an int: the conversion and the doubling were undefined.
  if (half > std::numeric_limits<int>::max() / 2)
    throw Error("count " + std::to_string(count) + ": the default periodogram size 2 floor(5 sqrt(N)) passes the largest int");
  return 2 * static_cast<int>(half);
}

void check_periodogram_size(int size) {
  if (size < 2 || size % 2 != 0 || size > 65536)
    throw Error("periodogram size must be even, 2 to 65536, got " + std::to_string(size));
}

Periodogram compute_periodogram(std::span<const Point> points, int size,
                                const std::function<void(std::size_t, std::size_t)>& progress) {
  if (periodogram_uses_nufft(points.size(), size)) return compute_periodogram_nufft(points, size, progress);
  return compute_periodogram_direct(points, size, progress);
}

bool periodogram_uses_nufft(std::size_t count, int size) {
  if (size < 2) return false;
  // Measured on one thread (docs/BENCHMARKS.md, "Analysis at scale"): the direct sum costs
  // about 0.6 ns per point and frequency (half the plane is summed), the non-uniform FFT about
  // 4 ns per butterfly of its two passes plus 400 ns to spread a point. The direct sum wins
  // below about 100 points, where both take a millisecond.
  constexpr double kDirectNsPerTerm = 0.6, kFftNsPerButterfly = 4.0, kSpreadNsPerPoint = 400.0;
  const double f = size, n = static_cast<double>(count);
  const double m = static_cast<double>(periodogram_nufft_grid(size));
  const double direct = kDirectNsPerTerm * n * f * f / 2.0;
  const double fast = kFftNsPerButterfly * m * (m + f / 2.0) * std::log2(m) / 2.0 + kSpreadNsPerPoint * n;
  return fast < direct;
}

Periodogram compute_periodogram_direct(std::span<const Point> points, int size,
                                       const std::function<void(std::size_t, std::size_t)>& progress) {
  if (points.empty()) throw Error("periodogram of an empty point set");
  check_periodogram_size(size);
  // As compute_periodogram_nufft: a NaN gave a NaN spectrum without a word.
  check_finite_points(points, "periodogram");
  const int half = size / 2;
  const std::size_t n = points.size();
  // Summed: kx in [-F/2, F/2] (one more column than the square, for mirroring), ky in [-F/2, 0].
  const int columns = size + 1, summed_rows = half + 1;
  const int tiles_x = (columns + tile_x - 1) / tile_x, tiles_y = (summed_rows + tile_y - 1) / tile_y;
  const std::size_t tiles = static_cast<std::size_t>(tiles_x) * static_cast<std::size_t>(tiles_y);
  std::vector<double> summed(static_cast<std::size_t>(columns) * static_cast<std::size_t>(summed_rows));

  std::mutex progress_mutex;
  std::size_t tiles_done = 0;
  if (progress) progress(0, tiles);
  parallel_for(tiles, 1, [&](std::size_t begin, std::size_t end) {
    std::vector<double> a_re(block_points * tile_x), a_im(block_points * tile_x);
    std::vector<double> b_re(block_points * tile_y), b_im(block_points * tile_y);
    std::vector<double> acc_re(tile_y * tile_x), acc_im(tile_y * tile_x);
    for (std::size_t tile = begin; tile < end; ++tile) {
      const int kx0 = -half + static_cast<int>(tile % static_cast<std::size_t>(tiles_x)) * tile_x;
      const int ky0 = -half + static_cast<int>(tile / static_cast<std::size_t>(tiles_x)) * tile_y;
      std::fill(acc_re.begin(), acc_re.end(), 0.0);
      std::fill(acc_im.begin(), acc_im.end(), 0.0);
      for (std::size_t j0 = 0; j0 < n; j0 += block_points) {
        const int count = static_cast<int>(std::min<std::size_t>(block_points, n - j0));
        for (int j = 0; j < count; ++j) {
          const Point& p = points[j0 + static_cast<std::size_t>(j)];
          fill_exponentials<lanes>(p.x, kx0, tile_x, &a_re[static_cast<std::size_t>(j * lanes)],
                                   &a_im[static_cast<std::size_t>(j * lanes)], block_points * lanes);
          fill_exponentials<rows>(p.y, ky0, tile_y, &b_re[static_cast<std::size_t>(j * rows)],
                                  &b_im[static_cast<std::size_t>(j * rows)], block_points * rows);
        }
        accumulate_block(count, a_re.data(), a_im.data(), b_re.data(), b_im.data(), acc_re.data(), acc_im.data());
      }
      for (int ty = 0; ty < tile_y; ++ty) {
        const int row = ky0 + half + ty;
        if (row >= summed_rows) break;
        for (int tx = 0; tx < tile_x; ++tx) {
          const int column = kx0 + half + tx;
          if (column >= columns) break;
          const double re = acc_re[static_cast<std::size_t>(ty * tile_x + tx)];
          const double im = acc_im[static_cast<std::size_t>(ty * tile_x + tx)];
          summed[static_cast<std::size_t>(row) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(column)] =
              (re * re + im * im) / static_cast<double>(n);
        }
      }
      if (progress) {
        std::lock_guard<std::mutex> lock(progress_mutex);
        progress(++tiles_done, tiles);
      }
    }
  });

  Periodogram result;
  result.size = size;
  result.power.resize(static_cast<std::size_t>(size) * static_cast<std::size_t>(size));
  const std::size_t f = static_cast<std::size_t>(size);
  for (int ky = -half; ky < half; ++ky) {
    for (int kx = -half; kx < half; ++kx) {
      // Rows ky > 0 are the mirror images P(kx, ky) = P(-kx, -ky).
      const int sx = ky <= 0 ? kx : -kx, sy = ky <= 0 ? ky : -ky;
      result.power[static_cast<std::size_t>(ky + half) * f + static_cast<std::size_t>(kx + half)] =
          summed[static_cast<std::size_t>(sy + half) * static_cast<std::size_t>(columns) +
                 static_cast<std::size_t>(sx + half)];
    }
  }
  return result;
}

void check_periodogram_values(const Periodogram& periodogram) {
  const auto side = static_cast<std::size_t>(std::max(periodogram.size, 0));
  if (periodogram.size < 0 || periodogram.power.size() != side * side)
    throw Error("periodogram of size " + std::to_string(periodogram.size) + " holds " +
                std::to_string(periodogram.power.size()) + " values, expected " + std::to_string(side * side));
}

Periodogram average_periodograms(std::span<const Periodogram> periodograms) {
  if (periodograms.empty()) throw Error("no periodograms to average");
  for (const Periodogram& p : periodograms) check_periodogram_values(p);
  Periodogram mean;
  mean.size = periodograms[0].size;
  mean.power.assign(periodograms[0].power.size(), 0.0);
  for (const Periodogram& p : periodograms) {
    if (p.size != mean.size)
      throw Error("cannot average periodograms of sizes " + std::to_string(mean.size) + " and " +
                  std::to_string(p.size));
    for (std::size_t i = 0; i < p.power.size(); ++i) mean.power[i] += p.power[i];
  }
  for (double& v : mean.power) v /= static_cast<double>(periodograms.size());
  return mean;
}

}  // namespace bluetile
