// Lattice decorrelation (see wang_lattice.h).
#include "bluetile/relax/wang_lattice.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "bluetile/analysis/tiling_metrics.h"
#include "bluetile/core/torus.h"

namespace bluetile {
namespace {

using Complex = std::complex<double>;

struct Frequency {
  int mx, my;
  double target;  // the coherence the objective divides by
  bool low;
};

constexpr double kLowTarget = 0.02, kMidTarget = 20.0;

// Half of the integer plane (m and -m have the same C): mx > 0, or mx = 0 and my > 0. The bands
// are the tiling metrics' (tiling_metrics.h) in tile units: the low band is LF's with C_LF's
// frequencies added, the mid band C_mid's.
std::vector<Frequency> frequencies(std::size_t n, bool mid_band) {
  const double root = std::sqrt(static_cast<double>(n));
  const int reach = static_cast<int>(std::ceil(std::max(mid_band ? 1.5 * root : 0.5 * root, std::sqrt(5.0)))) + 1;
  std::vector<Frequency> out;
  for (int mx = 0; mx <= reach; ++mx)
    for (int my = -reach; my <= reach; ++my) {
      if (mx == 0 && my <= 0) continue;
      const std::int64_t m2 = static_cast<std::int64_t>(mx) * mx + static_cast<std::int64_t>(my) * my;
      if (in_low_band(m2, n) || in_coherence_low_band(m2)) {
        out.push_back({mx, my, kLowTarget, true});
      } else if (mid_band && in_mid_band(m2, n)) {
        out.push_back({mx, my, kMidTarget, false});
      }
    }
  return out;
}

// exp(-2 pi i a x) for a = 0 .. reach, and for negative a by conjugation: the powers of one
// point's phase, so that each frequency costs one complex product per point.
class Phases {
 public:
  explicit Phases(int reach) : reach_(reach) {}
  void set(Point p) {
    x_.resize(static_cast<std::size_t>(reach_ + 1));
    y_.resize(static_cast<std::size_t>(reach_ + 1));
    const Complex ex = std::polar(1.0, -2.0 * std::numbers::pi * p.x), ey = std::polar(1.0, -2.0 * std::numbers::pi * p.y);
    x_[0] = y_[0] = 1.0;
    for (int a = 1; a <= reach_; ++a) {
      x_[static_cast<std::size_t>(a)] = x_[static_cast<std::size_t>(a - 1)] * ex;
      y_[static_cast<std::size_t>(a)] = y_[static_cast<std::size_t>(a - 1)] * ey;
    }
  }
  Complex at(const Frequency& f) const {
    const Complex y = f.my >= 0 ? y_[static_cast<std::size_t>(f.my)] : std::conj(y_[static_cast<std::size_t>(-f.my)]);
    return x_[static_cast<std::size_t>(f.mx)] * y;
  }

