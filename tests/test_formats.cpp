// Sample-table formats (core/point_table.h): choice by name and extension, exact round trips,
// bytes checked against hand-built files, and every kind of damaged file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "bluetile/core/error.h"
#include "bluetile/core/point_table.h"
#include "bluetile/core/text.h"
#include "test_support.h"

namespace bluetile {
namespace {

std::vector<PointSet> sample_sets(std::size_t sets, std::size_t points, bool levels) {
  std::vector<PointSet> result;
  for (std::size_t k = 0; k < sets; ++k) {
    PointSet set;
    set.points = test::uniform_points(points, 100 + k);
    if (levels)
      for (std::size_t i = 0; i < points; ++i) set.levels.push_back(static_cast<int>(i * 3 / points));
    result.push_back(std::move(set));
  }
  // Values at the edges of the domain: the largest double below 1 and the smallest subnormal.
  result[0].points[0] = {std::nextafter(1.0, 0.0), 5e-324};
  return result;
}

std::string encode(TableFormat format, const std::vector<PointSet>& sets, TableWriteOptions options = {},
                   const std::string& path = "table") {
  std::string bytes;
  write_table(format, point_sets_table(sets), options, path, [&](std::string_view piece) { bytes += piece; });
  return bytes;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

template <typename T>
void append(std::string& bytes, T value) {
  bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// A binary table written field by field, as a C reader of point_table.h's layout would.
std::string binary_by_hand(std::uint32_t value_bytes, std::uint32_t columns, std::uint64_t sets, std::uint64_t rows,
                           const std::vector<double>& values) {
  std::string bytes("\x89" "BTP\r\n\x1a\n", 8);
  append<std::uint32_t>(bytes, 1);
  append<std::uint32_t>(bytes, value_bytes);
  append<std::uint32_t>(bytes, columns);
  append<std::uint32_t>(bytes, 0);
  append<std::uint64_t>(bytes, sets);
  append<std::uint64_t>(bytes, rows);
  for (double v : values) {
    if (value_bytes == 4) {
      append<float>(bytes, static_cast<float>(v));
    } else {
      append<double>(bytes, v);
    }
  }
  return bytes;
}

// An npy file with a given header dictionary, version 1.0, padded as NumPy pads it.
std::string npy_by_hand(const std::string& dict, const std::string& data) {
  std::string header = dict;
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string bytes("\x93NUMPY\x01\x00", 8);
  append<std::uint16_t>(bytes, static_cast<std::uint16_t>(header.size()));
  return bytes + header + data;
}

void expect_same_sets(const std::vector<PointSet>& a, const std::vector<PointSet>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].points.size(), b[k].points.size()) << "set " << k;
    for (std::size_t i = 0; i < a[k].points.size(); ++i) ASSERT_EQ(a[k].points[i], b[k].points[i]) << k << ", " << i;
    EXPECT_EQ(a[k].levels, b[k].levels) << "set " << k;
  }
}

// The sets as float32 would hold them (point_table.h: nearest float, kept below 1).
std::vector<PointSet> as_float32(std::vector<PointSet> sets) {
  for (PointSet& set : sets)
    for (Point& p : set.points)
      for (double* c : {&p.x, &p.y}) {
        float f = static_cast<float>(*c);
        if (f >= 1.0f) f = std::nextafter(1.0f, 0.0f);
        *c = f;
      }
  return sets;
}

TEST(Formats, ChosenByNameOrExtensionAndUnknownOnesRefused) {
  EXPECT_EQ(table_format_for("a.txt"), TableFormat::text);
  EXPECT_EQ(table_format_for("dir.v2/points"), TableFormat::text);
  EXPECT_EQ(table_format_for("a.DAT"), TableFormat::text);
  EXPECT_EQ(table_format_for("-"), TableFormat::text);
  EXPECT_EQ(table_format_for("a.npy"), TableFormat::npy);
  EXPECT_EQ(table_format_for("a.bpt"), TableFormat::binary);
  EXPECT_EQ(table_format_for("a.h"), TableFormat::header);
  EXPECT_EQ(table_format_for("a.hpp"), TableFormat::header);
  EXPECT_EQ(table_format_for("a.anything", "npy"), TableFormat::npy);
  EXPECT_EQ(table_format_for("a.CSV"), TableFormat::csv);
  EXPECT_EQ(error_of([] { table_format_for("a.png"); }),
            "a.png: unknown extension '.png' (.txt .dat .pts: text, .npy, .bpt: binary, .h .hpp: C header, .csv; or say "
            "--format)");
  EXPECT_EQ(error_of([] { table_format_for("a.txt", "tsv"); }), "unknown table format 'tsv' (text, npy, binary, header, csv)");
}

TEST(Formats, CsvIsWrittenAsSpreadsheetsReadItAndReadBackExactly) {
  // CSV was read, never written: a table for a spreadsheet, pandas or R took a conversion.
  std::vector<PointSet> one{PointSet{{{0.25, 0.5}, {0.75, 0.125}}, {}}};
  EXPECT_EQ(encode(TableFormat::csv, one, {.float32 = false, .name = "", .comment = {"made by a test"}}),
            "# made by a test\nx,y\n0.25,0.5\n0.75,0.125\n");
  one[0].levels = {0, 3};
  EXPECT_EQ(encode(TableFormat::csv, one), "x,y,level\n0.25,0.5,0\n0.75,0.125,3\n");
  for (bool levels : {false, true}) {
    SCOPED_TRACE(levels ? "with levels" : "x y");
    std::vector<PointSet> sets = sample_sets(3, 50, levels);
    sets[2].points.pop_back();  // as text, sets of any sizes
    if (levels) sets[2].levels.pop_back();
    std::string bytes;
    write_point_table(TableFormat::csv, sets, {.float32 = false, .name = "", .comment = {"domain periodic"}}, "t.csv",
                      [&](std::string_view piece) { bytes += piece; });
    EXPECT_EQ(bytes.substr(0, bytes.find("# set 1")).find("# domain periodic\nx,y" + std::string(levels ? ",level" : "") +
                                                         "\n# set 0\n"),
              0u);
    const std::vector<PointSet> back = parse_csv_points(bytes, "t.csv");
    expect_same_sets(back, sets);
    EXPECT_EQ(back[0].declared_boundary, Boundary::periodic);
  }
  // A comment the readers would refuse is refused before any byte, as in text.
  std::string bytes;
  EXPECT_NE(error_of([&] {
              write_point_table(TableFormat::csv, one, {.float32 = false, .name = "", .comment = {"domain: bounded"}}, "t.csv",
                                [&](std::string_view piece) { bytes += piece; });
            }),
            "");
  EXPECT_EQ(bytes, "");
  // A table of named columns gets their names.
  TableView table;
  table.sets = 1;
  table.columns = 3;
  table.column_names = "cx cy area";
  table.named_fields = true;
  table.rows = [](std::size_t) { return std::size_t{1}; };
  table.value = [](std::size_t, std::size_t, std::size_t c) { return 0.5 / static_cast<double>(c + 1); };
  bytes.clear();
  write_table(TableFormat::csv, table, {}, "c.csv", [&](std::string_view piece) { bytes += piece; });
  EXPECT_EQ(bytes, "cx,cy,area\n0.5,0.25,0.16666666666666666\n");
}

TEST(Formats, NpyBytesAreNumpysLayout) {
  std::vector<PointSet> sets{PointSet{{{0.25, 0.5}, {0.75, 0.125}}, {}}};
  std::string bytes = encode(TableFormat::npy, sets);
  const std::string dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (1, 2, 2), }";
  std::string data;
  for (double v : {0.25, 0.5, 0.75, 0.125}) append(data, v);
  EXPECT_EQ(bytes, npy_by_hand(dict, data));
  EXPECT_EQ((bytes.size() - data.size()) % 64, 0u);  // the data is aligned, as NumPy wants
}

