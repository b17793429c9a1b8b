// The sweep four triangles at a time in AVX2 lanes: see delaunay_sweep.h. Only the functions
// marked with the target attribute use AVX2 (no -mavx2 for the file, so that no inline function
// of a header is compiled here for AVX2 and picked by the linker for every caller); FMA is not
// enabled, and the file is compiled with -ffp-contract=off besides.
#include "bluetile/voronoi/delaunay_sweep.h"

#include <cstddef>
#include <cstdlib>
#include <cstring>

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define BLUETILE_SWEEP_AVX2 1
#include <immintrin.h>
#else
#define BLUETILE_SWEEP_AVX2 0
#endif

namespace bluetile::detail {

#if BLUETILE_SWEEP_AVX2
namespace {

#define BLUETILE_AVX2 __attribute__((target("avx2")))

using Triangle = PeriodicDelaunay::Triangle;

// Whether a corner uses a shifted copy: shift_x[1], shift_x[2], shift_y[1], shift_y[2] in one load
// of the eight bytes from shift_x (the last two are padding).
static_assert(sizeof(Triangle) == 32 && offsetof(Triangle, shift_x) == 24 && offsetof(Triangle, shift_y) == 27);
inline bool shifted(const Triangle& t) {
  std::uint64_t shifts;
  std::memcpy(&shifts, reinterpret_cast<const unsigned char*>(&t) + offsetof(Triangle, shift_x), sizeof shifts);
  return (shifts & 0x0000ffff00ffff00u) != 0;
}

// Four points' coordinates, one point per lane.
struct Lanes {
  __m256d x, y;
};

BLUETILE_AVX2 inline Lanes gather(const Point* points, std::uint32_t i0, std::uint32_t i1, std::uint32_t i2,
                                  std::uint32_t i3) {
  const __m256d p02 =
      _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(&points[i0].x)), _mm_loadu_pd(&points[i2].x), 1);
  const __m256d p13 =
      _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(&points[i1].x)), _mm_loadu_pd(&points[i3].x), 1);
  return {_mm256_unpacklo_pd(p02, p13), _mm256_unpackhi_pd(p02, p13)};
}

// Four site indices as doubles, in an order-preserving map from unsigned to signed (exact).
BLUETILE_AVX2 inline __m256d site_lanes(std::span<const std::uint32_t> sites, const Triangle* t, int k) {
  const __m128i s = _mm_setr_epi32(static_cast<int>(sites[t[0].vertex[k]] ^ 0x80000000u),
                                   static_cast<int>(sites[t[1].vertex[k]] ^ 0x80000000u),
                                   static_cast<int>(sites[t[2].vertex[k]] ^ 0x80000000u),
                                   static_cast<int>(sites[t[3].vertex[k]] ^ 0x80000000u));
  return _mm256_cvtepi32_pd(s);
}

// Per lane: `b` where `mask`, else `a`.
BLUETILE_AVX2 inline __m256d pick(__m256d a, __m256d b, __m256d mask) { return _mm256_blendv_pd(a, b, mask); }

BLUETILE_AVX2 inline __m256d mul(__m256d a, __m256d b) { return _mm256_mul_pd(a, b); }
BLUETILE_AVX2 inline __m256d add(__m256d a, __m256d b) { return _mm256_add_pd(a, b); }
BLUETILE_AVX2 inline __m256d sub(__m256d a, __m256d b) { return _mm256_sub_pd(a, b); }
BLUETILE_AVX2 inline __m256d greater(__m256d a, __m256d b) { return _mm256_cmp_pd(a, b, _CMP_GT_OQ); }
BLUETILE_AVX2 inline __m256d less(__m256d a, __m256d b) { return _mm256_cmp_pd(a, b, _CMP_LT_OQ); }
BLUETILE_AVX2 inline __m256d equal(__m256d a, __m256d b) { return _mm256_cmp_pd(a, b, _CMP_EQ_OQ); }
BLUETILE_AVX2 inline __m256d neg(__m256d v) { return _mm256_xor_pd(v, _mm256_set1_pd(-0.0)); }
BLUETILE_AVX2 inline __m256d absolute(__m256d v) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), v); }

