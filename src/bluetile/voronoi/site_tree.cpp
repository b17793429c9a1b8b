// The k-d tree search for cells of far-from-uniform sites (see site_tree.h).
#include "bluetile/voronoi/site_tree.h"

#include <algorithm>
#include <cmath>

namespace bluetile {
namespace {

using Entry = SiteTree::Search::Entry;

// Squared distance from p (relative to the cell's site) to the oriented box with the given centre
// (relative too), axis and half extents.
double distance_squared(Point p, Point centre, Point axis, double half_along, double half_across) {
  const Point r = p - centre;
  const double along = std::max(std::abs(r.x * axis.x + r.y * axis.y) - half_along, 0.0);
  const double across = std::max(std::abs(r.y * axis.x - r.x * axis.y) - half_across, 0.0);
  return along * along + across * across;
}

// Min-heap order, total so that the visiting order (and with it every rounding) is fixed.
bool later(const Entry& a, const Entry& b) {
  if (a.bound != b.bound) return a.bound > b.bound;
  if (a.node != b.node) return a.node > b.node;
  if (a.kx != b.kx) return a.kx > b.kx;
  return a.ky > b.ky;
}

}  // namespace

SiteTree::SiteTree(std::span<const Point> sites, const Domain& domain, bool periodic)
    : domain_(domain), periodic_(periodic), margin_(1e-9 * std::max(domain.size.x, domain.size.y)) {
  std::vector<Item> items(sites.size());
  for (std::size_t i = 0; i < sites.size(); ++i) items[i] = {sites[i], static_cast<std::uint32_t>(i)};
  nodes_.reserve(2 * sites.size() / kLeafSize + 2);
  if (!items.empty()) build(items, 0, static_cast<std::uint32_t>(items.size()));
  points_.resize(items.size());
  index_.resize(items.size());
  for (std::size_t k = 0; k < items.size(); ++k) {
    points_[k] = items[k].p;
    index_[k] = items[k].index;
  }
}

std::uint32_t SiteTree::build(std::vector<Item>& items, std::uint32_t begin, std::uint32_t end) {
  // Principal axis of the sites: the covariance's leading eigenvector.
  const double count = end - begin;
  Point mean{0.0, 0.0};
  for (std::uint32_t i = begin; i < end; ++i) mean += items[i].p;
  mean /= count;
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (std::uint32_t i = begin; i < end; ++i) {
    const Point r = items[i].p - mean;
    sxx += r.x * r.x;
    sxy += r.x * r.y;
    syy += r.y * r.y;
  }
  const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  const Point axis{std::cos(angle), std::sin(angle)};
  auto along = [&](Point p) { return (p.x - mean.x) * axis.x + (p.y - mean.y) * axis.y; };
  auto across = [&](Point p) { return (p.y - mean.y) * axis.x - (p.x - mean.x) * axis.y; };
  double a0 = along(items[begin].p), a1 = a0, c0 = across(items[begin].p), c1 = c0;
  for (std::uint32_t i = begin + 1; i < end; ++i) {
    const double a = along(items[i].p), c = across(items[i].p);
    a0 = std::min(a0, a), a1 = std::max(a1, a), c0 = std::min(c0, c), c1 = std::max(c1, c);
  }
  const double mid_along = 0.5 * (a0 + a1), mid_across = 0.5 * (c0 + c1);
  const Point centre{mean.x + mid_along * axis.x - mid_across * axis.y, mean.y + mid_along * axis.y + mid_across * axis.x};
  const auto id = static_cast<std::uint32_t>(nodes_.size());
  nodes_.push_back({centre, axis, 0.5 * (a1 - a0) + margin_, 0.5 * (c1 - c0) + margin_, begin, end});
  if (end - begin <= kLeafSize || a1 == a0) return id;  // small, or every site at one place
  // Split at the median along the axis; ties by index, so the tree is the same on every run.
  const std::uint32_t middle = begin + (end - begin) / 2;
  std::nth_element(items.begin() + begin, items.begin() + middle, items.begin() + end, [&](const Item& p, const Item& q) {
    const double ap = along(p.p), aq = along(q.p);
    if (ap != aq) return ap < aq;
    return p.index < q.index;
  });
  const std::uint32_t left = build(items, begin, middle);
  const std::uint32_t right = build(items, middle, end);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

bool SiteTree::clip_cell(std::uint32_t site, Point origin, ConvexPolygon& cell, Search& search) const {
  if (nodes_.empty()) return true;
  auto& heap = search.heap;
  heap.clear();
  const Point period = domain_.size;
  // The box of `node` with its sites at offset `shift`, relative to the cell's site.
  auto distance_to = [&](Point p, const Node& node, Point shift) {
    return distance_squared(p, node.centre + shift, node.axis, node.half_along, node.half_across);
  };
  // Can a site in that box cut the cell? Only if the box comes within |v| of some vertex v
  // (site_tree.h). Ties count as reachable: the site itself must be met to find coincident sites.
  auto may_cut = [&](const Node& node, Point shift) {
    for (const PolygonVertex& v : cell.vertices())
      if (distance_to(v.p, node, shift) <= v.p.x * v.p.x + v.p.y * v.p.y) return true;
    return false;
  };
  auto push = [&](std::uint32_t node, std::int32_t kx, std::int32_t ky) {
    const Point shift{kx * period.x - origin.x, ky * period.y - origin.y};
    const double bound = distance_to(Point{0.0, 0.0}, nodes_[node], shift);
    if (bound >= 4.0 * cell.max_radius_squared()) return;
    heap.push_back({bound, node, kx, ky});
    std::push_heap(heap.begin(), heap.end(), later);
  };
  // Copies of the whole set that the starting cell can reach: offsets up to twice its radius.
  std::int32_t reach_x = 0, reach_y = 0;
  if (periodic_) {
    const double reach = 2.0 * std::sqrt(cell.max_radius_squared());
    reach_x = static_cast<std::int32_t>(std::ceil(reach / period.x)) + 1;
    reach_y = static_cast<std::int32_t>(std::ceil(reach / period.y)) + 1;
  }
  for (std::int32_t ky = -reach_y; ky <= reach_y; ++ky)
    for (std::int32_t kx = -reach_x; kx <= reach_x; ++kx) push(0, kx, ky);

  bool coincident = false;
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), later);
    const Entry e = heap.back();
    heap.pop_back();
    if (e.bound >= 4.0 * cell.max_radius_squared()) break;  // every box left is out of reach
    const Node& node = nodes_[e.node];
    const Point shift{e.kx * period.x - origin.x, e.ky * period.y - origin.y};
    if (!may_cut(node, shift)) continue;
    if (node.left != 0) {
      push(node.left, e.kx, e.ky);
      push(node.right, e.kx, e.ky);
      continue;
    }
    search.sites_visited += node.end - node.begin;
    for (std::uint32_t s = node.begin; s < node.end; ++s) {
      const Point d = points_[s] + shift;
      if (d.x == 0.0 && d.y == 0.0) {
        coincident |= index_[s] < site;
        continue;  // the site itself, or a copy of it at the same place
      }
      cell.clip_by_bisector(d, index_[s]);
    }
    if (coincident) return false;
  }
  return true;
}

