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
#pragma once

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

}  // namespace bluetile
