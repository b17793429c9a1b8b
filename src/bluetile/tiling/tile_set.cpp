// Tile-set kinds, their rules and hashed tilings (tile_set.h); the file format is
// tile_set_file.cpp.
#include "bluetile/tiling/tile_set.h"

#include <string>

#include "bluetile/core/error.h"

namespace bluetile {
namespace {

constexpr std::array<TileSetKind, 4> kKinds{TileSetKind::wang8, TileSetKind::wang16, TileSetKind::corner16,
                                            TileSetKind::corner81};

// Edge and corner slots in TileColours.
constexpr int kNorth = 0, kEast = 1, kSouth = 2, kWest = 3;
constexpr int kNorthWest = 0, kNorthEast = 1, kSouthEast = 2, kSouthWest = 3;

// Independent bit streams of the hashed tilings.
constexpr std::uint64_t kCellBit = 1;        // wang8: the bit of a cell
constexpr std::uint64_t kHorizontalEdge = 2;  // wang16: the edge below cell (i, j)
constexpr std::uint64_t kVerticalEdge = 3;    // wang16: the edge left of cell (i, j)
constexpr std::uint64_t kLatticePoint = 4;    // corner16, corner81: the lower-left corner of cell (i, j)

std::int64_t floor_mod(std::int64_t a, std::int64_t m) {
  std::int64_t r = a % m;
  return r < 0 ? r + m : r;
}

}  // namespace

std::string_view tile_set_kind_name(TileSetKind kind) {
  switch (kind) {
    case TileSetKind::wang8: return "wang8";
    case TileSetKind::wang16: return "wang16";
    case TileSetKind::corner16: return "corner16";
    case TileSetKind::corner81: return "corner81";
  }
  return "unknown";
}

std::optional<TileSetKind> parse_tile_set_kind(std::string_view name) {
  for (TileSetKind kind : kKinds)
    if (tile_set_kind_name(kind) == name) return kind;
  return std::nullopt;
}

std::span<const TileSetKind> tile_set_kinds() { return kKinds; }

std::string tile_set_kind_list() {
  std::string list;
  for (TileSetKind kind : kKinds) list += (list.empty() ? "" : ", ") + std::string(tile_set_kind_name(kind));
  return list;
}

TileRules::TileRules(TileSetKind kind) : kind_(kind) {
  switch (kind) {
    case TileSetKind::wang8:
      for (int id = 0; id < 8; ++id) {
        auto n = static_cast<std::uint8_t>((id >> 2) & 1), w = static_cast<std::uint8_t>((id >> 1) & 1),
             b = static_cast<std::uint8_t>(id & 1);
        colours_.push_back({n, b, b, w});
      }
      break;
    case TileSetKind::wang16:
    case TileSetKind::corner16:
      // Edge slots N E S W or corner slots NW NE SE SW: id's bits 3..0 in slot order.
      for (int id = 0; id < 16; ++id)
        colours_.push_back({static_cast<std::uint8_t>((id >> 3) & 1), static_cast<std::uint8_t>((id >> 2) & 1),
                            static_cast<std::uint8_t>((id >> 1) & 1), static_cast<std::uint8_t>(id & 1)});
      break;
    case TileSetKind::corner81:
      // Corner slots NW NE SE SW: id's base-3 digits, most significant first.
      for (int id = 0; id < 81; ++id)
        colours_.push_back({static_cast<std::uint8_t>(id / 27 % 3), static_cast<std::uint8_t>(id / 9 % 3),
                            static_cast<std::uint8_t>(id / 3 % 3), static_cast<std::uint8_t>(id % 3)});
      break;
  }
}

int TileRules::colour_count() const { return kind_ == TileSetKind::corner81 ? 3 : 2; }

int TileRules::tile_with(const TileColours& colours) const {
  for (int id = 0; id < tile_count(); ++id)
    if (colours_[static_cast<std::size_t>(id)] == colours) return id;
  return -1;
}

bool TileRules::fits_east(int west, int east) const {
  const TileColours& a = colours(west);
  const TileColours& b = colours(east);
  if (corner_coloured()) return a[kNorthEast] == b[kNorthWest] && a[kSouthEast] == b[kSouthWest];
  return a[kEast] == b[kWest];
}

bool TileRules::fits_north(int south, int north) const {
  const TileColours& a = colours(south);
  const TileColours& b = colours(north);
  if (corner_coloured()) return a[kNorthWest] == b[kSouthWest] && a[kNorthEast] == b[kSouthEast];
  return a[kNorth] == b[kSouth];
}

std::uint64_t TileRules::hash(std::int64_t i, std::int64_t j, std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t h = mix64(seed ^ (static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ull));
  return mix64(h ^ (static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4Full) ^ (stream << 56));
}

int TileRules::bit(std::int64_t i, std::int64_t j, std::uint64_t seed, std::uint64_t stream) {
  return static_cast<int>(hash(i, j, seed, stream) >> 63);
}

int TileRules::trit(std::int64_t i, std::int64_t j, std::uint64_t seed, std::uint64_t stream) {
  // The top 32 bits scaled to [0, 3): uniform to within 2^-32.
  return static_cast<int>(((hash(i, j, seed, stream) >> 32) * 3) >> 32);
}

int TileRules::tile_from_bits(std::int64_t i, std::int64_t j, std::uint64_t seed, std::int64_t period) const {
  // Cells (or lattice points) are folded onto the torus before hashing when a period is given.
  auto at = [&](std::int64_t x, std::int64_t y, std::uint64_t stream) {
    if (period > 0) x = floor_mod(x, period), y = floor_mod(y, period);
    return bit(x, y, seed, stream);
  };
  auto colour_at = [&](std::int64_t x, std::int64_t y) {
    if (period > 0) x = floor_mod(x, period), y = floor_mod(y, period);
    return trit(x, y, seed, kLatticePoint);
  };
  switch (kind_) {
    case TileSetKind::wang8: {
      int n = at(i, j + 1, kCellBit), w = at(i - 1, j, kCellBit), b = at(i, j, kCellBit);
      return 4 * n + 2 * w + b;
    }
    case TileSetKind::wang16: {
      int n = at(i, j + 1, kHorizontalEdge), s = at(i, j, kHorizontalEdge);
      int w = at(i, j, kVerticalEdge), e = at(i + 1, j, kVerticalEdge);
      return 8 * n + 4 * e + 2 * s + w;
    }
    case TileSetKind::corner16: {
      int nw = at(i, j + 1, kLatticePoint), ne = at(i + 1, j + 1, kLatticePoint);
      int se = at(i + 1, j, kLatticePoint), sw = at(i, j, kLatticePoint);
      return 8 * nw + 4 * ne + 2 * se + sw;
    }
    case TileSetKind::corner81: {
      int nw = colour_at(i, j + 1), ne = colour_at(i + 1, j + 1), se = colour_at(i + 1, j), sw = colour_at(i, j);
      return 27 * nw + 9 * ne + 3 * se + sw;
    }
  }
  return 0;
}

int TileRules::tile_at(std::int64_t i, std::int64_t j, std::uint64_t seed) const {
  return tile_from_bits(i, j, seed, 0);
}

int TileRules::tile_at_periodic(std::int64_t i, std::int64_t j, std::uint64_t seed, std::int64_t period) const {
  if (period < 1) throw Error("tile_at_periodic: period must be at least 1, got " + std::to_string(period));
  return tile_from_bits(i, j, seed, period);
}

std::vector<int> TileRules::scanline_tiling(int width, int height, Rng& rng) const {
  std::vector<int> tiles(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), -1);
  std::vector<int> candidates;
  for (int row = height - 1; row >= 0; --row)
    for (int column = 0; column < width; ++column) {
      candidates.clear();
      for (int t = 0; t < tile_count(); ++t) {
        if (row + 1 < height && !fits_north(t, tiles[static_cast<std::size_t>((row + 1) * width + column)])) continue;
        if (column > 0 && !fits_east(tiles[static_cast<std::size_t>(row * width + column - 1)], t)) continue;
        candidates.push_back(t);
      }
      // Every kind offers at least two tiles for any north and west neighbour.
      tiles[static_cast<std::size_t>(row * width + column)] =
          candidates[static_cast<std::size_t>(rng.below(candidates.size()))];
    }
  return tiles;
}

void TileRules::for_each_block(int width, int height, const std::function<void(std::span<const int>)>& visit) const {
  if (width < 1 || height < 1) throw Error("for_each_block: block must be at least 1 x 1");
  std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<int> block(count, -1);
  // Depth-first over positions in row-major order (row 0 first); each tile is checked against
  // its west and south neighbours, which are already placed.
  auto place = [&](auto& self, std::size_t position) -> void {
    if (position == count) {
      visit(block);
      return;
    }
    int row = static_cast<int>(position) / width, column = static_cast<int>(position) % width;
    for (int t = 0; t < tile_count(); ++t) {
      if (column > 0 && !fits_east(block[position - 1], t)) continue;
      if (row > 0 && !fits_north(block[position - static_cast<std::size_t>(width)], t)) continue;
      block[position] = t;
      self(self, position + 1);
    }
  };
  place(place, 0);
}

}  // namespace bluetile
