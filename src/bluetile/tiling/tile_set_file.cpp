// Tile-set files, version 1 (docs/DESIGN.md, tile-set file): reading with every check,
// writing that reads back bit for bit, and the same checks for a set built in memory.
#include "bluetile/tiling/tile_set_file.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string_view>
#include <vector>

#include "bluetile/core/error.h"
#include "bluetile/core/input_file.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace {

constexpr std::string_view kVersionLine = "# bluetile tiles 1";

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

  std::string_view unread = text;
  while (!unread.empty()) {
    std::string_view line = next_line(unread);
    ++number;
    if (line.find('\0') != std::string_view::npos) fail("binary data (NUL byte): not a tile-set file");
    if (number == 1) {
      if (line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);  // a UTF-8 byte-order mark
      // Compared word by word: spaces an editor left at the end (or doubled) change nothing.
      auto tokens = split_whitespace(line);
      const bool version_line = tokens.size() == 4 && tokens[0] == "#" && tokens[1] == "bluetile" && tokens[2] == "tiles";
      if (version_line && tokens[3] != "1")
        fail("tile-set file version " + quoted(tokens[3]) + " is not supported (this reads version 1)");
      if (!version_line) fail("not a tile-set file: the first line must be '" + std::string(kVersionLine) + "'");
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
      // "# Tile 3 0 1 1 1" was read as a comment, and its points as the tile before's: a line
      // that looks like a tile directive but for the case is refused.
      long long looks_like_id = 0;
      if (rules && words.size() >= 6 && words[0] != "tile" && lower_case(std::string(words[0])) == "tile" &&
          parse_int(words[1], looks_like_id))
        fail(quoted(words[0]) + " is not a directive: write '# tile ...'");
      if (!words.empty() && words[0] == "set") {
        if (rules) fail("a second set line");
        if (words.size() != 4 || words[2] != "colours") fail("expected '# set KIND colours C', got " + quoted(line));
        auto kind = parse_tile_set_kind(words[1]);
        if (!kind) fail("unknown tile-set kind " + quoted(words[1]) + " (known: " + tile_set_kind_list() + ")");
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
            fail("colour must be an integer in 0.." + std::to_string(rules->colour_count() - 1) + ", got " +
                 quoted(words[first_colour + c]));
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

// Every read checked, out of memory included (input_file.h): never a tile set cut short. "-" is
// standard input, named "stdin" in messages.
TileSet read_tile_set(const std::string& path) { return parse_tile_set(read_input(path), input_name(path)); }

std::string format_tile_set(const TileSet& set) {
  validate_tile_set(set);
  TileRules rules(set.kind);
  std::string text(kVersionLine);
  text += '\n';
  for (const std::string& line : set.header) text += line.empty() ? "#\n" : "# " + comment_line(line) + "\n";
  text += "# set " + std::string(tile_set_kind_name(set.kind)) + " colours " + std::to_string(rules.colour_count()) + "\n";
  const ClassicNumbers classic;
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
