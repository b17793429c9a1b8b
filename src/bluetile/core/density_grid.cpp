#include "bluetile/core/density_grid.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace {

int texel_index(long long i, int size, GridEdge edge) {
  if (edge == GridEdge::clamp) return static_cast<int>(std::clamp<long long>(i, 0, size - 1));
  long long m = i % size;
  return static_cast<int>(m < 0 ? m + size : m);
}

void check_grid_size(const DensityGrid& d) {
  if (d.width <= 0 || d.height <= 0 || d.texels.size() != static_cast<std::size_t>(d.width) * static_cast<std::size_t>(d.height))
    throw Error("density grid of " + std::to_string(d.width) + " x " + std::to_string(d.height) + " texels holds " +
                std::to_string(d.texels.size()) + " values");
}

}  // namespace

std::size_t DensityGrid::texel_count(int w, int h) {
  if (w < 0 || h < 0)
    throw Error("density grid of " + std::to_string(w) + " x " + std::to_string(h) +
                " texels: expected a width and a height of at least 0");
  return static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
}

bool check_density_grid(const DensityGrid& d) {
  check_grid_size(d);
  // One branch-free pass over the bits first (engines check the density on every call, and
  // this vectorizes): a texel is valid when it is +-0 or its bits, sign clear, lie below those of
  // infinity. The loop that names the bad texel runs only when there is one.
  std::uint32_t bad = 0, magnitude = 0;
  for (const float t : d.texels) {
    const std::uint32_t u = std::bit_cast<std::uint32_t>(t);
    bad |= static_cast<std::uint32_t>(u >= 0x7f800000u) & static_cast<std::uint32_t>(u != 0x80000000u);
    magnitude |= u & 0x7fffffffu;
  }
  for (std::size_t k = 0; bad != 0 && k < d.texels.size(); ++k) {
    const float t = d.texels[k];
    if (!std::isfinite(t) || t < 0.0f)
      throw Error("density texel (" + std::to_string(k % static_cast<std::size_t>(d.width)) + ", " +
                  std::to_string(k / static_cast<std::size_t>(d.width)) + ") is " + shortest_text(t) +
                  ": densities must be finite and non-negative");
  }
  return magnitude != 0;  // a valid texel with a magnitude is positive
}

double DensityGrid::mean() const {
  double sum = 0.0;
  for (float t : texels) sum += t;
  return texels.empty() ? 0.0 : sum / static_cast<double>(texels.size());
}

double sample_bilinear(const DensityGrid& grid, Point uv, GridEdge edge) {
  check_grid_size(grid);
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
    throw Error("density lookup at (" + shortest_text(uv.x) + ", " + shortest_text(uv.y) + "): expected finite coordinates");
  // Texel centres sit at half-integers of x, y below.
  const double x = uv.x * grid.width - 0.5, y = uv.y * grid.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double tx = x - fx, ty = y - fy;
  const auto i0 = static_cast<long long>(fx), j0 = static_cast<long long>(fy);
  const int a = texel_index(i0, grid.width, edge), b = texel_index(i0 + 1, grid.width, edge);
  const int c = texel_index(j0, grid.height, edge), d = texel_index(j0 + 1, grid.height, edge);
  const double bottom = (1.0 - tx) * grid.at(a, c) + tx * grid.at(b, c);
  const double top = (1.0 - tx) * grid.at(a, d) + tx * grid.at(b, d);
  return (1.0 - ty) * bottom + ty * top;
}

}  // namespace bluetile
