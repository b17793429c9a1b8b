// A complex fast Fourier transform of power-of-two length: iterative radix-2, decimation in
// time (Cooley and Tukey 1965; the layout of Press et al., "Numerical Recipes", 3rd ed.,
// section 12.2). Used by the non-uniform FFT of the periodogram (periodogram.h); Debian has
// FFTW, but the build takes no dependency for one transform.
#pragma once

#include <cstddef>
#include <vector>

namespace bluetile {

class Fft {
 public:
  // `size` a power of two, 1 to 2^26. Throws Error otherwise.
  explicit Fft(std::size_t size);

  std::size_t size() const { return size_; }

  // In place: X(k) = sum_l x(l) exp(-2 pi i k l / size), k = 0 .. size-1, real and imaginary
  // parts in separate arrays of `size` values. Twiddle factors come from sin and cos each (no
  // recurrence), so the relative RMS error grows like log2(size) ulps. Same bits on every call.
  void forward(double* re, double* im) const;

 private:
  std::size_t size_ = 0;
  std::vector<std::size_t> reversed_;  // bit-reversal permutation, as swaps i < reversed_[i]
  // Stage with half-length h (h = 1, 2, 4, ...) reads exp(-2 pi i j / (2 h)), j < h, at index h + j.
  std::vector<double> twiddle_re_, twiddle_im_;
};

}  // namespace bluetile
