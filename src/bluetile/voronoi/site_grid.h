// A uniform bucket grid over a scene's sites on the periodic domain, for the neighbour
// searches of the centroid engines: buckets visited nearest first (the exact engine's cells),
// and every site near a point (the raster engine's checks). Sites are stored contiguously in
// bucket order; within a bucket they keep index order, so every traversal has a fixed order.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile {

class SiteGrid {
 public:
  // Buckets about `sites_per_bucket` sites each on average (at least one bucket, at most
  // 2^14 per axis). Sites must lie inside the domain. Without `with_search_order` the grid has
  // no search_order() (it costs a sort per grid; only searches from sites need it). Throws Error
  // for a domain check_domain refuses and for sites_per_bucket not finite and positive (0 asked
  // for 2^28 buckets, NaN for a number of buckets of no value).
  SiteGrid(std::span<const Point> sites, const Domain& domain, double sites_per_bucket, bool with_search_order = true);

  // A bucket offset and the least distance from any point of bucket (0,0) to bucket (dx,dy).
  struct SearchStep {
    long dx, dy;
    double lower_bound_squared;
  };
  static constexpr long kSearchRadius = 6;
  // Offsets with the same gaps in whole buckets, max(0, |dx| - 1) and max(0, |dy| - 1), share a
  // bound: kGapGroups groups.
  static constexpr std::size_t kGapGroups = static_cast<std::size_t>(kSearchRadius * kSearchRadius);
  // The offsets of a search order and the gap group of each; grids whose bounds sort alike share
  // one (site_grid.cpp).
  struct SearchLayout {
    struct Offset {
      std::int8_t dx, dy;
      std::uint8_t group;
    };
    std::vector<Offset> offsets;
  };
  // A search order: the layout's offsets with this grid's bounds, read as SearchSteps.
  class SearchOrder {
   public:
    class Iterator {
     public:
      Iterator(const SearchLayout::Offset* at, const double* bounds) : at_(at), bounds_(bounds) {}
      SearchStep operator*() const { return {at_->dx, at_->dy, bounds_[at_->group]}; }
      Iterator& operator++() {
        ++at_;
        return *this;
      }
      bool operator!=(const Iterator& other) const { return at_ != other.at_; }

     private:
      const SearchLayout::Offset* at_;
      const double* bounds_;
    };
    std::size_t size() const { return layout_ ? layout_->offsets.size() : 0; }
    bool empty() const { return size() == 0; }
    SearchStep operator[](std::size_t k) const { return *Iterator(layout_->offsets.data() + k, bounds_.data()); }
    Iterator begin() const { return {layout_ ? layout_->offsets.data() : nullptr, bounds_.data()}; }
    Iterator end() const { return {layout_ ? layout_->offsets.data() + layout_->offsets.size() : nullptr, bounds_.data()}; }

   private:
    friend class SiteGrid;
    std::shared_ptr<const SearchLayout> layout_;
    std::array<double, kGapGroups> bounds_{};  // per gap group
  };
  // Every offset within kSearchRadius buckets whose lower bound is below kSearchRadius bucket
  // sides, nearest first (ties: the nearer bucket centre, then dy-major scan order): a search
  // from a site may stop at the first step whose bound reaches the distance it needs. Searches
  // that need more fall back to rings (rare: big empty regions, tiny N).
  const SearchOrder& search_order() const { return search_order_; }

  std::pair<long, long> bucket_coordinates(Point p) const {
    long cx = std::clamp<long>(static_cast<long>(p.x / cell_size_.x), 0, columns_ - 1);
    long cy = std::clamp<long>(static_cast<long>(p.y / cell_size_.y), 0, rows_ - 1);
    return {cx, cy};
  }

  long columns() const { return columns_; }
  long rows() const { return rows_; }
  // The side lengths of one bucket.
  Point cell_size() const { return cell_size_; }
  const Domain& domain() const { return domain_; }

