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
// rho w (t1^j + ... + t0^j) / (j + 1), with no cancellation). F_a(u1) comes from the table: for
// each row, the moments of rho t^a (a <= 2) from the start of each block of kBlock columns to
// each column; the blocks between column 0 of the frame and u1 are shifted to the frame
// (t -> t + d: q1 + d q0, q2 + 2 d q1 + d^2 q0) and summed. A cell costs a constant per row piece
// plus the blocks its rows span, instead of every texel of its box.
#include "bluetile/voronoi/density_prefix.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace bluetile {
namespace {

// Integrals of H dv for g = rho times 1, u, v, u^2, v^2 (texel units).
struct Sums {
  double s0 = 0.0, su = 0.0, sv = 0.0, suu = 0.0, svv = 0.0;
};

// Up to this many texels F is summed texel by texel: exact for cells a few texels wide, where
// the table's block shifts would cost relative precision.
constexpr long kDirectTexels = 6;

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

WeightedMoments DensityPrefix::moments(std::span<const Point> polygon, Point origin, Point domain_size,
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
  auto grid_index = [periodic](long i, long size) {
    if (!periodic) return std::clamp<long>(i, 0, size - 1);
    const long m = i % size;
    return m < 0 ? m + size : m;
  };
  thread_local std::vector<std::size_t> row_start;
  thread_local std::vector<std::size_t> row_block;
  thread_local std::vector<long> column_index;
  row_start.resize(static_cast<std::size_t>(rows));
  row_block.resize(static_cast<std::size_t>(rows));
  column_index.resize(static_cast<std::size_t>(columns));
  for (long r = 0; r < rows; ++r)
  {
    const std::size_t grid_row = static_cast<std::size_t>(grid_index(r0 + r, height));
    row_start[static_cast<std::size_t>(r)] = grid_row * static_cast<std::size_t>(width);
    row_block[static_cast<std::size_t>(r)] = grid_row * blocks_per_row_;
  }
  for (long c = 0; c < columns; ++c) column_index[static_cast<std::size_t>(c)] = grid_index(c0 + c, width);
  const long g0 = column_index[0];
  const float* texels = density.texels.data();
  const Entry* table = table_.data();
  // Each row piece reads a row of its own, so the rows' loads are issued up front: one after
  // another they would each wait out a cache miss (the box's rows lie a grid row apart).
  {
    const long last = std::min(width, g0 + columns);
    for (long r = 0; r < rows; ++r) {
      const float* rho = texels + row_start[static_cast<std::size_t>(r)];
      const Entry* row = table + row_block[static_cast<std::size_t>(r)];
      for (long g = g0; g < last; g += 16) __builtin_prefetch(rho + g);
      __builtin_prefetch(rho + last - 1);
      for (long b = g0 / kBlock; b <= (last - 1) / kBlock; b += 2) __builtin_prefetch(row + b);
    }
  }

  // F_0, F_1, F_2 at column line c of the frame (the texels [0, c) of a row). Accumulated in
  // locals: through a pointer they could alias the table, and every add would go through memory.
  struct Prefix {
    double f0 = 0.0, f1 = 0.0, f2 = 0.0;
    void add(long k, double r) {
      const double i = static_cast<double>(k);
      f0 += r;
      f1 += r * (i + 0.5);
      f2 += r * (i * i + i + 1.0 / 3.0);
    }
  };
  auto prefix = [&](const float* rho, const Entry* row, long c) {
    Prefix f;
    if (c <= kDirectTexels) {
      for (long k = 0; k < c; ++k) f.add(k, rho[column_index[static_cast<std::size_t>(k)]]);
      return f;
    }
    long x = 0, g = c0;
    if (periodic) {
      g = g0;
    } else {
      // A bounded box reaches past the grid only by rounding: those columns are clamped texels.
      for (; x < c && g < 0; ++x, ++g) f.add(x, rho[0]);
    }
    while (x < c) {
      if (g >= width) {
        if (!periodic) {
          for (; x < c; ++x) f.add(x, rho[width - 1]);
          break;
        }
        g -= width;
      }
      // Texels [g, g + len) of one block at frame columns [x, x + len): from the block's
      // moments when they are most of it, else texel by texel.
      const long block = g - g % kBlock;
      const long block_end = std::min(block + kBlock, width);
      const long len = std::min(block_end - g, c - x);
      if (2 * len <= block_end - block) {
        for (long i = 0; i < len; ++i) f.add(x + i, rho[g + i]);
      } else {
        const Entry e = row[block / kBlock];
        const double d = static_cast<double>(x - (g - block));  // the block's start in the frame
        f.f2 += e.q2 + d * (2.0 * e.q1 + d * e.q0);
        f.f1 += e.q1 + d * e.q0;
        f.f0 += e.q0;
        for (long i = block; i < g; ++i) f.add(x - (g - i), -rho[i]);
        for (long i = g + len; i < block_end; ++i) f.add(x + (i - g), -rho[i]);
      }
      x += len;
      g += len;
    }
    return f;
  };

  Sums sums;
  // The piece (pu, pv) -> (qu, qv) of an edge, inside frame row r.
  auto piece = [&](double pu, double pv, double qu, double qv, long r) {
    if (pv == qv) return;  // dv = 0
    const bool rightwards = pu <= qu;
    const double u1 = rightwards ? pu : qu, v1 = rightwards ? pv : qv;
    const double u2 = rightwards ? qu : pu, v2 = rightwards ? qv : pv;
    const double sign = rightwards ? 1.0 : -1.0;
    const float* rho = texels + row_start[static_cast<std::size_t>(r)];
    const Entry* row = table + row_block[static_cast<std::size_t>(r)];
    const long c1 = std::clamp(static_cast<long>(u1), 0L, columns - 1);
    const long c2 = std::clamp(static_cast<long>(u2), 0L, columns - 1);
    Prefix f;
    if (c1 > 0) f = prefix(rho, row, c1);
    {
      const double rw = rho[column_index[static_cast<std::size_t>(c1)]] * (u1 - static_cast<double>(c1));
      const double c = static_cast<double>(c1);
      f.f0 += rw;
      f.f1 += rw * (u1 + c) * 0.5;
      f.f2 += rw * (u1 * u1 + u1 * c + c * c) * (1.0 / 3.0);
    }
    const double dv = v2 - v1;
    double s0 = dv * f.f0, su = dv * f.f1, suu = dv * f.f2;
    double sv = dv * 0.5 * (v1 + v2) * f.f0;
    double svv = dv * (v1 * v1 + v1 * v2 + v2 * v2) * (1.0 / 3.0) * f.f0;
    if (c1 == c2) {
      // Inside one texel: N_j = rho du^(j + 1) / (j + 1), so with q = rho dv du the terms
      // m N_j lose their division (and vanish for a vertical piece).
      const double du = u2 - u1, q = rho[column_index[static_cast<std::size_t>(c1)]] * dv * du;
      s0 += 0.5 * q;
      su += q * (0.5 * u2 - du * (1.0 / 3.0));
      suu += q * (u2 * (0.5 * u2 - du * (2.0 / 3.0)) + 0.25 * du * du);
      sv += q * (0.5 * v2 - dv * (1.0 / 6.0));
      svv += q * (v2 * (0.5 * v2 - dv * (1.0 / 3.0)) + dv * dv * (1.0 / 12.0));
    } else {
      // N_j times (j + 1), texel by texel from the right end leftwards.
      double n1 = 0.0, n2 = 0.0, n3 = 0.0;
      double t0 = 0.0;  // s at the texel's right side
      for (long k = c2; k >= c1; --k) {
        const double left = k == c1 ? u1 : static_cast<double>(k);
        const double t1 = u2 - left;  // s at its left side
        const double w = k == c2 ? (k == c1 ? u2 - u1 : u2 - left) : (k == c1 ? static_cast<double>(k + 1) - u1 : 1.0);
        const double rw = rho[column_index[static_cast<std::size_t>(k)]] * w;
        const double t01 = t0 * t1, t00 = t0 * t0, t11 = t1 * t1;
        n1 += rw * (t0 + t1);
        n2 += rw * (t00 + t01 + t11);
        n3 += rw * (t0 + t1) * (t00 + t11);
        t0 = t1;
      }
      n1 *= 0.5;
      n2 *= 1.0 / 3.0;
      n3 *= 0.25;
      const double m = dv / (u2 - u1);
      s0 += m * n1;
      su += m * (u2 * n1 - n2);
      suu += m * (u2 * (u2 * n1 - 2.0 * n2) + n3);
      sv += m * (v2 * n1 - 0.5 * m * n2);
      svv += m * (v2 * (v2 * n1 - m * n2) + m * m * n3 * (1.0 / 3.0));
    }
    sums.s0 += sign * s0;
    sums.su += sign * su;
    sums.sv += sign * sv;
    sums.suu += sign * suu;
    sums.svv += sign * svv;
  };

  for (std::size_t e = 0; e < n; ++e) {
    const Point a = frame[e], b = frame[e + 1 == n ? 0 : e + 1];
    if (a.y == b.y) continue;  // dv = 0
    long r = std::clamp(static_cast<long>(a.y), 0L, rows - 1);
    const long r_end = std::clamp(static_cast<long>(b.y), 0L, rows - 1);
    const double du_dv = (b.x - a.x) / (b.y - a.y);
    const long step = r_end > r ? 1 : -1;
    double pu = a.x, pv = a.y;
    // A piece ending exactly on a row line has length 0 in the next row.
    for (; r != r_end; r += step) {
      const double line = static_cast<double>(step > 0 ? r + 1 : r);
      const double u = a.x + (line - a.y) * du_dv;
      piece(pu, pv, u, line, r);
      pu = u;
      pv = line;
    }
    piece(pu, pv, b.x, b.y, r);
  }
  // Back to domain units, moments about the box's corner, then about `origin` (x - site).
  const double area = texel.x * texel.y;
  moments.mass = sums.s0 * area;
  const Point first{sums.su * area * texel.x, sums.sv * area * texel.y};
  const double second = (sums.suu * texel.x * texel.x + sums.svv * texel.y * texel.y) * area;
  moments.first = first - moments.mass * site;
  moments.second = second - 2.0 * (first.x * site.x + first.y * site.y) + moments.mass * (site.x * site.x + site.y * site.y);
  return moments;
}

}  // namespace bluetile
