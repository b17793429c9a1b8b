// Effective Nyquist frequency and oscillations of the radial power spectrum derived from the
// RDF, as psa v1.1a computes them (Heck, Schlömer and Deussen, ACM TOG 32(3), 2013). See
// spectral_measures.h for the definitions.
#include "bluetile/analysis/spectral_measures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "bluetile/analysis/pair_correlation.h"
#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLowPower = 0.1;        // nu_eff: the disc's mean power is still "zero" below this
constexpr double kHalfPower = 0.5;       // ... and has risen once it exceeds this
constexpr double kFlatPower = 0.98;      // Omega starts where the power has (nearly) reached 1
constexpr float kOmegaRingPeaks = 10.0f;  // Omega's ring: 10 Nyquist frequencies sqrt(N) / 2 wide
constexpr std::size_t kGrain = 16;       // frequencies per parallel chunk

// psa keeps its curves in single precision: the frequency of sample i and the sample of a
// frequency are computed in float, so a bin boundary falls where psa's does.
struct FloatGrid {
  float dx;
  float x(std::size_t i) const { return static_cast<float>(i) * dx; }
  int index(float x) const { return static_cast<int>(x / dx); }
};

FloatGrid spectrum_grid(std::size_t count, std::size_t bins) {
  return {0.5f * static_cast<float>(count) / static_cast<float>(bins)};
}

double blackman(double x, double half_width) {
  if (x > half_width) return 0.0;
  return 0.43 + 0.5 * std::cos(kPi * x / half_width) + 0.08 * std::cos(2.0 * kPi * x / half_width);
}

}  // namespace

double normalised_frequency(double frequency, std::size_t count, double area) {
  if (count == 0) throw Error("normalised frequency: no points, so no Nyquist frequency");
  if (!(area > 0.0 && std::isfinite(area)))
    throw Error("normalised frequency: area " + exact_text(area) + " is not a finite positive number");
  return frequency / (0.5 * std::sqrt(static_cast<double>(count) / area));
}

std::size_t psa_bins(std::size_t count) {
  return static_cast<std::size_t>(100.0f * std::sqrt(static_cast<float>(count)));
}

double RdfPowerSpectrum::nu(std::size_t i) const { return frequency(i) / std::sqrt(static_cast<double>(count)); }

double bessel_j0(double x) {
  x = std::abs(x);
  if (x <= 3.0) {
    const double t = (x / 3.0) * (x / 3.0);
    return 1.0 +
           t * (-2.2499997 + t * (1.2656208 + t * (-0.3163866 + t * (0.0444479 + t * (-0.0039444 + t * 0.0002100)))));
  }
  const double y = 3.0 / x;
  const double f = 0.79788456 +
                   y * (-0.00000077 +
                        y * (-0.00552740 + y * (-0.00009512 + y * (0.00137237 + y * (-0.00072805 + y * 0.00014476)))));
  const double theta =
      x - 0.78539816 +
      y * (-0.04166397 + y * (-0.00003954 + y * (0.00262573 + y * (-0.00054125 + y * (-0.00029333 + y * 0.00013558)))));
  return f * std::cos(theta) / std::sqrt(x);
}

RdfPowerSpectrum rdf_power_spectrum(std::span<const Point> points) {
  const std::size_t n = points.size();
  if (n < 2) throw Error("the RDF power spectrum needs at least 2 points, got " + std::to_string(n));
  // A NaN or infinite point cannot be wrapped; it fell out of every bin without a word.
  check_finite_points(points, "RDF power spectrum");
  const std::size_t bins = psa_bins(n);
  const float dr = 0.5f / static_cast<float>(bins);
  // The window is at most 0.25 wide: bins beyond it never count, so pairs are only histogrammed
  // up to there (a quarter of the pair work of psa's full range 0.5).
  const std::size_t rdf_bins = std::min(bins, bins / 2 + 2);
  RdfOptions options;
  options.boundary = Boundary::periodic;
  options.bins = rdf_bins;
  const double range = static_cast<double>(rdf_bins) * static_cast<double>(dr);
  options.range = range / hexagonal_spacing(static_cast<double>(n));
  const RadialDistribution rdf = radial_distribution(points, options);

  RdfPowerSpectrum spectrum;
  spectrum.count = n;
  const FloatGrid grid = spectrum_grid(n, bins);
  spectrum.step = grid.dx;
  spectrum.power.assign(bins, 0.0);
  const float wstep = 1.0f / std::sqrt(static_cast<float>(n));
  const double scale = 2.0 * kPi * static_cast<double>(n) * static_cast<double>(dr);
  parallel_for(bins, kGrain, [&](std::size_t begin, std::size_t end) {
    // (g_j - 1) r_j w(r_j) for the window in use; above u = sqrt(N) / 8 it no longer changes.
    std::vector<double> weight;
    std::vector<float> radius;
    float weight_half_width = -1.0f;
    for (std::size_t i = begin; i < end; ++i) {
      const float u = grid.x(i);
      const float half_width = 0.5f * std::min(0.5f, std::max(0.2f, 4.0f * u * wstep));
      if (half_width != weight_half_width) {
        weight.clear();
        radius.clear();
        for (std::size_t j = 1; j < rdf.g.size(); ++j) {  // r_0 = 0 adds nothing
          const float r = static_cast<float>(j) * dr;
          if (r > half_width) break;
          radius.push_back(r);
          weight.push_back((rdf.g[j] - 1.0) * r * blackman(r, half_width));
        }
        weight_half_width = half_width;
      }
      const double a = 2.0 * kPi * static_cast<double>(u);
      double sum = 0.0;
      for (std::size_t j = 0; j < weight.size(); ++j) sum += weight[j] * bessel_j0(a * radius[j]);
      spectrum.power[i] = std::abs(1.0 + scale * sum);
    }
  });
  return spectrum;
}

