// Scalar measures of a radial power spectrum, after Heck, Schlömer and Deussen, "Blue noise
// sampling with controlled aliasing" (ACM TOG 32(3), 2013), computed the way their analysis
// tool psa (v1.1a, `psa --stats`) computes them, so figures paste beside psa's. The definitions
// were read from psa's source (src/statistics.cpp); this is our own code. psa assumes the unit
// torus, and so do these functions.
//
// The spectrum is not the periodogram: psa derives it from a fine radial distribution function
// (RDF) by a windowed Hankel transform. For N points, with B = int(100 sqrt N):
// - RDF: pair distances on the torus in B bins of width dr = 0.5 / B over [0, 0.5), bin j
//   divided by (N (N - 1) / 2) pi dr^2 (2 j + 1) (1 for white noise);
// - power at B frequencies u_i = i du, du = sqrt(N) / 200 (integer frequencies, 0 to N / 2):
//   P(u) = |1 + 2 pi N sum_j dr (g_j - 1) J0(2 pi u r_j) r_j w(r_j)|, r_j = j dr, and w a
//   Blackman window of half-width L = 0.5 clamp(4 u / sqrt N, 0.2, 0.5) (it tames the RDF's
//   truncation and noise: narrow at low frequencies, where nu_eff is decided).
// Frequencies are reported as nu = u / sqrt(N): a square lattice's first peak lies at nu = 1.
//
// - Effective Nyquist frequency nu_eff: with C(u) the mean power over the disc of radius u,
//   take the first u >= sqrt(N) / 2 where C exceeds 0.5; nu_eff is the last u' <= u where C is
//   below 0.1, as nu (0 when there is none). White noise gives 0; a step spectrum with its edge
//   at nu_e gives nu_e / sqrt(0.9); the window blurs a lattice's first peak, so a square
//   lattice of 256 points gives 0.815, not the 1 of its zero region.
// - Oscillations Omega: from u0, where the running maximum of P first reaches 0.98, to
//   u1 = min(u0 + 5 sqrt N, N / 2): Omega = 10 sqrt(2 pi integral (P - 1)^2 u du / (pi (u1^2 -
//   u0^2))), ten times the RMS deviation of P from 1 over that ring. psa's sampling of the
//   grid (single-precision bin indices, its trapezoid rule) is kept, so figures agree to a bin.
// See docs/RESULTS.md ("Analysis measures") for figures beside psa's.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile {

// The Nyquist frequency of a square lattice: |k| = sqrt(N / A) / 2 in integer frequencies is
// nu = 1 on the periodogram plots' axis (f / (sqrt(N / A) / 2)). Throws Error for no points or
// an area that is not a finite positive number (they gave infinity and NaN).
double normalised_frequency(double frequency, std::size_t count, double area = 1.0);

// psa's number of RDF bins and of spectrum samples, int(100 sqrt N).
std::size_t psa_bins(std::size_t count);

// The radial power spectrum of psa's statistics: power[i] at u_i = i * step (integer
// frequencies of the unit torus), i < psa_bins(count).
struct RdfPowerSpectrum {
  std::size_t count = 0;  // points per set
  std::size_t sets = 1;   // sets averaged
  double step = 0.0;      // du = (N / 2) / psa_bins(N)
  std::vector<double> power;

  double frequency(std::size_t i) const { return static_cast<double>(i) * step; }
  // u_i / sqrt(N): psa's normalisation of nu_eff.
  double nu(std::size_t i) const;
};

// From one set on the unit torus (coordinates wrapped into [0, 1)). Throws Error for fewer than
// 2 points and for a point that is not finite. Same result whatever the thread count. Cost: the pairs closer than 0.25 (about
// N^2 / 5, as psa's RDF) and B^2 / 2 Bessel functions; N = 16384 takes about 4 s on 2 cores.
RdfPowerSpectrum rdf_power_spectrum(std::span<const Point> points);

// The work of rdf_power_spectrum for `count` points, for estimates before it runs: the point
// pairs it histograms (those closer than the window's reach, about 0.25: pi 0.25^2 N^2 / 2, so
// O(N^2) by psa's definition: its RDF must reach a quarter of the torus) and the Bessel
// functions of its transform (about B^2 / 2 = 5000 N).
double rdf_power_spectrum_pairs(std::size_t count);
double rdf_power_spectrum_bessels(std::size_t count);

// The mean power of several spectra of equal count (psa --avg). Throws Error for none or for
// different counts.
RdfPowerSpectrum average_spectra(std::span<const RdfPowerSpectrum> spectra);

struct SpectralMeasures {
  double nu_eff = 0.0;
  double omega = 0.0;
  double omega_from_nu = 0.0;  // the ring Omega integrates over, u0 / sqrt(N) and u1 / sqrt(N)
  double omega_to_nu = 0.0;
};

// nu_eff and Omega as psa --stats prints them. Throws Error for a spectrum of fewer than 2
// samples.
SpectralMeasures spectral_measures(const RdfPowerSpectrum& spectrum);

// J0, the Bessel function of the first kind of order 0 (Abramowitz and Stegun 9.4.1 and 9.4.3,
// absolute error below 1e-7): std::cyl_bessel_j is some ten times slower, and the spectrum
// takes N B / 2 of them.
double bessel_j0(double x);

}  // namespace bluetile
