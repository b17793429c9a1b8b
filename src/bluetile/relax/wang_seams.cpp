// Seam spacing (see wang_seams.h).
#include "bluetile/relax/wang_seams.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <tuple>

#include "bluetile/core/error.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace {

// A tile that can sit at integer offset (dx, dy) from another in some admissible 2x2 block.
struct Neighbour {
  int tile;
  int dx, dy;
};

// Per tile, every (tile, offset) it can meet, itself at offset (0, 0) first.
std::vector<std::vector<Neighbour>> meeting_tiles(const TileRules& rules) {
  std::vector<std::set<std::tuple<int, int, int>>> meets(static_cast<std::size_t>(rules.tile_count()));
  constexpr std::array<std::array<int, 2>, 4> kPosition = {{{0, 0}, {1, 0}, {0, 1}, {1, 1}}};  // for_each_block's order
  rules.for_each_block(2, 2, [&](std::span<const int> tiles) {
    for (std::size_t a = 0; a < 4; ++a)
      for (std::size_t b = 0; b < 4; ++b)
        if (a != b)
          meets[static_cast<std::size_t>(tiles[a])].insert(
              {tiles[b], kPosition[b][0] - kPosition[a][0], kPosition[b][1] - kPosition[a][1]});
  });
  std::vector<std::vector<Neighbour>> out(meets.size());
  for (std::size_t t = 0; t < meets.size(); ++t) {
    out[t].push_back({static_cast<int>(t), 0, 0});
    for (const auto& [tile, dx, dy] : meets[t]) out[t].push_back({tile, dx, dy});
  }
  return out;
}

// The points a tile's points can meet, bucketed by a grid of `spacing` cells over the tile
// square grown by the spacing.
class MeetingGrid {
 public:
  struct Entry {
    Point p;
    int tile;
    int position;  // (dy + 1) * 3 + (dx + 1) of the neighbour offset; 4: the tile itself
    std::uint32_t index;
  };

  explicit MeetingGrid(double spacing) : spacing_(spacing), side_(static_cast<int>(std::ceil((1.0 + 2.0 * spacing) / spacing))) {}

  void fill(const std::vector<Neighbour>& neighbours, const TilePoints& tiles) {
    buckets_.resize(static_cast<std::size_t>(side_ * side_));
    for (std::vector<Entry>& bucket : buckets_) bucket.clear();  // keeps their storage for the next fill
    for (const Neighbour& n : neighbours) {
      const std::vector<Point>& pts = tiles[static_cast<std::size_t>(n.tile)];
      for (std::size_t k = 0; k < pts.size(); ++k) {
        const Point p{pts[k].x + n.dx, pts[k].y + n.dy};
        const int bx = bucket(p.x), by = bucket(p.y);
        if (bx < 0 || by < 0 || bx >= side_ || by >= side_) continue;  // too far to meet any point
        buckets_[static_cast<std::size_t>(by * side_ + bx)].push_back(
            {p, n.tile, (n.dy + 1) * 3 + (n.dx + 1), static_cast<std::uint32_t>(k)});
      }
    }
  }

  template <class Visit>
  void near(Point p, Visit visit) const {
    const int bx = bucket(p.x), by = bucket(p.y);
    for (int y = std::max(0, by - 1); y <= std::min(side_ - 1, by + 1); ++y)
      for (int x = std::max(0, bx - 1); x <= std::min(side_ - 1, bx + 1); ++x)
        for (const Entry& e : buckets_[static_cast<std::size_t>(y * side_ + x)]) visit(e);
  }

 private:
  int bucket(double x) const { return static_cast<int>(std::floor((x + spacing_) / spacing_)); }

  double spacing_;
  int side_;
  std::vector<std::vector<Entry>> buckets_;
};

}  // namespace

SeamSpacingResult space_seams(const TileRules& rules, WangPoints& points, const SeamSpacingOptions& options) {
  SeamSpacingResult result;
  if (options.iterations <= 0) return result;
  if (!(options.spacing > 0.0) || !std::isfinite(options.spacing))
    throw Error("seam spacing " + shortest_text(options.spacing) + " must be a positive number of tile units");
  const std::vector<std::vector<Neighbour>> neighbours = meeting_tiles(rules);
  const double tau = options.spacing;
  const double close_below = tau * (1.0 - 1e-9);
  MeetingGrid grid(tau);
  std::vector<std::vector<Point>> push(points.tiles.size());
  // One point's pushes per (position, tile): points at one position in different tiles are
  // alternatives (one tiling holds one of them), so a position pushes by its strongest tile;
  // points of one tile at one position, and different positions, coexist and add up.
  struct Alternative {
    int position, tile;
    Point push;
  };
  std::vector<Alternative> alternatives;
  // Each pass measures every moving point's pushes; all but the last apply them.
  for (int pass = 0;; ++pass) {
    std::size_t close = 0;
    for (std::size_t t = 0; t < points.tiles.size(); ++t) {
      grid.fill(neighbours[t], points.tiles);
      const std::vector<Point>& tile = points.tiles[t];
      push[t].assign(points.moving_count(), Point{0.0, 0.0});
      for (std::size_t k = points.moving_begin; k < tile.size(); ++k) {
        const Point p = tile[k];
        alternatives.clear();
        grid.near(p, [&](const MeetingGrid::Entry& e) {
          if (e.position == 4 && e.index == k) return;  // the point itself
          const Point v = p - e.p;
          const double r = std::sqrt(v.x * v.x + v.y * v.y);
          // Far enough (a pair moved apart to the spacing may land a rounding error short of
          // it), or coincident (no direction).
          if (!(r < close_below) || r == 0.0) return;
          const double share = e.index >= points.moving_begin ? 0.5 : 1.0;  // a fixed partner does not move
          const Point away = v * (share * (tau - r) / r);
          auto same = [&](const Alternative& a) { return a.position == e.position && a.tile == e.tile; };
          auto found = std::find_if(alternatives.begin(), alternatives.end(), same);
          if (found == alternatives.end()) {
            alternatives.push_back({e.position, e.tile, away});
          } else {
            found->push += away;
          }
        });
        Point& d = push[t][k - points.moving_begin];
        for (int position = 0; position < 9; ++position) {
          const Alternative* strongest = nullptr;
          for (const Alternative& a : alternatives) {
            if (a.position != position) continue;
            const double m = a.push.x * a.push.x + a.push.y * a.push.y;
            if (!strongest || m > strongest->push.x * strongest->push.x + strongest->push.y * strongest->push.y)
              strongest = &a;
          }
          if (strongest) d += strongest->push;
        }
        close += !alternatives.empty();
      }
    }
    result.close_points = close;
    if (close == 0 || pass == options.iterations) break;
    result.iterations = pass + 1;
    for (std::size_t t = 0; t < points.tiles.size(); ++t)
      for (std::size_t m = 0; m < points.moving_count(); ++m) {
        Point& p = points.tiles[t][points.moving_begin + m];
        p = inside_tile(p + push[t][m], options.edge_margin);
      }
  }
  return result;
}

}  // namespace bluetile
