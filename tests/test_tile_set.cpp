// Tile sets: the rules of each kind against hand-derived counts, hashed and scanline tilings
// against the rules and against each other (chi-square), and the tile-set file format.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "bluetile/core/error.h"
#include "bluetile/tiling/tile_set.h"
#include "bluetile/tiling/tile_set_file.h"
#include "test_support.h"

namespace bluetile {
namespace {

// Independent of TileRules::fits_*: the shared edge or corner colours compared slot by slot.
bool corner_kind(TileSetKind kind) { return kind == TileSetKind::corner16 || kind == TileSetKind::corner81; }
bool colours_fit_east(TileSetKind kind, const TileColours& w, const TileColours& e) {
  if (corner_kind(kind)) return w[1] == e[0] && w[2] == e[3];  // NE = NW, SE = SW
  return w[1] == e[3];                                                     // E = W
}
bool colours_fit_north(TileSetKind kind, const TileColours& s, const TileColours& n) {
  if (corner_kind(kind)) return s[0] == n[3] && s[1] == n[2];  // NW = SW, NE = SE
  return s[0] == n[2];                                                     // N = S
}

// How many admissible w x h blocks each kind has, counted by its free colours: wang8 one bit
// per cell plus the bits of the row above and the column to the left; wang16 one bit per edge;
// corner16 one bit per lattice point; corner81 one of 3 colours per lattice point.
std::size_t expected_blocks(TileSetKind kind, int w, int h) {
  int bits = 0;
  switch (kind) {
    case TileSetKind::wang8: bits = w * h + w + h; break;
    case TileSetKind::wang16: bits = w * (h + 1) + (w + 1) * h; break;
    case TileSetKind::corner16: bits = (w + 1) * (h + 1); break;
    case TileSetKind::corner81: {
      std::size_t blocks = 1;
      for (int p = 0; p < (w + 1) * (h + 1); ++p) blocks *= 3;
      return blocks;
    }
  }
  return std::size_t{1} << bits;
}

TEST(TileSet, KindNamesRoundTrip) {
  ASSERT_EQ(tile_set_kinds().size(), 4u);
  for (TileSetKind kind : tile_set_kinds()) EXPECT_EQ(parse_tile_set_kind(tile_set_kind_name(kind)), kind);
  EXPECT_FALSE(parse_tile_set_kind("wang13").has_value());
  EXPECT_EQ(tile_set_kind_list(), "wang8, wang16, corner16, corner81");
}

TEST(TileSet, EveryTileIsDistinctAndNumberedByItsColours) {
  for (TileSetKind kind : tile_set_kinds()) {
    TileRules rules(kind);
    std::set<TileColours> seen;
    for (int id = 0; id < rules.tile_count(); ++id) {
      EXPECT_TRUE(seen.insert(rules.colours(id)).second);
      EXPECT_EQ(rules.tile_with(rules.colours(id)), id);
    }
  }
  EXPECT_EQ(TileRules(TileSetKind::wang8).tile_count(), 8);
  EXPECT_EQ(TileRules(TileSetKind::wang16).tile_count(), 16);
  EXPECT_EQ(TileRules(TileSetKind::corner16).tile_count(), 16);
  EXPECT_EQ(TileRules(TileSetKind::corner81).tile_count(), 81);
  EXPECT_EQ(TileRules(TileSetKind::corner81).colour_count(), 3);
  EXPECT_EQ(TileRules(TileSetKind::corner81).colours(27 * 2 + 9 * 0 + 3 * 1 + 2), (TileColours{2, 0, 1, 2}));
  EXPECT_EQ(TileRules(TileSetKind::wang8).tile_with({0, 1, 0, 0}), -1);  // S != E: not in the set
}

TEST(TileSet, Wang8HasTwoTilesPerNorthWestPairDifferingInSouthAndEast) {
  TileRules rules(TileSetKind::wang8);
  for (int n = 0; n < 2; ++n)
    for (int w = 0; w < 2; ++w) {
      std::vector<TileColours> matching;
      for (int id = 0; id < 8; ++id)
        if (rules.colours(id)[0] == n && rules.colours(id)[3] == w) matching.push_back(rules.colours(id));
      ASSERT_EQ(matching.size(), 2u);
      EXPECT_NE(matching[0][1], matching[1][1]);
      EXPECT_NE(matching[0][2], matching[1][2]);
    }
}

TEST(TileSet, AdmissibleNeighboursPerEdge) {
  // wang8: 4 per edge (the paper); wang16: 8; corner16: 4 (two corners shared); corner81: 3 x 3.
  std::map<TileSetKind, int> expected{
      {TileSetKind::wang8, 4}, {TileSetKind::wang16, 8}, {TileSetKind::corner16, 4}, {TileSetKind::corner81, 9}};
  for (TileSetKind kind : tile_set_kinds()) {
    TileRules rules(kind);
    for (int a = 0; a < rules.tile_count(); ++a) {
      int east = 0, north = 0, west = 0, south = 0;
      for (int b = 0; b < rules.tile_count(); ++b) {
        EXPECT_EQ(rules.fits_east(a, b), colours_fit_east(kind, rules.colours(a), rules.colours(b)));
        EXPECT_EQ(rules.fits_north(a, b), colours_fit_north(kind, rules.colours(a), rules.colours(b)));
        east += rules.fits_east(a, b);
        west += rules.fits_east(b, a);
        north += rules.fits_north(a, b);
        south += rules.fits_north(b, a);
      }
      EXPECT_EQ(east, expected[kind]) << tile_set_kind_name(kind) << " tile " << a;
      EXPECT_EQ(west, expected[kind]);
      EXPECT_EQ(north, expected[kind]);
      EXPECT_EQ(south, expected[kind]);
    }
  }
}

TEST(TileSet, BlockEnumerationCountsAndValidity) {
  struct Case {
    TileSetKind kind;
    int w, h;
  };
  // 2 x 2 for all (256, 4096, 512, 3^9); 3 x 3 where it stays small (wang8 2^15, corner16 2^16).
  std::vector<Case> cases{{TileSetKind::wang8, 2, 2},   {TileSetKind::wang16, 2, 2}, {TileSetKind::corner16, 2, 2},
                          {TileSetKind::corner81, 2, 2}, {TileSetKind::corner81, 3, 1},
                          {TileSetKind::wang8, 3, 3},   {TileSetKind::corner16, 3, 3}, {TileSetKind::wang16, 3, 1},
                          {TileSetKind::wang8, 1, 1}};
  for (const Case& c : cases) {
    TileRules rules(c.kind);
    std::size_t count = 0;
    std::set<std::vector<int>> distinct;
    bool all_valid = true;
    rules.for_each_block(c.w, c.h, [&](std::span<const int> block) {
      ++count;
      if (c.w * c.h <= 4) distinct.insert(std::vector<int>(block.begin(), block.end()));
      for (int r = 0; r < c.h; ++r)
        for (int col = 0; col < c.w; ++col) {
          const TileColours& t = rules.colours(block[static_cast<std::size_t>(r * c.w + col)]);
          if (col + 1 < c.w &&
              !colours_fit_east(c.kind, t, rules.colours(block[static_cast<std::size_t>(r * c.w + col + 1)])))
            all_valid = false;
          if (r + 1 < c.h &&
              !colours_fit_north(c.kind, t, rules.colours(block[static_cast<std::size_t>((r + 1) * c.w + col)])))
            all_valid = false;
        }
    });
    EXPECT_EQ(count, expected_blocks(c.kind, c.w, c.h)) << tile_set_kind_name(c.kind) << " " << c.w << "x" << c.h;
    EXPECT_TRUE(all_valid);
    if (c.w * c.h <= 4) {
      EXPECT_EQ(distinct.size(), count);
    }
  }
  EXPECT_EQ(expected_blocks(TileSetKind::wang8, 2, 2), 256u);
  EXPECT_EQ(expected_blocks(TileSetKind::wang8, 3, 3) / 8, 4096u);  // neighbour configurations per tile
}

TEST(TileSet, HashedTilingsAreValidNearAndFarFromTheOrigin) {
  const std::int64_t far = 1'000'000;
  const std::int64_t huge = std::int64_t{1} << 61;
  for (TileSetKind kind : tile_set_kinds()) {
    TileRules rules(kind);
    for (std::int64_t centre : {std::int64_t{0}, far, -far, huge, -huge})
      for (std::uint64_t seed : {1ull, 2ull, 0xFFFFFFFFFFFFFFFFull})
        for (std::int64_t j = centre - 6; j <= centre + 6; ++j)
          for (std::int64_t i = centre - 6; i <= centre + 6; ++i) {
            int t = rules.tile_at(i, j, seed);
            ASSERT_TRUE(t >= 0 && t < rules.tile_count());
            ASSERT_TRUE(rules.fits_east(t, rules.tile_at(i + 1, j, seed))) << i << " " << j;
            ASSERT_TRUE(rules.fits_north(t, rules.tile_at(i, j + 1, seed))) << i << " " << j;
          }
  }
}

TEST(TileSet, PeriodicTilingsWrapAround) {
  for (TileSetKind kind : tile_set_kinds()) {
    TileRules rules(kind);
    for (std::int64_t period : {1, 2, 3, 16}) {
      for (std::int64_t j = 0; j < period; ++j)
        for (std::int64_t i = 0; i < period; ++i) {
          int t = rules.tile_at_periodic(i, j, 7, period);
          EXPECT_EQ(t, rules.tile_at_periodic(i + period, j - 3 * period, 7, period));
          EXPECT_TRUE(rules.fits_east(t, rules.tile_at_periodic((i + 1) % period, j, 7, period)));
          EXPECT_TRUE(rules.fits_north(t, rules.tile_at_periodic(i, (j + 1) % period, 7, period)));
        }
    }
    EXPECT_THROW(rules.tile_at_periodic(0, 0, 1, 0), Error);
  }
}

TEST(TileSet, HashedTilingsArePinned) {
  // The tiling is part of the output contract: the same (cell, seed) gives the same tile in
  // every version. Values recorded from this implementation.
  TileRules wang8(TileSetKind::wang8), wang16(TileSetKind::wang16), corner16(TileSetKind::corner16);
  std::vector<int> got;
  for (std::int64_t i : {0, 1, -1, 1000000})
    got.push_back(wang8.tile_at(i, 3, 42)), got.push_back(wang16.tile_at(i, 3, 42)),
        got.push_back(corner16.tile_at(i, 3, 42));
  EXPECT_EQ(got, (std::vector<int>{7, 9, 9, 3, 12, 4, 3, 15, 15, 1, 3, 2}));
  TileRules corner81(TileSetKind::corner81);
  std::vector<int> got81;
  for (std::int64_t i : {0, 1, -1, 1000000}) got81.push_back(corner81.tile_at(i, 3, 42));
  EXPECT_EQ(got81, (std::vector<int>{29, 18, 44, 6}));
}

// Pearson's chi-square of observed counts against equal expected counts.
double chi_square_uniform(const std::vector<double>& counts) {
  double total = 0.0;
  for (double c : counts) total += c;
  double expected = total / static_cast<double>(counts.size());
  double chi = 0.0;
  for (double c : counts) chi += (c - expected) * (c - expected) / expected;
  return chi;
}

TEST(TileSet, HashedAndScanlineTilingsAreUniformOverTilesAndPairs) {
  // Both constructions make every tile and every admissible horizontal pair equally likely
  // (independent uniform colours). Bounds: the chi-square 99.9 % quantiles for 7, 15 and 31
  // (wang8 pairs), 63 (corner16 pairs), 127 (wang16 pairs), 80 (corner81 tiles) and 728
  // (corner81 pairs) degrees of freedom (the last two by the Wilson-Hilferty approximation).
  std::map<int, double> quantile{{7, 24.32},  {15, 37.70},  {31, 61.10},
                                 {63, 103.4}, {127, 181.99}, {80, 124.8}, {728, 851.6}};
  const int side = 160;
  for (TileSetKind kind : tile_set_kinds()) {
    TileRules rules(kind);
    int tiles = rules.tile_count();
    std::vector<int> pair_index(static_cast<std::size_t>(tiles * tiles), -1);
    int pairs = 0;
    for (int a = 0; a < tiles; ++a)
      for (int b = 0; b < tiles; ++b)
        if (rules.fits_east(a, b)) pair_index[static_cast<std::size_t>(a * tiles + b)] = pairs++;
    Rng rng(11);
    std::vector<int> scanline = rules.scanline_tiling(side, side, rng);
    for (int construction = 0; construction < 2; ++construction) {
      auto tile = [&](int i, int j) {
        return construction == 0 ? rules.tile_at(i, j, 5) : scanline[static_cast<std::size_t>(j * side + i)];
      };
      std::vector<double> tile_counts(static_cast<std::size_t>(tiles)), pair_counts(static_cast<std::size_t>(pairs));
      for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
          tile_counts[static_cast<std::size_t>(tile(i, j))] += 1;
          if (i + 1 < side) {
            int p = pair_index[static_cast<std::size_t>(tile(i, j) * tiles + tile(i + 1, j))];
            ASSERT_GE(p, 0);
            pair_counts[static_cast<std::size_t>(p)] += 1;
          }
          if (j + 1 < side) {
            ASSERT_TRUE(rules.fits_north(tile(i, j), tile(i, j + 1)));
          }
        }
      EXPECT_LT(chi_square_uniform(tile_counts), quantile[tiles - 1]) << tile_set_kind_name(kind) << " " << construction;
      EXPECT_LT(chi_square_uniform(pair_counts), quantile[pairs - 1]) << tile_set_kind_name(kind) << " " << construction;
    }
  }
}

// A small valid set of `kind` with n points per tile, levels 0 and 1, ranks reversed.
TileSet small_set(TileSetKind kind, std::size_t n) {
  TileRules rules(kind);
  TileSet set;
  set.kind = kind;
  set.header = {"made by test_tile_set.cpp", ""};
  for (int id = 0; id < rules.tile_count(); ++id) {
    Tile tile;
    tile.colours = rules.colours(id);
    tile.points = test::uniform_points(n, static_cast<std::uint64_t>(100 + id));
    for (std::size_t k = 0; k < n; ++k) {
      tile.ranks.push_back(static_cast<std::uint32_t>(n - 1 - k));
      tile.levels.push_back(n - 1 - k < n / 2 ? 0 : 1);
    }
    set.tiles.push_back(tile);
  }
  return set;
}

TEST(TileSet, FilesRoundTripBitForBit) {
  test::TempDir dir;
  for (TileSetKind kind : tile_set_kinds()) {
    TileSet set = small_set(kind, 7);
    std::string path = dir.file(std::string(tile_set_kind_name(kind)) + ".txt");
    write_tile_set(path, set);
    std::string text = test::read_text(path);
    EXPECT_EQ(text.rfind("# bluetile tiles 1\n# made by test_tile_set.cpp\n#\n# set ", 0), 0u) << text.substr(0, 80);
    TileSet back = read_tile_set(path);
    EXPECT_EQ(back.kind, kind);
    EXPECT_EQ(back.header, set.header);
    ASSERT_EQ(back.tiles.size(), set.tiles.size());
    for (std::size_t t = 0; t < set.tiles.size(); ++t) {
      EXPECT_EQ(back.tiles[t].colours, set.tiles[t].colours);
      EXPECT_EQ(back.tiles[t].points, set.tiles[t].points);  // exact doubles
      EXPECT_EQ(back.tiles[t].levels, set.tiles[t].levels);
      EXPECT_EQ(back.tiles[t].ranks, set.tiles[t].ranks);
    }
    EXPECT_EQ(format_tile_set(back), text);
    // CR LF and classic Mac OS's lone CR end lines too (a lone CR made the file one line: "not a
    // tile-set file").
    std::string crlf, cr;
    for (char c : text) {
      crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
      cr += c == '\n' ? '\r' : c;
    }
    EXPECT_EQ(format_tile_set(parse_tile_set(crlf, "crlf.tiles")), text);
    EXPECT_EQ(format_tile_set(parse_tile_set(cr, "cr.tiles")), text);
  }
  EXPECT_EQ(test::error_of([] { parse_tile_set("# bluetile tiles 1\r# set wang8 colours 2\rx\r", "cr.tiles"); }).substr(0, 12),
            "cr.tiles:3: ");
  EXPECT_NE(test::read_text(dir.file("corner16.txt")).find("# tile 5 corners 0 1 0 1\n"), std::string::npos);
  EXPECT_NE(test::read_text(dir.file("wang8.txt")).find("# tile 5 1 1 1 0\n"), std::string::npos);
  const std::string corner81 = test::read_text(dir.file("corner81.txt"));
  EXPECT_NE(corner81.find("# set corner81 colours 3\n"), std::string::npos);
  EXPECT_NE(corner81.find("# tile 59 corners 2 0 1 2\n"), std::string::npos);
}

std::string parse_error(const std::string& text) {
  try {
    parse_tile_set(text, "t.txt");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// A one-point-per-tile wang8 file with `tile3` in place of tile 3's block.
std::string wang8_file(const std::string& tile3 = "# tile 3 0 1 1 1\n0.5 0.5 0 0\n") {
  TileRules rules(TileSetKind::wang8);
  std::string text = "# bluetile tiles 1\n# set wang8 colours 2\n";
  for (int id = 0; id < 8; ++id) {
    if (id == 3) {
      text += tile3;
      continue;
    }
    const TileColours& c = rules.colours(id);
    text += "# tile " + std::to_string(id) + " " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " +
            std::to_string(c[2]) + " " + std::to_string(c[3]) + "\n0.25 0.75 0 0\n";
  }
  return text;
}

TEST(TileSet, MalformedFilesNameLineAndValue) {
  EXPECT_EQ(parse_error(wang8_file()), "");
  EXPECT_EQ(parse_error("\xEF\xBB\xBF" + wang8_file()), "");  // byte-order mark accepted
  // "# Tile 3 ..." was a comment, and its points tile 2's: "duplicate rank".
  EXPECT_EQ(parse_error(wang8_file("# Tile 3 0 1 1 1\n0.5 0.5 0 0\n")), "t.txt:9: 'Tile' is not a directive: write '# tile ...'");
  // Spaces an editor leaves at the end of the first line made the file "not a tile-set file".
  EXPECT_EQ(parse_error("# bluetile tiles 1  \t" + wang8_file().substr(18)), "");
  EXPECT_EQ(parse_error("0.5 0.5 0 0\n"), "t.txt:1: not a tile-set file: the first line must be '# bluetile tiles 1'");
  EXPECT_EQ(parse_error("# bluetile tiles 2\n"), "t.txt:1: tile-set file version '2' is not supported (this reads version 1)");
  EXPECT_EQ(parse_error("# bluetile tiles 1\n# set wang13 colours 2\n"),
            "t.txt:2: unknown tile-set kind 'wang13' (known: wang8, wang16, corner16, corner81)");
  EXPECT_EQ(parse_error("# bluetile tiles 1\n# set wang8 colours 3\n"), "t.txt:2: wang8 has 2 colours, the file says 3");
  EXPECT_EQ(parse_error("# bluetile tiles 1\n# tile 0 0 0 0 0\n"), "t.txt:2: tile before the '# set KIND colours C' line");
  EXPECT_EQ(parse_error("# bluetile tiles 1\n# set wang8 colours 2\n0.5 0.5 0 0\n"),
            "t.txt:3: point before the first '# tile' line");
  EXPECT_EQ(parse_error("# bluetile tiles 1\n"), "t.txt:2: no '# set KIND colours C' line");
  // Tile 3 of wang8 is N=0, W=1, S=E=1.
  EXPECT_EQ(parse_error(wang8_file("# tile 3 0 0 1 1\n0.5 0.5 0 0\n")),
            "t.txt:9: tile 3 of wang8 has colours 0 1 1 1, the file says 0 0 1 1");
  EXPECT_EQ(parse_error(wang8_file("# tile 3 0 1 2 1\n")), "t.txt:9: colour must be an integer in 0..1, got '2'");
  EXPECT_EQ(parse_error(wang8_file("# tile 8 0 1 1 1\n")), "t.txt:9: tile id must be an integer in 0..7, got '8'");
  EXPECT_EQ(parse_error(wang8_file("# tile 2 0 1 1 0\n")), "t.txt:9: tile 2 again (first on line 7)");
  EXPECT_EQ(parse_error(wang8_file("")), "t.txt:17: tile 3 is missing");
  EXPECT_EQ(parse_error(wang8_file("# tile 3 0 1 1 1\n1 0.5 0 0\n")),
            "t.txt:10: point outside the tile: '1' is not in [0,1)");
  EXPECT_EQ(parse_error(wang8_file("# tile 3 0 1 1 1\n0.5 -1e-300 0 0\n")),
            "t.txt:10: point outside the tile: '-1e-300' is not in [0,1)");
  EXPECT_EQ(parse_error(wang8_file("# tile 3 0 1 1 1\nnan 0.5 0 0\n")), "t.txt:10: not a finite number 'nan'");
  EXPECT_EQ(parse_error(wang8_file("# tile 3 0 1 1 1\n0.5 0.5 0\n")), "t.txt:10: expected 'x y level rank', got '0.5 0.5 0'");
  EXPECT_EQ(parse_error(wang8_file("# tile 3 0 1 1 1\n0.5 0.5 -1 0\n")),
            "t.txt:10: level must be an integer in 0..1000000, got '-1'");
  EXPECT_EQ(parse_error(wang8_file("# tile 3 0 1 1 1\n0.5 0.5 0 0\n0.1 0.1 0 0\n")), "t.txt:11: tile 3: duplicate rank 0");
  EXPECT_EQ(parse_error(wang8_file("# tile 3 0 1 1 1\n0.5 0.5 0 0\n0.1 0.1 0 2\n")),
            "t.txt:11: tile 3: rank 2 out of range: the tile has 2 points");
  EXPECT_EQ(parse_error(wang8_file("# tile 3 0 1 1 1\n0.5 0.5 1 0\n0.1 0.1 0 1\n")),
            "t.txt:11: tile 3: rank 1 has level 0 after rank 0 of level 1: levels must not decrease along the rank order");
  std::string corner = "# bluetile tiles 1\n# set corner16 colours 2\n# tile 0 0 0 0 0\n";
  EXPECT_EQ(parse_error(corner), "t.txt:3: expected '# tile ID corners NW NE SE SW', got '# tile 0 0 0 0 0'");
  // A long bad line is cut in the message.
  std::string long_line = parse_error(wang8_file("# tile 3 0 1 1 1\n0.5 0.5 0 0 " + std::string(500, 'x') + "\n"));
  EXPECT_EQ(long_line.rfind("t.txt:10: expected 'x y level rank', got '0.5 0.5 0 0 xxx", 0), 0u);
  EXPECT_EQ(long_line.substr(long_line.size() - 5), "x...'");
  EXPECT_LT(long_line.size(), 140u);
}

TEST(TileSet, TilesWithoutPointsOrFarFromEqualAreRefused) {
  // The reader accepted a tile without points, and tiles of wildly unequal
  // counts; both name the tile's line.
  EXPECT_EQ(parse_error(wang8_file("# tile 3 0 1 1 1\n")), "t.txt:9: tile 3 has no points");
  std::string tile3 = "# tile 3 0 1 1 1\n";
  for (int k = 0; k < 4; ++k) tile3 += "0." + std::to_string(k + 1) + " 0.5 0 " + std::to_string(k) + "\n";
  EXPECT_EQ(parse_error(wang8_file(tile3)), "");  // 4 times the others: still a tile set
  tile3 += "0.5 0.25 0 4\n";
  EXPECT_EQ(parse_error(wang8_file(tile3)), "t.txt:9: tile 3 has 5 points, more than 4 times the 1 of tile 0: a set's "
                                            "tiles hold about as many points each");
}

TEST(TileSet, WritingRefusesWhatCouldNotBeRead) {
  TileSet set = small_set(TileSetKind::wang8, 3);
  set.tiles[2].points[1].x = 1.0;
  EXPECT_THROW(format_tile_set(set), Error);
  set = small_set(TileSetKind::wang8, 3);
  set.tiles[2].ranks[1] = set.tiles[2].ranks[0];
  EXPECT_THROW(format_tile_set(set), Error);
  set = small_set(TileSetKind::wang8, 3);
  set.header.push_back("set wang16 colours 2");
  EXPECT_THROW(format_tile_set(set), Error);
  set = small_set(TileSetKind::wang8, 3);
  set.tiles.pop_back();
  EXPECT_THROW(format_tile_set(set), Error);
  test::TempDir dir;
  EXPECT_THROW(write_tile_set(dir.file("bad.txt"), set), Error);
  EXPECT_TRUE(dir.list().empty());
}

}  // namespace
}  // namespace bluetile
