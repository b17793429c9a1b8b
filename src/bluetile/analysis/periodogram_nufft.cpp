// The periodogram by a type-1 non-uniform FFT: the "exponential of semicircle" (ES) kernel
// method of Barnett, Magland and af Klinteberg, "A parallel non-uniform fast Fourier transform
// library based on an exponential of semicircle kernel" (SIAM J. Sci. Comput. 41(5), 2019),
// sections 2 and 3, written here from the paper's description.
//
// Each point is spread onto an M x M grid (M a power of two >= 1.5 F) with the separable kernel
// psi(t) = exp(beta (sqrt(1 - (2 t / w)^2) - 1)), |t| <= w / 2 grid cells; the grid's FFT at
// integer frequency k is then sum_j exp(-2 pi i k.x_j) psi^(kx / M) psi^(ky / M), up to the
// aliased tails of psi^ beyond M / 2 (which the paper's choice of w and beta for the upsampling
// sigma = M / F keeps near the tolerance, section 3), and dividing by the kernel's Fourier
// transform psi^ (by Gauss-Legendre quadrature) gives the sums.
//
// Determinism: the grid is cut into stripes of rows; each stripe is spread by one task from the
// points whose kernel touches it, in point order, and transformed along x by the same task, so
// every grid value and every transform is the same whatever the thread count. The columns are
// then transformed along y, one task per block of columns, each writing its own outputs.
// The grid is real (unit weights): two rows go through one complex FFT, and only kx >= 0 is
// transformed, P(-k) = P(k) giving the rest.
#include <algorithm>
#include <cstdint>
#include <cmath>
#include <mutex>
#include <numbers>
#include <string>

#include "bluetile/analysis/fft.h"
#include "bluetile/analysis/periodogram.h"
#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"

namespace bluetile {
namespace {

constexpr double kPi = std::numbers::pi;
// The paper's tolerance parameter. Its errors are not a bound: with 1e-11 a single point's power
// was off by up to 5e-10 (of P(0) = N = 1, the worst case: sums of many points average their
// errors down); with 1e-12 by at most 3e-11, well inside the 1e-9 the periodogram promises.
constexpr double kTolerance = 1e-12;
constexpr double kMinUpsampling = 1.5;   // M >= 1.5 F: memory and FFT work against kernel width
constexpr int kMaxWidth = 16;            // w for kTolerance at sigma = 1.5 is 16
constexpr std::size_t kStripeRows = 32;  // grid rows per spreading task (>= kMaxWidth: a point touches <= 2 stripes)
constexpr std::size_t kColumnBlock = 16;  // kx per column task: whole cache lines per written output row
constexpr int kQuadratureNodes = 64;     // Gauss-Legendre nodes for psi^: psi is analytic inside [-w/2, w/2]

struct EsKernel {
  int width = 0;      // w, grid cells
  double beta = 0.0;
  double value(double t) const {  // t in grid cells, |t| <= w / 2 (clamped)
    const double z = 2.0 * t / width;
    const double s = 1.0 - z * z;
    return s > 0.0 ? std::exp(beta * (std::sqrt(s) - 1.0)) : 0.0;
  }
};

// The paper's parameter choice (section 3, equation (3.3) and after): for upsampling sigma,
// w = ceil(ln(1 / eps) / (pi sqrt(1 - 1 / sigma))) and beta = 0.97 pi w (1 - 1 / (2 sigma)).
EsKernel choose_kernel(double sigma) {
  EsKernel k;
  k.width = static_cast<int>(std::ceil(std::log(1.0 / kTolerance) / (kPi * std::sqrt(1.0 - 1.0 / sigma))));
  k.width = std::clamp(k.width, 2, kMaxWidth);
  k.beta = 0.97 * kPi * k.width * (1.0 - 1.0 / (2.0 * sigma));
  return k;
}

// Gauss-Legendre nodes and weights on [-1, 1] by Newton's method on P_n (Press et al.,
// "Numerical Recipes", 3rd ed., section 4.6).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.assign(static_cast<std::size_t>(n), 0.0);
  weights.assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = 0.0;
      for (int j = 1; j <= n; ++j) {
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * j - 1.0) * x * p1 - (j - 1.0) * p2) / j;
      }
      derivative = n * (x * p0 - p1) / (x * x - 1.0);
      const double step = p0 / derivative;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    const double w = 2.0 / ((1.0 - x * x) * derivative * derivative);
    nodes[static_cast<std::size_t>(i)] = -x, nodes[static_cast<std::size_t>(n - 1 - i)] = x;
    weights[static_cast<std::size_t>(i)] = weights[static_cast<std::size_t>(n - 1 - i)] = w;
  }
}

