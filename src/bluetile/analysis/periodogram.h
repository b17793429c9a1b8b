// The periodogram of a point set on the unit torus, by the direct sum (DESIGN section 5, psa's
// convention, Heck & Schlömer): P(k) = |sum_j exp(-2 pi i k.x_j)|^2 / N over integer frequency
// vectors k in [-F/2, F/2)^2. White noise gives P about 1 away from k = 0, and P(0) = N. The
// paper's spectral power R_f (section 1.2) is P / N.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile {

struct Periodogram {
  int size = 0;  // F, even: frequencies -F/2 .. F/2-1 on each axis
  // F * F values, row by row: index (ky + F/2) * F + (kx + F/2).
  std::vector<double> power;

  int half() const { return size / 2; }
  double at(int kx, int ky) const {
    return power[static_cast<std::size_t>(ky + half()) * static_cast<std::size_t>(size) +
                 static_cast<std::size_t>(kx + half())];
  }
};

// psa's default F = 2 floor(5 sqrt(N)): frequencies up to 5 sqrt(N), about 2.7 times the
// frequency of the hexagonal lattice of N points.
int default_periodogram_size(std::size_t count);

// Direct sum over all points for every k, in double precision, on all threads. The result is
// bit-identical whatever the thread count (each value is summed over the points in a fixed
// order). P(0) = N exactly. `size` must be even and >= 2; points must not be empty. `progress`
// (optional) is called with (done, total) work units, serialised, from any thread. Throws Error
// on bad arguments.
Periodogram compute_periodogram(std::span<const Point> points, int size,
                                const std::function<void(std::size_t, std::size_t)>& progress = {});

// Mean of several periodograms of the same size (the usual way spectra are shown: psa
// --avg). Throws Error when sizes differ or the list is empty.
Periodogram average_periodograms(std::span<const Periodogram> periodograms);

}  // namespace bluetile