TEST(Formats, EveryFormatRoundTripsExactly) {
  for (bool levels : {false, true}) {
    SCOPED_TRACE(levels ? "with levels" : "x y");
    std::vector<PointSet> sets = sample_sets(3, 50, levels);
    expect_same_sets(parse_npy_table(encode(TableFormat::npy, sets), "t.npy"), sets);
    expect_same_sets(parse_binary_table(encode(TableFormat::binary, sets), "t.bpt"), sets);
    TableWriteOptions f32;
    f32.float32 = true;
    expect_same_sets(parse_npy_table(encode(TableFormat::npy, sets, f32), "t.npy"), as_float32(sets));
    expect_same_sets(parse_binary_table(encode(TableFormat::binary, sets, f32), "t.bpt"), as_float32(sets));
  }
}

TEST(Formats, Float32KeepsPointsBelowOne) {
  std::vector<PointSet> sets{PointSet{{{1.0 - 1e-9, 0.5}}, {}}};
  TableWriteOptions f32;
  f32.float32 = true;
  auto back = parse_binary_table(encode(TableFormat::binary, sets, f32), "t.bpt");
  EXPECT_EQ(back[0].points[0].x, static_cast<double>(std::nextafter(1.0f, 0.0f)));
}

TEST(Formats, HeaderLiteralsAreExactFloats) {
  std::vector<PointSet> sets = sample_sets(2, 5, false);
  sets[1].points[0] = {0.0, 1e-30};
  std::string text = encode(TableFormat::header, sets, {.float32 = false, .name = "", .comment = {"made by a test"}},
                            "out/blue-noise 64.h");
  EXPECT_NE(text.find("// made by a test\n"), std::string::npos);
  EXPECT_NE(text.find("static const float blue_noise_64[2][5][2] = {\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\n// 2 sets of 5 points, columns x y;"), std::string::npos) << text;
  // One of each, counted as words are ("1 set(s) of 1 points").
  EXPECT_EQ(encode(TableFormat::header, sample_sets(1, 1, false), {}, "one.h").find("// 1 set of 1 point, columns x y;"), 0u);
  // Every literal, read as C reads it, is the float of the value.
  std::vector<float> literals;
  std::size_t line_start = 0;
  while ((line_start = text.find("\n    {", line_start)) != std::string::npos) {
    const char* at = text.c_str() + line_start + 6;  // past "\n    {"
    for (int c = 0; c < 2; ++c) {
      char* end = nullptr;
      literals.push_back(std::strtof(at, &end));
      ASSERT_EQ(*end, 'f') << "literal without its f suffix at: " << std::string(at, 20);
      at = end + 3;  // past "f, "
    }
    line_start += 6;
  }
  std::vector<float> expected;
  for (const PointSet& set : as_float32(sets))
    for (Point p : set.points) expected.insert(expected.end(), {static_cast<float>(p.x), static_cast<float>(p.y)});
  EXPECT_EQ(literals, expected);
  EXPECT_NE(text.find("{0.0f, 1e-30f}"), std::string::npos);
  EXPECT_EQ(error_of([&] { encode(TableFormat::header, sets, {.float32 = false, .name = "2x", .comment = {}}, "t.h"); }),
            "t.h: '2x' is not a C identifier (letters, digits, '_')");
  EXPECT_EQ(table_name_for_path("7.h"), "points_7");
  EXPECT_EQ(table_name_for_path("--.h"), "bluetile_points");
  // Letters outside ASCII were dropped without a word: "ünï.h" named the array 'n'.
  EXPECT_EQ(error_of([&] { encode(TableFormat::header, sets, {}, "dir/ünï.h"); }),
            "dir/ünï.h: the file name holds letters outside ASCII, which a C name cannot, so the array would be 'n'; "
            "name the array (--name, or name= in Python)");
  EXPECT_EQ(error_of([&] { checked_table_name("tables/größe.h", ""); }),
            "tables/größe.h: the file name holds letters outside ASCII, which a C name cannot, so the array would be "
            "'gr_e'; name the array (--name, or name= in Python)");
  EXPECT_EQ(checked_table_name("ünï/points.h", ""), "points");  // the folder is no part of the name
  EXPECT_EQ(checked_table_name("ünï.h", "uni"), "uni");
}

