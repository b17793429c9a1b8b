// Radial power and anisotropy (the paper, section 1.2; DESIGN section 5; psa's RadialPower and
// Anisotropy). Sums run over the square in row order, so results do not depend on threads.
#include "bluetile/analysis/radial_power.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <limits>

#include "bluetile/core/error.h"
#include "bluetile/core/text.h"

namespace bluetile {

double annulus_count(int size, double bin_width) { return std::floor(static_cast<double>(size / 2) / bin_width); }

std::vector<Annulus> radial_power(const Periodogram& periodogram, double bin_width) {
  if (!(bin_width > 0.0) || !std::isfinite(bin_width)) throw Error("annulus width must be positive");
  if (periodogram.size < 2) throw Error("radial power of an empty periodogram");
  check_periodogram_values(periodogram);
  const int half = periodogram.half();
  const double count = annulus_count(periodogram.size, bin_width);
  const ClassicNumbers classic;
  char width[32];
  std::snprintf(width, sizeof width, "%.17g", bin_width);
  if (count < 1.0)
    throw Error("annulus width " + std::string(width) + " is wider than half the periodogram size (" +
                std::to_string(half) + ")");
  if (count > kMaxAnnuli) {
    char text[160];
    std::snprintf(text, sizeof text, "annulus width %s is too narrow: %.3g annuli, more than the limit of %.0e", width,
                  count, kMaxAnnuli);
    throw Error(text);
  }
  const auto annuli = static_cast<std::size_t>(count);

  auto annulus_of = [&](int kx, int ky) -> std::size_t {
    double r = std::sqrt(static_cast<double>(kx * kx + ky * ky));
    return static_cast<std::size_t>(std::floor(r / bin_width));
  };
  std::vector<Annulus> result(annuli);
  std::vector<double> sum(annuli, 0.0), squares(annuli, 0.0);
  for (int ky = -half; ky < half; ++ky) {
    for (int kx = -half; kx < half; ++kx) {
      std::size_t i = annulus_of(kx, ky);
      if (i >= annuli) continue;
      sum[i] += periodogram.at(kx, ky);
      ++result[i].count;
    }
  }
  for (std::size_t i = 0; i < annuli; ++i) {
    result[i].frequency = static_cast<double>(i) * bin_width;
    result[i].power = result[i].count ? sum[i] / static_cast<double>(result[i].count) : 0.0;
  }
  for (int ky = -half; ky < half; ++ky) {
    for (int kx = -half; kx < half; ++kx) {
      std::size_t i = annulus_of(kx, ky);
      if (i >= annuli) continue;
      double d = periodogram.at(kx, ky) - result[i].power;
      squares[i] += d * d;
    }
  }
  for (std::size_t i = 0; i < annuli; ++i) {
    Annulus& a = result[i];
    if (a.count < 2 || !(a.power > 0.0)) {
      a.anisotropy_db = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    double variance = squares[i] / static_cast<double>(a.count - 1);
    a.anisotropy_db = 10.0 * std::log10(variance / (a.power * a.power));
  }
  return result;
}

}  // namespace bluetile
