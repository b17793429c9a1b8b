// Mean radial power and anisotropy per annulus (the paper, section 1.2; DESIGN section 5, psa's
// convention). Annulus i holds the integer frequencies k with floor(|k| / w) = i; only annuli
// lying wholly inside the periodogram's square are kept (|k| < F/2). P_i is the mean of P over
// the annulus; the anisotropy A_i = s_i^2 / P_i^2 with s_i^2 the sample variance (n - 1), given
// as 10 log10(A_i) dB (white noise: about 0 dB).
#pragma once

#include <cstddef>
#include <vector>

#include "bluetile/analysis/periodogram.h"

namespace bluetile {

struct Annulus {
  double frequency = 0.0;  // inner radius i * w, in integer-frequency units (psa's abscissa)
  double power = 0.0;      // P_i
  // 10 log10(A_i); NaN when the annulus holds fewer than two frequencies or P_i = 0.
  double anisotropy_db = 0.0;
  std::size_t count = 0;   // frequencies in the annulus
};

// The most annuli a radial curve may have: a thousand times the finest useful one (w = 1/1000 at
// the largest periodogram, F = 65536) and far beyond any plot or table.
inline constexpr double kMaxAnnuli = 1e9;

// The annuli of width w in a periodogram of size F: floor((F / 2) / w), in double (a tiny w
// makes more than a size_t holds).
double annulus_count(int size, double bin_width);

// Throws Error when bin_width <= 0 or not finite, when it is wider than half the periodogram's
// size or makes more than kMaxAnnuli annuli (both naming the width), or the periodogram is empty
// or does not hold size^2 values (check_periodogram_values).
std::vector<Annulus> radial_power(const Periodogram& periodogram, double bin_width = 1.0);

}  // namespace bluetile
