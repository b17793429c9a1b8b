// Weighted polygon moments from row prefix tables (Secord 2002 integrates a cell against a
// texel-constant density; this is the prefix-table form of that integral).
//
// Green's theorem with L = 0, M = H: for a counter-clockwise polygon P and H(u, v) = integral of
// g(t, v) dt from a reference u0 to u, the integral of g over P is the contour integral of H dv.
// Cut P at the texel row lines: inside a row strip the density depends on u alone, the strip's
// horizontal sides have dv = 0, and the reference may be any column per strip; we take the
// polygon's box left column (frame u = 0) for all. Frame: texel units, (0, 0) at the lower-left
// corner of the polygon's box of texels, so u, v >= 0 (up to rounding) and
// F_a(u) = integral from 0 to u of rho(t) t^a dt. For g = rho u^a v^b (mass a = b = 0, first
// moments u and v, second moments u^2 and v^2), H = v^b F_a(u).
//
// A piece inside one row, from its left end (u1, v1) to its right end (u2, v2) (a piece running
// leftwards is integrated rightwards and negated), with slope m = dv/du and v(u) linear: with
// V_b(t) = integral from t to u2 of v(u)^b m du, integration by parts gives
//   integral of F_a(u) v(u)^b m du = V_b(u1) F_a(u1) + integral from u1 to u2 of rho(t) t^a V_b(t) dt,
// V_b(u1) = dv * mean(v^b) over the piece (dv = v2 - v1; the mean of v is (v1 + v2) / 2, of v^2
// (v1^2 + v1 v2 + v2^2) / 3). With s = u2 - t and v(u) = v2 - m (u2 - u):
//   V_0(t) = m s,   V_1(t) = m (v2 s - m s^2 / 2),   V_2(t) = m (v2^2 s - v2 m s^2 + m^2 s^3 / 3),
// and t = u2 - s, so t s = u2 s - s^2 and t^2 s = u2^2 s - 2 u2 s^2 + s^3. Hence with
// N_j = integral from u1 to u2 of rho(t) s^j dt (j = 1, 2, 3) the piece adds
//   g = 1:   dv F_0(u1)             + m N_1
//   g = u:   dv F_1(u1)             + m (u2 N_1 - N_2)
//   g = u^2: dv F_2(u1)             + m (u2^2 N_1 - 2 u2 N_2 + N_3)
//   g = v:   dv mean(v) F_0(u1)     + m (v2 N_1 - m N_2 / 2)
//   g = v^2: dv mean(v^2) F_0(u1)   + m (v2^2 N_1 - v2 m N_2 + m^2 N_3 / 3).
// A vertical piece (du = 0) adds the first column only. The N_j are sums over the few texels the
// piece spans (in a texel of width w whose right side is s = t0 from u2 and left side s = t1,
// rho w (t1^j + ... + t0^j) / (j + 1), with no cancellation); a piece inside one texel or across
// one column line (about nine in ten) has them written out for its two texels and is integrated
// with the others of the cell in one loop without branches, two pieces a step.
//
// F_a(u1) = F_a(c1) + rho (the partial texel), with F_a(c1) a sum of whole texels. A box of up to
// kScanColumns columns (every cell but those of a few dozen sites on a large map) has F_a from its
// left column to each of its columns summed once, row by row, four rows at a time: a piece reads
// its F in one place. A wider box does not: in each row the pieces that run up (the right side of
// a convex cell) take the first such piece's column as their reference, the ones running down
// likewise, so that a piece sums only the texels between its end and its side's reference; then,
// once per row, the whole texels between the two references (from the table: for each row the
// moments of rho t^a of each block of kBlock columns, shifted to the frame, t -> t + d:
// q1 + d q0, q2 + 2 d q1 + d^2 q0) times the up pieces' integral of v^b dv move those pieces to
// the down pieces' reference. Either way F is summed from the frame's columns, never from a
// grid row's start (a prefix over a whole row of 1024 texels lost about 1e-3 relative on a
// cell's second moment by cancellation).
#include "bluetile/voronoi/density_prefix.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace bluetile {
namespace {

// Integrals of H dv for g = rho times 1, u, v, u^2, v^2 (texel units).
struct Sums {
  double s0 = 0.0, su = 0.0, sv = 0.0, suu = 0.0, svv = 0.0;
};

// Integrals of rho, rho t, rho t^2 (texel units).
struct Moments3 {
  double m0, m1, m2;
};

// A piece across more than one column line: N_j texel by texel. `f` holds F from the row's
// reference column to c1; `column_index` maps frame columns to grid columns. Out of line: about one piece
// in eight at 10^4 sites, and inlined it would crowd the common path's registers.
template <bool kSecond>
[[gnu::noinline]] void wide_piece(const float* rho, const long* column_index, double u1, double v1, double u2,
                                  double v2, double sign, long c1, long c2, Moments3 f, Sums& sums) {
  const double rw1 = rho[column_index[c1]] * (u1 - static_cast<double>(c1));
  const double c = static_cast<double>(c1);
  f.m0 += rw1;
  f.m1 += rw1 * (u1 + c) * 0.5;
  if constexpr (kSecond) f.m2 += rw1 * (u1 * u1 + u1 * c + c * c) * (1.0 / 3.0);
  // N_j times (j + 1), texel by texel from the right end leftwards (c2 > c1 + 1): the partial
  // texel at the right end, whole ones, the partial one at the left end.
  double n1 = 0.0, n2 = 0.0, n3 = 0.0;
  double t0 = 0.0;  // s at the texel's right side
  auto texel = [&](double t1, double rw) __attribute__((always_inline)) {  // t1: s at its left side
    const double t01 = t0 * t1, t00 = t0 * t0, t11 = t1 * t1;
    n1 += rw * (t0 + t1);
    n2 += rw * (t00 + t01 + t11);
    if constexpr (kSecond) n3 += rw * (t0 + t1) * (t00 + t11);
    t0 = t1;
  };
  {
    const double t1 = u2 - static_cast<double>(c2);
    texel(t1, rho[column_index[c2]] * t1);
  }
  for (long k = c2 - 1; k > c1; --k) texel(u2 - static_cast<double>(k), rho[column_index[k]] * 1.0);
  texel(u2 - u1, rho[column_index[c1]] * (static_cast<double>(c1 + 1) - u1));
  n1 *= 0.5;
  n2 *= 1.0 / 3.0;
  n3 *= 0.25;
  const double dv = v2 - v1;
  const double m = dv / (u2 - u1);
  sums.s0 += sign * (dv * f.m0 + m * n1);
  sums.su += sign * (dv * f.m1 + m * (u2 * n1 - n2));
  sums.sv += sign * (dv * 0.5 * (v1 + v2) * f.m0 + m * (v2 * n1 - 0.5 * m * n2));
  if constexpr (kSecond) {
    sums.suu += sign * (dv * f.m2 + m * (u2 * (u2 * n1 - 2.0 * n2) + n3));
    sums.svv += sign * (dv * (v1 * v1 + v1 * v2 + v2 * v2) * (1.0 / 3.0) * f.m0 +
                        m * (v2 * (v2 * n1 - m * n2) + m * m * n3 * (1.0 / 3.0)));
  }
}

using Lanes = double __attribute__((vector_size(16)));

// Boxes up to this many texels wide are scanned whole (the cells of 10^4 sites over 1024^2
// texels span about 13): a scan costs the box's texels once, a row's sides cost a span per row.
constexpr long kScanColumns = 64;

// Below this du a piece counts as vertical: its m N_j terms (about rho dv du) vanish against
// any cell's moments, and m = dv / du would overflow in m^2.
constexpr double kVerticalDu = 1e-100;

// Pieces inside one texel or across one column line, as columns of numbers: u1 <= u2, the
// piece's sign, its first column k, the densities of its texels (the same one twice for a piece
// inside one texel) and F from the row's reference column to k. Integrated kChunk pieces at a
// time into lane sums that run on across chunks, so that a cell of any size adds its pieces in
// the same order and the columns have fixed addresses (no capacity to load or check per piece).
template <bool kSecond>
class PieceBatch {
 public:
  void clear() {
    size_ = 0;
    a0_ = a1_ = a2_ = a3_ = a4_ = Lanes{0.0, 0.0};
  }
  void push(double u1, double v1, double u2, double v2, double sign, double k, double rho1, double rho2, double f0,
            double f1, double f2) {
    double* at = data_ + size_;
    const double values[kFields] = {u1, v1, u2, v2, sign, k, rho1, rho2, f0, f1, f2};
    for (std::size_t i = 0; i < kFields; ++i) at[i * kChunk] = values[i];
    if (++size_ == kChunk) integrate();
  }

