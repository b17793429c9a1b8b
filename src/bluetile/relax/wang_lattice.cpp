// Lattice decorrelation (see wang_lattice.h).
#include "bluetile/relax/wang_lattice.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include "bluetile/analysis/tiling_metrics.h"
#include "bluetile/core/error.h"
#include "bluetile/core/field_checks.h"
#include "bluetile/core/torus.h"
#include "bluetile/relax/wang_relax.h"

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

int reach_of(const std::vector<Frequency>& fs) {
  int reach = 0;
  for (const Frequency& f : fs) reach = std::max({reach, f.mx, std::abs(f.my)});
  return reach;
}

// exp(-2 pi i m.p) of one point p at every frequency m of a band, in the band's order. The
// powers of exp(-2 pi i p.x) and exp(-2 pi i p.y) come from one complex product each; a
// frequency is then x^mx y^my (y^-my the conjugate). The band's frequencies are taken as runs of
// consecutive my at one mx (a band here is a disc or a ring in half the plane, so a run is one
// of its rows), each run's products a loop over contiguous y powers that the compiler
// vectorizes; the products are the ones std::complex computes (ac - bd, ad + bc), bit for bit.
class BandPhases {
 public:
  explicit BandPhases(const std::vector<Frequency>& fs) : reach_(reach_of(fs)), size_(fs.size()) {
    for (std::size_t k = 0; k < fs.size(); ++k) {
      if (k > 0 && fs[k].mx == fs[k - 1].mx && fs[k].my == fs[k - 1].my + 1) {
        ++runs_.back().size;
      } else {
        runs_.push_back({fs[k].mx, fs[k].my, k, 1});
      }
    }
    const std::size_t powers = static_cast<std::size_t>(reach_) + 1, row = 2 * powers - 1;
    x_.resize(powers);
    y_.resize(powers);
    y_re_.resize(row);
    y_im_.resize(row);
  }

  std::size_t size() const { return size_; }

  // re[k] + i im[k] = exp(-2 pi i fs[k].p) for every k.
  void compute(Point p, double* re, double* im) {
    const Complex ex = std::polar(1.0, -2.0 * std::numbers::pi * p.x), ey = std::polar(1.0, -2.0 * std::numbers::pi * p.y);
    x_[0] = y_[0] = 1.0;
    for (std::size_t a = 1; a < x_.size(); ++a) {
      x_[a] = x_[a - 1] * ex;
      y_[a] = y_[a - 1] * ey;
    }
    // y^my for my = -reach .. reach at [reach + my].
    const std::size_t centre = static_cast<std::size_t>(reach_);
    for (std::size_t a = 0; a < y_.size(); ++a) {
      y_re_[centre + a] = y_re_[centre - a] = y_[a].real();
      y_im_[centre - a] = -y_[a].imag();
      y_im_[centre + a] = y_[a].imag();  // last: my = 0 keeps the +0 of y^0
    }
    for (const Run& run : runs_) {
      const double a = x_[static_cast<std::size_t>(run.mx)].real(), b = x_[static_cast<std::size_t>(run.mx)].imag();
      const double* c = y_re_.data() + (reach_ + run.my);
      const double* d = y_im_.data() + (reach_ + run.my);
      double* out_re = re + run.begin;
      double* out_im = im + run.begin;
      for (std::size_t j = 0; j < run.size; ++j) {
        out_re[j] = a * c[j] - b * d[j];
        out_im[j] = a * d[j] + b * c[j];
      }
    }
  }

 private:
  struct Run {
    int mx, my;  // the run's first frequency
    std::size_t begin, size;
  };
  int reach_;
  std::size_t size_;
  std::vector<Run> runs_;
  std::vector<Complex> x_, y_;
  std::vector<double> y_re_, y_im_;
};

// Per-frequency sums of phases, kept as the real and imaginary arrays BandPhases writes.
struct BandSums {
  std::vector<double> re, im;

  void clear(std::size_t band) {
    re.assign(band, 0.0);
    im.assign(band, 0.0);
  }
  void add(const double* e_re, const double* e_im) {
    for (std::size_t k = 0; k < re.size(); ++k) {
      re[k] += e_re[k];
      im[k] += e_im[k];
    }
  }
  Complex at(std::size_t k) const { return {re[k], im[k]}; }
  std::vector<Complex> complex() const {
    std::vector<Complex> out(re.size());
    for (std::size_t k = 0; k < re.size(); ++k) out[k] = at(k);
    return out;
  }
};

