// The exact orientation and in-circle tests (voronoi/predicates.h) against an independent
// reference: the same determinants in exact integer arithmetic (every double is an integer
// multiple of a power of two), on inputs where rounding decides: points a few ulps from a line or
// a circle, the classic grid near (0.5, 0.5) where the floating-point orientation is wrong, and
// periodic copies across the border.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "bluetile/core/rng.h"
#include "bluetile/voronoi/predicates.h"

namespace bluetile {
namespace {

// A signed integer of any size: magnitude in base 2^32, least significant limb first.
struct BigInt {
  bool negative = false;
  std::vector<std::uint32_t> limbs;

  static BigInt from_u64(std::uint64_t v) {
    BigInt r;
    while (v) {
      r.limbs.push_back(static_cast<std::uint32_t>(v));
      v >>= 32;
    }
    return r;
  }
  void trim() {
    while (!limbs.empty() && limbs.back() == 0) limbs.pop_back();
    if (limbs.empty()) negative = false;
  }
  int sign() const { return limbs.empty() ? 0 : (negative ? -1 : 1); }
};

int compare_magnitude(const BigInt& a, const BigInt& b) {
  if (a.limbs.size() != b.limbs.size()) return a.limbs.size() < b.limbs.size() ? -1 : 1;
  for (std::size_t i = a.limbs.size(); i-- > 0;)
    if (a.limbs[i] != b.limbs[i]) return a.limbs[i] < b.limbs[i] ? -1 : 1;
  return 0;
}

BigInt add_magnitudes(const BigInt& a, const BigInt& b) {
  BigInt r;
  std::uint64_t carry = 0;
  for (std::size_t i = 0; i < std::max(a.limbs.size(), b.limbs.size()) || carry; ++i) {
    std::uint64_t s = carry + (i < a.limbs.size() ? a.limbs[i] : 0u) + (i < b.limbs.size() ? b.limbs[i] : 0u);
    r.limbs.push_back(static_cast<std::uint32_t>(s));
    carry = s >> 32;
  }
  return r;
}

// |a| - |b| for |a| >= |b|.
BigInt subtract_magnitudes(const BigInt& a, const BigInt& b) {
  BigInt r;
  std::int64_t borrow = 0;
  for (std::size_t i = 0; i < a.limbs.size(); ++i) {
    std::int64_t d = static_cast<std::int64_t>(a.limbs[i]) - borrow - (i < b.limbs.size() ? b.limbs[i] : 0u);
    borrow = d < 0;
    if (d < 0) d += std::int64_t{1} << 32;
    r.limbs.push_back(static_cast<std::uint32_t>(d));
  }
  r.trim();
  return r;
}

BigInt operator+(const BigInt& a, const BigInt& b) {
  if (a.negative == b.negative) {
    BigInt r = add_magnitudes(a, b);
    r.negative = a.negative;
    r.trim();
    return r;
  }
  if (compare_magnitude(a, b) >= 0) {
    BigInt r = subtract_magnitudes(a, b);
    r.negative = a.negative && r.sign() != 0;
    return r;
  }
  BigInt r = subtract_magnitudes(b, a);
  r.negative = b.negative && r.sign() != 0;
  return r;
}

BigInt operator-(const BigInt& a) {
  BigInt r = a;
  if (r.sign() != 0) r.negative = !r.negative;
  return r;
}
BigInt operator-(const BigInt& a, const BigInt& b) { return a + (-b); }

BigInt operator*(const BigInt& a, const BigInt& b) {
  BigInt r;
  r.limbs.assign(a.limbs.size() + b.limbs.size() + 1, 0u);
  for (std::size_t i = 0; i < a.limbs.size(); ++i) {
    std::uint64_t carry = 0;
    for (std::size_t j = 0; j < b.limbs.size() || carry; ++j) {
      std::uint64_t cur = r.limbs[i + j] + carry + (j < b.limbs.size() ? static_cast<std::uint64_t>(a.limbs[i]) * b.limbs[j] : 0u);
      r.limbs[i + j] = static_cast<std::uint32_t>(cur);
      carry = cur >> 32;
    }
  }
  r.negative = a.negative != b.negative;
  r.trim();
  return r;
}

BigInt shifted_left(const BigInt& a, int bits) {
  BigInt r;
  r.limbs.assign(static_cast<std::size_t>(bits / 32), 0u);
  std::uint32_t carry = 0;
  const int rest = bits % 32;
  for (std::uint32_t limb : a.limbs) {
    r.limbs.push_back(rest ? (limb << rest) | carry : limb);
    carry = rest ? limb >> (32 - rest) : 0u;
  }
  r.limbs.push_back(carry);
  r.negative = a.negative;
  r.trim();
  return r;
}

// x * 2^kScale as an integer: exact for every double with no bits below 2^-kScale (all test
// inputs are 0 or at least 2^-140 in magnitude).
constexpr int kScale = 200;
BigInt exact(double x) {
  if (x == 0.0) return {};
  int exponent = 0;
  const double mantissa = std::frexp(std::abs(x), &exponent);  // x = mantissa 2^exponent, mantissa in [0.5, 1)
  const auto bits = static_cast<std::uint64_t>(std::ldexp(mantissa, 53));
  BigInt r = BigInt::from_u64(bits);
  const int shift = exponent - 53 + kScale;
  EXPECT_GE(shift, 0) << x;
  r = shifted_left(r, shift);
  r.negative = x < 0.0;
  r.trim();
  return r;
}

struct ExactPoint {
  BigInt x, y;
};
ExactPoint exact(const PeriodicPoint& p) { return {exact(p.p.x) + exact(p.shift.x), exact(p.p.y) + exact(p.shift.y)}; }

int reference_orientation(const PeriodicPoint& a, const PeriodicPoint& b, const PeriodicPoint& c) {
  const ExactPoint A = exact(a), B = exact(b), C = exact(c);
  return ((A.x - C.x) * (B.y - C.y) - (A.y - C.y) * (B.x - C.x)).sign();
}

int reference_incircle(const PeriodicPoint& a, const PeriodicPoint& b, const PeriodicPoint& c, const PeriodicPoint& d) {
  const ExactPoint A = exact(a), B = exact(b), C = exact(c), D = exact(d);
  const BigInt adx = A.x - D.x, ady = A.y - D.y, bdx = B.x - D.x, bdy = B.y - D.y, cdx = C.x - D.x, cdy = C.y - D.y;
  const BigInt det = (adx * adx + ady * ady) * (bdx * cdy - bdy * cdx) + (bdx * bdx + bdy * bdy) * (cdx * ady - cdy * adx) +
                     (cdx * cdx + cdy * cdy) * (adx * bdy - ady * bdx);
  return det.sign();
}

// The textbook formulas in floating point, for showing that the inputs are hard.
int naive_orientation(Point a, Point b, Point c) {
  const double det = (a.x - c.x) * (b.y - c.y) - (a.y - c.y) * (b.x - c.x);
  return (det > 0) - (det < 0);
}
int naive_incircle(Point a, Point b, Point c, Point d) {
  const double adx = a.x - d.x, ady = a.y - d.y, bdx = b.x - d.x, bdy = b.y - d.y, cdx = c.x - d.x, cdy = c.y - d.y;
  const double det = (adx * adx + ady * ady) * (bdx * cdy - bdy * cdx) + (bdx * bdx + bdy * bdy) * (cdx * ady - cdy * adx) +
                     (cdx * cdx + cdy * cdy) * (adx * bdy - ady * bdx);
  return (det > 0) - (det < 0);
}

double ulps(double x, int n) {
  for (; n > 0; --n) x = std::nextafter(x, 2.0 * std::abs(x) + 1.0);
  for (; n < 0; ++n) x = std::nextafter(x, -2.0 * std::abs(x) - 1.0);
  return x;
}

TEST(Predicates, OrientationOnTheGridNearOneHalf) {
  // Kettner, Mehlhorn, Pion, Schirra and Yap, "Classroom examples of robustness problems in
  // geometric computations" (2008): p on the 2^-53 grid near (0.5, 0.5), q = (12, 12),
  // r = (24, 24); the floating-point sign is wrong for many p.
  const double u = std::ldexp(1.0, -53);
  int naive_wrong = 0, collinear = 0;
  for (int i = 0; i < 48; ++i) {
    for (int j = 0; j < 48; ++j) {
      const Point p{0.5 + i * u, 0.5 + j * u}, q{12.0, 12.0}, r{24.0, 24.0};
      const int expected = reference_orientation({p}, {q}, {r});
      ASSERT_EQ(orientation(p, q, r), expected) << i << " " << j;
      ASSERT_EQ(orientation(q, r, p), expected) << i << " " << j;
      ASSERT_EQ(orientation(r, q, p), -expected) << i << " " << j;
      naive_wrong += naive_orientation(p, q, r) != expected;
      collinear += expected == 0;
    }
  }
  EXPECT_GT(naive_wrong, 100);  // the inputs are hard
  EXPECT_GE(collinear, 48);     // i == j at least
}

TEST(Predicates, NearlyCollinearPointsOneUlpApart) {
  Rng rng(3);
  int naive_wrong = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Point a{rng.uniform(), rng.uniform()}, b{rng.uniform(), rng.uniform()};
    const double t = rng.uniform() * 3.0 - 1.0;
    Point c = a + t * (b - a);  // on the line up to rounding
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        const Point d{ulps(c.x, dx), ulps(c.y, dy)};
        const int expected = reference_orientation({a}, {b}, {d});
        ASSERT_EQ(orientation(a, b, d), expected) << trial;
        ASSERT_EQ(orientation(d, a, b), expected) << trial;
        naive_wrong += naive_orientation(a, b, d) != expected;
      }
    }
  }
  EXPECT_GT(naive_wrong, 0);
  // Exactly collinear: on the diagonal, and a point moved off it by one ulp either way.
  const Point a{0.1, 0.1}, b{0.3, 0.3};
  EXPECT_EQ(orientation(a, b, {0.7, 0.7}), 0);
  EXPECT_EQ(orientation(a, b, {0.7, ulps(0.7, 1)}), 1);
  EXPECT_EQ(orientation(a, b, {0.7, ulps(0.7, -1)}), -1);
}

