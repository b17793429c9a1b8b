// Scalar measures of a radial power spectrum, after Heck, Schlömer and Deussen, "Blue noise
// sampling with controlled aliasing" (ACM TOG 32(3), 2013), and psa, their analysis tool.
//
// Frequencies are normalised the way psa plots them: nu = f / (sqrt(N / A) / 2), f in integer
// frequencies of the unit torus. nu = 1 is the Nyquist frequency of a square lattice of N
// points, so curves of sets of different N overlay.
//
// - Effective Nyquist frequency nu_eff: half the radius of the zero region (where the radial
//   power stays below 0.1), as the Nyquist frequency is half the sampling rate: a signal below
//   nu_eff is sampled without aliasing onto itself. A square lattice has nu_eff = 1 and the
//   hexagonal lattice 1.0746 (its first ring of peaks lies at f = sqrt(2 N / sqrt 3)); white
//   noise has 0. Step blue noise cannot exceed 1/sqrt(pi) = 0.564 (TOG 2013, section 5).
// - Oscillations Omega: how far the spectrum strays from the flat white-noise level 1,
//   Omega = integral of (P - 1)^2 over the signal frequency nu / 2 from 0 to 5 (psa's range,
//   nu up to 10; fixed, so it does not depend on nu_eff, as in psa 1.1). White noise gives about
//   0; peaks (structured aliasing) raise it.
// Both are our reading of the published definitions; psa's code (GPL) was not consulted. See
// docs/RESULTS.md ("Analysis measures") for how they compare with published values.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "bluetile/analysis/radial_power.h"

namespace bluetile {

constexpr double kZeroRegionPower = 0.1;      // radial power that ends the zero region
constexpr double kOscillationRangeNu = 10.0;  // Omega integrates up to nu = 10 (psa's frange)

// f / (sqrt(N / A) / 2).
double normalised_frequency(double frequency, std::size_t count, double area = 1.0);

struct SpectralMeasures {
  double nu_eff = 0.0;
  double omega = 0.0;
  double omega_range = 0.0;  // the nu up to which Omega could integrate (10 unless the curve ends earlier)
};

// From samples of a radial power curve: normalised frequencies `nu` (increasing, >= 0) and
// powers. nu_eff interpolates linearly where the curve first reaches kZeroRegionPower (0 when
// the first sample does; the last nu when none does). Omega integrates by the trapezoid rule
// over the samples up to kOscillationRangeNu. Throws Error for fewer than 2 samples or
// mismatched sizes.
SpectralMeasures spectral_measures(std::span<const double> nu, std::span<const double> power);

// The same from annuli of a periodogram of `count` points (annulus 0, k = 0, left out; each
// annulus taken at its centre frequency).
SpectralMeasures spectral_measures(std::span<const Annulus> radial, double bin_width, std::size_t count,
                                   double area = 1.0);

}  // namespace bluetile
