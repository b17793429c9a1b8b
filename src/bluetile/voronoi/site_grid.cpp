// The periodic site grid: see site_grid.h.
#include "bluetile/voronoi/site_grid.h"

#include <algorithm>
#include <cmath>

namespace bluetile {

SiteGrid::SiteGrid(std::span<const Point> sites, const Domain& domain, double sites_per_bucket, bool with_search_order)
    : domain_(domain) {
  const std::size_t n = sites.size();
  const double bucket_side = std::sqrt(sites_per_bucket * domain_.area() / static_cast<double>(std::max<std::size_t>(n, 1)));
  columns_ = std::clamp<long>(std::lround(domain_.size.x / bucket_side), 1, 1 << 14);
  rows_ = std::clamp<long>(std::lround(domain_.size.y / bucket_side), 1, 1 << 14);
  cell_size_ = {domain_.size.x / static_cast<double>(columns_), domain_.size.y / static_cast<double>(rows_)};

  std::vector<std::uint32_t> bucket_of(n);
  start_.assign(static_cast<std::size_t>(columns_ * rows_) + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    auto [cx, cy] = bucket_coordinates(sites[i]);
    bucket_of[i] = static_cast<std::uint32_t>(cy * columns_ + cx);
    ++start_[bucket_of[i] + 1];
  }
  for (std::size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
  points_.resize(n);
  index_.resize(n);
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) {  // stable: within a bucket, sites keep index order
    std::uint32_t slot = fill[bucket_of[i]]++;
    points_[slot] = sites[i];
    index_[slot] = static_cast<std::uint32_t>(i);
  }
  if (with_search_order) build_search_order();
}

void SiteGrid::build_search_order() {
  // Offsets beyond the radius have a bound of at least this; keeping only steps below it makes
  // the list complete up to it, whatever the bucket shape.
  const double limit = static_cast<double>(kSearchRadius) * std::min(cell_size_.x, cell_size_.y);
  for (long dy = -kSearchRadius; dy <= kSearchRadius; ++dy) {
    for (long dx = -kSearchRadius; dx <= kSearchRadius; ++dx) {
      double gx = static_cast<double>(std::max(0L, std::labs(dx) - 1)) * cell_size_.x;
      double gy = static_cast<double>(std::max(0L, std::labs(dy) - 1)) * cell_size_.y;
      double bound = gx * gx + gy * gy;
      if (bound < limit * limit) search_order_.push_back({dx, dy, bound});
    }
  }
  // Nearest first; among equal bounds the nearer bucket centre first, then a fixed order.
  std::stable_sort(search_order_.begin(), search_order_.end(), [](const SearchStep& a, const SearchStep& b) {
    if (a.lower_bound_squared != b.lower_bound_squared) return a.lower_bound_squared < b.lower_bound_squared;
    return a.dx * a.dx + a.dy * a.dy < b.dx * b.dx + b.dy * b.dy;
  });
}

}  // namespace bluetile