TEST(Predicates, NearlyCocircularPointsOneUlpApart) {
  // d put on the circle through a, b, c in floating point: within rounding of it, then moved by
  // up to two ulps along each axis.
  Rng rng(4);
  int naive_wrong = 0, ties = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Point a{rng.uniform(), rng.uniform()}, b{rng.uniform(), rng.uniform()}, c{rng.uniform(), rng.uniform()};
    if (reference_orientation({a}, {b}, {c}) < 0) std::swap(b, c);
    const Point ab = b - a, ac = c - a;
    const double det = 2.0 * (ab.x * ac.y - ab.y * ac.x);
    if (std::abs(det) < 1e-3) continue;
    const Point centre = a + Point{(ac.y * (ab.x * ab.x + ab.y * ab.y) - ab.y * (ac.x * ac.x + ac.y * ac.y)) / det,
                                   (ab.x * (ac.x * ac.x + ac.y * ac.y) - ac.x * (ab.x * ab.x + ab.y * ab.y)) / det};
    const double radius = std::hypot(a.x - centre.x, a.y - centre.y), angle = rng.uniform() * 6.283185307179586;
    const Point on = centre + radius * Point{std::cos(angle), std::sin(angle)};
    for (int dx = -2; dx <= 2; ++dx) {
      for (int dy = -2; dy <= 2; ++dy) {
        const Point d{ulps(on.x, dx), ulps(on.y, dy)};
        const int expected = reference_incircle({a}, {b}, {c}, {d});
        ASSERT_EQ(incircle(a, b, c, d), expected) << trial << " " << dx << " " << dy;
        ASSERT_EQ(incircle(b, c, a, d), expected) << trial;
        ASSERT_EQ(incircle(a, c, b, d), -expected) << trial;
        naive_wrong += naive_incircle(a, b, c, d) != expected;
        ties += expected == 0;
      }
    }
  }
  EXPECT_GT(naive_wrong, 0);
  (void)ties;
}

