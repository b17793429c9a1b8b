// Exact stages of the orientation and in-circle tests (predicates.h), after Shewchuk 1997:
// expansions (sums of non-overlapping doubles ordered by magnitude) built with error-free
// transformations: Knuth's two-sum, and the two-product by a fused multiply-add (the rounding
// error of a * b is exactly fma(a, b, -fl(a * b))). Every operation is exact, so the sign of the
// final expansion, the sign of its largest component, is the sign of the exact determinant.
// Speed matters little here: the filters in predicates.h decide all but near-degenerate cases.
#include "bluetile/voronoi/predicates.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace bluetile {
namespace detail {
namespace {

// x + y = a + b exactly, x = fl(a + b).
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double b_virtual = x - a;
  const double a_virtual = x - b_virtual;
  y = (a - a_virtual) + (b - b_virtual);
}

// x + y = a * b exactly, x = fl(a * b).
inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  y = std::fma(a, b, -x);
}

// An expansion: components[0, size) non-overlapping, increasing in magnitude, none zero
// (the empty expansion is zero). Capacity: two expansions of at most 21 components each (the 1100
// bits between the largest and the smallest double) multiply into at most 2 * 21 * 21 before
// compressing; the determinants of differences exact as doubles need at most 96.
template <int Capacity>
struct BasicExpansion {
  static constexpr int kCapacity = Capacity;
  std::array<double, Capacity> c;
  int size = 0;

  BasicExpansion() = default;
  // Copies only the components in use (the array is large, expansions short).
  BasicExpansion(const BasicExpansion& other) : size(other.size) { std::copy_n(other.c.begin(), size, c.begin()); }
  BasicExpansion& operator=(const BasicExpansion& other) {
    size = other.size;
    std::copy_n(other.c.begin(), size, c.begin());
    return *this;
  }

  void push(double x) {
    assert(size < kCapacity);
    if (x != 0.0) c[static_cast<std::size_t>(size++)] = x;
  }
  int sign() const { return size == 0 ? 0 : (c[static_cast<std::size_t>(size - 1)] > 0.0 ? 1 : -1); }
};
using Expansion = BasicExpansion<1024>;
using SmallExpansion = BasicExpansion<128>;

// h = e + b (Shewchuk's grow-expansion, zero components dropped).
template <typename E>
void grow(const E& e, double b, E& h) {
  h.size = 0;
  double q = b;
  for (int i = 0; i < e.size; ++i) {
    double sum, error;
    two_sum(q, e.c[static_cast<std::size_t>(i)], sum, error);
    h.push(error);
    q = sum;
  }
  h.push(q);
}

// h = e + f (Shewchuk's expansion-sum, his theorem 12): f's components are added one at a time,
// each from its own place in the sum (the components below it are final there), then the zeros
// dropped. h must not be e or f.
template <typename E>
void add(const E& e, const E& f, E& h) {
  if (f.size == 0) {
    h = e;
    return;
  }
  if (e.size == 0) {
    h = f;
    return;
  }
  assert(e.size + f.size <= E::kCapacity);
  int last = 0;
  double q = f.c[0];
  for (int i = 0; i < e.size; ++i) {
    double sum, error;
    two_sum(q, e.c[static_cast<std::size_t>(i)], sum, error);
    h.c[static_cast<std::size_t>(i)] = error;
    q = sum;
  }
  last = e.size;
  h.c[static_cast<std::size_t>(last)] = q;
  for (int j = 1; j < f.size; ++j) {
    q = f.c[static_cast<std::size_t>(j)];
    for (int i = j; i <= last; ++i) {
      double sum, error;
      two_sum(q, h.c[static_cast<std::size_t>(i)], sum, error);
      h.c[static_cast<std::size_t>(i)] = error;
      q = sum;
    }
    h.c[static_cast<std::size_t>(++last)] = q;
  }
  int kept = 0;
  for (int i = 0; i <= last; ++i)
    if (h.c[static_cast<std::size_t>(i)] != 0.0) h.c[static_cast<std::size_t>(kept++)] = h.c[static_cast<std::size_t>(i)];
  h.size = kept;
}

template <typename E>
void negate(E& e) {
  for (int i = 0; i < e.size; ++i) e.c[static_cast<std::size_t>(i)] = -e.c[static_cast<std::size_t>(i)];
}

// h = e * b (Shewchuk's scale-expansion, zero components dropped).
template <typename E>
void scale(const E& e, double b, E& h) {
  h.size = 0;
  if (e.size == 0 || b == 0.0) return;
  double q, low;
  two_product(e.c[0], b, q, low);
  h.push(low);
  for (int i = 1; i < e.size; ++i) {
    double product, product_low, sum, error;
    two_product(e.c[static_cast<std::size_t>(i)], b, product, product_low);
    two_sum(q, product_low, sum, error);
    h.push(error);
    two_sum(product, sum, q, error);
    h.push(error);
  }
  h.push(q);
}