  // Adds the pieces' integrals of H dv to `sums` (the last chunk, then the lanes).
  void finish(Sums& sums) {
    if (size_ % 2) push(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);  // adds nothing
    integrate();
    sums.s0 += a0_[0] + a0_[1];
    sums.su += a1_[0] + a1_[1];
    sums.sv += a3_[0] + a3_[1];
    if constexpr (kSecond) {
      sums.suu += a2_[0] + a2_[1];
      sums.svv += a4_[0] + a4_[1];
    }
  }

 private:
  // The pieces' integrals of H dv into the lanes (the derivation at the top of this file): the
  // texel the piece starts in covers s from ta = du down to tb, the next one from tb to 0 (tb = 0
  // for a piece inside one texel). Two pieces a step in two lanes. Without kSecond the u^2 and
  // v^2 sums are left alone (the other three take the same steps either way).
  void integrate() {
    Lanes a0 = a0_, a1 = a1_, a2 = a2_, a3 = a3_, a4 = a4_;
    const Lanes third{1.0 / 3.0, 1.0 / 3.0};
    for (std::size_t i = 0; i < size_; i += 2) {
      const Lanes u1 = load(0, i), v1 = load(1, i), u2 = load(2, i), v2 = load(3, i), sign = load(4, i);
      const Lanes k = load(5, i), rho1 = load(6, i), rho2 = load(7, i);
      const Lanes du = u2 - u1, dv = v2 - v1;
      const Lanes line = select(u2 < k + 1.0, u2, k + 1.0);  // the column line crossed, or u2
      const Lanes ta = du, tb = u2 - line;                   // s at the left end and at the line
      const Lanes p1 = rho1 * (line - u1), p2 = rho2 * tb;
      const Lanes n1 = 0.5 * (p1 * (ta + tb) + p2 * tb);
      const Lanes n2 = third * (p1 * (ta * ta + ta * tb + tb * tb) + p2 * (tb * tb));
      const Lanes rw = rho1 * (u1 - k);
      const Lanes f0 = load(8, i) + rw, f1 = load(9, i) + rw * (u1 + k) * 0.5;
      const auto slanted = du > kVerticalDu;
      const Lanes m = select(slanted, dv, Lanes{0.0, 0.0}) / select(slanted, du, Lanes{1.0, 1.0});
      a0 += sign * (dv * f0 + m * n1);
      a1 += sign * (dv * f1 + m * (u2 * n1 - n2));
      a3 += sign * (dv * 0.5 * (v1 + v2) * f0 + m * (v2 * n1 - 0.5 * m * n2));
      if constexpr (kSecond) {
        const Lanes n3 = 0.25 * (p1 * (ta + tb) * (ta * ta + tb * tb) + p2 * (tb * tb * tb));
        const Lanes f2 = load(10, i) + rw * (u1 * u1 + u1 * k + k * k) * third;
        a2 += sign * (dv * f2 + m * (u2 * (u2 * n1 - 2.0 * n2) + n3));
        a4 += sign * (dv * (v1 * v1 + v1 * v2 + v2 * v2) * third * f0 + m * (v2 * (v2 * n1 - m * n2) + m * m * n3 * third));
      }
    }
    a0_ = a0, a1_ = a1, a2_ = a2, a3_ = a3, a4_ = a4;
    size_ = 0;
  }

