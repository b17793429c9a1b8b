// Exact orientation and in-circle tests on double-precision points, by the method of Shewchuk,
// "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric Predicates" (Discrete
// and Computational Geometry 18, 1997): the determinant is first evaluated in floating point
// beside a bound on its rounding error (his error bounds "A"); when the bound cannot decide the
// sign, the determinant is evaluated exactly as a floating-point expansion (a sum of
// non-overlapping doubles, his sections 2.3-2.8). The answer is always the sign of the exact
// determinant of the inputs, whatever the roundings.
//
// Points may be periodic copies: a site p in [0, W) x [0, H) shifted by whole periods, the copy
// p + (kx W, ky H). The tests act on that exact copy, never on a rounded p + kx W, so a
// configuration gives the same answer wherever its copies lie. The differences between the
// points of one test must be at most half a period along each axis (what a triangulation with
// edges shorter than a quarter period gives); they are then formed with one rounding.
//
// Exact as long as no product of four coordinate differences underflows or overflows: nonzero
// differences between about 2^-200 and 2^200 (the kept triangulation, kept_delaunay.h, holds its
// scenes to sides of 2^-20 to 2^20 and coordinates that are 0 or at least 2^-100).
#pragma once

#include <cmath>
#include <cstdint>

#include "bluetile/core/torus.h"

namespace bluetile {

// The copy p + shift of a site, shift = (kx W, ky H) for small whole kx, ky (an exact double).
struct PeriodicPoint {
  Point p;
  Point shift{0.0, 0.0};
};

namespace detail {

// The difference a - b of two periodic copies along one axis, exact as hi + lo with hi the
// correctly rounded difference (the precondition of the header comment makes the period
// shifts cancel exactly).
struct ExactDifference {
  double hi, lo;
};
ExactDifference exact_difference(double a, double a_shift, double b, double b_shift);

// The exact stages (predicates.cpp), for callers that ran the filter themselves.
int orientation_exact(const PeriodicPoint& a, const PeriodicPoint& b, const PeriodicPoint& c);
int incircle_exact(const PeriodicPoint& a, const PeriodicPoint& b, const PeriodicPoint& c, const PeriodicPoint& d);

// The unit roundoff of double precision (half an ulp of 1).
inline constexpr double kUnitRoundoff = 0x1p-53;
// Relative error bounds of the floating-point evaluations (Shewchuk's ccwerrboundA and
// iccerrboundA), doubled: the room costs a few more exact evaluations near ties, nothing else.
inline constexpr double kOrientationBound = 2.0 * (3.0 + 16.0 * kUnitRoundoff) * kUnitRoundoff;
inline constexpr double kIncircleBound = 2.0 * (10.0 + 96.0 * kUnitRoundoff) * kUnitRoundoff;

// The rounded difference a - b (a correctly rounded one: see exact_difference).
inline double rounded_difference(double a, double a_shift, double b, double b_shift) {
  if (a_shift == b_shift) return a - b;
  return exact_difference(a, a_shift, b, b_shift).hi;
}

}  // namespace detail

// Sign of the orientation of (a, b, c): +1 counter-clockwise, -1 clockwise, 0 collinear. Inline:
// the floating-point evaluation decides nearly every call.
inline int orientation(const PeriodicPoint& a, const PeriodicPoint& b, const PeriodicPoint& c) {
  using namespace detail;
  const double acx = rounded_difference(a.p.x, a.shift.x, c.p.x, c.shift.x);
  const double acy = rounded_difference(a.p.y, a.shift.y, c.p.y, c.shift.y);
  const double bcx = rounded_difference(b.p.x, b.shift.x, c.p.x, c.shift.x);
  const double bcy = rounded_difference(b.p.y, b.shift.y, c.p.y, c.shift.y);
  const double left = acx * bcy, right = acy * bcx;
  const double det = left - right;
  const double bound = kOrientationBound * (std::abs(left) + std::abs(right));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return orientation_exact(a, b, c);
}

// Sign of the in-circle determinant: +1 when d lies inside the circle through a, b, c (given
// counter-clockwise), -1 outside, 0 on it. For a, b, c clockwise the sign is reversed.
inline int incircle(const PeriodicPoint& a, const PeriodicPoint& b, const PeriodicPoint& c, const PeriodicPoint& d) {
  using namespace detail;
  const double adx = rounded_difference(a.p.x, a.shift.x, d.p.x, d.shift.x);
  const double ady = rounded_difference(a.p.y, a.shift.y, d.p.y, d.shift.y);
  const double bdx = rounded_difference(b.p.x, b.shift.x, d.p.x, d.shift.x);
  const double bdy = rounded_difference(b.p.y, b.shift.y, d.p.y, d.shift.y);
  const double cdx = rounded_difference(c.p.x, c.shift.x, d.p.x, d.shift.x);
  const double cdy = rounded_difference(c.p.y, c.shift.y, d.p.y, d.shift.y);
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double alift = adx * adx + ady * ady;
  const double blift = bdx * bdx + bdy * bdy;
  const double clift = cdx * cdx + cdy * cdy;
  const double det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * alift + (std::abs(cdxady) + std::abs(adxcdy)) * blift +
                           (std::abs(adxbdy) + std::abs(bdxady)) * clift;
  const double bound = kIncircleBound * permanent;
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return incircle_exact(a, b, c, d);
}

inline int orientation(Point a, Point b, Point c) { return orientation(PeriodicPoint{a}, PeriodicPoint{b}, PeriodicPoint{c}); }
inline int incircle(Point a, Point b, Point c, Point d) {
  return incircle(PeriodicPoint{a}, PeriodicPoint{b}, PeriodicPoint{c}, PeriodicPoint{d});
}

// The in-circle test under a symbolic perturbation (Edelsbrunner and Mücke, "Simulation of
// Simplicity", ACM TOG 9, 1990): each site's lifted height |p|^2 is raised by an infinitesimal
// that is larger the lower its index (`index_*`, the site's index, shared by its copies), so
// four cocircular sites get a definite answer that every test agrees with: the Delaunay
// triangulation under the perturbation is unique. Never 0 for a, b, c counter-clockwise and
// four different sites. `exact_sign` receives the unperturbed sign (0: a true tie).
int incircle_perturbed(const PeriodicPoint& a, const PeriodicPoint& b, const PeriodicPoint& c, const PeriodicPoint& d,
                       std::uint32_t index_a, std::uint32_t index_b, std::uint32_t index_c, std::uint32_t index_d,
                       int& exact_sign);

}  // namespace bluetile
