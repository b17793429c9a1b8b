// The periodic site grid: see site_grid.h.
#include "bluetile/voronoi/site_grid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/text.h"

namespace bluetile {

SiteGrid::SiteGrid(std::span<const Point> sites, const Domain& domain, double sites_per_bucket, bool with_search_order)
    : domain_(domain) {
  check_domain(domain, "site grid");
  if (!(sites_per_bucket > 0.0 && std::isfinite(sites_per_bucket)))
    throw Error("site grid: sites per bucket " + exact_text(sites_per_bucket) + ": expected a finite positive number");
  const std::size_t n = sites.size();
  const double bucket_side = std::sqrt(sites_per_bucket * domain_.area() / static_cast<double>(std::max<std::size_t>(n, 1)));
  columns_ = std::clamp<long>(std::lround(domain_.size.x / bucket_side), 1, 1 << 14);
  rows_ = std::clamp<long>(std::lround(domain_.size.y / bucket_side), 1, 1 << 14);
  cell_size_ = {domain_.size.x / static_cast<double>(columns_), domain_.size.y / static_cast<double>(rows_)};

  // Each site's bucket, on the stack for small grids (the Wang loop builds one per crop scene
  // of about 15 sites, where an allocation costs as much as the grid).
  constexpr std::size_t kOnStack = 256;
  std::array<std::uint32_t, kOnStack> small_buckets;
  std::vector<std::uint32_t> large_buckets(n > kOnStack ? n : 0);
  std::uint32_t* bucket_of = n > kOnStack ? large_buckets.data() : small_buckets.data();
  start_.assign(static_cast<std::size_t>(columns_ * rows_) + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    auto [cx, cy] = bucket_coordinates(sites[i]);
    bucket_of[i] = static_cast<std::uint32_t>(cy * columns_ + cx);
    ++start_[bucket_of[i] + 1];
  }
  for (std::size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
  points_.resize(n);
  index_.resize(n);
  // start_[b] serves as bucket b's fill position, which ends at bucket b + 1's start; shifted
  // back by one bucket afterwards.
  for (std::size_t i = 0; i < n; ++i) {  // stable: within a bucket, sites keep index order
    std::uint32_t slot = start_[bucket_of[i]]++;
    points_[slot] = sites[i];
    index_[slot] = static_cast<std::uint32_t>(i);
  }
  for (std::size_t b = start_.size() - 1; b > 0; --b) start_[b] = start_[b - 1];
  start_[0] = 0;
  if (with_search_order) build_search_order();
}

namespace {

// The search offsets grouped by their gaps in whole buckets, a = max(0, |dx| - 1) and
// b = max(0, |dy| - 1): every offset of a group has the same lower bound, (a w)^2 + (b h)^2 for
// buckets w x h. kGap groups per axis (a, b in [0, kSearchRadius - 1]).
constexpr long kGap = SiteGrid::kSearchRadius;
constexpr long kSide = 2 * SiteGrid::kSearchRadius + 1;

// An offset of the scan and its rank in a tie of bounds: the nearer bucket centre first, then
// the place in the dy-major scan of the square (a total order).
struct ScanOffset {
  long dx = 0, dy = 0;
  std::uint16_t tie_rank = 0;
  std::uint8_t group = 0;  // its gap group, b * kGap + a
};

struct GapGroup {
  std::uint8_t count = 0;
  std::uint8_t member[9] = {};  // scan places in tie order; at most 9 (a = b = 0)
};

struct SearchTables {
  std::array<ScanOffset, kSide * kSide> offsets;
  std::array<GapGroup, kGap * kGap> groups;
};

const SearchTables& search_tables() {
  static const SearchTables tables = [] {
    SearchTables t;
    for (long place = 0; place < kSide * kSide; ++place) {
      ScanOffset& o = t.offsets[static_cast<std::size_t>(place)];
      o.dx = place % kSide - SiteGrid::kSearchRadius;
      o.dy = place / kSide - SiteGrid::kSearchRadius;
      o.tie_rank = static_cast<std::uint16_t>((o.dx * o.dx + o.dy * o.dy) * kSide * kSide + place);
      const long a = std::max(0L, std::labs(o.dx) - 1), b = std::max(0L, std::labs(o.dy) - 1);
      o.group = static_cast<std::uint8_t>(b * kGap + a);
      GapGroup& group = t.groups[o.group];
      group.member[group.count++] = static_cast<std::uint8_t>(place);
    }
    for (GapGroup& group : t.groups) {
      std::sort(group.member, group.member + group.count, [&](std::uint8_t p, std::uint8_t q) {
        return t.offsets[p].tie_rank < t.offsets[q].tie_rank;
      });
    }
    return t;
  }();
  return tables;
}

// The last order a thread built, as a function of its inputs: the groups in (bound, group)
// order, which neighbours in it had equal bounds, and how many lay below the limit. A grid whose
// bounds give the same three has the same offsets in the same order, only other bounds.
struct OrderMemo {
  std::array<std::uint8_t, kGap * kGap> groups{};
  std::array<bool, kGap * kGap> tied_with_next{};
  std::size_t kept = 0;  // groups below the limit
  std::shared_ptr<const SiteGrid::SearchLayout> layout;  // null: nothing built yet
};

}  // namespace

void SiteGrid::build_search_order() {
  // Offsets beyond the radius have a bound of at least this; keeping only steps below it makes
  // the list complete up to it, whatever the bucket shape.
  const double limit = static_cast<double>(kSearchRadius) * std::min(cell_size_.x, cell_size_.y);
  const double limit_squared = limit * limit;
  // Nearest first; among equal bounds the nearer bucket centre first, then the dy-major scan
  // order: the order a stable sort of the scan by (bound, centre distance) gives. The bounds are
  // those of the 36 gap groups, so the groups are sorted rather than the 169 offsets (a sort of
  // all offsets per grid cost as much as the cells of a small scene). Small scenes come in runs
  // of like shapes (the crops of one Wang group), so most grids share the layout of the grid
  // before, checked in 36 comparisons.
  static_assert(kGap * kGap == kGapGroups);
  const SearchTables& tables = search_tables();
  std::array<double, kGapGroups>& bound = search_order_.bounds_;
  for (long b = 0; b < kGap; ++b) {
    for (long a = 0; a < kGap; ++a) {
      const double gx = static_cast<double>(a) * cell_size_.x, gy = static_cast<double>(b) * cell_size_.y;
      bound[static_cast<std::size_t>(b * kGap + a)] = gx * gx + gy * gy;
    }
  }
  thread_local OrderMemo memo;
  auto memo_holds = [&] {
    if (!memo.layout) return false;
    for (std::size_t k = 0; k + 1 < memo.groups.size(); ++k) {
      const double here = bound[memo.groups[k]], next = bound[memo.groups[k + 1]];
      // Tied groups are in increasing group order in the memo (the sort's tie-break).
      if (memo.tied_with_next[k] ? !(here == next) : !(here < next)) return false;
    }
    return (memo.kept == 0 || bound[memo.groups[memo.kept - 1]] < limit_squared) &&
           (memo.kept == memo.groups.size() || !(bound[memo.groups[memo.kept]] < limit_squared));
  };
  if (!memo_holds()) {
    std::array<std::uint8_t, kGapGroups> order;
    for (std::size_t g = 0; g < order.size(); ++g) order[g] = static_cast<std::uint8_t>(g);
    std::sort(order.begin(), order.end(), [&](std::uint8_t p, std::uint8_t q) {
      return bound[p] != bound[q] ? bound[p] < bound[q] : p < q;
    });
    memo.groups = order;
    memo.kept = 0;
    for (std::size_t k = 0; k < order.size(); ++k) {
      memo.tied_with_next[k] = k + 1 < order.size() && bound[order[k]] == bound[order[k + 1]];
      memo.kept += bound[order[k]] < limit_squared;  // sorted: these come first
    }
    auto layout = std::make_shared<SearchLayout>();
    std::vector<SearchLayout::Offset>& offsets = layout->offsets;
    offsets.reserve(static_cast<std::size_t>(kSide * kSide));
    auto offset = [&](std::uint8_t place, std::uint8_t group) {
      const ScanOffset& o = tables.offsets[place];
      return SearchLayout::Offset{static_cast<std::int8_t>(o.dx), static_cast<std::int8_t>(o.dy), group};
    };
    std::array<std::uint8_t, kSide * kSide> tied_places;
    for (std::size_t first = 0; first < memo.kept;) {
      std::size_t last = first + 1;
      while (memo.tied_with_next[last - 1]) ++last;
      if (last == first + 1) {
        const GapGroup& group = tables.groups[order[first]];
        for (std::uint8_t m = 0; m < group.count; ++m) offsets.push_back(offset(group.member[m], order[first]));
      } else {
        // Groups with equal bounds (square buckets: (a, b) and (b, a)) interleave by tie rank;
        // each offset keeps its own group, whose bound is the run's.
        std::size_t n = 0;
        for (std::size_t k = first; k < last; ++k) {
          const GapGroup& group = tables.groups[order[k]];
          for (std::uint8_t m = 0; m < group.count; ++m) tied_places[n++] = group.member[m];
        }
        std::sort(tied_places.begin(), tied_places.begin() + static_cast<std::ptrdiff_t>(n),
                  [&](std::uint8_t p, std::uint8_t q) { return tables.offsets[p].tie_rank < tables.offsets[q].tie_rank; });
        for (std::size_t k = 0; k < n; ++k) offsets.push_back(offset(tied_places[k], tables.offsets[tied_places[k]].group));
      }
      first = last;
    }
    memo.layout = std::move(layout);
  }
  search_order_.layout_ = memo.layout;
}

}  // namespace bluetile