 private:
  int reach_;
  std::vector<Complex> x_, y_;
};

int reach_of(const std::vector<Frequency>& fs) {
  int reach = 0;
  for (const Frequency& f : fs) reach = std::max({reach, f.mx, std::abs(f.my)});
  return reach;
}

// sum over every point of every tile of exp(-2 pi i m.x), per frequency.
std::vector<Complex> lattice_sums(const TilePoints& tiles, const std::vector<Frequency>& fs) {
  std::vector<Complex> sums(fs.size(), 0.0);
  Phases phases(reach_of(fs));
  for (const std::vector<Point>& tile : tiles)
    for (const Point& p : tile) {
      phases.set(p);
      for (std::size_t k = 0; k < fs.size(); ++k) sums[k] += phases.at(fs[k]);
    }
  return sums;
}

// exp(-2 pi i m.x) of every point of every tile (tile by tile, point by point) at every
// frequency, into `phase` (point-major), and their sums per frequency as lattice_sums adds them:
// a lattice step reads each phase twice (the sums, then the gradient of the moving points).
void point_phases(const TilePoints& tiles, const std::vector<Frequency>& fs, Phases& phases, std::vector<Complex>& phase,
                  std::vector<Complex>& sums) {
  std::size_t count = 0;
  for (const std::vector<Point>& tile : tiles) count += tile.size();
  phase.resize(count * fs.size());
  sums.assign(fs.size(), 0.0);
  Complex* e = phase.data();
  for (const std::vector<Point>& tile : tiles)
    for (const Point& p : tile) {
      phases.set(p);
      for (std::size_t k = 0; k < fs.size(); ++k) {
        e[k] = phases.at(fs[k]);
        sums[k] += e[k];
      }
      e += fs.size();
    }
}

}  // namespace

LatticeCoherence lattice_coherence(const TilePoints& tiles) {
  LatticeCoherence c;
  if (tiles.empty() || tiles[0].empty()) return c;
  const std::size_t n = tiles[0].size();
  const std::vector<Frequency> fs = frequencies(n, true);
  const std::vector<Complex> sums = lattice_sums(tiles, fs);
  const double norm = 1.0 / static_cast<double>(tiles.size() * n);
  for (std::size_t k = 0; k < fs.size(); ++k) {
    const double value = std::norm(sums[k]) * norm;
    (fs[k].low ? c.low : c.mid) = std::max(fs[k].low ? c.low : c.mid, value);
  }
  return c;
}

void decorrelate_lattice(WangPoints& points, const LatticeDecorrelationOptions& options) {
  if (options.iterations <= 0 || points.tiles.empty() || points.moving_count() == 0) return;
  const std::size_t n = points.tiles[0].size();
  const std::vector<Frequency> fs = frequencies(n, options.mid_band);
  const double norm = 1.0 / static_cast<double>(points.tiles.size() * n);
  const double largest_move = options.step * hexagonal_spacing(static_cast<double>(n));
  Phases phases(reach_of(fs));
  std::vector<Complex> weight(fs.size()), phase, sums;
  std::vector<Point> gradient(points.tiles.size() * points.moving_count());
  for (int it = 0; it < options.iterations; ++it) {
    // d/dx_j of (C_m / t)^4 / 4 = (C_m / t)^3 / t * dC_m/dx_j, with
    // dC_m/dx_j = 2 norm Re(conj(S_m) (-2 pi i m) e_j(m)); both halves of the plane count.
    point_phases(points.tiles, fs, phases, phase, sums);
    for (std::size_t k = 0; k < fs.size(); ++k) {
      const double c = std::norm(sums[k]) * norm / fs[k].target;
      weight[k] = std::conj(sums[k]) * (2.0 * 2.0 * norm * c * c * c / fs[k].target);
    }
    double longest = 0.0;
    for (std::size_t t = 0; t < points.tiles.size(); ++t)
      for (std::size_t m = 0; m < points.moving_count(); ++m) {
        // Every tile holds n points: this point's phases start at (t n + its index) phases in.
        const Complex* e = phase.data() + (t * n + points.moving_begin + m) * fs.size();
        Point g{0.0, 0.0};
        for (std::size_t k = 0; k < fs.size(); ++k) {
          // Re(w (-2 pi i) e) m = 2 pi Im(w e) m
          const double s = 2.0 * std::numbers::pi * std::imag(weight[k] * e[k]);
          g.x += s * fs[k].mx;
          g.y += s * fs[k].my;
        }
        gradient[t * points.moving_count() + m] = g;
        longest = std::max(longest, std::sqrt(g.x * g.x + g.y * g.y));
      }
    if (!(longest > 0.0)) break;
    const double scale = largest_move / longest;
    for (std::size_t t = 0; t < points.tiles.size(); ++t)
      for (std::size_t m = 0; m < points.moving_count(); ++m) {
        Point& p = points.tiles[t][points.moving_begin + m];
        const Point g = gradient[t * points.moving_count() + m];
        p = inside_tile(p - scale * g, options.edge_margin);
      }
  }
}

}  // namespace bluetile
