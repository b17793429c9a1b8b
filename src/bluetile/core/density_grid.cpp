#include "bluetile/core/density_grid.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace bluetile {
namespace {

int texel_index(long long i, int size, GridEdge edge) {
  if (edge == GridEdge::clamp) return static_cast<int>(std::clamp<long long>(i, 0, size - 1));
  long long m = i % size;
  return static_cast<int>(m < 0 ? m + size : m);
}

}  // namespace

double DensityGrid::mean() const {
  double sum = 0.0;
  for (float t : texels) sum += t;
  return texels.empty() ? 0.0 : sum / static_cast<double>(texels.size());
}

double sample_bilinear(const DensityGrid& grid, Point uv, GridEdge edge) {
  assert(!grid.empty() && std::isfinite(uv.x) && std::isfinite(uv.y));
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
