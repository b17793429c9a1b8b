// Lattice decorrelation: a short gradient descent after the constrained Lloyd iterations of a
// level. A tiling of T tiles repeats each tile on the integer lattice, so at a lattice frequency
// k = M m of an M x M window the plane's Fourier sum is the sum over tiles of each tile's own
// sum F_t(m) = sum over its points of exp(-2 pi i m.x) (x tile-local, m integer), weighted by how
// often the tile occurs: the tile-lattice coherence C(m) = |sum_t F_t(m)|^2 / (T n) sets the
// peaks at those frequencies (C_LF and C_mid of analysis/tiling_metrics.h; the periodogram
// there is C(m) M^2 / T). Tiles relaxed under the same constraints have correlated F_t(m), so C(m) is
// larger than independent tiles would give; here the moving points take a few small steps down
// the gradient of sum_m (C(m) / target)^4 over the low band 0 < |m| < 0.5 sqrt(n) or
// 0 < |m|^2 <= 5 (target 0.02) and, where asked, the mid band 0.5 sqrt(n) <= |m| < 1.5 sqrt(n)
// (target 20), the metrics' bands in tile units (tiling_metrics.h), each step moving the point
// that moves most by `step` hexagonal spacings. Only the level's
// moving points move, inside their tile; the seam spacing step runs after it.
//
// Filled levels (the fill order, band_fill.h) are not relaxed, and their points, placed alike in
// tiles that look alike, repeat across the tiles too: decorrelate_filled_level gives them steps of
// their own, against the coherence of the level's middle prefix and of its boundary over the whole
// band the tile-lattice peak reads (0 < |m|^2 < k for a prefix of k), each move kept only where
// the point keeps its distance from every point it can meet in a tiling. The plane's peak is about
// (M^2 / T) C + p, p a tile's own periodogram: filled corner81 tiles have C 3-5 times p there
// (docs/RESULTS.md, "Lattice steps for filled levels").
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "bluetile/relax/band_fill.h"
#include "bluetile/relax/wang_step.h"

namespace bluetile {

struct LatticeDecorrelationOptions {
  int iterations = 0;        // gradient steps (0: none)
  double step = 0.005;       // the largest move of one step, in hexagonal spacings of the tile's points
  bool mid_band = true;      // also the mid band (cost grows as n^2 per step; level 0 only by default)
  double edge_margin = 0.0;  // points stay in [margin, 1 - margin] of their tile
};

// The largest C(m) over each band, as the objective sees them.
struct LatticeCoherence {
  double low = 0.0, mid = 0.0;
};

// The largest C(m) of `tiles` (every point of every tile) over each band, the bands those of
// the points per tile of the first tile.
LatticeCoherence lattice_coherence(const TilePoints& tiles);

void decorrelate_lattice(WangPoints& points, const LatticeDecorrelationOptions& options);

// 150 steps of 0.01 hexagonal spacings take corner81's worst lattice peak from 32 to 128 points per
// tile from 4.2-8.0 to 1.6-2.5, and at 24 from 7.7 to 4.05, at a spacing of 0.62 (docs/RESULTS.md,
// "Lattice steps for filled levels"); steps of 0.005 left 24 at 4.4 (under the first spacing rule).
inline constexpr double kFilledLatticeStep = 0.01;

struct FilledLatticeOptions {
  int iterations = 0;     // gradient steps (0: none)
  // A move may not bring a pair closer than this many hexagonal spacings of the prefix that its
  // later point completes (the fill's own floor is kFillFloor), nor a pair already closer (the
  // fill's fallback) closer still; such a move is halved, then dropped.
  double spacing = 0.62;
  std::function<void(int done, int total)> on_step{};  // after each step
};

// Moves points [begin, size) of every tile of `tiles` (all of one size, in rank order) down the
// gradient of sum over P and m of E_P(m)^4, E the coherence C in excess of independent tiles' (the
// mean of the tiles' own |F_t(m)|^2 / k), P the level's middle prefix and its boundary, each step
// moving the point that moves most by kFilledLatticeStep hexagonal spacings of the tile's count.
// `sources` are the fill's (band_fill.h): where the points of each tile can lie near it. One
// thread; the same bits every run. Throws Error for a layout check_fill_layout refuses, `begin`
// past the tiles' points, and iterations or a spacing outside WangRefinement's ranges.
void decorrelate_filled_level(TilePoints& tiles, std::size_t begin, std::span<const std::vector<FillSource>> sources,
                              const FilledLatticeOptions& options);

// About how many phase products (a complex product and a sum each) decorrelate_filled_level
// computes for `tiles` tiles of `count` points whose level begins at `begin`, for the time note
// before the work: about kFilledLatticeSecondsPerPhase each on this project's machines, one
// thread (corner81's built-in recipe: 0.91e9 for the levels to 128 per tile, 3.8 s of CPU more
// than without the steps).
double filled_lattice_phases(std::size_t tiles, std::size_t begin, std::size_t count, int steps);
inline constexpr double kFilledLatticeSecondsPerPhase = 4e-9;

}  // namespace bluetile