TEST(Predicates, ExactlyCocircularIntegerPointsAndTheirNeighbours) {
  // 65^2 = 16^2 + 63^2 = 25^2 + 60^2 = 33^2 + 56^2: points exactly on one circle, scaled by a
  // power of two and moved far from the origin (all exact), then one moved by an ulp.
  const double s = std::ldexp(1.0, -20);
  const Point o{0.75, 0.375};
  auto on = [&](double x, double y) { return o + Point{x * s, y * s}; };
  const Point a = on(65, 0), b = on(16, 63), c = on(-25, 60), d = on(-33, -56), e = on(60, -25);
  EXPECT_EQ(incircle(a, b, c, d), 0);
  EXPECT_EQ(incircle(b, c, d, e), 0);
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      const Point moved{ulps(d.x, dx), ulps(d.y, dy)};
      EXPECT_EQ(incircle(a, b, c, moved), reference_incircle({a}, {b}, {c}, {moved})) << dx << " " << dy;
    }
  }
  // Moving d outward along its radius (down and left) puts it outside; inward, inside.
  EXPECT_EQ(incircle(a, b, c, {ulps(d.x, -1), ulps(d.y, -1)}), -1);
  EXPECT_EQ(incircle(a, b, c, {ulps(d.x, 1), ulps(d.y, 1)}), 1);
}