  // Calls visit(site index, offset from `origin` to that copy of the site) for every site in
  // bucket (cx, cy), where cx, cy may lie outside the grid: they then name a periodic copy.
  template <typename Visit>
  void for_each_in_bucket(long cx, long cy, Point origin, Visit visit) const {
    long wx = wrap_count(cx, columns_), wy = wrap_count(cy, rows_);
    std::size_t b = static_cast<std::size_t>((cy - wy * rows_) * columns_ + (cx - wx * columns_));
    Point shift{static_cast<double>(wx) * domain_.size.x - origin.x, static_cast<double>(wy) * domain_.size.y - origin.y};
    for (std::uint32_t s = start_[b]; s < start_[b + 1]; ++s) visit(index_[s], points_[s] + shift);
  }

  // Calls visit(site index) once for every site of every bucket that may hold a site within
  // `reach` of p on the torus (a superset of those sites; callers measure the distance).
  template <typename Visit>
  void for_each_near(Point p, double reach, Visit visit) const {
    for_each_site_near(p, reach, [&](std::uint32_t index, Point) { visit(index); });
  }

  // As for_each_near, calling visit(site index, site position) from the grid's own copy of the
  // positions, stored bucket by bucket: no lookup by index, so a scan stays in cache.
  template <typename Visit>
  void for_each_site_near(Point p, double reach, Visit visit) const {
    auto [cx, cy] = bucket_coordinates(p);
    const double kx = std::ceil(reach / cell_size_.x), ky = std::ceil(reach / cell_size_.y);
    long x0 = 0, x1 = columns_ - 1, y0 = 0, y1 = rows_ - 1;
    if (2.0 * kx + 1.0 < static_cast<double>(columns_)) x0 = cx - static_cast<long>(kx), x1 = cx + static_cast<long>(kx);
    if (2.0 * ky + 1.0 < static_cast<double>(rows_)) y0 = cy - static_cast<long>(ky), y1 = cy + static_cast<long>(ky);
    for (long by = y0; by <= y1; ++by) {
      const long row = by - wrap_count(by, rows_) * rows_;
      for (long bx = x0; bx <= x1; ++bx) {
        const std::size_t b = static_cast<std::size_t>(row * columns_ + (bx - wrap_count(bx, columns_) * columns_));
        for (std::uint32_t s = start_[b]; s < start_[b + 1]; ++s) visit(index_[s], points_[s]);
      }
    }
  }
  // Site position of storage slot s (slots in bucket order, site_indices()[s] its index).
  Point stored_point(std::size_t s) const { return points_[s]; }

  // The storage itself (for copying the grid to a device): bucket b holds the sites
  // site_indices()[bucket_starts()[b] .. bucket_starts()[b + 1]), bucket b = row * columns + column.
  std::span<const std::uint32_t> bucket_starts() const { return start_; }
  std::span<const std::uint32_t> site_indices() const { return index_; }

  // How many periods bucket index a lies away from [0, n): floor(a / n), without a division in
  // the common case of a neighbour at most one period away (divisions dominated the search).
  static long wrap_count(long a, long n) {
    if (a >= 0) return a < n ? 0 : a < 2 * n ? 1 : a / n;
    return a >= -n ? -1 : -((-a + n - 1) / n);
  }

  // Buckets in storage order, for cache-friendly traversal.
  std::size_t bucket_count() const { return start_.size() - 1; }
  std::span<const std::uint32_t> sites_in_bucket(std::size_t b) const {
    return {index_.data() + start_[b], index_.data() + start_[b + 1]};
  }

 private:
  void build_search_order();

  Domain domain_;
  long columns_ = 1, rows_ = 1;
  Point cell_size_;
  std::vector<std::uint32_t> start_;   // bucket b holds storage slots [start_[b], start_[b+1])
  std::vector<Point> points_;          // site positions in storage order
  std::vector<std::uint32_t> index_;   // site indices in storage order
  SearchOrder search_order_;
};

}  // namespace bluetile