TEST(Formats, SetsOfDifferentSizesNeedText) {
  std::vector<PointSet> sets = sample_sets(2, 4, false);
  sets[1].points.pop_back();
  EXPECT_EQ(error_of([&] { encode(TableFormat::npy, sets, {}, "t.npy"); }),
            "t.npy: set 0 has 4 points but set 1 has 3: the npy format needs the same count in every set (text takes any)");
}

TEST(Formats, PointsThatAreNotFiniteAreNeverWritten) {
  // A NaN went into text and .bpt tables, which every reader then refused.
  std::vector<PointSet> sets = sample_sets(2, 4, false);
  sets[1].points[2].y = std::nan("");
  for (TableFormat format : kTableFormats)
    EXPECT_EQ(error_of([&] { write_point_table(format, sets, {}, "t", [](std::string_view) {}); }),
              "t: set 1, point 2 (" + exact_text(sets[1].points[2].x) + ", nan) is not finite: no reader would take it back");
}

TEST(Formats, TableValuesThatAreNotFiniteAreNeverWritten) {
  // Any table (centroids: cx cy area) went through write_table and write_text_table unchecked: a
  // NaN or infinity was written, as "nan" in text and headers, and readers refused the file.
  // Now refused before any byte, naming the set, the row and the column.
  for (double bad : {std::nan(""), HUGE_VAL, -HUGE_VAL}) {
    TableView table;
    table.sets = 2;
    table.columns = 3;
    table.column_names = "cx cy area";
    table.rows = [](std::size_t) { return std::size_t{3}; };
    table.value = [bad](std::size_t k, std::size_t i, std::size_t c) {
      return k == 1 && i == 2 && c == 2 ? bad : 0.125 * static_cast<double>(k + i + c);
    };
    const std::string message = "c: set 1, row 2: area is " + exact_text(bad) + ", not a finite number: no reader would take it back";
    std::string bytes;
    const ByteSink sink = [&](std::string_view piece) { bytes += piece; };
    for (TableFormat format : {TableFormat::npy, TableFormat::binary, TableFormat::header, TableFormat::csv}) {
      EXPECT_EQ(error_of([&] { write_table(format, table, {}, "c", sink); }), message);
      EXPECT_EQ(bytes, "") << table_format_name(format);
    }
    EXPECT_EQ(error_of([&] { write_text_table(table, "c", sink); }), message);
    EXPECT_EQ(bytes, "");
    // The first column of the first set, for a table whose names are fewer than its columns.
    table.column_names = "";
    table.value = [bad](std::size_t, std::size_t, std::size_t) { return bad; };
    EXPECT_EQ(error_of([&] { write_text_table(table, "c", sink); }),
              "c: set 0, row 0: column 0 is " + exact_text(bad) + ", not a finite number: no reader would take it back");
  }
}