  // Pieces per chunk: even (pairs), and the columns (kFields x kChunk doubles, 5.6 KB) stay in
  // L1; a cell at 10^4 sites over 1024^2 texels has about 30 pieces.
  static constexpr std::size_t kChunk = 64;
  static constexpr std::size_t kFields = 11;
  Lanes load(std::size_t field, std::size_t i) const {
    Lanes v;
    std::memcpy(&v, data_ + field * kChunk + i, sizeof v);
    return v;
  }
  template <class Mask>
  static Lanes select(Mask mask, Lanes yes, Lanes no) {
    using Bits = std::int64_t __attribute__((vector_size(16)));
    const Bits bits = reinterpret_cast<Bits>(mask);
    return reinterpret_cast<Lanes>((reinterpret_cast<Bits>(yes) & bits) | (reinterpret_cast<Bits>(no) & ~bits));
  }
  Lanes a0_, a1_, a2_, a3_, a4_;
  std::size_t size_ = 0;
  double data_[kFields * kChunk];
};

}  // namespace

DensityPrefix::DensityPrefix(const DensityGrid& density) : density_(&density) {
  assert(!density.empty());
  const std::size_t width = static_cast<std::size_t>(density.width);
  blocks_per_row_ = (width + kBlock - 1) / kBlock;
  table_.resize(blocks_per_row_ * static_cast<std::size_t>(density.height));
  for (std::size_t row = 0; row < static_cast<std::size_t>(density.height); ++row) {
    const float* rho = density.texels.data() + row * width;
    Entry* out = table_.data() + row * blocks_per_row_;
    for (std::size_t block = 0; block < width; block += kBlock) {
      double q0 = 0.0, q1 = 0.0, q2 = 0.0;
      const std::size_t end = std::min(width, block + kBlock);
      for (std::size_t c = block; c < end; ++c) {
        const double r = rho[c], i = static_cast<double>(c - block);
        q0 += r;
        q1 += r * (i + 0.5);                // integral of t over [i, i + 1]
        q2 += r * (i * i + i + 1.0 / 3.0);  // integral of t^2 over [i, i + 1]
      }
      out[block / kBlock] = {q0, q1, q2};
    }
  }
}

