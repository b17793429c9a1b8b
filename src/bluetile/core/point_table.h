// Sample tables: K point sets in one file, in the format a consumer wants (docs/DESIGN.md,
// section 6). Text is the point-file format of point_file.h; the others are binary or code:
//
// - npy: NumPy's format, version 1.0, C order, shape (K, N, C) with C = 2 (x y) or 3 (x y
//   level), little-endian float64 ('<f8') or float32 ('<f4'). Read back: any version (1-3),
//   either byte order, C or Fortran order, shape (N, C) or (K, N, C).
// - binary: the bluetile point table (.bpt), for C and C++ readers, all little-endian:
//     offset  size  field
//          0     8  magic 0x89 'B' 'T' 'P' '\r' '\n' 0x1A '\n'
//          8     4  version, 1
//         12     4  bytes per value: 4 (float32) or 8 (float64), IEEE 754
//         16     4  columns C: 2 (x y) or 3 (x y level)
//         20     4  reserved, 0
//         24     8  sets K
//         32     8  points per set N
//         40        K * N * C values, set by set, point by point, column by column
//   The file is exactly 40 + K * N * C * bytes long.
// - header: C/C++ source, `static const float NAME[K][N][C] = {...};`, each literal exact for
//   its float (9 significant digits).
//
// Coordinates are on the unit torus, in [0, 1). Float32 values are the nearest float, except
// that a value rounding up to 1 is stored as the largest float below 1, so every stored point
// stays in the domain. Levels (the third column) are whole numbers in [0, kMaxTableLevel].
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "bluetile/core/point_file.h"

