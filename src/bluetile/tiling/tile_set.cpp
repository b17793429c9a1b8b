#include "bluetile/tiling/tile_set.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "bluetile/core/error.h"
#include "bluetile/core/input_file.h"
#include "bluetile/core/output_file.h"

namespace bluetile {
namespace {

constexpr std::array<TileSetKind, 3> kKinds{TileSetKind::wang8, TileSetKind::wang16, TileSetKind::corner16};
constexpr std::string_view kVersionLine = "# bluetile tiles 1";

// Edge and corner slots in TileColours.
constexpr int kNorth = 0, kEast = 1, kSouth = 2, kWest = 3;
constexpr int kNorthWest = 0, kNorthEast = 1, kSouthEast = 2, kSouthWest = 3;

// Independent bit streams of the hashed tilings.
constexpr std::uint64_t kCellBit = 1;        // wang8: the bit of a cell
constexpr std::uint64_t kHorizontalEdge = 2;  // wang16: the edge below cell (i, j)
constexpr std::uint64_t kVerticalEdge = 3;    // wang16: the edge left of cell (i, j)
constexpr std::uint64_t kLatticePoint = 4;    // corner16: the lower-left corner of cell (i, j)

std::int64_t floor_mod(std::int64_t a, std::int64_t m) {
  std::int64_t r = a % m;
  return r < 0 ? r + m : r;
}

std::vector<std::string_view> split_whitespace(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

// Long lines are cut in messages so one bad line cannot flood stderr.
std::string quoted(std::string_view text) {
  constexpr std::size_t kMaxQuoted = 80;  // enough to recognise the line
  // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on a literal + string chain here.
  std::string out(1, '\'');
  out.append(text.substr(0, kMaxQuoted));
  if (text.size() > kMaxQuoted) out += "...";
  out += '\'';
  return out;
}

bool parse_int(std::string_view token, long long& value) {
  auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

std::string colours_text(const TileColours& c) {
  return std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + " " +
         std::to_string(c[3]);
}

// Every read checked, out of memory included (input_file.h): never a tile set cut short.
std::string read_whole_file(const std::string& path) { return read_input(path); }

// Checks one finished tile: ranks a permutation of 0..n-1, levels non-decreasing along ranks.
// Returns an empty string when the tile is sound, else what is wrong and the index of the point.
std::string tile_problem(const Tile& tile, std::size_t& point) {
  std::size_t n = tile.points.size();
  if (tile.levels.size() != n || tile.ranks.size() != n) {
    point = 0;
    return "points, levels and ranks differ in number";
  }
  std::vector<std::int64_t> by_rank(n, -1);
  for (std::size_t k = 0; k < n; ++k) {
    std::uint32_t r = tile.ranks[k];
    if (r >= n) {
      point = k;
      return "rank " + std::to_string(r) + " out of range: the tile has " + std::to_string(n) + " points";
    }
    if (by_rank[r] >= 0) {
      point = k;
      return "duplicate rank " + std::to_string(r);
    }
    by_rank[r] = static_cast<std::int64_t>(k);
  }
  for (std::size_t r = 1; r < n; ++r) {
    auto before = static_cast<std::size_t>(by_rank[r - 1]);
    auto here = static_cast<std::size_t>(by_rank[r]);
    if (tile.levels[here] < tile.levels[before]) {
      point = here;
      return "rank " + std::to_string(r) + " has level " + std::to_string(tile.levels[here]) +
             " after rank " + std::to_string(r - 1) + " of level " + std::to_string(tile.levels[before]) +
             ": levels must not decrease along the rank order";
    }
  }
  return {};
}

}  // namespace

std::string_view tile_set_kind_name(TileSetKind kind) {
  switch (kind) {
    case TileSetKind::wang8: return "wang8";
    case TileSetKind::wang16: return "wang16";
    case TileSetKind::corner16: return "corner16";
  }
  return "unknown";
}

std::optional<TileSetKind> parse_tile_set_kind(std::string_view name) {
  for (TileSetKind kind : kKinds)
    if (tile_set_kind_name(kind) == name) return kind;
  return std::nullopt;
}

std::span<const TileSetKind> tile_set_kinds() { return kKinds; }

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
  }
}

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

int TileRules::bit(std::int64_t i, std::int64_t j, std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t h = mix64(seed ^ (static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ull));
  h = mix64(h ^ (static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4Full) ^ (stream << 56));
  return static_cast<int>(h >> 63);
}

int TileRules::tile_from_bits(std::int64_t i, std::int64_t j, std::uint64_t seed, std::int64_t period) const {
  // Cells (or lattice points) are folded onto the torus before hashing when a period is given.
  auto at = [&](std::int64_t x, std::int64_t y, std::uint64_t stream) {
    if (period > 0) x = floor_mod(x, period), y = floor_mod(y, period);
    return bit(x, y, seed, stream);
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

void validate_tile_set(const TileSet& set) {
  TileRules rules(set.kind);
  std::string kind(tile_set_kind_name(set.kind));
  for (const std::string& line : set.header) {
    // Such a line would read back as a directive.
    auto words = split_whitespace(line);
    if (line.find('\n') != std::string::npos || (!words.empty() && (words[0] == "set" || words[0] == "tile")))
      throw Error("tile set " + kind + ": header line " + quoted(line) + " would not read back as a comment");
  }
  if (static_cast<int>(set.tiles.size()) != rules.tile_count())
    throw Error("tile set " + kind + ": " + std::to_string(set.tiles.size()) + " tiles, the kind has " +
                std::to_string(rules.tile_count()));
  for (int id = 0; id < rules.tile_count(); ++id) {
    const Tile& tile = set.tiles[static_cast<std::size_t>(id)];
    std::string where = "tile set " + kind + ": tile " + std::to_string(id);
    if (tile.colours != rules.colours(id))
      throw Error(where + ": colours " + colours_text(tile.colours) + ", tile " + std::to_string(id) + " of " +
                  kind + " has " + colours_text(rules.colours(id)));
    for (std::size_t k = 0; k < tile.points.size(); ++k) {
      Point p = tile.points[k];
      if (!(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0))
        throw Error(where + ": point " + std::to_string(k) + " outside the tile [0,1)^2");
      if (k < tile.levels.size() && tile.levels[k] < 0)
        throw Error(where + ": point " + std::to_string(k) + " has a negative level");
    }
    std::size_t point = 0;
    std::string problem = tile_problem(tile, point);
    if (!problem.empty()) throw Error(where + ": point " + std::to_string(point) + ": " + problem);
  }
}

// Tiles of one set differ in points only by the thinning of their last level: a factor beyond
// this is no tile set the tool makes.
constexpr std::size_t kMaxTileImbalance = 4;

TileSet parse_tile_set(const std::string& text, const std::string& name) {
  TileSet set;
  std::optional<TileRules> rules;
  std::vector<std::size_t> tile_line;       // per id: the line of its "# tile", 0 when not seen
  std::vector<std::size_t> point_line;      // per point of the current tile: its line
  std::vector<std::vector<std::size_t>> point_lines;  // per id
  int current = -1;                          // id of the tile whose points follow
  std::size_t number = 0;
  auto fail = [&](const std::string& what) -> void { throw Error(name + ":" + std::to_string(number) + ": " + what); };

  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + start, end - start);
    start = end + 1;
    ++number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.find('\0') != std::string_view::npos) fail("binary data (NUL byte): not a tile-set file");
    if (number == 1) {
      if (line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);  // a UTF-8 byte-order mark
      auto tokens = split_whitespace(line);
      if (tokens.size() == 4 && tokens[0] == "#" && tokens[1] == "bluetile" && tokens[2] == "tiles" &&
          tokens[3] != "1")
        fail("tile-set file version " + quoted(tokens[3]) + " is not supported (this reads version 1)");
      if (line != kVersionLine) fail("not a tile-set file: the first line must be '" + std::string(kVersionLine) + "'");
      continue;
    }
    auto tokens = split_whitespace(line);
    if (tokens.empty()) continue;
    if (tokens[0].front() == '#') {
      // "# set ..." and "# tile ..." are directives; other comment lines are kept as header
      // while no set line has been seen, and ignored after.
      std::vector<std::string_view> words = tokens;
      if (words[0] == "#") words.erase(words.begin());
      else words[0].remove_prefix(1);
      if (!words.empty() && words[0] == "set") {
        if (rules) fail("a second set line");
        if (words.size() != 4 || words[2] != "colours") fail("expected '# set KIND colours C', got " + quoted(line));
        auto kind = parse_tile_set_kind(words[1]);
        if (!kind) fail("unknown tile-set kind " + quoted(words[1]) + " (known: wang8, wang16, corner16)");
        long long colours = 0;
        if (!parse_int(words[3], colours)) fail("colour count must be an integer, got " + quoted(words[3]));
        set.kind = *kind;
        rules.emplace(*kind);
        if (colours != rules->colour_count())
          fail(std::string(tile_set_kind_name(*kind)) + " has " + std::to_string(rules->colour_count()) +
               " colours, the file says " + std::string(words[3]));
        set.tiles.resize(static_cast<std::size_t>(rules->tile_count()));
        tile_line.assign(set.tiles.size(), 0);
        point_lines.assign(set.tiles.size(), {});
      } else if (!words.empty() && words[0] == "tile") {
        if (!rules) fail("tile before the '# set KIND colours C' line");
        bool corners = rules->corner_coloured();
        std::size_t first_colour = corners ? 3 : 2;
        if (words.size() != first_colour + 4 || (corners && words[2] != "corners"))
          fail(corners ? "expected '# tile ID corners NW NE SE SW', got " + quoted(line)
                       : "expected '# tile ID N E S W', got " + quoted(line));
        long long id = 0;
        if (!parse_int(words[1], id) || id < 0 || id >= rules->tile_count())
          fail("tile id must be an integer in 0.." + std::to_string(rules->tile_count() - 1) + ", got " +
               quoted(words[1]));
        auto index = static_cast<std::size_t>(id);
        if (tile_line[index] != 0) fail("tile " + std::to_string(id) + " again (first on line " + std::to_string(tile_line[index]) + ")");
        TileColours colours{};
        for (std::size_t c = 0; c < 4; ++c) {
          long long value = 0;
          if (!parse_int(words[first_colour + c], value) || value < 0 || value >= rules->colour_count())
            fail("colour must be 0 or 1, got " + quoted(words[first_colour + c]));
          colours[c] = static_cast<std::uint8_t>(value);
        }
        if (colours != rules->colours(static_cast<int>(id)))
          fail("tile " + std::to_string(id) + " of " + std::string(tile_set_kind_name(set.kind)) + " has colours " +
               colours_text(rules->colours(static_cast<int>(id))) + ", the file says " + colours_text(colours));
        tile_line[index] = number;
        set.tiles[index].colours = colours;
        current = static_cast<int>(id);
      } else if (!rules) {
        std::string_view rest = line.substr(1);
        if (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
        set.header.emplace_back(rest);
      }
      continue;
    }
    if (current < 0) fail("point before the first '# tile' line");
    if (tokens.size() != 4) fail("expected 'x y level rank', got " + quoted(line));
    Tile& tile = set.tiles[static_cast<std::size_t>(current)];
    double xy[2];
    for (int c = 0; c < 2; ++c) {
      std::string_view token = tokens[static_cast<std::size_t>(c)];
      auto [p, ec] = std::from_chars(token.data(), token.data() + token.size(), xy[c]);
      if (ec != std::errc() || p != token.data() + token.size() || !std::isfinite(xy[c]))
        fail("not a finite number " + quoted(token));
      if (!(xy[c] >= 0.0 && xy[c] < 1.0)) fail("point outside the tile: " + quoted(token) + " is not in [0,1)");
    }
    long long level = 0, rank = 0;
    if (!parse_int(tokens[2], level) || level < 0 || level > 1000000)
      fail("level must be an integer in 0..1000000, got " + quoted(tokens[2]));
    if (!parse_int(tokens[3], rank) || rank < 0 || rank > 0xFFFFFFFFll)
      fail("rank must be a non-negative integer, got " + quoted(tokens[3]));
    tile.points.push_back({xy[0], xy[1]});
    tile.levels.push_back(static_cast<int>(level));
    tile.ranks.push_back(static_cast<std::uint32_t>(rank));
    point_lines[static_cast<std::size_t>(current)].push_back(number);
  }
  ++number;
  if (!rules) fail("no '# set KIND colours C' line");
  for (std::size_t id = 0; id < set.tiles.size(); ++id) {
    if (tile_line[id] == 0) fail("tile " + std::to_string(id) + " is missing");
    std::size_t point = 0;
    std::string problem = tile_problem(set.tiles[id], point);
    if (!problem.empty()) {
      number = point_lines[id].empty() ? tile_line[id] : point_lines[id][point];
      fail("tile " + std::to_string(id) + ": " + problem);
    }
  }
  // Every tile samples the same density over the same area: one without points, or one with
  // several times the points of another, is a damaged or hand-made file, not a tile set.
  std::size_t fewest = 0, most = 0;
  for (std::size_t id = 0; id < set.tiles.size(); ++id) {
    const std::size_t n = set.tiles[id].points.size();
    if (n == 0) {
      number = tile_line[id];
      fail("tile " + std::to_string(id) + " has no points");
    }
    if (n < set.tiles[fewest].points.size()) fewest = id;
    if (n > set.tiles[most].points.size()) most = id;
  }
  const std::size_t low = set.tiles[fewest].points.size(), high = set.tiles[most].points.size();
  if (high > kMaxTileImbalance * low) {
    number = tile_line[most];
    fail("tile " + std::to_string(most) + " has " + std::to_string(high) + " points, more than " +
         std::to_string(kMaxTileImbalance) + " times the " + std::to_string(low) + " of tile " + std::to_string(fewest) +
         ": a set's tiles hold about as many points each");
  }
  return set;
}

TileSet read_tile_set(const std::string& path) { return parse_tile_set(read_whole_file(path), path); }

std::string format_tile_set(const TileSet& set) {
  validate_tile_set(set);
  TileRules rules(set.kind);
  std::string text(kVersionLine);
  text += '\n';
  for (const std::string& line : set.header) text += line.empty() ? "#\n" : "# " + line + "\n";
  text += "# set " + std::string(tile_set_kind_name(set.kind)) + " colours " + std::to_string(rules.colour_count()) + "\n";
  char buffer[128];
  for (std::size_t id = 0; id < set.tiles.size(); ++id) {
    const Tile& tile = set.tiles[id];
    text += "# tile " + std::to_string(id) + (rules.corner_coloured() ? " corners " : " ") + colours_text(tile.colours) + "\n";
    for (std::size_t k = 0; k < tile.points.size(); ++k) {
      int n = std::snprintf(buffer, sizeof buffer, "%.17g %.17g %d %u\n", tile.points[k].x, tile.points[k].y,
                            tile.levels[k], tile.ranks[k]);
      text.append(buffer, static_cast<std::size_t>(n));
    }
  }
  return text;
}

void write_tile_set(const std::string& path, const TileSet& set) { write_output(path, format_tile_set(set)); }

}  // namespace bluetile