TEST(Formats, ATableOfNamedColumnsIsAStructuredNpyAndNoPointTable) {
  // centroids' cx cy area went into npy and .bpt as shape (K, N, 3), which the formats define as
  // x y level: a structured array names its fields instead (same bytes after the header), and a
  // .bpt, which has no names, is refused.
  TableView table;
  table.sets = 2;
  table.columns = 3;
  table.column_names = "cx cy area";
  table.rows = [](std::size_t) { return std::size_t{4}; };
  table.value = [](std::size_t k, std::size_t i, std::size_t c) { return 0.0625 * static_cast<double>(k * 12 + i * 3 + c); };
  auto bytes_of = [&](TableFormat format, bool float32) {
    std::string bytes;
    write_table(format, table, {.float32 = float32, .name = {}, .comment = {}}, "c",
                [&](std::string_view piece) { bytes += piece; });
    return bytes;
  };
  for (bool float32 : {false, true}) {
    const std::string plain = bytes_of(TableFormat::npy, float32);
    table.named_fields = true;
    const std::string named = bytes_of(TableFormat::npy, float32);
    table.named_fields = false;
    const std::string type = float32 ? "<f4" : "<f8";
    const std::size_t header = 10 + (static_cast<unsigned char>(named[8]) | static_cast<unsigned char>(named[9]) << 8);
    const std::string dict = "{'descr': [('cx', '" + type + "'), ('cy', '" + type + "'), ('area', '" + type +
                             "')], 'fortran_order': False, 'shape': (2, 4), }";
    EXPECT_EQ(named.substr(10, header - 10), dict + std::string(header - 11 - dict.size(), ' ') + "\n");
    EXPECT_EQ(header % 64, 0u);
    EXPECT_EQ(named.back(), plain.back());
    EXPECT_EQ(named.substr(header), plain.substr(plain.size() - (named.size() - header))) << type;
    EXPECT_EQ(named.size() - header, 2u * 4u * 3u * (float32 ? 4u : 8u));
    // Not read back as points.
    EXPECT_NE(error_of([&] { parse_npy_table(named, "c.npy"); }), "");
  }
  table.named_fields = true;
  std::string bytes;
  EXPECT_EQ(error_of([&] { write_table(TableFormat::binary, table, {}, "c.bpt", [&](std::string_view b) { bytes += b; }); }),
            "c.bpt: a bluetile point table's columns are x y or x y level, not cx cy area; write .npy (a field per "
            "column), text or a C header");
  EXPECT_EQ(bytes, "");
  EXPECT_NE(bytes_of(TableFormat::header, false).find("columns cx cy area"), std::string::npos);
}

TEST(Formats, LevelsNoReaderTakesAreNeverWritten) {
  // A level of -1 went into every format (a point file's "x y -1", -1.0 in npy), and every
  // reader then refused the file.
  for (int bad : {-1, kMaxTableLevel + 1}) {
    std::vector<PointSet> sets = sample_sets(2, 4, true);
    sets[1].levels[3] = bad;
    std::string bytes;
    for (TableFormat format : {TableFormat::text, TableFormat::npy, TableFormat::binary, TableFormat::header}) {
      EXPECT_EQ(error_of([&] { write_point_table(format, sets, {}, "t", [&](std::string_view b) { bytes += b; }); }),
                "t: set 1, point 3: level " + std::to_string(bad) + " is outside 0 to " + std::to_string(kMaxTableLevel) +
                    ": no reader would take it back");
      EXPECT_EQ(bytes, "") << table_format_name(format);
    }
  }
}

TEST(Formats, ReadsNpyInFortranOrderBigEndianAndFloat32) {
  // Shape (2, 2, 2): value of [k][i][c] = k + 0.5 i + 0.25 c, so every element differs.
  auto value = [](int k, int i, int c) { return 0.125 * k + 0.5 * i + 0.25 * c; };
  std::string fortran, big;
  for (int c = 0; c < 2; ++c)
    for (int i = 0; i < 2; ++i)
      for (int k = 0; k < 2; ++k) append(fortran, value(k, i, c));
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < 2; ++i)
      for (int c = 0; c < 2; ++c) {
        float f = static_cast<float>(value(k, i, c));
        char b[4];
        std::memcpy(b, &f, 4);
        big += std::string{b[3], b[2], b[1], b[0]};
      }
  auto from_fortran = parse_npy_table(
      npy_by_hand("{'descr': '<f8', 'fortran_order': True, 'shape': (2, 2, 2), }", fortran), "f.npy");
  auto from_big = parse_npy_table(npy_by_hand("{'descr': '>f4', 'fortran_order': False, 'shape': (2, 2, 2), }", big),
                                  "b.npy");
  for (const auto& sets : {from_fortran, from_big}) {
    ASSERT_EQ(sets.size(), 2u);
    for (int k = 0; k < 2; ++k)
      for (int i = 0; i < 2; ++i) EXPECT_EQ(sets[k].points[i], Point(value(k, i, 0), value(k, i, 1))) << k << i;
  }
  // (N, 2): one set.
  std::string data;
  for (double v : {0.1, 0.2, 0.3, 0.4}) append(data, v);
  auto one = parse_npy_table(npy_by_hand("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 2), }", data), "o.npy");
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].points[1], Point(0.3, 0.4));
}