// Stores the circumcentres of four consecutive triangles relative to their corners: `x[k]`,
// `y[k]` for corner k, lane j for triangle j.
BLUETILE_AVX2 inline void store_centres(Point* out, const __m256d* x, const __m256d* y) {
  // [lane 0, lane 2] and [lane 1, lane 3] of each corner, as (x, y) pairs.
  const __m256d even0 = _mm256_unpacklo_pd(x[0], y[0]), odd0 = _mm256_unpackhi_pd(x[0], y[0]);
  const __m256d even1 = _mm256_unpacklo_pd(x[1], y[1]), odd1 = _mm256_unpackhi_pd(x[1], y[1]);
  const __m256d even2 = _mm256_unpacklo_pd(x[2], y[2]), odd2 = _mm256_unpackhi_pd(x[2], y[2]);
  double* d = &out[0].x;
  _mm256_storeu_pd(d + 0, _mm256_permute2f128_pd(even0, even1, 0x20));
  _mm256_storeu_pd(d + 4, _mm256_permute2f128_pd(even2, odd0, 0x20));
  _mm256_storeu_pd(d + 8, _mm256_permute2f128_pd(odd1, odd2, 0x20));
  _mm256_storeu_pd(d + 12, _mm256_permute2f128_pd(even0, even1, 0x31));
  _mm256_storeu_pd(d + 16, _mm256_permute2f128_pd(even2, odd0, 0x31));
  _mm256_storeu_pd(d + 20, _mm256_permute2f128_pd(odd1, odd2, 0x31));
}