namespace bluetile {

// csv: comma-separated text with a header naming the columns (x,y or x,y,level), what spreadsheets,
// pandas and R read; parse_csv_points reads it back.
enum class TableFormat { text, npy, binary, header, csv };
inline constexpr TableFormat kTableFormats[] = {TableFormat::text, TableFormat::npy, TableFormat::binary,
                                                TableFormat::header, TableFormat::csv};

// The largest level a table may hold: as point files.
inline constexpr int kMaxTableLevel = kMaxLevel;

// The extension of the file name in `path` (after its last '/'), lower case, with its dot: "" when
// it has none or its only dot starts the name (".hidden"). Every format-by-extension rule reads it.
std::string file_extension(const std::string& path);

// The extensions (as file_extension gives them) that name `format` when a table is written;
// "" stands for a name without one: .txt .dat .pts and "" for text, .npy, .bpt, .h .hpp, .csv.
std::span<const std::string_view> table_format_extensions(TableFormat format);

// The format to write `path` in: `requested` when not empty ("text", "npy", "binary",
// "header", "csv"), else by the extension: .txt .dat .pts or none -> text, .npy -> npy, .bpt ->
// binary, .h .hpp -> header, .csv -> csv; "-" (standard output) -> text. Throws Error naming the
// path or the name for an unknown one: a table is never written in a format nobody asked for.
TableFormat table_format_for(const std::string& path, const std::string& requested = "");

// "text", "npy", "binary", "header", "csv".
std::string_view table_format_name(TableFormat format);

// The words for a format whose bytes are binary ("NumPy (.npy)", "point table (.bpt)"), "" for
// text: OutputOptions::binary_format, so that no front end spills them onto a terminal.
std::string_view binary_table_format(TableFormat format);

// Receives the bytes of a table in order, in pieces.
using ByteSink = std::function<void(std::string_view bytes)>;

// What the table writers read: `sets` sets of `rows(k)` rows of `columns` values each.
struct TableView {
  std::size_t sets = 0;
  std::size_t columns = 2;
  std::string column_names = "x y";  // for the comment of a C header
  // A table that is no point table (centroids: cx cy area), whose columns a point-table reader
  // would take for x y level: npy writes it as a structured array, one float field per column
  // name, shape (K, N), so that NumPy names the columns (c["area"]) and no reader takes it for
  // points; binary (whose columns are x y or x y level) refuses it.
  bool named_fields = false;
  std::function<std::size_t(std::size_t set)> rows;
  std::function<double(std::size_t set, std::size_t row, std::size_t column)> value;
};

// Columns x y, and level when the sets have levels (all of them or none; Error otherwise, and for a
// level column whose length is not its set's number of points).
TableView point_sets_table(std::span<const PointSet> sets);

// Text of a table: a '# set k' line before each set when there are several (UTK's convention),
// one row a line, values with 17 significant digits. Point sets have their own writer
// (write_points, point_file.h); this one is for other tables (centroids: cx cy area). Throws
// Error("<path>: set k, row i: <column> is nan, ...") before any byte for a value that is not
// finite.
void write_text_table(const TableView& table, const std::string& path, const ByteSink& sink);

struct TableWriteOptions {
  bool float32 = false;  // npy and binary: 4-byte floats instead of 8 (header: always float)
  // header: the array's name; empty picks one from the file name (table_name_for_path).
  std::string name{};
  // header and csv: comment lines at the top of the file.
  std::vector<std::string> comment{};
};

// Writes `table` in a binary, code or CSV format (npy, binary, header, csv; text goes through
// point_file.h). Every set must have the same number of rows (a CSV takes any). A CSV holds the
// comment lines ('# ...'), a header of the column names joined by ',' ("x,y", "cx,cy,area"), then
// one row a line with 17 significant digits, a '# set k' line before each set when there are
// several (pandas: read_csv(path, comment='#')). `path` names the output in messages and gives the
// header's default name. Throws Error("<path>: <what>"), before any byte, for a value that is not
// finite (as write_text_table) and sets of different sizes.
void write_table(TableFormat format, const TableView& table, const TableWriteOptions& options,
                 const std::string& path, const ByteSink& sink);

// Writes point sets in any format: text as point files with a '# set k' line before each set
// when there are several (UTK's convention), the others by write_table. options.comment: header
// lines of text, CSV and C headers; in text and CSV, one the readers refuse (check_comment_line,
// point_file.h) throws Error before any byte. `path` names the output in messages.
void write_point_table(TableFormat format, std::span<const PointSet> sets, const TableWriteOptions& options,
                       const std::string& path, const ByteSink& sink);

// A C identifier from a file name: "tables/blue-noise 64.h" -> "blue_noise_64"; "points_" goes
// before one that starts with a digit or is a C or C++ keyword ("int.h" -> "points_int").
std::string table_name_for_path(const std::string& path);

// The array name a C header output at `path` gets: `name`, or table_name_for_path when empty.
// Throws Error("<path>: '<name>' is not a C identifier ...") for a name that is not one or is a C
// or C++ keyword, and when `name` is empty and the file name holds bytes outside ASCII (letters a
// C name cannot hold, which table_name_for_path drops); commands call it when they declare the
// output, before any work.
std::string checked_table_name(const std::string& path, const std::string& name);

// Reads every set of a file in any readable format, recognised by its first bytes: npy,
// binary, psa's .rps and CSV (parse_csv_points) by their extensions, else text (point_file.h;
// sets apart at '#' lines, UTK's convention). Throws
// Error("<path>: <what>") for a damaged file: short, wrong magic, sizes that do not match,
// unknown value types, non-finite values, levels that are not whole numbers; and for a zip archive
// (NumPy's .npz), an npy of other values (integers, a structured or one-dimensional array), saying
// how NumPy saves the array read here. `options`: as read_points_by_extension's (by default
// points are wrapped onto the unit torus).
std::vector<PointSet> read_point_table(const std::string& path, const ReadOptions& options = {});

// The same decoders over bytes in memory; `name` stands for the file in messages.
// `options`: the domain and range check of ReadOptions (point_file.h); by default points are
// wrapped onto the unit torus.
std::vector<PointSet> parse_npy_table(std::string_view bytes, const std::string& name, const ReadOptions& options = {});
std::vector<PointSet> parse_binary_table(std::string_view bytes, const std::string& name,
                                         const ReadOptions& options = {});

// Comma-separated points: an optional header line "x,y" or "x,y,level" (any case, names may be
// quoted), then one point a line, "x,y" or "x,y,level"; '#' lines separate sets and comment, as
// in text. A header whose first column is unnamed (",x,y": the index pandas' to_csv and R's
// write.csv add by default) makes the first field of every row an index, skipped. Throws
// Error("<name>:<line>: ...") naming the value for an empty or malformed field, a wrong column
// count, a header naming other columns, and everything the text format refuses.
std::vector<PointSet> parse_csv_points(std::string_view text, const std::string& name, const ReadOptions& options = {});

// Every set of a file in the format its extension names (any case): .npy, .bpt, .csv, .rps; any
// other name (and "-") by its content, as read_point_table: .npy or .bpt by their magic, else
// text; `options` applies to every format. What `bluetile analyze`
// reads. Throws Error naming the file (and line or point) like the readers above, and for sets
// that differ in their columns (levels in some only).
std::vector<PointSet> read_points_by_extension(const std::string& path, const ReadOptions& options = {});

// psa's raw point sets (.rps, Heck, Schlömer and Deussen's analysis tool): no header, one set of
// little-endian float32 pairs x y, so a file of B bytes holds B / 8 points. It has no magic:
// read_point_table and `bluetile analyze` take it by its extension, .rps in any case.
bool is_rps_path(const std::string& path);
// Throws Error("<name>: ...") for a size not a multiple of 8, a non-finite value ("point i" from
// 0), and (options.wrap false) a coordinate outside [0, 1); else such coordinates are wrapped.
PointSet parse_rps_points(std::string_view bytes, const std::string& name, const ReadOptions& options = {});
PointSet read_rps_file(const std::string& path, const ReadOptions& options = {});

}  // namespace bluetile