TEST(Formats, DamagedNpyFilesGiveClearErrors) {
  std::string data;
  for (double v : {0.1, 0.2, 0.3, 0.4}) append(data, v);
  auto npy_error = [](const std::string& bytes) { return error_of([&] { parse_npy_table(bytes, "d.npy"); }); };
  EXPECT_EQ(npy_error("not numpy"), "d.npy: not a .npy file (wrong magic)");
  // Arrays NumPy writes well but of another kind say how to save the one read here (they were
  // "bad .npy header: dtype '<i8'" and "shape has 1 dimensions").
  EXPECT_EQ(npy_error(npy_by_hand("{'descr': '<i8', 'fortran_order': False, 'shape': (2, 2), }", data)),
            "d.npy: values of dtype '<i8'; expected float64 ('<f8') or float32 ('<f4'): save a.astype(numpy.float64)");
  EXPECT_EQ(npy_error(npy_by_hand("{'descr': '|O', 'fortran_order': False, 'shape': (2, 2), }", data)),
            "d.npy: values of dtype '|O'; expected float64 ('<f8') or float32 ('<f4'): save a.astype(numpy.float64)");
  EXPECT_EQ(npy_error(npy_by_hand("{'descr': '<f8', 'fortran_order': False, 'shape': (4,), }", data)),
            "d.npy: shape (4,) is one-dimensional; expected (N, 2), (N, 3) or (K, N, C): save a.reshape(-1, 2) for "
            "x y pairs");
  EXPECT_EQ(npy_error(npy_by_hand("{'descr': [('x', '<f8'), ('y', '<f8')], 'fortran_order': False, 'shape': (2,), }",
                                  data)),
            "d.npy: a structured array (named fields); expected plain float64 or float32 values: save "
            "numpy.stack([a['x'], a['y']], axis=-1)");
  EXPECT_EQ(npy_error(npy_by_hand("{'descr': '<f8', 'fortran_order': False, 'shape': (1, 1, 2, 2), }", data)),
            "d.npy: shape of 4 dimensions; expected (N, C) or (K, N, C)");
  EXPECT_EQ(npy_error(npy_by_hand("{'descr': '<f8', 'fortran_order': False, 'shape': (4, 1), }", data)),
            "d.npy: 1 column per point; expected 2 (x y) or 3 (x y level)");
  // x and y as rows (numpy.array([xs, ys])) was "4 columns per point", with no word of the cause.
  EXPECT_EQ(npy_error(npy_by_hand("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 4), }", data + data)),
            "d.npy: shape (2, 4) holds 4 columns per point; expected 2 (x y) or 3 (x y level): coordinates as rows? "
            "save a.T");
  EXPECT_EQ(npy_error(npy_by_hand("{'descr': '<f8', 'fortran_order': False, 'shape': (1, 3, 5), }", data)),
            "d.npy: shape (1, 3, 5) holds 5 columns per point; expected 2 (x y) or 3 (x y level): coordinates as "
            "rows? save a.transpose(0, 2, 1)");
  EXPECT_EQ(npy_error(npy_by_hand("{'descr': '<f8', 'fortran_order': False, 'shape': (3, 2), }", data)),
            "d.npy: shape (1, 3, 2) needs 48 data bytes but the file has 32");
  EXPECT_EQ(npy_error(npy_by_hand("{'descr': '<f8', 'shape': (2, 2), }", data)), "d.npy: bad .npy header: no 'fortran_order'");
  EXPECT_EQ(npy_error(npy_by_hand("{'descr': '<f8', 'fortran_order': False, 'shape': (281474976710656, 0, 2), }", "")),
            "d.npy: the table holds 281474976710656 sets of 0 points");
  EXPECT_EQ(npy_error(npy_by_hand("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 2), }", data).substr(0, 40)),
            "d.npy: .npy file cut short in its header");
  std::string nan_data = data;
  double nan = std::nan("");
  std::memcpy(nan_data.data() + 24, &nan, 8);
  EXPECT_EQ(npy_error(npy_by_hand("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 2), }", nan_data)),
            "d.npy: set 0, point 1: not a finite number 'nan'");
}