// Triangles [begin, begin + 4 floor((end - begin) / 4)); returns where it stopped. Each lane
// repeats sweep_triangle's operations (delaunay_cells.cpp) in its order; the lanes' results are
// then taken in triangle order, a triangle the lanes cannot finish going through sweep_triangle.
BLUETILE_AVX2 std::size_t sweep_quads(const SweepFrame& frame, std::size_t begin, std::size_t end,
                                      DelaunayCells::Sweep& found) {
  const PeriodicDelaunay& triangulation = frame.triangulation;
  const auto triangles = triangulation.triangles();
  const Point* positions = triangulation.positions().data();
  const auto sites = triangulation.sites();
  const __m256d zero = _mm256_setzero_pd();
  const __m256d orientation_bound = _mm256_set1_pd(kOrientationBound), incircle_bound = _mm256_set1_pd(kIncircleBound);
  const __m256d limit = _mm256_set1_pd(frame.limit);
  std::size_t ti = begin;
  for (; ti + 4 <= end; ti += 4) {
    const Triangle* t = &triangles[ti];
    int oversized = 0;
    // Lanes the scalar form takes whole: a corner at a shifted copy (its offsets need the exact
    // difference), later an orientation the filter cannot decide.
    int scalar = 0;
    for (int j = 0; j < 4; ++j) scalar |= static_cast<int>(shifted(t[j])) << j;
    if (scalar == 0xf) {
      for (int j = 0; j < 4; ++j) sweep_triangle(frame, static_cast<std::uint32_t>(ti + j), found);
      continue;
    }
    const Lanes a = gather(positions, t[0].vertex[0], t[1].vertex[0], t[2].vertex[0], t[3].vertex[0]);
    const Lanes b = gather(positions, t[0].vertex[1], t[1].vertex[1], t[2].vertex[1], t[3].vertex[1]);
    const Lanes c = gather(positions, t[0].vertex[2], t[1].vertex[2], t[2].vertex[2], t[3].vertex[2]);
    // offsets() of delaunay_cells.cpp.
    const __m256d abx = sub(b.x, a.x), aby = sub(b.y, a.y), acx = sub(c.x, a.x), acy = sub(c.y, a.y);
    const __m256d bcx = sub(c.x, b.x), bcy = sub(c.y, b.y);
    const __m256d ab2 = add(mul(abx, abx), mul(aby, aby));
    const __m256d ac2 = add(mul(acx, acx), mul(acy, acy));
    const __m256d bc2 = add(mul(bcx, bcx), mul(bcy, bcy));
    // The orientation filter.
    const __m256d left = mul(abx, acy), right = mul(aby, acx);
    const __m256d turn = sub(left, right);
    const __m256d left_right = add(absolute(left), absolute(right));
    scalar |= ~_mm256_movemask_pd(greater(turn, mul(orientation_bound, left_right))) & 0xf;
    // circumcentres(): the corner x opposite the longest edge (ties: the lower site index, read
    // only where two lengths are equal); m1 where corner 1 beats corner 0, m2 where corner 2 wins.
    const __m256d tie1 = equal(ac2, bc2);
    __m256d m1 = greater(ac2, bc2);
    if (_mm256_movemask_pd(tie1))
      m1 = _mm256_or_pd(m1, _mm256_and_pd(tie1, less(site_lanes(sites, t, 1), site_lanes(sites, t, 0))));
    const __m256d best = pick(bc2, ac2, m1), tie2 = equal(ab2, best);
    __m256d m2 = greater(ab2, best);
    if (_mm256_movemask_pd(tie2)) {
      const __m256d best_site = pick(site_lanes(sites, t, 0), site_lanes(sites, t, 1), m1);
      m2 = _mm256_or_pd(m2, _mm256_and_pd(tie2, less(site_lanes(sites, t, 2), best_site)));
    }
    {
      const __m256d bx = pick(pick(abx, bcx, m1), neg(acx), m2), by = pick(pick(aby, bcy, m1), neg(acy), m2);
      const __m256d bb = pick(pick(ab2, bc2, m1), ac2, m2);
      const __m256d cx = pick(pick(acx, neg(abx), m1), neg(bcx), m2), cy = pick(pick(acy, neg(aby), m1), neg(bcy), m2);
      const __m256d cc = pick(pick(ac2, ab2, m1), bc2, m2);
      const __m256d d = mul(_mm256_set1_pd(2.0), sub(mul(bx, cy), mul(by, cx)));
      const __m256d px = _mm256_div_pd(sub(mul(cy, bb), mul(by, cc)), d);
      const __m256d py = _mm256_div_pd(sub(mul(bx, cc), mul(cx, bb)), d);
      oversized = _mm256_movemask_pd(_mm256_cmp_pd(add(mul(px, px), mul(py, py)), limit, _CMP_NLT_UQ));
      // The centre relative to corner k: p minus the offset from corner x to corner k (p + o is
      // p - (-o) in IEEE arithmetic, and p - 0 is p).
      __m256d out_x[3], out_y[3];
      out_x[0] = sub(px, pick(pick(zero, neg(abx), m1), neg(acx), m2));
      out_y[0] = sub(py, pick(pick(zero, neg(aby), m1), neg(acy), m2));
      out_x[1] = sub(px, pick(pick(abx, zero, m1), neg(bcx), m2));
      out_y[1] = sub(py, pick(pick(aby, zero, m1), neg(bcy), m2));
      out_x[2] = sub(px, pick(pick(acx, bcx, m1), zero, m2));
      out_y[2] = sub(py, pick(pick(acy, bcy, m1), zero, m2));
      if (scalar == 0) {
        store_centres(&frame.centres[3 * ti], out_x, out_y);
      } else {
        // Not over the triangles the scalar form takes (an invalid one keeps what it had).
        alignas(32) double x[3][4], y[3][4];
        for (int k = 0; k < 3; ++k) _mm256_store_pd(x[k], out_x[k]), _mm256_store_pd(y[k], out_y[k]);
        for (int j = 0; j < 4; ++j)
          if (!(scalar >> j & 1))
            for (int k = 0; k < 3; ++k) frame.centres[3 * (ti + j) + k] = {x[k][j], y[k][j]};
      }
    }
    alignas(32) double area[4];
    _mm256_store_pd(area, mul(_mm256_set1_pd(0.5), turn));
    // The in-circle filter of each edge k against the corner across it, owned or not; `settle`:
    // the owned edges the filter does not pass, or whose corner across is at a shifted copy.
    int fail[3], settle = 0;
    for (int k = 0; k < 3; ++k) {
      std::uint32_t across[4];
      int owned = 0, across_shifted = 0;
      for (int j = 0; j < 4; ++j) {
        const std::uint32_t l = t[j].neighbour[k];
        const std::uint32_t ui = PeriodicDelaunay::triangle_of(l);
        const Triangle& u = triangles[ui];
        across[j] = u.vertex[PeriodicDelaunay::edge_of(l)];
        owned |= static_cast<int>(ui >= ti + j) << j;
        across_shifted |= static_cast<int>(shifted(u)) << j;
      }
      const Lanes p = gather(positions, across[0], across[1], across[2], across[3]);
      const __m256d adx = sub(p.x, a.x), ady = sub(p.y, a.y);
      const __m256d ad2 = add(mul(adx, adx), mul(ady, ady));
      const __m256d acad_l = mul(acx, ady), acad_r = mul(acy, adx);
      const __m256d adab_l = mul(adx, aby), adab_r = mul(ady, abx);
      const __m256d det = add(add(mul(ab2, sub(acad_l, acad_r)), mul(ac2, sub(adab_l, adab_r))), mul(ad2, turn));
      const __m256d permanent =
          add(add(mul(ab2, add(absolute(acad_l), absolute(acad_r))), mul(ac2, add(absolute(adab_l), absolute(adab_r)))),
              mul(ad2, left_right));
      const __m256d bound = mul(incircle_bound, permanent);
      const int pass = _mm256_movemask_pd(greater(det, bound));
      fail[k] = _mm256_movemask_pd(greater(neg(det), bound)) & ~across_shifted;
      settle |= (owned & (~pass | across_shifted)) << 4 * k;
    }
    // The lanes' results in triangle order (the area summed in the scalar form's order).
    if ((scalar | oversized | settle) == 0) {
      found.area += area[0], found.area += area[1], found.area += area[2], found.area += area[3];
      continue;
    }
    for (int j = 0; j < 4; ++j) {
      const auto tri = static_cast<std::uint32_t>(ti + j);
      if (scalar >> j & 1) {
        sweep_triangle(frame, tri, found);
        continue;
      }
      found.area += area[j];
      if (oversized >> j & 1) found.oversized.push_back(tri);
      for (int k = 0; k < 3; ++k) {
        if (!(settle >> (4 * k + j) & 1)) continue;
        if (fail[k] >> j & 1) {
          found.suspects.push_back(PeriodicDelaunay::link(tri, k));
        } else {
          // The filter could not decide, or the offset to the corner across needs the exact
          // difference.
          sweep_edge(frame, tri, k, found);
        }
      }
    }
  }
  return ti;
}