void SiteTree::copies_in_disks(std::span<const Disk> disks, std::vector<Copy>& out) const {
  if (nodes_.empty()) return;
  const Point period = domain_.size;
  std::vector<std::uint32_t> stack;
  const std::int32_t reach = copy_reach();
  for (std::int32_t ky = -reach; ky <= reach; ++ky)
    for (std::int32_t kx = -reach; kx <= reach; ++kx) {
      const Point shift{kx * period.x, ky * period.y};
      auto reached = [&](const Node& node) {
        for (const Disk& disk : disks)
          if (distance_squared(disk.centre, node.centre + shift, node.axis, node.half_along, node.half_across) <=
              disk.radius * disk.radius)
            return true;
        return false;
      };
      stack.assign(1, 0u);
      while (!stack.empty()) {
        const Node& node = nodes_[stack.back()];
        stack.pop_back();
        if (!reached(node)) continue;
        if (node.left != 0) {
          stack.push_back(node.left);
          stack.push_back(node.right);
          continue;
        }
        for (std::uint32_t s = node.begin; s < node.end; ++s) out.push_back({index_[s], kx, ky});
      }
    }
}

double SiteTree::nearest_squared(Point p) const {
  double best = HUGE_VAL;
  if (nodes_.empty()) return best;
  const Point period = domain_.size;
  // Depth first, the nearer child first, so that `best` shrinks early and prunes the rest.
  std::vector<std::pair<double, std::uint32_t>> stack;
  const std::int32_t reach = copy_reach();
  for (std::int32_t ky = -reach; ky <= reach; ++ky)
    for (std::int32_t kx = -reach; kx <= reach; ++kx) {
      const Point q{p.x - kx * period.x, p.y - ky * period.y};  // p relative to the unshifted sites
      auto bound = [&](std::uint32_t n) {
        const Node& node = nodes_[n];
        return distance_squared(q, node.centre, node.axis, node.half_along, node.half_across);
      };
      stack.assign(1, {bound(0), 0u});
      while (!stack.empty()) {
        const auto [b, n] = stack.back();
        stack.pop_back();
        if (b > best) continue;
        const Node& node = nodes_[n];
        if (node.left == 0) {
          for (std::uint32_t s = node.begin; s < node.end; ++s) {
            const Point d = points_[s] - q;
            best = std::min(best, d.x * d.x + d.y * d.y);
          }
          continue;
        }
        const double bl = bound(node.left), br = bound(node.right);
        if (bl <= br) {
          stack.push_back({br, node.right});
          stack.push_back({bl, node.left});
        } else {
          stack.push_back({bl, node.left});
          stack.push_back({br, node.right});
        }
      }
    }
  return best;
}

}  // namespace bluetile
