// libFuzzer target for the tile-set reader's semantic checks (tiling/tile_set.h). The bytes do not
// become the file: they describe one, always well formed line by line (a version line, a set
// line, tile lines and 'x y level rank' lines), whose content may be wrong in every way the format
// forbids: a tile missing or given twice, wrong edge colours, no points, unequal counts, levels
// that fall along the rank order, ranks out of range or repeated. This target judges the file
// on its own, from the format's rules (docs/DESIGN.md, tile-set file, and tile_set.h), and the
// reader must agree: it accepts exactly the sound files, and a refusal names this file and a line
// of it.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "bluetile/core/error.h"
#include "bluetile/tiling/tile_set.h"
#include "bluetile/tiling/tile_set_file.h"
#include "fuzz_support.h"

namespace {

// Reads the fuzzer's bytes as small numbers; zeros once they run out.
class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  unsigned next() { return at_ < size_ ? data_[at_++] : 0u; }
  bool more() const { return at_ < size_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_, at_ = 0;
};

struct TileText {
  int id = 0;
  bluetile::TileColours colours{};
  std::vector<int> levels;
  std::vector<long long> ranks;
};

// The verdict of the format's rules on the tiles as written; the order of the checks does not
// matter, only whether any fails.
bool sound(bluetile::TileSetKind kind, const std::vector<TileText>& tiles) {
  const bluetile::TileRules rules(kind);
  std::vector<int> seen(static_cast<std::size_t>(rules.tile_count()), 0);
  for (const TileText& tile : tiles) {
    if (tile.id < 0 || tile.id >= rules.tile_count()) return false;
    if (++seen[static_cast<std::size_t>(tile.id)] > 1) return false;
    if (tile.colours != rules.colours(tile.id)) return false;
    const std::size_t n = tile.ranks.size();
    if (n == 0) return false;
    // Ranks: a permutation of 0..n-1; along it, levels never fall.
    std::vector<int> level_of_rank(n, -1);
    for (std::size_t k = 0; k < n; ++k) {
      if (tile.ranks[k] < 0 || tile.ranks[k] >= static_cast<long long>(n)) return false;
      int& slot = level_of_rank[static_cast<std::size_t>(tile.ranks[k])];
      if (slot >= 0) return false;
      slot = tile.levels[k];
    }
    for (std::size_t r = 1; r < n; ++r)
      if (level_of_rank[r] < level_of_rank[r - 1]) return false;
  }
  for (int count : seen)
    if (count != 1) return false;
  std::size_t fewest = SIZE_MAX, most = 0;
  for (const TileText& tile : tiles) {
    fewest = std::min(fewest, tile.ranks.size());
    most = std::max(most, tile.ranks.size());
  }
  return most <= 4 * fewest;  // tile_set.h: tiles hold about as many points each
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes bytes(data, size);
  const unsigned header = bytes.next();
  const auto kind = bluetile::tile_set_kinds()[header % 3];
  const bluetile::TileRules rules(kind);
  // Mostly sound sets with one thing wrong: each damage below is chosen rarely.
  std::vector<TileText> tiles;
  for (int id = 0; id < rules.tile_count(); ++id) {
    const unsigned shape = bytes.next();
    if (shape == 1) continue;  // tile missing
    TileText tile;
    tile.id = shape == 2 ? (id + 1) % rules.tile_count() : shape == 3 ? rules.tile_count() : id;
    tile.colours = rules.colours(id);
    if (shape == 4) tile.colours[bytes.next() % 4] ^= 1;  // a wrong edge or corner colour
    const unsigned count = shape == 5 ? 0 : shape == 6 ? 13 + bytes.next() % 8 : 2 + (shape >> 6);
    for (unsigned k = 0; k < count; ++k) {
      tile.levels.push_back(k * 2 < count ? 0 : 1);
      tile.ranks.push_back(k);
    }
    const unsigned damage = bytes.next();
    if (count > 0 && damage < 16) {
      const std::size_t a = damage % count, b = (damage / 4) % count;
      switch (damage % 4) {
        case 0: std::swap(tile.levels[a], tile.levels[b]); break;  // levels fall along the ranks
        case 1: tile.ranks[a] = tile.ranks[b]; break;              // a rank twice
        case 2: tile.ranks[a] = static_cast<long long>(count + b); break;  // a rank out of range
        case 3: std::swap(tile.ranks[a], tile.ranks[b]); break;    // still a permutation
      }
    }
    tiles.push_back(tile);
  }
  if (bytes.more() && bytes.next() == 7 && !tiles.empty()) tiles.push_back(tiles.front());  // a tile twice

  std::string text = "# bluetile tiles 1\n# set " + std::string(bluetile::tile_set_kind_name(kind)) + " colours 2\n";
  std::size_t point = 0;
  for (const TileText& tile : tiles) {
    text += "# tile " + std::to_string(tile.id) + (rules.corner_coloured() ? " corners" : "");
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on a literal + string chain.
    for (std::uint8_t c : tile.colours) {
      text += ' ';
      text += std::to_string(c);
    }
    text += "\n";
    for (std::size_t k = 0; k < tile.ranks.size(); ++k, ++point) {
      // Distinct points inside the tile; where they lie is no concern of these checks.
      const double x = static_cast<double>((point * 7919) % 1000) / 1000.0, y = static_cast<double>(k % 97) / 97.0;
      text += std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(tile.levels[k]) + " " +
              std::to_string(tile.ranks[k]) + "\n";
    }
  }
  std::size_t lines = 0;
  for (char c : text) lines += c == '\n';

  const bool expected = sound(kind, tiles);
  try {
    const bluetile::TileSet set = bluetile::parse_tile_set(text, "fuzz");
    BLUETILE_FUZZ_CHECK(expected);
    std::size_t read = 0;
    for (const bluetile::Tile& tile : set.tiles) read += tile.points.size();
    BLUETILE_FUZZ_CHECK(read == point);
  } catch (const bluetile::Error& e) {
    BLUETILE_FUZZ_CHECK(!expected);
    // "fuzz:LINE: ...", LINE within the file (one past its end for what is missing at the end).
    const std::string message = e.what();
    BLUETILE_FUZZ_CHECK(message.rfind("fuzz:", 0) == 0);
    const std::size_t line = std::stoul(message.substr(5));
    BLUETILE_FUZZ_CHECK(line >= 1 && line <= lines + 1);
    BLUETILE_FUZZ_CHECK(message.find('\n') == std::string::npos);
  }
  return 0;
}