WeightedMoments DensityPrefix::moments(std::span<const Point> polygon, Point origin, Point domain_size, bool periodic,
                                       bool second) const {
  return second ? integrate<true>(polygon, origin, domain_size, periodic)
                : integrate<false>(polygon, origin, domain_size, periodic);
}

template <bool kSecond>
WeightedMoments DensityPrefix::integrate(std::span<const Point> polygon, Point origin, Point domain_size,
                                         bool periodic) const {
  WeightedMoments moments;
  const std::size_t n = polygon.size();
  if (n < 3) return moments;
  const DensityGrid& density = *density_;
  thread_local std::vector<Point> frame;
  const TexelFrame box = texel_frame(polygon, origin, density, domain_size, frame);
  const Point texel = box.texel, site = box.site;
  const long c0 = box.column, r0 = box.row, columns = box.columns, rows = box.rows;
  const long width = density.width, height = density.height;
  // The grid's index of frame row or column 0, then of the next ones in turn (one remainder per
  // cell and axis, not one per row and column).
  auto first_index = [periodic](long i, long size) {
    if (!periodic) return std::clamp<long>(i, 0, size - 1);
    const long m = i % size;
    return m < 0 ? m + size : m;
  };
  auto next_index = [periodic](long g, long i, long size) {
    if (!periodic) return std::clamp<long>(i, 0, size - 1);
    return g + 1 == size ? 0 : g + 1;
  };
  // Per frame row its texels and blocks, per frame column its grid column.
  thread_local std::vector<const float*> row_texels;
  thread_local std::vector<const Entry*> row_entries;
  thread_local std::vector<long> column_index;
  row_texels.resize(static_cast<std::size_t>(rows));
  row_entries.resize(static_cast<std::size_t>(rows));
  column_index.resize(static_cast<std::size_t>(columns));
  for (long r = 0, g = first_index(r0, height); r < rows; ++r, g = next_index(g, r0 + r, height)) {
    const std::size_t grid_row = static_cast<std::size_t>(g);
    row_texels[static_cast<std::size_t>(r)] = density.texels.data() + grid_row * static_cast<std::size_t>(width);
    row_entries[static_cast<std::size_t>(r)] = table_.data() + grid_row * blocks_per_row_;
  }
  for (long c = 0, g = first_index(c0, width); c < columns; ++c, g = next_index(g, c0 + c, width))
    column_index[static_cast<std::size_t>(c)] = g;
  // F_0, F_1, F_2 over the whole texels [from, to) of a row, frame columns (from <= to), for a
  // box too wide to scan. Blocks whose texels lie in order in the grid come from the table, the
  // rest texel by texel. Accumulated in locals: through a pointer they could alias the table.
  struct Span {
    double f0 = 0.0, f1 = 0.0, f2 = 0.0;
    void add(long k, double r) {
      const double i = static_cast<double>(k);
      f0 += r;
      f1 += r * (i + 0.5);
      f2 += r * (i * i + i + 1.0 / 3.0);
    }
  };
  auto span = [&](const float* rho, const Entry* row, long from, long to) {
    Span f;
    for (long x = from; x < to;) {
      const long g = column_index[static_cast<std::size_t>(x)];
      if (to - x >= kBlock && g % kBlock == 0 && g + kBlock <= width &&
          column_index[static_cast<std::size_t>(x + kBlock - 1)] == g + kBlock - 1) {
        const Entry e = row[g / kBlock];
        const double d = static_cast<double>(x);  // the block's start in the frame
        f.f2 += e.q2 + d * (2.0 * e.q1 + d * e.q0);
        f.f1 += e.q1 + d * e.q0;
        f.f0 += e.q0;
        x += kBlock;
      } else {
        f.add(x, rho[g]);
        ++x;
      }
    }
    return f;
  };

  // A box too wide to scan: each row's two sides and their reference columns (the top of this
  // file), so that a cell costs a constant per piece plus one span per row.
  struct RowSides {
    long down, up;       // the sides' reference columns; kNoColumn until a piece sets one
    double w0, w1, w2;   // the up pieces' integrals of v^0, v^1, v^2 dv
  };
  constexpr long kNoColumn = -1;
  thread_local std::vector<RowSides> sides;
  // A box up to kScanColumns wide: F from its left column to each column of each row, once.
  const bool scan = columns <= kScanColumns;
  // Rows in groups of four, two to a lane pair: for each column the pair's three sums, two rows
  // each, stored as they are (one store per sum and pair, which is what bounds the scan).
  const std::size_t group_stride = 12 * (static_cast<std::size_t>(columns) + 1);
  thread_local std::vector<double> scanned;
  thread_local std::vector<const double*> row_scanned;  // per frame row, its F at column 0
  if (scan) {
    row_scanned.resize(static_cast<std::size_t>(rows));
    scanned.resize(group_stride * static_cast<std::size_t>((rows + 3) / 4));
    for (long r = 0; r < rows; r += 4) {
      const float* rho[4];
      for (long j = 0; j < 4; ++j)
        rho[j] = row_texels[static_cast<std::size_t>(std::min(r + j, rows - 1))];  // a missing row repeats the last
      double* out = scanned.data() + group_stride * static_cast<std::size_t>(r / 4);
      for (long j = 0; j < 4 && r + j < rows; ++j) row_scanned[static_cast<std::size_t>(r + j)] = out + 6 * (j / 2) + j % 2;
      Lanes a0{0.0, 0.0}, a1{0.0, 0.0}, a2{0.0, 0.0}, b0{0.0, 0.0}, b1{0.0, 0.0}, b2{0.0, 0.0};
      for (long c = 0;; ++c) {
        double* at = out + 12 * c;  // F_0, F_1, F_2 of rows r, r + 1; then of rows r + 2, r + 3
        std::memcpy(at, &a0, sizeof a0);
        std::memcpy(at + 2, &a1, sizeof a1);
        std::memcpy(at + 6, &b0, sizeof b0);
        std::memcpy(at + 8, &b1, sizeof b1);
        if constexpr (kSecond) {  // the stores bound the scan: F_2's are left out without it
          std::memcpy(at + 4, &a2, sizeof a2);
          std::memcpy(at + 10, &b2, sizeof b2);
        }
        if (c == columns) break;
        const long g = column_index[static_cast<std::size_t>(c)];
        const double i = static_cast<double>(c), w1 = i + 0.5, w2 = i * i + i + 1.0 / 3.0;
        const Lanes ta{rho[0][g], rho[1][g]}, tb{rho[2][g], rho[3][g]};
        a0 += ta;
        a1 += ta * w1;
        b0 += tb;
        b1 += tb * w1;
        if constexpr (kSecond) {
          a2 += ta * w2;
          b2 += tb * w2;
        }
      }
    }
  } else {
    sides.assign(static_cast<std::size_t>(rows), RowSides{kNoColumn, kNoColumn, 0.0, 0.0, 0.0});
  }

  // The side's reference column for a box too wide to scan (see RowSides), and F from it to c1.
  auto side_columns = [&](long r, long c1, bool up, double sign, double v1, double v2, const float* rho,
                          const Entry* row, Span& f) {
    RowSides& side = sides[static_cast<std::size_t>(r)];
    if (up) {
      // dv and the means of v and v^2 over the piece, as oriented in the polygon.
      const double w = (v2 - v1) * sign;
      side.w0 += w;
      side.w1 += w * 0.5 * (v1 + v2);
      side.w2 += w * (v1 * v1 + v1 * v2 + v2 * v2) * (1.0 / 3.0);
    }
    long& base = up ? side.up : side.down;
    if (base == kNoColumn) base = c1;
    if (c1 > base) {
      f = span(rho, row, base, c1);
    } else if (c1 < base) {
      f = span(rho, row, c1, base);
      f = {-f.f0, -f.f1, -f.f2};
    }
  };

  Sums sums;
  // Pieces inside one or two texels (about nine in ten) are kept in `batch` and integrated
  // together below; wider ones here.
  thread_local PieceBatch<kSecond> batch;
  batch.clear();
  // The piece (pu, pv) -> (qu, qv) of an edge, inside frame row r. Inlined: it runs for every
  // piece, and GCC kept it out of line.
  auto piece = [&](double pu, double pv, double qu, double qv, long r, bool up) __attribute__((always_inline)) {
    if (pv == qv) return;  // dv = 0
    const bool rightwards = pu <= qu;
    const double u1 = rightwards ? pu : qu, v1 = rightwards ? pv : qv;
    const double u2 = rightwards ? qu : pu, v2 = rightwards ? qv : pv;
    const double sign = rightwards ? 1.0 : -1.0;
    const float* rho = row_texels[static_cast<std::size_t>(r)];
    const Entry* row = row_entries[static_cast<std::size_t>(r)];
    const long c1 = std::clamp(static_cast<long>(u1), 0L, columns - 1);
    const long c2 = std::clamp(static_cast<long>(u2), 0L, columns - 1);
    Span f;  // F from the row's reference column to c1
    if (scan) {
      const double* at = row_scanned[static_cast<std::size_t>(r)] + 12 * c1;
      f = {at[0], at[2], kSecond ? at[4] : 0.0};
    } else {
      side_columns(r, c1, up, sign, v1, v2, rho, row, f);
    }
    if (c2 - c1 <= 1) {
      batch.push(u1, v1, u2, v2, sign, static_cast<double>(c1), rho[column_index[static_cast<std::size_t>(c1)]],
                 rho[column_index[static_cast<std::size_t>(c2)]], f.f0, f.f1, f.f2);
      return;
    }
    wide_piece<kSecond>(rho, column_index.data(), u1, v1, u2, v2, sign, c1, c2, {f.f0, f.f1, f.f2}, sums);
  };

  for (std::size_t e = 0; e < n; ++e) {
    const Point a = frame[e], b = frame[e + 1 == n ? 0 : e + 1];
    if (a.y == b.y) continue;  // dv = 0
    long r = std::clamp(static_cast<long>(a.y), 0L, rows - 1);
    const long r_end = std::clamp(static_cast<long>(b.y), 0L, rows - 1);
    const double du_dv = (b.x - a.x) / (b.y - a.y);
    const bool up = b.y > a.y;
    const long step = r_end > r ? 1 : -1;
    double pu = a.x, pv = a.y;
    // A piece ending exactly on a row line has length 0 in the next row.
    for (; r != r_end; r += step) {
      const double line = static_cast<double>(step > 0 ? r + 1 : r);
      const double u = a.x + (line - a.y) * du_dv;
      piece(pu, pv, u, line, r, up);
      pu = u;
      pv = line;
    }
    piece(pu, pv, b.x, b.y, r, up);
  }
  batch.finish(sums);
  // Wide boxes: the up pieces' H from their column, moved to the down pieces' column (the whole
  // texels between the two, once per row).
  for (long r = 0; !scan && r < rows; ++r) {
    const RowSides& side = sides[static_cast<std::size_t>(r)];
    if (side.up == kNoColumn || side.down == kNoColumn || side.up == side.down) continue;
    const float* rho = row_texels[static_cast<std::size_t>(r)];
    const Entry* row = row_entries[static_cast<std::size_t>(r)];
    Span d;
    if (side.up > side.down) {
      d = span(rho, row, side.down, side.up);
    } else {
      d = span(rho, row, side.up, side.down);
      d = {-d.f0, -d.f1, -d.f2};
    }
    sums.s0 += side.w0 * d.f0;
    sums.su += side.w0 * d.f1;
    sums.suu += side.w0 * d.f2;
    sums.sv += side.w1 * d.f0;
    sums.svv += side.w2 * d.f0;
  }
  // Back to domain units, moments about the box's corner, then about `origin` (x - site).
  const double area = texel.x * texel.y;
  moments.mass = sums.s0 * area;
  const Point first{sums.su * area * texel.x, sums.sv * area * texel.y};
  moments.first = first - moments.mass * site;
  if constexpr (kSecond) {
    const double second = (sums.suu * texel.x * texel.x + sums.svv * texel.y * texel.y) * area;
    moments.second =
        second - 2.0 * (first.x * site.x + first.y * site.y) + moments.mass * (site.x * site.x + site.y * site.y);
  }
  return moments;
}

}  // namespace bluetile