TEST(Formats, DamagedBinaryFilesGiveClearErrors) {
  auto binary_error = [](const std::string& bytes) { return error_of([&] { parse_binary_table(bytes, "d.bpt"); }); };
  const std::vector<double> four{0.1, 0.2, 0.3, 0.4};
  std::string good = binary_by_hand(8, 2, 1, 2, four);
  ASSERT_EQ(good.size(), 40u + 32u);
  EXPECT_EQ(binary_error(good), "");
  EXPECT_EQ(binary_error(good.substr(0, 20)), "d.bpt: binary point table cut short: 20 bytes, the header alone is 40");
  EXPECT_EQ(binary_error(good.substr(0, 60)),
            "d.bpt: header says 1 set of 2 points (72 bytes) but the file has 60 bytes");
  std::string wrong_magic = good;
  wrong_magic[3] = 'X';
  EXPECT_EQ(binary_error(wrong_magic), "d.bpt: not a bluetile binary point table (wrong magic)");
  EXPECT_EQ(binary_error(binary_by_hand(8, 2, 1, 3, four)),
            "d.bpt: header says 1 set of 3 points (88 bytes) but the file has 72 bytes");
  EXPECT_EQ(binary_error(binary_by_hand(8, 2, 1ull << 62, 1ull << 62, four)),
            "d.bpt: sizes 4611686018427387904 x 4611686018427387904 x 2 overflow: a damaged file");
  EXPECT_EQ(binary_error(binary_by_hand(8, 4, 1, 1, four)), "d.bpt: 4 columns per point; expected 2 (x y) or 3 (x y level)");
  // Sets of no points take no bytes: a header may claim 2^48 of them (found by the fuzzer).
  EXPECT_EQ(binary_error(binary_by_hand(8, 3, 1ull << 48, 0, {})), "d.bpt: the table holds 281474976710656 sets of 0 points");
  std::string v2 = good;
  v2[8] = 2;
  EXPECT_EQ(binary_error(v2), "d.bpt: binary point table version 2, this reader knows version 1");
  std::string three_bytes = good;
  three_bytes[12] = 3;
  EXPECT_EQ(binary_error(three_bytes), "d.bpt: 3 bytes per value; expected 4 (float32) or 8 (float64)");
  EXPECT_EQ(binary_error(binary_by_hand(4, 2, 1, 2, {0.1, INFINITY, 0.3, 0.4})),
            "d.bpt: set 0, point 0: not a finite number 'inf'");
  EXPECT_EQ(binary_error(binary_by_hand(8, 3, 1, 1, {0.1, 0.2, 1.5})),
            "d.bpt: set 0, point 0: level must be a whole number in [0, 1000000], got '1.5' (a point file's third column is the level; a table such as centroids' cx cy area is no point file)");
  // Coordinates outside [0, 1) wrap onto the torus, as in point files.
  auto wrapped = parse_binary_table(binary_by_hand(8, 2, 1, 1, {-0.25, 1.5}), "w.bpt");
  EXPECT_EQ(wrapped[0].points[0], Point(0.75, 0.5));
}

// psa's .rps bytes, built by hand: little-endian float32 x y pairs, nothing else.
std::string rps_bytes(const std::vector<float>& values) {
  std::string bytes;
  for (float v : values) {
    std::uint32_t u;
    std::memcpy(&u, &v, sizeof u);
    for (int b = 0; b < 4; ++b) bytes += static_cast<char>((u >> (8 * b)) & 0xffu);
  }
  return bytes;
}

TEST(Formats, PsaRpsIsRawLittleEndianFloatPairs) {
  const std::vector<float> values = {0.25f, 0.5f, 0.1f, 0.9999999f, 0.0f, 0.75f};
  PointSet set = parse_rps_points(rps_bytes(values), "three.rps");
  ASSERT_EQ(set.points.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(set.points[i].x, static_cast<double>(values[2 * i]));
    EXPECT_EQ(set.points[i].y, static_cast<double>(values[2 * i + 1]));
  }
  EXPECT_FALSE(set.has_levels());
  EXPECT_TRUE(parse_rps_points("", "empty.rps").points.empty());
  // Outside [0, 1): wrapped, or refused when asked.
  EXPECT_EQ(parse_rps_points(rps_bytes({1.25f, -0.25f}), "out.rps").points[0].x, 0.25);
  EXPECT_EQ(parse_rps_points(rps_bytes({1.25f, -0.25f}), "out.rps").points[0].y, 0.75);
  EXPECT_EQ(error_of([] { parse_rps_points(rps_bytes({0.5f, 0.5f, 0.5f, 1.5f}), "out.rps", {.wrap = false}); }),
            "out.rps: point 1: y = 1.5 is outside [0, 1)");
  // The extension decides, in any case.
  EXPECT_TRUE(is_rps_path("dir.x/points.RPS"));
  EXPECT_FALSE(is_rps_path("points.rps.txt"));
  EXPECT_FALSE(is_rps_path("rps"));
  test::TempDir dir;
  const std::string path = dir.write("psa.rps", rps_bytes(values));
  std::vector<PointSet> sets = read_point_table(path);
  ASSERT_EQ(sets.size(), 1u);
  EXPECT_EQ(sets[0].points.size(), 3u);
  EXPECT_EQ(sets[0].points[2].y, 0.75);
}

