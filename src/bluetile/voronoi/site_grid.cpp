// The periodic site grid: see site_grid.h.
#include "bluetile/voronoi/site_grid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>

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

namespace {

// The search offsets grouped by their gaps in whole buckets, a = max(0, |dx| - 1) and
// b = max(0, |dy| - 1): every offset of a group has the same lower bound, (a w)^2 + (b h)^2 for
// buckets w x h. kGap groups per axis (a, b in [0, kSearchRadius - 1]).
constexpr long kGap = SiteGrid::kSearchRadius;
constexpr long kSide = 2 * SiteGrid::kSearchRadius + 1;

struct GapGroup {
  // Members in the order of a tie of bounds: the nearer bucket centre first, then the place in
  // the dy-major scan of the square; at most 9 (a = b = 0).
  std::uint8_t count = 0;
  std::uint8_t member[9] = {};
};

long offset_dx(long place) { return place % kSide - SiteGrid::kSearchRadius; }
long offset_dy(long place) { return place / kSide - SiteGrid::kSearchRadius; }
long centre_distance_squared(long place) { return offset_dx(place) * offset_dx(place) + offset_dy(place) * offset_dy(place); }

// Ties among equal bounds are broken by the centre distance, then by the scan place: a total order.
bool tie_before(long p, long q) {
  const long dp = centre_distance_squared(p), dq = centre_distance_squared(q);
  return dp != dq ? dp < dq : p < q;
}

const std::array<GapGroup, kGap * kGap>& gap_groups() {
  static const std::array<GapGroup, kGap * kGap> groups = [] {
    std::array<GapGroup, kGap * kGap> g{};
    for (long place = 0; place < kSide * kSide; ++place) {
      const long a = std::max(0L, std::labs(offset_dx(place)) - 1), b = std::max(0L, std::labs(offset_dy(place)) - 1);
      GapGroup& group = g[static_cast<std::size_t>(b * kGap + a)];
      group.member[group.count++] = static_cast<std::uint8_t>(place);
    }
    for (GapGroup& group : g) std::sort(group.member, group.member + group.count, [](std::uint8_t p, std::uint8_t q) { return tie_before(p, q); });
    return g;
  }();
  return groups;
}

}  // namespace

void SiteGrid::build_search_order() {
  // Offsets beyond the radius have a bound of at least this; keeping only steps below it makes
  // the list complete up to it, whatever the bucket shape.
  const double limit = static_cast<double>(kSearchRadius) * std::min(cell_size_.x, cell_size_.y);
  // Nearest first; among equal bounds the nearer bucket centre first, then the dy-major scan
  // order. The bounds are those of the 36 gap groups, so the groups are sorted rather than the
  // 169 offsets (a sort per grid of all offsets cost as much as the cells of a small scene);
  // the order is the one a stable sort of the scan by (bound, centre distance) gives.
  const std::array<GapGroup, kGap * kGap>& groups = gap_groups();
  struct Bound {
    double value;
    std::uint8_t group;
  };
  std::array<Bound, kGap * kGap> bounds;
  for (long b = 0; b < kGap; ++b) {
    for (long a = 0; a < kGap; ++a) {
      const double gx = static_cast<double>(a) * cell_size_.x, gy = static_cast<double>(b) * cell_size_.y;
      bounds[static_cast<std::size_t>(b * kGap + a)] = {gx * gx + gy * gy, static_cast<std::uint8_t>(b * kGap + a)};
    }
  }
  std::sort(bounds.begin(), bounds.end(), [](const Bound& p, const Bound& q) {
    return p.value != q.value ? p.value < q.value : p.group < q.group;
  });
  search_order_.reserve(static_cast<std::size_t>(kSide * kSide));
  auto emit = [&](long place, double bound) { search_order_.push_back({offset_dx(place), offset_dy(place), bound}); };
  for (std::size_t first = 0; first < bounds.size();) {
    const double bound = bounds[first].value;
    if (!(bound < limit * limit)) break;  // sorted: every later group is beyond the limit too
    std::size_t last = first + 1;
    while (last < bounds.size() && bounds[last].value == bound) ++last;
    if (last == first + 1) {
      const GapGroup& group = groups[bounds[first].group];
      for (std::uint8_t k = 0; k < group.count; ++k) emit(group.member[k], bound);
    } else {  // groups with equal bounds (square buckets: (a, b) and (b, a)) interleave
      std::array<std::uint8_t, kSide * kSide> tied;
      std::size_t n = 0;
      for (std::size_t k = first; k < last; ++k) {
        const GapGroup& group = groups[bounds[k].group];
        for (std::uint8_t m = 0; m < group.count; ++m) tied[n++] = group.member[m];
      }
      std::sort(tied.begin(), tied.begin() + static_cast<std::ptrdiff_t>(n), [](std::uint8_t p, std::uint8_t q) { return tie_before(p, q); });
      for (std::size_t k = 0; k < n; ++k) emit(tied[k], bound);
    }
    first = last;
  }
}

}  // namespace bluetile