double rdf_power_spectrum_pairs(std::size_t count) {
  const double bins = static_cast<double>(psa_bins(count));
  const double reach = 0.5 / bins * std::min(bins, std::floor(bins / 2.0) + 2.0);  // the histogram's range
  const double n = static_cast<double>(count);
  return kPi * reach * reach * n * (n - 1.0) / 2.0;
}

double rdf_power_spectrum_bessels(std::size_t count) {
  const double bins = static_cast<double>(psa_bins(count));
  return bins * std::min(bins, std::floor(bins / 2.0) + 2.0);
}

RdfPowerSpectrum average_spectra(std::span<const RdfPowerSpectrum> spectra) {
  if (spectra.empty()) throw Error("no spectra to average");
  RdfPowerSpectrum mean = spectra[0];
  for (std::size_t k = 1; k < spectra.size(); ++k) {
    if (spectra[k].count != mean.count || spectra[k].power.size() != mean.power.size())
      throw Error("cannot average spectra of sets of different sizes (" + std::to_string(mean.count) + " and " +
                  std::to_string(spectra[k].count) + " points)");
    for (std::size_t i = 0; i < mean.power.size(); ++i) mean.power[i] += spectra[k].power[i];
  }
  for (double& p : mean.power) p /= static_cast<double>(spectra.size());
  mean.sets = spectra.size();
  return mean;
}

SpectralMeasures spectral_measures(const RdfPowerSpectrum& spectrum) {
  const std::vector<double>& p = spectrum.power;
  const std::size_t size = p.size();
  if (size < 2 || spectrum.count < 2) throw Error("spectral measures need a spectrum of at least 2 samples");
  const FloatGrid grid = spectrum_grid(spectrum.count, size);
  const float root_n = std::sqrt(static_cast<float>(spectrum.count));
  const double to_nu = 1.0 / std::sqrt(static_cast<double>(spectrum.count));
  SpectralMeasures m;

  // nu_eff. mean[i]: mean power over the disc of radius u_i; low[i]: the last j in [1, i] whose
  // mean is below kLowPower (0 for none).
  std::vector<double> mean(size, 0.0);
  std::vector<std::size_t> low(size, 0);
  double cumulative = 0.0;
  for (std::size_t i = 0; i < size; ++i) {
    const double u = grid.x(i);
    cumulative += p[i] * grid.dx * 2.0 * u;
    if (i == 0) continue;
    mean[i] = cumulative / (u * u);
    low[i] = mean[i] < kLowPower ? i : low[i - 1];
  }
  const auto start = static_cast<std::size_t>(std::max(0, grid.index(0.5f * root_n)));
  for (std::size_t i = start; i < size; ++i) {
    if (mean[i] > kHalfPower && low[i] > 0) {
      m.nu_eff = static_cast<double>(grid.x(low[i])) * to_nu;
      break;
    }
  }

  // Omega. u0: where the running maximum of the power first reaches kFlatPower (else the
  // maximum's frequency).
  float u0 = 0.0f;
  double highest = 0.0;
  for (std::size_t i = 0; i < size && highest < kFlatPower; ++i) {
    if (p[i] > highest) {
      highest = p[i];
      u0 = grid.x(i);
    }
  }
  const float u1 = std::min(u0 + kOmegaRingPeaks * (0.5f * root_n), 0.5f * static_cast<float>(spectrum.count));
  auto integrand = [&](int i) {
    const float u = grid.x(static_cast<std::size_t>(i));
    return u < u0 ? 0.0 : (p[i] - 1.0) * (p[i] - 1.0) * u;
  };
  // psa's quadrature: ends half-weighted, every sample between counted once, except that the
  // sample before the last is left out when the two ends are an even number of samples apart.
  const int last = static_cast<int>(size) - 1;
  const int i0 = std::clamp(grid.index(u0), 0, last), i1 = std::clamp(grid.index(u1 + grid.dx), 0, last);
  double sum = 0.5 * (integrand(i0) + integrand(i1));
  for (int i = i0 + 2; i < i1; i += 2) sum += integrand(i) + integrand(i - 1);
  const double integral = grid.dx * sum;
  const double ring = kPi * (static_cast<double>(u1) * u1 - static_cast<double>(u0) * u0);
  m.omega = ring > 0.0 ? 10.0 * std::sqrt(2.0 * kPi * integral / ring) : std::numeric_limits<double>::quiet_NaN();
  m.omega_from_nu = u0 * to_nu;
  m.omega_to_nu = u1 * to_nu;
  return m;
}

}  // namespace bluetile