// The index in the centres of a corner (a link: triangle, corner).
inline std::uint32_t centre_of(std::uint32_t corner) {
  return 3 * PeriodicDelaunay::triangle_of(corner) + static_cast<std::uint32_t>(PeriodicDelaunay::edge_of(corner));
}

template <bool kSecond>
BLUETILE_AVX2 void walk_quad(const PeriodicDelaunay& triangulation, const Point* centres, const std::uint32_t* vertices,
                             WalkSums& sums) {
  std::uint32_t start[4], corner[4];
  for (int j = 0; j < 4; ++j) corner[j] = start[j] = triangulation.corner_of(vertices[j]);
  const Lanes first = gather(centres, centre_of(start[0]), centre_of(start[1]), centre_of(start[2]), centre_of(start[3]));
  __m256d px = first.x, py = first.y, pr = add(mul(px, px), mul(py, py));
  __m256d cross = _mm256_setzero_pd(), sx = cross, sy = cross, second = cross, radius_squared = cross;
  // Lanes still walking (all bits set), and the same as bits.
  __m256d active = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
  int open = 0xf;
  while (open) {
    std::uint32_t next[4];
    int closed = 0;
    for (int j = 0; j < 4; ++j) {
      // A lane that closed its cell reads its first centre again (its sums no longer change).
      if (open >> j & 1) corner[j] = triangulation.next_around(corner[j]);
      closed |= static_cast<int>(corner[j] == start[j]) << j;
      next[j] = centre_of(corner[j]);
    }
    // The closing edge's q is the first vertex again, so walk's q and its square are the same
    // bits as loaded and squared here.
    const Lanes q = gather(centres, next[0], next[1], next[2], next[3]);
    const __m256d qr = add(mul(q.x, q.x), mul(q.y, q.y));
    const __m256d c = sub(mul(px, q.y), mul(q.x, py));
    cross = pick(cross, add(cross, c), active);
    sx = pick(sx, add(sx, mul(add(px, q.x), c)), active);
    sy = pick(sy, add(sy, mul(add(py, q.y), c)), active);
    if constexpr (kSecond) second = pick(second, add(second, mul(add(add(pr, add(mul(px, q.x), mul(py, q.y))), qr), c)), active);
    radius_squared = pick(radius_squared, pr, _mm256_and_pd(active, less(radius_squared, pr)));
    px = q.x, py = q.y, pr = qr;
    open &= ~closed;
    active = _mm256_and_pd(active, _mm256_castsi256_pd(_mm256_cmpeq_epi64(
                                       _mm256_and_si256(_mm256_set1_epi64x(open), _mm256_setr_epi64x(1, 2, 4, 8)),
                                       _mm256_setr_epi64x(1, 2, 4, 8))));
  }
  _mm256_storeu_pd(sums.cross, cross);
  _mm256_storeu_pd(sums.sx, sx);
  _mm256_storeu_pd(sums.sy, sy);
  _mm256_storeu_pd(sums.second, second);
  _mm256_storeu_pd(sums.radius_squared, radius_squared);
}

}  // namespace