// psi^(k / M) = integral of psi(t) exp(-2 pi i k t / M) dt = 2 integral_0^(w/2) psi(t) cos(2 pi k t / M) dt,
// for k = 0 .. count-1.
std::vector<double> kernel_transform(const EsKernel& kernel, std::size_t grid, std::size_t count) {
  std::vector<double> nodes, weights;
  gauss_legendre(kQuadratureNodes, nodes, weights);
  const double half = 0.5 * kernel.width;
  std::vector<double> t(nodes.size()), f(nodes.size());
  for (std::size_t q = 0; q < nodes.size(); ++q) {
    t[q] = half * 0.5 * (nodes[q] + 1.0);  // [0, w/2]
    f[q] = kernel.value(t[q]) * weights[q] * half * 0.5;
  }
  std::vector<double> result(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double a = 2.0 * kPi * static_cast<double>(k) / static_cast<double>(grid);
    double sum = 0.0;
    for (std::size_t q = 0; q < t.size(); ++q) sum += f[q] * std::cos(a * t[q]);
    result[k] = 2.0 * sum;
  }
  return result;
}

std::size_t grid_size(int size) {
  std::size_t m = 32;  // at least twice the widest kernel
  while (static_cast<double>(m) < kMinUpsampling * size) m *= 2;
  return m;
}

// The kernel's support of coordinate c in [0, 1) on a grid of m cells: first cell (may be
// negative, to be wrapped) and the w values.
long long kernel_values(const EsKernel& kernel, double c, std::size_t m, double* values) {
  const double u = c * static_cast<double>(m);
  const auto first = static_cast<long long>(std::ceil(u - 0.5 * kernel.width));
  for (int i = 0; i < kernel.width; ++i) values[i] = kernel.value(static_cast<double>(first + i) - u);
  return first;
}

double unit_coordinate(double c) {
  c -= std::floor(c);
  return c < 1.0 ? c : 0.0;  // -1e-20 - floor(...) rounds to 1
}

}  // namespace

std::size_t periodogram_nufft_grid(int size) { return grid_size(size); }

std::size_t periodogram_memory_bytes(std::size_t count, int size) {
  // Sizes past 65536 are estimated, so that a plane too large is refused for its memory first.
  if (size < 2) throw Error("periodogram memory: size " + std::to_string(size) + ": expected at least 2");
  const auto f = static_cast<double>(size);
  const auto m = static_cast<double>(grid_size(size));
  // The result (F^2 doubles), the half spectrum after the x pass ((M + 8) (F/2 + 1) complex),
  // the stripe lists (up to four indices per point) and per thread a stripe, a row pair and the
  // stripe's spectrum.
  const double threads = static_cast<double>(thread_count());
  const double columns = f / 2.0 + 1.0;
  return static_cast<std::size_t>(8.0 * f * f + 16.0 * (m + 8.0) * columns + 16.0 * static_cast<double>(count) +
                                  threads * (8.0 * kStripeRows * m + 16.0 * m + 16.0 * kStripeRows * columns));
}