// The same value in as few components as the non-overlapping form allows (Shewchuk's compress):
// a pass from the largest component down gathers carries, a pass back up separates them again.
template <typename E>
void compress(E& e) {
  if (e.size < 2) return;
  std::array<double, E::kCapacity> g;
  int bottom = e.size - 1;
  double q = e.c[static_cast<std::size_t>(bottom)];
  for (int i = e.size - 2; i >= 0; --i) {
    double sum, error;
    two_sum(q, e.c[static_cast<std::size_t>(i)], sum, error);
    if (error != 0.0) {
      g[static_cast<std::size_t>(bottom--)] = sum;
      q = error;
    } else {
      q = sum;
    }
  }
  g[static_cast<std::size_t>(bottom)] = q;
  E h;
  double top = g[static_cast<std::size_t>(bottom)];
  for (int i = bottom + 1; i < e.size; ++i) {
    double sum, error;
    two_sum(g[static_cast<std::size_t>(i)], top, sum, error);
    h.push(error);
    top = sum;
  }
  h.push(top);
  e = h;
}

// h = e * f, compressed.
template <typename E>
void multiply(const E& e, const E& f, E& h) {
  // The partial sums alternate between two buffers: no copies.
  E sums[2], term;
  int current = 0;
  for (int j = 0; j < f.size; ++j) {
    scale(e, f.c[static_cast<std::size_t>(j)], term);
    add(sums[current], term, sums[1 - current]);
    current = 1 - current;
  }
  compress(sums[current]);
  h = sums[current];
}

// The exact difference of two copies' coordinates as an expansion (always exact, whether or
// not the shifts cancel exactly).
Expansion difference(double a, double a_shift, double b, double b_shift) {
  double hi, lo;
  two_sum(a, -b, hi, lo);
  Expansion e;
  e.push(lo);
  e.push(hi);
  if (a_shift != b_shift) {
    Expansion shifted;
    grow(e, a_shift - b_shift, shifted);  // a_shift - b_shift: a whole number of periods, exact
    e = shifted;
    compress(e);
  }
  return e;
}

Expansion cross(const Expansion& ax, const Expansion& ay, const Expansion& bx, const Expansion& by) {
  Expansion left, right, det;
  multiply(ax, by, left);
  multiply(ay, bx, right);
  negate(right);
  add(left, right, det);
  compress(det);
  return det;
}

// Whether the difference of two copies' coordinates is a double, and that double.
bool difference_as_double(double a, double a_shift, double b, double b_shift, double& out) {
  double hi, lo;
  two_sum(a, -b, hi, lo);
  if (a_shift == b_shift) {
    out = hi;
    return lo == 0.0;
  }
  double shifted, error;
  two_sum(hi, a_shift - b_shift, shifted, error);  // a_shift - b_shift: whole periods, exact
  out = shifted;
  return lo == 0.0 && error == 0.0;
}

// The in-circle determinant when every difference is exact as a double (Shewchuk's stage B):
// each term lift * cross as two scalings of the cross product's expansion per coordinate.
int incircle_of_exact_differences(double adx, double ady, double bdx, double bdy, double cdx, double cdy) {
  auto cross2 = [](double px, double py, double qx, double qy) {
    SmallExpansion left, right, out;
    double hi, lo;
    two_product(px, qy, hi, lo);
    left.push(lo);
    left.push(hi);
    two_product(py, qx, hi, lo);
    right.push(-lo);
    right.push(-hi);
    add(left, right, out);
    return out;
  };
  auto term = [](const SmallExpansion& cross, double x, double y) {
    SmallExpansion xc, xxc, yc, yyc, sum;
    scale(cross, x, xc);
    scale(xc, x, xxc);
    scale(cross, y, yc);
    scale(yc, y, yyc);
    add(xxc, yyc, sum);
    return sum;
  };
  const SmallExpansion a = term(cross2(bdx, bdy, cdx, cdy), adx, ady);
  const SmallExpansion b = term(cross2(cdx, cdy, adx, ady), bdx, bdy);
  const SmallExpansion c = term(cross2(adx, ady, bdx, bdy), cdx, cdy);
  SmallExpansion ab, det;
  add(a, b, ab);
  add(ab, c, det);
  return det.sign();
}

}  // namespace

ExactDifference exact_difference(double a, double a_shift, double b, double b_shift) {
  double hi, lo;
  two_sum(a, -b, hi, lo);
  if (a_shift == b_shift) return {hi, lo};
  // |a - b + shift| <= half a period puts hi within a factor 2 of the shift: Sterbenz's lemma
  // makes hi + shift exact, and one more sum gives the correctly rounded difference.
  const double shifted = hi + (a_shift - b_shift);
  double rounded, error;
  two_sum(shifted, lo, rounded, error);
  return {rounded, error};
}

