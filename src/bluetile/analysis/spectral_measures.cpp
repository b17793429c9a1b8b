// Effective Nyquist frequency and oscillations of a radial power spectrum (Heck, Schlömer and
// Deussen 2013; psa). See spectral_measures.h for the definitions as we read them.
#include "bluetile/analysis/spectral_measures.h"

#include <algorithm>
#include <cmath>

#include "bluetile/core/error.h"

namespace bluetile {

double normalised_frequency(double frequency, std::size_t count, double area) {
  return frequency / (0.5 * std::sqrt(static_cast<double>(count) / area));
}

SpectralMeasures spectral_measures(std::span<const double> nu, std::span<const double> power) {
  if (nu.size() != power.size() || nu.size() < 2)
    throw Error("spectral measures need at least 2 samples of frequency and power");
  SpectralMeasures m;
  // Zero region: up to the first frequency whose power reaches the threshold.
  double edge = nu.back();
  for (std::size_t i = 0; i < nu.size(); ++i) {
    if (!(power[i] >= kZeroRegionPower)) continue;
    if (i == 0) {
      edge = 0.0;
    } else {
      const double t = (kZeroRegionPower - power[i - 1]) / (power[i] - power[i - 1]);
      edge = nu[i - 1] + std::clamp(t, 0.0, 1.0) * (nu[i] - nu[i - 1]);
    }
    break;
  }
  if (nu.front() > 0.0 && power.front() >= kZeroRegionPower) edge = 0.0;
  m.nu_eff = 0.5 * edge;

  // Omega over the signal frequency nu / 2: half the integral over nu.
  double integral = 0.0;
  for (std::size_t i = 0; i + 1 < nu.size() && nu[i] < kOscillationRangeNu; ++i) {
    const double a = nu[i], b = std::min(nu[i + 1], kOscillationRangeNu);
    if (!(b > a) || !std::isfinite(power[i]) || !std::isfinite(power[i + 1])) continue;
    // Linear power between the samples, cut at the range.
    const double pb = power[i] + (power[i + 1] - power[i]) * (b - a) / (nu[i + 1] - nu[i]);
    const double da = power[i] - 1.0, db = pb - 1.0;
    integral += 0.5 * (da * da + db * db) * (b - a);
  }
  m.omega = 0.5 * integral;
  m.omega_range = std::min(nu.back(), kOscillationRangeNu);
  return m;
}

SpectralMeasures spectral_measures(std::span<const Annulus> radial, double bin_width, std::size_t count,
                                   double area) {
  std::vector<double> nu, power;
  for (std::size_t i = 1; i < radial.size(); ++i) {
    if (radial[i].count == 0) continue;
    nu.push_back(normalised_frequency(radial[i].frequency + 0.5 * bin_width, count, area));
    power.push_back(radial[i].power);
  }
  return spectral_measures(nu, power);
}

}  // namespace bluetile