// sum over every point of every tile of exp(-2 pi i m.x), per frequency.
std::vector<Complex> lattice_sums(const TilePoints& tiles, const std::vector<Frequency>& fs) {
  BandPhases phases(fs);
  BandSums sums;
  sums.clear(fs.size());
  std::vector<double> re(fs.size()), im(fs.size());
  for (const std::vector<Point>& tile : tiles)
    for (const Point& p : tile) {
      phases.compute(p, re.data(), im.data());
      sums.add(re.data(), im.data());
    }
  return sums.complex();
}

// exp(-2 pi i m.x) of every point of every tile (tile by tile, point by point) at every
// frequency, into `re` and `im` (point-major), and their sums per frequency as lattice_sums
// adds them: a lattice step reads each phase twice (the sums, then the gradient of the moving
// points).
void point_phases(const TilePoints& tiles, BandPhases& phases, std::vector<double>& re, std::vector<double>& im,
                  std::vector<Complex>& sums) {
  const std::size_t band = phases.size();
  std::size_t count = 0;
  for (const std::vector<Point>& tile : tiles) count += tile.size();
  re.resize(count * band);
  im.resize(count * band);
  BandSums total;
  total.clear(band);
  for (std::size_t offset = 0; const std::vector<Point>& tile : tiles)
    for (const Point& p : tile) {
      phases.compute(p, re.data() + offset, im.data() + offset);
      total.add(re.data() + offset, im.data() + offset);
      offset += band;
    }
  sums = total.complex();
}

double squared_distance(Point a, Point b) {
  const Point d = a - b;
  return d.x * d.x + d.y * d.y;
}

// Whether point i of a tile, moved from p to q, keeps options.spacing hexagonal spacings (of the
// prefix that the later point of each pair completes) from every point it can meet: those of its
// own tile and of every tile that can lie next to it, shifted there. A pair already closer than
// that (the fill takes the farthest place where none is far enough) may not come closer still.
class SpacingCheck {
 public:
  SpacingCheck(const TilePoints& tiles, std::span<const std::vector<FillSource>> sources, double spacing)
      : tiles_(tiles), sources_(sources) {
    const std::size_t n = tiles.empty() ? 0 : tiles[0].size();
    least_.resize(n);
    for (std::size_t r = 0; r < n; ++r) least_[r] = spacing * hexagonal_spacing(static_cast<double>(r + 1));
  }

  bool keeps(std::size_t tile, std::size_t i, Point p, Point q) const {
    const double reach = least_[i];  // the largest distance any pair with point i must keep
    for (const FillSource& source : sources_[tile]) {
      // Nothing of a neighbour farther than the reach from q's side of it can be too close.
      const double bx = std::max({0.0, source.shift.x - q.x, q.x - (source.shift.x + 1.0)});
      const double by = std::max({0.0, source.shift.y - q.y, q.y - (source.shift.y + 1.0)});
      if (bx * bx + by * by >= reach * reach) continue;
      const bool itself = source.tile == tile && source.shift.x == 0.0 && source.shift.y == 0.0;
      const std::vector<Point>& other = tiles_[source.tile];
      for (std::size_t j = 0; j < other.size(); ++j) {
        if (itself && j == i) continue;
        const Point o = other[j] + source.shift;
        const double after = squared_distance(o, q), least = least_[std::max(i, j)];
        if (after < least * least && after < squared_distance(o, p)) return false;
      }
    }
    return true;
  }

