// A k-d tree over a scene's sites (Bentley 1975), for the exact engine's cell search when the
// sites are far from uniform: on a line, nearly on one, in a small cluster. The uniform grid
// (site_grid.h) then holds most sites in a few buckets and leaves the rest empty, and a cell's
// search visits O(N) buckets or sites; here it visits O(log N) boxes.
//
// Each node bounds its sites by a box along their principal axis (an oriented box), and splits
// them at the median along it: the boxes of sites on a line of any slope are thin strips along
// it (axis-aligned boxes of a diagonal line would be squares, and a cell's search would meet
// O(sqrt N) of them).
//
// The search is best first over (box, periodic shift) pairs ordered by their distance from the
// site. A box is skipped when no site in it can cut the cell: a site at offset d cuts the convex
// cell only if d lies in the disk centred at some vertex v through the site, |d - v| < |v| (the
// bisector keeps x.d <= |d|^2/2, which fails at a vertex exactly then), so a box farther than
// |v| from every vertex holds no such site. Since the cell only shrinks, a skipped box stays
// skipped. The search stops when the nearest box left is at least twice the cell's radius away.
// For sites on a line each cell (a strip) meets O(1) leaf boxes: O(log N) per cell.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "bluetile/core/torus.h"
#include "bluetile/voronoi/polygon.h"

namespace bluetile {

class SiteTree {
 public:
  // Sites inside the domain; `periodic`: the search visits periodic copies.
  SiteTree(std::span<const Point> sites, const Domain& domain, bool periodic);

  // Scratch space of one search (one per thread; reused between cells).
  struct Search;

  // Clips `cell`, relative to site `site` at `origin`, by every site (and periodic copy) whose
  // bisector can reach it, edges labelled with the other site's index. Returns false when the
  // site coincides with a site of lower index (which owns the cell); the polygon is then
  // unspecified.
  bool clip_cell(std::uint32_t site, Point origin, ConvexPolygon& cell, Search& search) const;

  // A site (its index) at a periodic copy kx, ky (whole periods; 0, 0 in a bounded domain).
  struct Copy {
    std::uint32_t index;
    std::int32_t kx, ky;
  };
  struct Disk {
    Point centre;
    double radius;
  };
  // Appends to `out` every site copy that lies within some disk of `disks` (centres anywhere
  // near the domain), and possibly a few more: boxes carry a margin, so roundings never leave
  // one out; callers measure the distance themselves. Unordered. On a torus copies up to two
  // periods away are visited (disks of radius up to a period).
  void copies_in_disks(std::span<const Disk> disks, std::vector<Copy>& out) const;

  // The least squared distance from p (near the domain) to a site copy, formed as
  // |site - (p - shift)|^2 (other ways of forming it agree up to rounding). Infinity without sites.
  double nearest_squared(Point p) const;

 private:
  struct Node {
    Point centre;              // oriented bounding box of the node's sites: centre,
    Point axis;                // unit principal axis (the box's other axis is its normal),
    double half_along = 0.0;   // half extents along the axis and across it
    double half_across = 0.0;
    std::uint32_t begin, end;  // its sites: storage slots [begin, end)
    std::uint32_t left = 0;    // children (0: a leaf; the root is node 0, never a child)
    std::uint32_t right = 0;
  };
  struct Item {
    Point p;
    std::uint32_t index;
  };
  std::uint32_t build(std::vector<Item>& items, std::uint32_t begin, std::uint32_t end);
  // The periodic copies of the whole set a search near the domain visits.
  std::int32_t copy_reach() const { return periodic_ ? 2 : 0; }

  // Leaves hold at most this many sites: a clip costs about what a box test does.
  static constexpr std::uint32_t kLeafSize = 8;

  Domain domain_;
  bool periodic_;
  double margin_;  // added to every box: roundings of projections and shifts never exclude a site
  std::vector<Point> points_;          // sites in storage (tree) order
  std::vector<std::uint32_t> index_;   // their indices
  std::vector<Node> nodes_;
};

struct SiteTree::Search {
  struct Entry {
    double bound;  // squared distance from the site to the shifted box
    std::uint32_t node;
    std::int32_t kx, ky;  // periodic shift in periods
  };
  std::vector<Entry> heap;
  std::size_t sites_visited = 0;  // over every search with this scratch (tests, benchmarks)
};

}  // namespace bluetile
