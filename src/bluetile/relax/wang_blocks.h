// Neighbour configurations of a tile, for Lloyd relaxation with multiple edge constraints (the
// paper, section 3, Figure 5): a tile's points move by the mean of their Lloyd displacements
// over the configurations of neighbouring tiles the tile can be placed in.
//
// A configuration is a 3x3 block of tiles around the tile (the centre). A point only sees the
// neighbour positions within twice its cell's radius, so it needs the projections of all
// admissible blocks onto the positions it sees, each weighted by the number of blocks that agree
// with it: the mean over those projections is the mean over all blocks. Admissibility is pairwise
// (every two edge-adjacent tiles fit, TileRules::fits_east / fits_north), and the eight positions
// around the centre form a cycle of such pairs, so the blocks that agree with a projection are
// counted along the cycle by products of 0/1 transfer matrices, without enumerating them.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "bluetile/core/rng.h"
#include "bluetile/tiling/tile_set.h"

namespace bluetile {

// Positions of a 3x3 block: index (dy + 1) * 3 + (dx + 1) for the offset (dx, dy) in {-1, 0, 1}^2
// of the position's tile from the centre tile; row 0 at the bottom, as TileRules::for_each_block
// numbers its blocks.
inline constexpr int kBlockPositions = 9;
inline constexpr int kBlockCentre = 4;
inline constexpr int block_dx(int position) { return position % 3 - 1; }
inline constexpr int block_dy(int position) { return position / 3 - 1; }

// Bit p set: the tile at position p is known. The centre is always known.
using PositionMask = std::uint16_t;
inline constexpr PositionMask kCentreOnly = PositionMask{1} << kBlockCentre;
inline constexpr PositionMask kWholeBlock = (PositionMask{1} << kBlockPositions) - 1;

// A partial 3x3 block: tiles[p] is the tile at position p, or -1 where it is not known; the
// weight is the number of admissible 3x3 blocks that agree with it.
struct BlockConfiguration {
  std::array<std::int16_t, kBlockPositions> tiles{};
  double weight = 0.0;
};

class BlockConfigurations {
 public:
  explicit BlockConfigurations(const TileRules& rules);

  const TileRules& rules() const { return rules_; }

  // The distinct restrictions to the positions of `mask` of the admissible 3x3 blocks with tile
  // `centre` at the centre, each with the number of blocks restricting to it, in a fixed order.
  // Cached: the reference stays valid for the life of this object. Not thread-safe.
  const std::vector<BlockConfiguration>& projections(int centre, PositionMask mask);

  // How many admissible 3x3 blocks have `centre` at the centre (4096 per tile for wang8).
  double block_count(int centre) const;

  // Admissible blocks agreeing with a partial block (known positions must already fit each
  // other); 0 when none does.
  double completions(const std::array<std::int16_t, kBlockPositions>& tiles) const;

  // Whole blocks around `centre` such that every tile that can sit at each edge position (N, E, S,
  // W) sits there in at least one of them, as few as the search finds (the largest number of
  // tiles that fit one edge when it succeeds: 4 for wang8), corners drawn at random among those
  // that fit. The "rounds" reading of the paper's Figure 5: one configuration per neighbour.
  std::vector<BlockConfiguration> covering_blocks(int centre, Rng& rng) const;

  // The tiles that fit at `position` next to `centre` alone (every tile for a corner position).
  const std::vector<int>& candidates(int centre, int position) const {
    return candidates_[static_cast<std::size_t>(centre)][static_cast<std::size_t>(position)];
  }

 private:
  // Do tile a at position pa and tile b at the edge-adjacent position pb fit?
  bool fit(int pa, int a, int pb, int b) const;

  const TileRules& rules_;
  // TileRules::fits_east / fits_north of every pair (a * tile_count + b), read in the inner loop
  // of completions().
  std::vector<std::uint8_t> fits_east_, fits_north_;
  std::vector<std::array<std::vector<int>, kBlockPositions>> candidates_;
  std::vector<double> block_counts_;
  std::map<std::pair<int, PositionMask>, std::vector<BlockConfiguration>> cache_;
};

}  // namespace bluetile