TEST(Formats, DamagedRpsFilesGiveClearErrors) {
  std::string bytes = rps_bytes({0.5f, 0.5f});
  EXPECT_EQ(error_of([&] { parse_rps_points(bytes + "abc", "cut.rps"); }),
            "cut.rps: 11 bytes is not a whole number of points (.rps holds 8-byte pairs of float32 x y)");
  EXPECT_EQ(error_of([] { parse_rps_points(rps_bytes({0.5f, std::nanf("")}), "nan.rps"); }),
            "nan.rps: point 0: not a finite number 'nan'");
  EXPECT_NE(error_of([] { parse_rps_points(rps_bytes({0.5f, 0.5f, INFINITY, 0.5f}), "inf.rps"); })
                .find("inf.rps: point 1: not a finite number"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_rps_file("/nonexistent/x.rps"); }).find("/nonexistent/x.rps"), std::string::npos);
}

TEST(Formats, CsvIsReadByItsExtensionWithPandasAndRIndexColumns) {
  // relax -i and progressive -i read a .csv as text ("expected 'x y'"), and the index column that
  // pandas' to_csv and R's write.csv add by default was "an empty field" everywhere.
  test::TempDir dir;
  const std::vector<Point> points{{0.25, 0.5}, {0.75, 0.125}};
  for (const char* csv : {"x,y\n0.25,0.5\n0.75,0.125\n", ",x,y\n0,0.25,0.5\n1,0.75,0.125\n",
                          "\xEF\xBB\xBF\"\",\"x\",\"y\"\r\n\"1\",0.25,0.5\r\n\"2\",0.75,0.125", "# x,y\n2.5e-01,5e-1\n+.75,0.125\n",
                          "x,y\r0.25,0.5\r0.75,0.125\r"}) {  // classic Mac OS line ends were one line
    std::vector<PointSet> sets = read_point_table(dir.write("p.csv", csv));
    ASSERT_EQ(sets.size(), 1u) << csv;
    EXPECT_EQ(sets[0].points, points) << csv;
    EXPECT_EQ(parse_csv_points(csv, "p.csv")[0].points, points) << csv;
  }
  EXPECT_EQ(read_point_table(dir.write("l.CSV", ",X,Y,Level\n7,0.25,0.5,0\n8,0.75,0.125,1\n"))[0].levels,
            (std::vector<int>{0, 1}));
  auto csv_error = [](const std::string& text) { return error_of([&] { parse_csv_points(text, "p.csv"); }); };
  const std::string header_fix =
      " names other columns: a CSV's header names x,y or x,y,level (an unnamed first column, pandas' or R's index, "
      "is skipped); in pandas: df[['x', 'y']].to_csv(path, index=False)";
  EXPECT_EQ(csv_error("px,py\n0.25,0.5\n"), "p.csv:1: header 'px,py'" + header_fix);
  EXPECT_EQ(csv_error("# made by pandas\nid,x,y\n0,0.25,0.5\n"), "p.csv:2: header 'id,x,y'" + header_fix);
  EXPECT_EQ(csv_error(",x,y\n0,0.25,0.5\n0.75\n"),
            "p.csv:3: expected 'index,x,y' or 'index,x,y,level' (the header's first column is unnamed), got '0.75'");
  EXPECT_EQ(csv_error(",x,y\n0,0.25,\n"), "p.csv:2: an empty field, got '0,0.25,'");
  EXPECT_EQ(csv_error("nan,0.5\n"), "p.csv:1: not a finite number 'nan'");  // a number, not a header
  EXPECT_EQ(csv_error("x,y\r0.25,0.5\r0.75\r"), "p.csv:3: expected 'x,y' or 'x,y,level' (comma-separated), got '0.75'");
  EXPECT_EQ(csv_error("x,y\r\n0.25,0.5\r\n0.75\r\n"), "p.csv:3: expected 'x,y' or 'x,y,level' (comma-separated), got '0.75'");
  // A spreadsheet's export in a decimal-comma locale was "header 'x;y'" or "an empty field".
  const std::string semicolons = "fields separated by ';' (a spreadsheet's export where the decimal point is a comma); "
                                 "a CSV here has ',' between fields and '.' in numbers";
  EXPECT_EQ(csv_error("x;y\n0,5;0,25\n"), "p.csv:1: " + semicolons + ", got 'x;y'");
  EXPECT_EQ(csv_error("0,5;0,25\n"), "p.csv:1: " + semicolons + ", got '0,5;0,25'");
  EXPECT_EQ(csv_error("0,5;0,25;1\n"), "p.csv:1: " + semicolons + ", got '0,5;0,25;1'");
  EXPECT_EQ(csv_error(std::string("\xFF\xFEx\0,\0y\0\r\0\n\0", 12)).substr(0, 22), "p.csv: UTF-16 text (Wi");
}

