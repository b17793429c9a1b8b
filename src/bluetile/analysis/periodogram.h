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
// frequency of the hexagonal lattice of N points. Throws Error for a count whose size passes an int
// (beyond 4.6e16 points).
int default_periodogram_size(std::size_t count);

// The periodogram by whichever of the two methods below is faster for N and F: the direct sum
// for small sets, the non-uniform FFT above a few thousand points (their values agree to 1e-9 of
// P(0) = N). Bit-identical whatever the thread count. P(0) = N exactly. `size` must be even, 2
// to 65536; points must not be empty. `progress` (optional) is called with (done, total) work
// units, serialised, from any thread. Throws Error on bad arguments.
Periodogram compute_periodogram(std::span<const Point> points, int size,
                                const std::function<void(std::size_t, std::size_t)>& progress = {});

// Direct sum over all points for every k, in double precision, on all threads (each value is
// summed over the points in a fixed order): O(N F^2), the oracle of the fast method. Points off
// [0, 1) are taken modulo 1. Errors as compute_periodogram.
Periodogram compute_periodogram_direct(std::span<const Point> points, int size,
                                       const std::function<void(std::size_t, std::size_t)>& progress = {});

// Type-1 non-uniform FFT (exponential-of-semicircle kernel, upsampled grid M = the power of two
// >= 1.5 F, periodogram_nufft.cpp): O(N w^2 + M^2 log M) with w about 14. Every value within
// 1e-9 N of the direct sum (in practice about 1e-12 N). Errors as compute_periodogram.
Periodogram compute_periodogram_nufft(std::span<const Point> points, int size,
                                      const std::function<void(std::size_t, std::size_t)>& progress = {});

// Whether compute_periodogram takes the non-uniform FFT for `count` points and size F.
bool periodogram_uses_nufft(std::size_t count, int size);

// Side M of the non-uniform FFT's grid for size F.
std::size_t periodogram_nufft_grid(int size);

// Throws Error("periodogram size must be even, 2 to 65536, got <size>") for a size the
// periodograms above refuse.
void check_periodogram_size(int size);

// Bytes compute_periodogram allocates at its peak for `count` points and size F (on the
// current thread count), for up-front memory checks (also for sizes past 65536, which
// compute_periodogram refuses). Throws Error for a size below 2 (-2 gave 17440 bytes).
std::size_t periodogram_memory_bytes(std::size_t count, int size);

// Throws Error unless `periodogram` holds size^2 values (a Periodogram filled by hand with fewer
// was read past its end).
void check_periodogram_values(const Periodogram& periodogram);

// Mean of several periodograms of the same size (the usual way spectra are shown: psa
// --avg). Throws Error when sizes differ, a periodogram fails check_periodogram_values or the list
// is empty.
Periodogram average_periodograms(std::span<const Periodogram> periodograms);

}  // namespace bluetile