int orientation_exact(const PeriodicPoint& a, const PeriodicPoint& b, const PeriodicPoint& c) {
  const Expansion acx = difference(a.p.x, a.shift.x, c.p.x, c.shift.x);
  const Expansion acy = difference(a.p.y, a.shift.y, c.p.y, c.shift.y);
  const Expansion bcx = difference(b.p.x, b.shift.x, c.p.x, c.shift.x);
  const Expansion bcy = difference(b.p.y, b.shift.y, c.p.y, c.shift.y);
  return cross(acx, acy, bcx, bcy).sign();
}

int incircle_exact(const PeriodicPoint& a, const PeriodicPoint& b, const PeriodicPoint& c, const PeriodicPoint& d) {
  // Nearly cocircular sites on a lattice: differences often exact as doubles, and the determinant
  // of doubles is much cheaper than the general one.
  double adx_, ady_, bdx_, bdy_, cdx_, cdy_;
  if (difference_as_double(a.p.x, a.shift.x, d.p.x, d.shift.x, adx_) && difference_as_double(a.p.y, a.shift.y, d.p.y, d.shift.y, ady_) &&
      difference_as_double(b.p.x, b.shift.x, d.p.x, d.shift.x, bdx_) && difference_as_double(b.p.y, b.shift.y, d.p.y, d.shift.y, bdy_) &&
      difference_as_double(c.p.x, c.shift.x, d.p.x, d.shift.x, cdx_) && difference_as_double(c.p.y, c.shift.y, d.p.y, d.shift.y, cdy_))
    return incircle_of_exact_differences(adx_, ady_, bdx_, bdy_, cdx_, cdy_);
  const Expansion adx = difference(a.p.x, a.shift.x, d.p.x, d.shift.x);
  const Expansion ady = difference(a.p.y, a.shift.y, d.p.y, d.shift.y);
  const Expansion bdx = difference(b.p.x, b.shift.x, d.p.x, d.shift.x);
  const Expansion bdy = difference(b.p.y, b.shift.y, d.p.y, d.shift.y);
  const Expansion cdx = difference(c.p.x, c.shift.x, d.p.x, d.shift.x);
  const Expansion cdy = difference(c.p.y, c.shift.y, d.p.y, d.shift.y);
  auto lift = [](const Expansion& x, const Expansion& y) {
    Expansion xx, yy, sum;
    multiply(x, x, xx);
    multiply(y, y, yy);
    add(xx, yy, sum);
    compress(sum);
    return sum;
  };
  // det = |a - d|^2 (b - d) x (c - d) + |b - d|^2 (c - d) x (a - d) + |c - d|^2 (a - d) x (b - d)
  Expansion terms[3];
  multiply(lift(adx, ady), cross(bdx, bdy, cdx, cdy), terms[0]);
  multiply(lift(bdx, bdy), cross(cdx, cdy, adx, ady), terms[1]);
  multiply(lift(cdx, cdy), cross(adx, ady, bdx, bdy), terms[2]);
  Expansion partial, det;
  add(terms[0], terms[1], partial);
  add(partial, terms[2], det);
  return det.sign();
}

}  // namespace detail

int incircle_perturbed(const PeriodicPoint& a, const PeriodicPoint& b, const PeriodicPoint& c, const PeriodicPoint& d,
                       std::uint32_t index_a, std::uint32_t index_b, std::uint32_t index_c, std::uint32_t index_d,
                       int& exact_sign) {
  exact_sign = incircle(a, b, c, d);
  if (exact_sign != 0) return exact_sign;
  // With the lifted height of point X raised by e_X, the determinant gains e_X times X's
  // cofactor: orient(d, b, c), orient(d, c, a), orient(d, a, b) for a, b, c, and -orient(a, b, c)
  // for d. The lowest index has the largest e_X: its cofactor decides, or the next one's when it
  // is zero (three of the points collinear).
  assert(index_a != index_b && index_a != index_c && index_a != index_d && index_b != index_c && index_b != index_d &&
         index_c != index_d);
  std::array<std::pair<std::uint32_t, int>, 4> order{{{index_a, 0}, {index_b, 1}, {index_c, 2}, {index_d, 3}}};
  std::sort(order.begin(), order.end());
  for (const auto& [index, which] : order) {
    (void)index;
    int sign = 0;
    switch (which) {
      case 0: sign = orientation(d, b, c); break;
      case 1: sign = orientation(d, c, a); break;
      case 2: sign = orientation(d, a, b); break;
      default: sign = -orientation(a, b, c); break;
    }
    if (sign != 0) return sign;
  }
  return 0;
}

}  // namespace bluetile