 private:
  const TilePoints& tiles_;
  std::span<const std::vector<FillSource>> sources_;
  std::vector<double> least_;
};

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
  BandPhases phases(fs);
  std::vector<double> weight_re(fs.size()), weight_im(fs.size()), phase_re, phase_im;
  std::vector<Complex> sums;
  std::vector<Point> gradient(points.tiles.size() * points.moving_count());
  for (int it = 0; it < options.iterations; ++it) {
    // d/dx_j of (C_m / t)^4 / 4 = (C_m / t)^3 / t * dC_m/dx_j, with
    // dC_m/dx_j = 2 norm Re(conj(S_m) (-2 pi i m) e_j(m)); both halves of the plane count.
    point_phases(points.tiles, phases, phase_re, phase_im, sums);
    for (std::size_t k = 0; k < fs.size(); ++k) {
      const double c = std::norm(sums[k]) * norm / fs[k].target;
      const Complex w = std::conj(sums[k]) * (2.0 * 2.0 * norm * c * c * c / fs[k].target);
      weight_re[k] = w.real();
      weight_im[k] = w.imag();
    }
    double longest = 0.0;
    for (std::size_t t = 0; t < points.tiles.size(); ++t)
      for (std::size_t m = 0; m < points.moving_count(); ++m) {
        // Every tile holds n points: this point's phases start at (t n + its index) phases in.
        const std::size_t offset = (t * n + points.moving_begin + m) * fs.size();
        const double* e_re = phase_re.data() + offset;
        const double* e_im = phase_im.data() + offset;
        Point g{0.0, 0.0};
        for (std::size_t k = 0; k < fs.size(); ++k) {
          // Re(w (-2 pi i) e) m = 2 pi Im(w e) m
          const double s = 2.0 * std::numbers::pi * (weight_re[k] * e_im[k] + weight_im[k] * e_re[k]);
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

namespace {

// The peak's band of a prefix of n: integer m in half the plane with 0 < |m|^2 < n.
std::vector<Frequency> peak_band(std::size_t n) {
  const int reach = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  std::vector<Frequency> fs;
  for (int mx = 0; mx <= reach; ++mx)
    for (int my = -reach; my <= reach; ++my) {
      if (mx == 0 && my <= 0) continue;
      if (static_cast<std::size_t>(mx * mx + my * my) < n) fs.push_back({mx, my, 1.0, false});
    }
  return fs;
}

}  // namespace

double filled_lattice_phases(std::size_t tiles, std::size_t begin, std::size_t count, int steps) {
  if (steps <= 0 || count <= begin) return 0.0;
  const std::size_t middle = begin + (count - begin + 1) / 2;
  // Per step: every point's phases into the sums of the prefixes it belongs to, then the level's.
  const double per_tile = static_cast<double>(count + middle + (count - begin));
  return static_cast<double>(steps) * static_cast<double>(tiles) * per_tile * static_cast<double>(peak_band(count).size());
}

void decorrelate_filled_level(TilePoints& tiles, std::size_t begin, std::span<const std::vector<FillSource>> sources,
                              const FilledLatticeOptions& options) {
  check_whole_field("iterations", options.iterations, 0, kMaxLatticeSteps);
  check_real_field("spacing", options.spacing, kMinSeamSpacing, kMaxSeamSpacing, " hexagonal spacings");
  check_fill_layout(tiles, sources, "filled lattice steps");
  if (begin > tiles[0].size())
    throw Error("filled lattice steps: the level begins at point " + std::to_string(begin) + ", past the tiles' " +
                std::to_string(tiles[0].size()) + " points");
  if (options.iterations == 0 || tiles[0].size() == begin) return;
  const std::size_t n = tiles[0].size(), moving = n - begin;
  // The level's middle prefix and its boundary, and the peak's band of each: 0 < |m|^2 < k.
  const std::array<std::size_t, 2> prefixes{begin + (moving + 1) / 2, n};
  const std::vector<Frequency> fs = peak_band(n);
  std::vector<std::size_t> squared;
  for (const Frequency& f : fs) squared.push_back(static_cast<std::size_t>(f.mx * f.mx + f.my * f.my));
  const double largest_move = kFilledLatticeStep * hexagonal_spacing(static_cast<double>(n));
  const SpacingCheck check(tiles, sources, options.spacing);
  BandPhases phases(fs);
  std::vector<double> e_re(fs.size()), e_im(fs.size());
  std::array<std::vector<Complex>, 2> sums, weights;
  std::array<std::vector<double>, 2> own;
  std::array<BandSums, 2> tile_sums;
  std::vector<double> top_re(fs.size()), top_im(fs.size()), both_re(fs.size()), both_im(fs.size());
  std::vector<Point> gradient(tiles.size() * moving);
  for (int it = 0; it < options.iterations; ++it) {
    // Per prefix: the sum over every tile, and the sum of each tile's own |F_t|^2.
    for (std::size_t p = 0; p < prefixes.size(); ++p) {
      sums[p].assign(fs.size(), 0.0);
      own[p].assign(fs.size(), 0.0);
    }
    for (const std::vector<Point>& tile : tiles) {
      for (BandSums& t : tile_sums) t.clear(fs.size());
      for (std::size_t i = 0; i < n; ++i) {
        phases.compute(tile[i], e_re.data(), e_im.data());
        for (std::size_t p = 0; p < prefixes.size(); ++p)
          if (i < prefixes[p]) tile_sums[p].add(e_re.data(), e_im.data());
      }
      for (std::size_t p = 0; p < prefixes.size(); ++p)
        for (std::size_t k = 0; k < fs.size(); ++k) {
          const Complex tile_sum = tile_sums[p].at(k);
          sums[p][k] += tile_sum;
          own[p][k] += std::norm(tile_sum);
        }
    }
    // The objective is the coherence in excess of independent tiles' (whose C(m) is the mean of
    // their own |F_t(m)|^2 / k): pushing C below that makes the tiles anti-correlated, which the
    // peak does not need, at a cost in low-frequency power (corner81, 128 per tile: LF 0.066
    // against 0.070 with C^4 itself). With that excess E fixed within a step, d/dx_j of E^4 / 4 =
    // E^3 dC/dx_j, dC/dx_j = 2 norm Re(conj(S) (-2 pi i m) e_j(m)), as decorrelate_lattice;
    // frequencies outside a prefix's band weigh nothing for it.
    for (std::size_t p = 0; p < prefixes.size(); ++p) {
      const double norm = 1.0 / static_cast<double>(tiles.size() * prefixes[p]);
      weights[p].assign(fs.size(), 0.0);
      for (std::size_t k = 0; k < fs.size(); ++k) {
        if (squared[k] >= prefixes[p]) continue;
        const double excess = std::max(0.0, (std::norm(sums[p][k]) - own[p][k]) * norm);
        weights[p][k] = std::conj(sums[p][k]) * (4.0 * norm * excess * excess * excess);
      }
    }
    // A point's weight: the sum over the prefixes that hold it (the boundary always; the middle
    // prefix for the level's first half).
    for (std::size_t k = 0; k < fs.size(); ++k) {
      top_re[k] = weights[1][k].real();
      top_im[k] = weights[1][k].imag();
      const Complex both = weights[1][k] + weights[0][k];
      both_re[k] = both.real();
      both_im[k] = both.imag();
    }
    double longest = 0.0;
    for (std::size_t t = 0; t < tiles.size(); ++t)
      for (std::size_t m = 0; m < moving; ++m) {
        const std::size_t i = begin + m;
        phases.compute(tiles[t][i], e_re.data(), e_im.data());
        const std::vector<double>& w_re = i < prefixes[0] ? both_re : top_re;
        const std::vector<double>& w_im = i < prefixes[0] ? both_im : top_im;
        Point g{0.0, 0.0};
        for (std::size_t k = 0; k < fs.size(); ++k) {
          const double s = 2.0 * std::numbers::pi * (w_re[k] * e_im[k] + w_im[k] * e_re[k]);  // Im(w e)
          g.x += s * fs[k].mx;
          g.y += s * fs[k].my;
        }
        gradient[t * moving + m] = g;
        longest = std::max(longest, std::sqrt(g.x * g.x + g.y * g.y));
      }
    if (!(longest > 0.0)) break;
    const double scale = largest_move / longest;
    // One point after the other, each checked against the others where they stand now.
    for (std::size_t t = 0; t < tiles.size(); ++t)
      for (std::size_t m = 0; m < moving; ++m) {
        Point& p = tiles[t][begin + m];
        const Point g = gradient[t * moving + m];
        for (const double share : {1.0, 0.5}) {
          const Point q = inside_tile(p - share * scale * g, 0.0);
          if (check.keeps(t, begin + m, p, q)) {
            p = q;
            break;
          }
        }
      }
    if (options.on_step) options.on_step(it + 1, options.iterations);
  }
}

}  // namespace bluetile