TEST(Predicates, PeriodicCopiesAreTestedExactly) {
  // Sites near the border of the unit torus and their copies one period away: the tests see the
  // exact copy p + k, not the rounded sum, so translating a configuration by whole periods (each
  // point wrapped back with its own shift) never changes an answer.
  Rng rng(5);
  int rounded_wrong = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    // Four points around a corner of the torus, on a circle up to rounding.
    const Point centre{rng.uniform() * 0.02 - 0.01, rng.uniform() * 0.02 - 0.01};
    const double radius = 0.005 + 0.01 * rng.uniform();
    PeriodicPoint q[4];
    Point plain[4];
    double angle = rng.uniform();
    for (int k = 0; k < 4; ++k) {
      angle += 0.5 + rng.uniform();
      Point p = centre + radius * Point{std::cos(angle), std::sin(angle)};
      if (k == 3) p = Point{ulps(p.x, trial % 3 - 1), ulps(p.y, trial % 5 - 2)};
      plain[k] = p;
      const Point wrapped = wrap_point(p, Domain{});
      q[k] = {wrapped, Point{std::round(p.x - wrapped.x), std::round(p.y - wrapped.y)}};
    }
    if (reference_orientation(q[0], q[1], q[2]) <= 0) continue;
    const int expected = reference_incircle(q[0], q[1], q[2], q[3]);
    ASSERT_EQ(incircle(q[0], q[1], q[2], q[3]), expected) << trial;
    ASSERT_EQ(orientation(q[0], q[1], q[3]), reference_orientation(q[0], q[1], q[3])) << trial;
    // The same points, every one a period to the right.
    PeriodicPoint moved[4];
    for (int k = 0; k < 4; ++k) moved[k] = {q[k].p, q[k].shift + Point{1.0, 0.0}};
    ASSERT_EQ(incircle(moved[0], moved[1], moved[2], moved[3]), expected) << trial;
    // The rounded copies (p + k formed in floating point) are other points: the answer may change.
    Point rounded[4];
    for (int k = 0; k < 4; ++k) rounded[k] = q[k].p + q[k].shift + Point{1.0, 0.0};
    rounded_wrong += incircle(rounded[0], rounded[1], rounded[2], rounded[3]) != expected;
    (void)plain;
  }
  EXPECT_GT(rounded_wrong, 0);
}

TEST(Predicates, PerturbationBreaksEveryTieConsistently) {
  // A unit square's corners are cocircular: exactly one diagonal is Delaunay under the
  // perturbation, the same whichever triangle asks, for every assignment of indices.
  const PeriodicPoint p[4] = {{{0.25, 0.25}}, {{0.5, 0.25}}, {{0.5, 0.5}}, {{0.25, 0.5}}};  // counter-clockwise
  std::uint32_t index[4] = {0, 1, 2, 3};
  int flips_ac = 0;
  do {
    int exact = 1;
    // Edge ac, triangles (a, b, c) and (a, c, d): flip when d is inside (a, b, c), asked from
    // either triangle.
    const int from_abc = incircle_perturbed(p[0], p[1], p[2], p[3], index[0], index[1], index[2], index[3], exact);
    EXPECT_EQ(exact, 0);
    const int from_acd = incircle_perturbed(p[0], p[2], p[3], p[1], index[0], index[2], index[3], index[1], exact);
    const int rotated = incircle_perturbed(p[1], p[2], p[0], p[3], index[1], index[2], index[0], index[3], exact);
    EXPECT_NE(from_abc, 0);
    EXPECT_EQ(from_abc, from_acd);
    EXPECT_EQ(from_abc, rotated);
    // Edge bd, triangles (b, c, d) and (b, d, a): the other diagonal.
    const int from_bcd = incircle_perturbed(p[1], p[2], p[3], p[0], index[1], index[2], index[3], index[0], exact);
    EXPECT_EQ(from_bcd, -from_abc);
    flips_ac += from_abc > 0;
  } while (std::next_permutation(index, index + 4));
  EXPECT_GT(flips_ac, 0);   // both diagonals occur over the index orders
  EXPECT_LT(flips_ac, 24);
  // No tie: the perturbation changes nothing.
  int exact = 0;
  EXPECT_EQ(incircle_perturbed({{0.0, 0.0}}, {{1.0, 0.0}}, {{0.0, 1.0}}, {{0.2, 0.2}}, 3, 2, 1, 0, exact), 1);
  EXPECT_EQ(exact, 1);
}

}  // namespace
}  // namespace bluetile