TEST(Formats, CsvOfQuotedNumbersTrailingCommasOrBlankSeparatedTextIsRead) {
  // Quoted numbers (Python's csv.QUOTE_ALL) were "header names other columns" or "not a number
  // '"0.25"'"; a ',' ending every line "an empty field"; and the text points `relax -o - >
  // points.csv` writes (read as text before .csv was read as CSV) "expected 'x,y'".
  test::TempDir dir;
  const std::vector<Point> points{{0.25, 0.5}, {0.75, 0.125}};
  for (const char* csv : {"\"0.25\",\"0.5\"\n\"0.75\",\"0.125\"\n", "\"x\",\"y\"\n\" 0.25\",\"0.5\"\n\"0.75\",\"0.125\"\n",
                          "x,y,\n0.25,0.5,\n0.75,0.125,\n", "0.25,0.5,\r\n0.75,0.125,\r\n",
                          "# bluetile relax: 2 points, seed 1\n0.25 0.5\n0.75\t0.125 # a, b\n",
                          "\xEF\xBB\xBF" "0.25 0.5\r\n0.75 0.125\r\n"}) {
    std::vector<PointSet> sets = read_point_table(dir.write("p.csv", csv));
    ASSERT_EQ(sets.size(), 1u) << csv;
    EXPECT_EQ(sets[0].points, points) << csv;
    EXPECT_EQ(read_points_by_extension(dir.file("p.csv"))[0].points, points) << csv;
  }
  auto csv_error = [](const std::string& text) { return error_of([&] { parse_csv_points(text, "p.csv"); }); };
  // A ',' ending some lines only is an empty field, as is a comma-separated file with a blank one.
  EXPECT_EQ(csv_error("0.25,0.5\n0.75,0.125,\n"), "p.csv:2: an empty field, got '0.75,0.125,'");
  EXPECT_EQ(csv_error("0.25,0.5\n0.75 0.125\n"), "p.csv:2: expected 'x,y' or 'x,y,level' (comma-separated), got '0.75 0.125'");
  EXPECT_EQ(csv_error("0.25;0.5\n").substr(0, 33), "p.csv:1: fields separated by ';' ");
  // The tables bluetile writes as .csv say what they are (the advice was pandas' df[['x', 'y']]).
  EXPECT_EQ(csv_error("frequency,power,anisotropy_db,nu\n0,64,,0\n"),
            "p.csv:1: header 'frequency,power,anisotropy_db,nu': bluetile analyze's radial.csv (radial power by "
            "frequency), not points; give the point file that was analysed or relaxed");
  EXPECT_EQ(csv_error("r,r_relative,g,set\n").substr(0, 58), "p.csv:1: header 'r,r_relative,g,set': bluetile analyze's r");
  EXPECT_EQ(csv_error("iteration,energy,max_displacement\n"),
            "p.csv:1: header 'iteration,energy,max_displacement': a --log of bluetile relax or stipple (energy and "
            "displacement by iteration), not points; give the point file that was analysed or relaxed");
}

TEST(Formats, NumpyArchivesAreRefusedSayingHowToSaveOneArray) {
  // numpy.savez's .npz was "binary data (NUL byte): not a point file".
  test::TempDir dir;
  const std::string zip = std::string("PK\x03\x04\x14\x00\x00\x00\x00\x00", 10) + "arr_0.npy";
  const std::string fix = ": a zip archive (numpy.savez writes .npz), not a point table: save one array with "
                          "numpy.save('points.npy', a)";
  EXPECT_EQ(error_of([&] { read_point_table(dir.write("z.npz", zip)); }), dir.file("z.npz") + fix);
  EXPECT_EQ(error_of([&] { read_point_table(dir.write("z.data", zip)); }), dir.file("z.data") + fix);
  EXPECT_EQ(error_of([&] { read_points_by_extension(dir.file("z.npz")); }), dir.file("z.npz") + fix);
}

TEST(Formats, FilesAreRecognisedByTheirFirstBytes) {
  test::TempDir dir;
  std::vector<PointSet> sets = sample_sets(2, 10, true);
  auto save = [&](const std::string& name, const std::string& bytes) { return dir.write(name, bytes); };
  // Extensions do not matter for reading: the content says what a file is.
  expect_same_sets(read_point_table(save("a.data", encode(TableFormat::npy, sets))), sets);
  expect_same_sets(read_point_table(save("b.data", encode(TableFormat::binary, sets))), sets);
  auto text = read_point_table(save("c.txt", "# header\n# set 0\n0.5 0.5\n# set 1\n0.25 0.25\n0.75 0.75\n"));
  ASSERT_EQ(text.size(), 2u);
  EXPECT_EQ(text[1].points.size(), 2u);
  EXPECT_EQ(error_of([&] { read_point_table(save("d.bpt", std::string("\x89" "BTP\r\n", 6))); }),
            dir.file("d.bpt") + ": not a bluetile binary point table (wrong magic)");
}

}  // namespace
}  // namespace bluetile
