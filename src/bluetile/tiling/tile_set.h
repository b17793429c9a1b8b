// Tile sets for aperiodic tilings of the plane: the paper's section 3 (Hiller, Deussen, Keller
// 2001, after Wang 1965 and Shade et al. 2000), with the complete edge set and the corner tiles
// of Lagae and Dutré 2006 ("An alternative for Wang tiles: colored edges versus colored corners").
//
// Conventions (docs/DESIGN.md, tiles): tile (i, j) of a tiling covers [i, i+1] x [j, j+1], y up.
// Edge tiles carry colours (N, E, S, W); neighbours must agree along the shared edge:
// tile(i,j).E == tile(i+1,j).W and tile(i,j).N == tile(i,j+1).S. Corner tiles carry colours
// (NW, NE, SE, SW) on their corners; the four tiles around a lattice point agree on its colour.
// Every kind has 2 colours but corner81, which has 3.
//
// The three kinds and how a tiling is drawn (all O(1) per cell from hashed bits, so any window
// of the plane, at any distance from the origin, gives the same tiles):
//  - wang8: the paper's set. A random bit b(i,j) per cell; tile(i,j) = (N = b(i,j+1),
//    W = b(i-1,j), S = E = b(i,j)). For each (N, W) pair exactly two tiles exist, differing in
//    S and E, so a scanline tiling (each tile drawn among those fitting its north and west
//    neighbours) and the hashed one have the same distribution. Each edge has 4 admissible
//    neighbours.
//  - wang16: every combination of 2 edge colours; each edge colour is an independent hashed
//    bit. 8 admissible neighbours per edge.
//  - corner16: every combination of 2 corner colours; each lattice point's colour is a hashed
//    bit. The diagonal neighbours are constrained too (no corner problem).
//  - corner81: every combination of 3 corner colours; each lattice point's colour is hashed to
//    0, 1 or 2. An M x M tiling holds about M^2 / 81 copies of each tile instead of M^2 / 8, so the
//    repetition that shows at the tile lattice's frequencies is about 10 times weaker than wang8's
//    (docs/RESULTS.md, "More tiles: corner81"). 9 admissible neighbours per edge.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "bluetile/core/rng.h"
#include "bluetile/core/torus.h"

namespace bluetile {

enum class TileSetKind : std::uint8_t { wang8, wang16, corner16, corner81 };

// "wang8", "wang16", "corner16", "corner81": the names `--set` takes and tile-set files use.
std::string_view tile_set_kind_name(TileSetKind kind);
std::optional<TileSetKind> parse_tile_set_kind(std::string_view name);
// "wang8, wang16, corner16, corner81", for messages that list the known kinds.
std::string tile_set_kind_list();
// All kinds, for option help and tests.
std::span<const TileSetKind> tile_set_kinds();

// Edge colours in the order N, E, S, W, or corner colours in the order NW, NE, SE, SW.
using TileColours = std::array<std::uint8_t, 4>;

// The combinatorics of one kind: the tiles, which may sit next to which, and seeded tilings.
// Tiles are numbered 0 .. tile_count()-1 (a tile's id): for wang8 id = 4 N + 2 W + S (S == E),
// for wang16 id = 8 N + 4 E + 2 S + W, for corner16 id = 8 NW + 4 NE + 2 SE + SW, for corner81
// id = 27 NW + 9 NE + 3 SE + SW.
class TileRules {
 public:
  explicit TileRules(TileSetKind kind);

  TileSetKind kind() const { return kind_; }
  bool corner_coloured() const { return kind_ == TileSetKind::corner16 || kind_ == TileSetKind::corner81; }
  int tile_count() const { return static_cast<int>(colours_.size()); }
  int colour_count() const;
  const TileColours& colours(int tile) const { return colours_[static_cast<std::size_t>(tile)]; }
  // The id of the tile with these colours, or -1 when the set has no such tile.
  int tile_with(const TileColours& colours) const;

  // May tile `east` sit directly east of (to the right of) tile `west`?
  bool fits_east(int west, int east) const;
  // May tile `north` sit directly north of (above) tile `south`?
  bool fits_north(int south, int north) const;

  // The tile of cell (i, j) of the infinite plane for `seed`: a pure function, O(1).
  int tile_at(std::int64_t i, std::int64_t j, std::uint64_t seed) const;
  // The same tiling folded onto a period x period torus (cells taken modulo `period` >= 1): a
  // valid tiling of the torus, for periodic scenes of tiled planes.
  int tile_at_periodic(std::int64_t i, std::int64_t j, std::uint64_t seed, std::int64_t period) const;

  // A width x height tiling (tiles[row * width + column], row 0 at the bottom) built in scanline
  // order from the top row down, left to right, each tile drawn uniformly among those that fit
  // the tiles already placed above and to the left of it. For tests: the hashed tiling must have
  // the same distribution.
  std::vector<int> scanline_tiling(int width, int height, Rng& rng) const;

  // Calls visit(tiles) for every admissible block of width x height tiles (tiles[row * width +
  // column], row 0 at the bottom), in a fixed order. 2 x 2: 256 blocks for wang8, 4096 for
  // wang16, 512 for corner16 and 19683 for corner81.
  void for_each_block(int width, int height, const std::function<void(std::span<const int>)>& visit) const;

 private:
  // The hashed bit `stream` of cell or lattice point (i, j): the tiling's only randomness.
  static std::uint64_t hash(std::int64_t i, std::int64_t j, std::uint64_t seed, std::uint64_t stream);
  static int bit(std::int64_t i, std::int64_t j, std::uint64_t seed, std::uint64_t stream);
  // The hashed colour 0, 1 or 2 of lattice point (i, j), for three-colour sets.
  static int trit(std::int64_t i, std::int64_t j, std::uint64_t seed, std::uint64_t stream);
  int tile_from_bits(std::int64_t i, std::int64_t j, std::uint64_t seed, std::int64_t period) const;

  TileSetKind kind_;
  std::vector<TileColours> colours_;
};

// One tile's point set, in tile-local coordinates [0,1)^2. Point k has level levels[k] and rank
// ranks[k], its place in the tile's progressive order: the first m ranks are the tile thinned to
// m points. Ranks are a permutation of 0 .. size-1 and levels never decrease along the rank order.
struct Tile {
  TileColours colours{};
  std::vector<Point> points;
  std::vector<int> levels;
  std::vector<std::uint32_t> ranks;
};

// A tile set: one Tile per id of its kind's rules, in id order.
struct TileSet {
  TileSetKind kind = TileSetKind::wang8;
  // Free comment lines written after the version line (without "# "), e.g. the command that
  // made the set; kept on reading so that files round-trip.
  std::vector<std::string> header;
  std::vector<Tile> tiles;
};

}  // namespace bluetile