bool sweep_lanes_available() {
  static const bool available = [] {
    const char* simd = std::getenv("BLUETILE_SIMD");
    return __builtin_cpu_supports("avx2") && !(simd && std::strcmp(simd, "0") == 0);
  }();
  return available;
}

void sweep_lanes(const SweepFrame& frame, std::size_t begin, std::size_t end, DelaunayCells::Sweep& found) {
  for (std::size_t ti = sweep_quads(frame, begin, end, found); ti < end; ++ti)
    sweep_triangle(frame, static_cast<std::uint32_t>(ti), found);
}

void walk_lanes(const PeriodicDelaunay& triangulation, const Point* centres, const std::uint32_t* vertices, bool second,
                WalkSums& sums) {
  if (second) {
    walk_quad<true>(triangulation, centres, vertices, sums);
  } else {
    walk_quad<false>(triangulation, centres, vertices, sums);
  }
}

#else

bool sweep_lanes_available() { return false; }

void sweep_lanes(const SweepFrame& frame, std::size_t begin, std::size_t end, DelaunayCells::Sweep& found) {
  for (std::size_t ti = begin; ti < end; ++ti) sweep_triangle(frame, static_cast<std::uint32_t>(ti), found);
}

void walk_lanes(const PeriodicDelaunay&, const Point*, const std::uint32_t*, bool, WalkSums&) {}

#endif

}  // namespace bluetile::detail
