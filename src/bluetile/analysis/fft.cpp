// Iterative radix-2 FFT (Cooley and Tukey 1965; Press et al., "Numerical Recipes", 3rd ed.,
// section 12.2). See fft.h.
#include "bluetile/analysis/fft.h"

#include <cmath>
#include <numbers>
#include <string>

#include "bluetile/core/error.h"

namespace bluetile {

Fft::Fft(std::size_t size) : size_(size) {
  if (size == 0 || (size & (size - 1)) != 0 || size > (std::size_t{1} << 26))
    throw Error("FFT length must be a power of two from 1 to 2^26, got " + std::to_string(size));
  int bits = 0;
  while ((std::size_t{1} << bits) < size) ++bits;
  reversed_.resize(size);
  for (std::size_t i = 0; i < size; ++i) {
    std::size_t r = 0;
    for (int b = 0; b < bits; ++b) r |= ((i >> b) & 1u) << (bits - 1 - b);
    reversed_[i] = r;
  }
  twiddle_re_.assign(size, 0.0);
  twiddle_im_.assign(size, 0.0);
  for (std::size_t h = 1; h < size; h *= 2) {
    for (std::size_t j = 0; j < h; ++j) {
      const double angle = -std::numbers::pi * static_cast<double>(j) / static_cast<double>(h);
      twiddle_re_[h + j] = std::cos(angle);
      twiddle_im_[h + j] = std::sin(angle);
    }
  }
}

void Fft::forward(double* __restrict re, double* __restrict im) const {
  const std::size_t n = size_;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t r = reversed_[i];
    if (i < r) {
      std::swap(re[i], re[r]);
      std::swap(im[i], im[r]);
    }
  }
  if (n >= 2) {  // h = 1: twiddle 1, no multiplications
    for (std::size_t i = 0; i < n; i += 2) {
      const double ar = re[i], ai = im[i], br = re[i + 1], bi = im[i + 1];
      re[i] = ar + br, im[i] = ai + bi;
      re[i + 1] = ar - br, im[i + 1] = ai - bi;
    }
  }
  for (std::size_t h = 2; h < n; h *= 2) {
    const double* __restrict wr = twiddle_re_.data() + h;
    const double* __restrict wi = twiddle_im_.data() + h;
    for (std::size_t start = 0; start < n; start += 2 * h) {
      double* __restrict ar = re + start;
      double* __restrict ai = im + start;
      double* __restrict br = re + start + h;
      double* __restrict bi = im + start + h;
      for (std::size_t j = 0; j < h; ++j) {
        const double tr = br[j] * wr[j] - bi[j] * wi[j];
        const double ti = br[j] * wi[j] + bi[j] * wr[j];
        br[j] = ar[j] - tr, bi[j] = ai[j] - ti;
        ar[j] = ar[j] + tr, ai[j] = ai[j] + ti;
      }
    }
  }
}

}  // namespace bluetile
