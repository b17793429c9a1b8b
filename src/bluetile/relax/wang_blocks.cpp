// Neighbour configurations of a tile (see wang_blocks.h for the method).
#include "bluetile/relax/wang_blocks.h"

#include <algorithm>
#include <cassert>
#include <cstdlib>
#include <functional>
#include <string>

#include "bluetile/core/error.h"

namespace bluetile {
namespace {

// The eight positions around the centre in cycle order (SW, S, SE, E, NE, N, NW, W): each is
// edge-adjacent to the next.
constexpr std::array<int, 8> kRing{0, 1, 2, 5, 8, 7, 6, 3};
constexpr std::array<int, 4> kEdgePositions{7, 5, 1, 3};  // N, E, S, W

bool edge_adjacent(int pa, int pb) {
  return std::abs(block_dx(pa) - block_dx(pb)) + std::abs(block_dy(pa) - block_dy(pb)) == 1;
}

// A projection's enumeration stops with an error beyond this many configurations: the exact
// strategy then builds one scene per configuration, and so many mean cells as wide as a tile.
constexpr std::size_t kMaxProjections = std::size_t{1} << 16;

}  // namespace

BlockConfigurations::BlockConfigurations(const TileRules& rules) : rules_(rules) {
  const int count = rules.tile_count();
  fits_east_.resize(static_cast<std::size_t>(count * count));
  fits_north_.resize(static_cast<std::size_t>(count * count));
  for (int a = 0; a < count; ++a)
    for (int b = 0; b < count; ++b) {
      fits_east_[static_cast<std::size_t>(a * count + b)] = rules.fits_east(a, b);
      fits_north_[static_cast<std::size_t>(a * count + b)] = rules.fits_north(a, b);
    }
  candidates_.resize(static_cast<std::size_t>(count));
  for (int c = 0; c < count; ++c) {
    for (int p = 0; p < kBlockPositions; ++p) {
      auto& list = candidates_[static_cast<std::size_t>(c)][static_cast<std::size_t>(p)];
      if (p == kBlockCentre) {
        list.push_back(c);
        continue;
      }
      for (int t = 0; t < count; ++t)
        if (!edge_adjacent(p, kBlockCentre) || fit(kBlockCentre, c, p, t)) list.push_back(t);
    }
  }
  for (int c = 0; c < count; ++c) {
    std::array<std::int16_t, kBlockPositions> tiles;
    tiles.fill(-1);
    tiles[kBlockCentre] = static_cast<std::int16_t>(c);
    block_counts_.push_back(completions(tiles));
  }
}

bool BlockConfigurations::fit(int pa, int a, int pb, int b) const {
  const int dx = block_dx(pb) - block_dx(pa), dy = block_dy(pb) - block_dy(pa);
  assert(std::abs(dx) + std::abs(dy) == 1);
  const std::size_t count = static_cast<std::size_t>(rules_.tile_count());
  const auto pair = [count](int west_or_south, int east_or_north) {
    return static_cast<std::size_t>(west_or_south) * count + static_cast<std::size_t>(east_or_north);
  };
  if (dx == 1) return fits_east_[pair(a, b)];
  if (dx == -1) return fits_east_[pair(b, a)];
  if (dy == 1) return fits_north_[pair(a, b)];
  return fits_north_[pair(b, a)];
}

double BlockConfigurations::block_count(int centre) const { return block_counts_[static_cast<std::size_t>(centre)]; }

double BlockConfigurations::completions(const std::array<std::int16_t, kBlockPositions>& tiles) const {
  const int centre = tiles[kBlockCentre];
  assert(centre >= 0);
  // Walk the cycle from a known position when there is one (a single start tile), else sum
  // the closed walks over every start tile.
  std::size_t start = 0;
  for (std::size_t i = 0; i < kRing.size(); ++i)
    if (tiles[static_cast<std::size_t>(kRing[i])] >= 0) {
      start = i;
      break;
    }
  // The tiles each ring position may hold, in walk order: its known tile (if it fits the
  // centre), else every candidate. Views, not copies: the exact strategy's search calls this at
  // every leaf.
  struct Options {
    const int* begin = nullptr;
    std::size_t size = 0;
    int known = -1;
  };
  std::array<Options, kRing.size()> options;
  for (std::size_t i = 0; i < kRing.size(); ++i) {
    const int position = kRing[(start + i) % kRing.size()];
    const auto& fitting = candidates(centre, position);
    Options& o = options[i];
    o.known = tiles[static_cast<std::size_t>(position)];
    if (o.known < 0) {
      o.begin = fitting.data();
      o.size = fitting.size();
    } else {
      o.begin = &o.known;
      o.size = 1;
    }
    if (o.size == 0 || (o.known >= 0 && std::find(fitting.begin(), fitting.end(), o.known) == fitting.end()))
      return 0.0;
  }
  // walks[a]: closed-walk counts so far ending in tile a, kept with the list of tiles where it
  // is not zero, so a step costs (tiles reached) x (tiles allowed next), not tile_count^2.
  const std::size_t count = static_cast<std::size_t>(rules_.tile_count());
  std::vector<double> walks(count, 0.0), next(count, 0.0);
  std::vector<int> reached, reached_next;
  reached.reserve(count);
  reached_next.reserve(count);
  double total = 0.0;
  for (std::size_t f = 0; f < options[0].size; ++f) {
    const int first = options[0].begin[f];
    for (int a : reached) walks[static_cast<std::size_t>(a)] = 0.0;
    reached.assign(1, first);
    walks[static_cast<std::size_t>(first)] = 1.0;
    int previous = kRing[start];
    for (std::size_t i = 1; i <= kRing.size() && !reached.empty(); ++i) {
      const int position = kRing[(start + i) % kRing.size()];
      const Options& here = i == kRing.size() ? options[0] : options[i];
      const std::size_t from = i == kRing.size() ? f : 0, to = i == kRing.size() ? f + 1 : here.size;
      reached_next.clear();
      for (std::size_t k = from; k < to; ++k) {
        const int b = here.begin[k];
        double sum = 0.0;
        for (int a : reached)
          if (fit(previous, a, position, b)) sum += walks[static_cast<std::size_t>(a)];
        if (sum != 0.0) {
          next[static_cast<std::size_t>(b)] = sum;
          reached_next.push_back(b);
        }
      }
      for (int a : reached) walks[static_cast<std::size_t>(a)] = 0.0;
      walks.swap(next);
      reached.swap(reached_next);
      previous = position;
    }
    for (int a : reached) total += walks[static_cast<std::size_t>(a)];  // only `first` is left
  }
  return total;
}

const std::vector<BlockConfiguration>& BlockConfigurations::projections(int centre, PositionMask mask) {
  mask |= kCentreOnly;
  auto key = std::make_pair(centre, mask);
  auto found = cache_.find(key);
  if (found != cache_.end()) return found->second;

  std::vector<BlockConfiguration> result;
  BlockConfiguration partial;
  partial.tiles.fill(-1);
  partial.tiles[kBlockCentre] = static_cast<std::int16_t>(centre);
  std::vector<int> known;
  for (int p : kRing)
    if (mask & (PositionMask{1} << p)) known.push_back(p);
  // Depth-first over the known positions in cycle order, each tile checked against the
  // positions already set beside it; the count along the cycle drops the rest.
  std::function<void(std::size_t)> assign = [&](std::size_t depth) {
    if (depth == known.size()) {
      double weight = completions(partial.tiles);
      if (weight > 0.0) {
        if (result.size() >= kMaxProjections) {
          throw Error("exact strategy: more than " + std::to_string(kMaxProjections) +
                      " neighbour configurations for one group of points (cells nearly as wide as a tile); use "
                      "more points per tile or the instances strategy");
        }
        partial.weight = weight;
        result.push_back(partial);
      }
      return;
    }
    const int position = known[depth];
    for (int t : candidates(centre, position)) {
      bool fits = true;
      for (std::size_t d = 0; d < depth && fits; ++d) {
        const int other = known[d];
        if (edge_adjacent(position, other)) fits = fit(other, partial.tiles[static_cast<std::size_t>(other)], position, t);
      }
      if (!fits) continue;
      partial.tiles[static_cast<std::size_t>(position)] = static_cast<std::int16_t>(t);
      assign(depth + 1);
    }
    partial.tiles[static_cast<std::size_t>(position)] = -1;
  };
  assign(0);
  return cache_.emplace(key, std::move(result)).first->second;
}

std::vector<BlockConfiguration> BlockConfigurations::covering_blocks(int centre, Rng& rng) const {
  // Enough rounds for the edge with the most fitting tiles; a few random restarts look for a
  // cover in that many, else the best attempt gets rounds added until every neighbour appears.
  constexpr int kAttempts = 16;  // covers of wang8, wang16 and corner16 are found in 1-3
  std::size_t rounds = 0;
  for (int p : kEdgePositions) rounds = std::max(rounds, candidates(centre, p).size());

  std::vector<BlockConfiguration> best;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    std::vector<BlockConfiguration> blocks;
    // uses[edge][tile]: how often the tile sat at that edge position so far.
    std::array<std::vector<int>, 4> uses;
    for (auto& u : uses) u.assign(static_cast<std::size_t>(rules_.tile_count()), 0);
    auto uncovered = [&] {
      for (std::size_t e = 0; e < 4; ++e)
        for (int t : candidates(centre, kEdgePositions[e]))
          if (uses[e][static_cast<std::size_t>(t)] == 0) return true;
      return false;
    };
    while (blocks.size() < rounds || (uncovered() && blocks.size() < 4 * rounds)) {
      BlockConfiguration block;
      block.tiles.fill(-1);
      block.tiles[kBlockCentre] = static_cast<std::int16_t>(centre);
      block.weight = 1.0;
      // Edges first, each the least used fitting tile (ties at random), then the corners.
      for (std::size_t e = 0; e < 4; ++e) {
        const int position = kEdgePositions[e];
        std::vector<int> choices;
        int least = -1;
        for (int t : candidates(centre, position)) {
          block.tiles[static_cast<std::size_t>(position)] = static_cast<std::int16_t>(t);
          if (completions(block.tiles) == 0.0) continue;
          int u = uses[e][static_cast<std::size_t>(t)];
          if (least < 0 || u < least) {
            least = u;
            choices.clear();
          }
          if (u == least) choices.push_back(t);
        }
        assert(!choices.empty());  // the block so far extends to some admissible block
        block.tiles[static_cast<std::size_t>(position)] =
            static_cast<std::int16_t>(choices[static_cast<std::size_t>(rng.below(choices.size()))]);
        ++uses[e][static_cast<std::size_t>(block.tiles[static_cast<std::size_t>(position)])];
      }
      for (int position : {0, 2, 6, 8}) {
        std::vector<int> choices;
        for (int t : candidates(centre, position)) {
          block.tiles[static_cast<std::size_t>(position)] = static_cast<std::int16_t>(t);
          if (completions(block.tiles) > 0.0) choices.push_back(t);
        }
        assert(!choices.empty());
        block.tiles[static_cast<std::size_t>(position)] =
            static_cast<std::int16_t>(choices[static_cast<std::size_t>(rng.below(choices.size()))]);
      }
      blocks.push_back(block);
    }
    if (best.empty() || blocks.size() < best.size()) best = std::move(blocks);
    if (best.size() == rounds) break;
  }
  return best;
}

}  // namespace bluetile