Periodogram compute_periodogram_nufft(std::span<const Point> points, int size,
                                      const std::function<void(std::size_t, std::size_t)>& progress) {
  if (points.empty()) throw Error("periodogram of an empty point set");
  check_periodogram_size(size);
  const std::size_t n = points.size();
  if (n > std::size_t{0xffffffff}) throw Error("periodogram: more than 2^32 - 1 points");
  const int half = size / 2;
  const std::size_t m = grid_size(size), mask = m - 1;
  const EsKernel kernel = choose_kernel(static_cast<double>(m) / size);
  const int w = kernel.width;
  // Frequencies 0 .. F/2 on each axis are deconvolved (negative ones by symmetry of psi^).
  const std::size_t columns = static_cast<std::size_t>(half) + 1;
  const std::vector<double> transform = kernel_transform(kernel, m, columns);
  const Fft fft(m);

  // Points per stripe, in point order: a point's rows first .. first + w - 1 (mod M) touch the
  // stripe of its first row and perhaps the next.
  const std::size_t stripes = m / kStripeRows;
  std::vector<std::size_t> offsets(stripes + 1, 0);
  std::vector<std::uint32_t> first_stripe(n), second_stripe(n);
  for (std::size_t j = 0; j < n; ++j) {
    if (!std::isfinite(points[j].x) || !std::isfinite(points[j].y))
      throw Error("periodogram: point " + std::to_string(j) + " is not finite");
    const double u = unit_coordinate(points[j].y) * static_cast<double>(m);
    const auto first = static_cast<long long>(std::ceil(u - 0.5 * w));
    const std::size_t a = (static_cast<std::size_t>(first) & mask) / kStripeRows;
    const std::size_t b = (static_cast<std::size_t>(first + w - 1) & mask) / kStripeRows;
    first_stripe[j] = static_cast<std::uint32_t>(a);
    second_stripe[j] = static_cast<std::uint32_t>(b);
    ++offsets[a + 1];
    if (b != a) ++offsets[b + 1];
  }
  for (std::size_t s = 0; s < stripes; ++s) offsets[s + 1] += offsets[s];
  std::vector<std::uint32_t> members(offsets[stripes]);
  {
    std::vector<std::size_t> fill(offsets.begin(), offsets.end() - 1);
    for (std::size_t j = 0; j < n; ++j) {
      members[fill[first_stripe[j]]++] = static_cast<std::uint32_t>(j);
      if (second_stripe[j] != first_stripe[j]) members[fill[second_stripe[j]]++] = static_cast<std::uint32_t>(j);
    }
  }
  first_stripe = {};
  second_stripe = {};

  const std::size_t column_tasks = (columns + kColumnBlock - 1) / kColumnBlock;
  const std::size_t total_work = stripes + column_tasks;
  std::mutex progress_mutex;
  std::size_t work_done = 0;
  auto step_done = [&] {
    if (!progress) return;
    std::lock_guard<std::mutex> lock(progress_mutex);
    progress(++work_done, total_work);
  };
  if (progress) progress(0, total_work);

  // Pass 1: spread each stripe and transform its rows along x, stored by column:
  // half_re/half_im[kx * stride + row]. Columns are `stride` apart, not M: M-apart columns would
  // share cache sets when pass 2 reads a row across them.
  const std::size_t stride = m + 8;
  std::vector<double> half_re(columns * stride), half_im(columns * stride);
  parallel_for(stripes, 1, [&](std::size_t begin, std::size_t end) {
    std::vector<double> stripe(kStripeRows * m);
    std::vector<double> re(m), im(m);
    std::vector<double> spectrum_re(kStripeRows * columns), spectrum_im(kStripeRows * columns);
    double wx[kMaxWidth], wy[kMaxWidth];
    for (std::size_t s = begin; s < end; ++s) {
      std::fill(stripe.begin(), stripe.end(), 0.0);
      const long long row0 = static_cast<long long>(s * kStripeRows);
      for (std::size_t q = offsets[s]; q < offsets[s + 1]; ++q) {
        const Point& p = points[members[q]];
        const long long fx = kernel_values(kernel, unit_coordinate(p.x), m, wx);
        const long long fy = kernel_values(kernel, unit_coordinate(p.y), m, wy);
        for (int iy = 0; iy < w; ++iy) {
          const long long row = static_cast<long long>(static_cast<std::size_t>(fy + iy) & mask) - row0;
          if (row < 0 || row >= static_cast<long long>(kStripeRows)) continue;
          double* line = stripe.data() + static_cast<std::size_t>(row) * m;
          const double v = wy[iy];
          for (int ix = 0; ix < w; ++ix) line[static_cast<std::size_t>(fx + ix) & mask] += v * wx[ix];
        }
      }
      // Two real rows a, b as one complex row z = a + i b: A(k) = (Z(k) + conj Z(M - k)) / 2,
      // B(k) = (Z(k) - conj Z(M - k)) / (2 i).
      for (std::size_t r = 0; r < kStripeRows; r += 2) {
        std::copy_n(stripe.data() + r * m, m, re.data());
        std::copy_n(stripe.data() + (r + 1) * m, m, im.data());
        fft.forward(re.data(), im.data());
        for (std::size_t k = 0; k < columns; ++k) {
          const std::size_t mk = (m - k) & mask;
          const double zr = re[k], zi = im[k], cr = re[mk], ci = -im[mk];
          const double scale = 0.5 / transform[k];
          spectrum_re[r * columns + k] = (zr + cr) * scale;
          spectrum_im[r * columns + k] = (zi + ci) * scale;
          spectrum_re[(r + 1) * columns + k] = (zi - ci) * scale;
          spectrum_im[(r + 1) * columns + k] = (cr - zr) * scale;
        }
      }
      for (std::size_t k = 0; k < columns; ++k) {
        double* column_re = half_re.data() + k * stride + s * kStripeRows;
        double* column_im = half_im.data() + k * stride + s * kStripeRows;
        for (std::size_t r = 0; r < kStripeRows; ++r) {
          column_re[r] = spectrum_re[r * columns + k];
          column_im[r] = spectrum_im[r * columns + k];
        }
      }
      step_done();
    }
  });
  members = {};

  // Pass 2: each block of columns kx along y, in place; P(kx, ky) for kx < F/2 and its mirror P(-kx, -ky).
  Periodogram result;
  result.size = size;
  result.power.assign(static_cast<std::size_t>(size) * static_cast<std::size_t>(size), 0.0);
  const auto f = static_cast<std::size_t>(size);
  const double inverse_n = 1.0 / static_cast<double>(n);
  std::vector<double> inverse_transform(columns);
  for (std::size_t k = 0; k < columns; ++k) inverse_transform[k] = 1.0 / transform[k];
  parallel_for(column_tasks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t task = begin; task < end; ++task) {
      const std::size_t k0 = task * kColumnBlock, k1 = std::min(columns, k0 + kColumnBlock);
      double* re = half_re.data() + k0 * stride;
      double* im = half_im.data() + k0 * stride;
      for (std::size_t k = k0; k < k1; ++k) fft.forward(re + (k - k0) * stride, im + (k - k0) * stride);
      // Row by row, so that each output row takes a run of kx.
      for (int ky = -half; ky <= half; ++ky) {
        const std::size_t at = static_cast<std::size_t>(static_cast<long long>(ky)) & mask;
        const double scale = inverse_transform[static_cast<std::size_t>(std::abs(ky))];
        double* direct = result.power.data() + static_cast<std::size_t>(ky + half) * f + static_cast<std::size_t>(half);
        double* mirror = result.power.data() + static_cast<std::size_t>(-ky + half) * f + static_cast<std::size_t>(half);
        for (std::size_t k = k0; k < k1; ++k) {
          const double sr = re[(k - k0) * stride + at] * scale, si = im[(k - k0) * stride + at] * scale;
          const double power = (sr * sr + si * si) * inverse_n;
          const int kx = static_cast<int>(k);
          if (kx < half && ky < half) direct[kx] = power;
          if (kx > 0 && ky > -half) mirror[-kx] = power;
        }
      }
      step_done();
    }
  });
  // Unit weights: the sum at k = 0 is N exactly.
  result.power[static_cast<std::size_t>(half) * f + static_cast<std::size_t>(half)] = static_cast<double>(n);
  return result;
}

}  // namespace bluetile
