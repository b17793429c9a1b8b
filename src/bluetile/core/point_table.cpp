#include "bluetile/core/point_table.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>

#include <sys/stat.h>

#include "bluetile/core/error.h"
#include "bluetile/core/input_file.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace {

constexpr char kBinaryMagic[8] = {'\x89', 'B', 'T', 'P', '\r', '\n', '\x1a', '\n'};
constexpr std::size_t kBinaryHeaderBytes = 40;
constexpr std::uint32_t kBinaryVersion = 1;
constexpr char kNpyMagic[6] = {'\x93', 'N', 'U', 'M', 'P', 'Y'};
// Bytes gathered before each call of the sink: large enough that the sink's cost per call
// vanishes, small enough to stay in cache.
constexpr std::size_t kSinkChunk = 1 << 16;

// "1 set of 64 points", "3 sets of 1 point".
std::string sets_of_points(std::size_t sets, std::size_t rows) {
  return counted(static_cast<long long>(sets), "set") + " of " + counted(static_cast<long long>(rows), "point");
}


// Buffers bytes for a sink.
class ChunkedWriter {
 public:
  explicit ChunkedWriter(const ByteSink& sink) : sink_(sink) { buffer_.reserve(kSinkChunk); }
  ~ChunkedWriter() = default;

  void write(const void* data, std::size_t size) {
    const char* bytes = static_cast<const char*>(data);
    buffer_.append(bytes, size);
    if (buffer_.size() >= kSinkChunk) flush();
  }
  void write(std::string_view text) { write(text.data(), text.size()); }
  template <typename T>
  void little_endian(T value) {
    if constexpr (std::endian::native == std::endian::big) value = byte_swapped(value);
    write(&value, sizeof value);
  }
  void flush() {
    if (!buffer_.empty()) sink_(buffer_);
    buffer_.clear();
  }

  template <typename T>
  static T byte_swapped(T value) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    std::reverse(bytes, bytes + sizeof(T));
    std::memcpy(&value, bytes, sizeof(T));
    return value;
  }

 private:
  const ByteSink& sink_;
  std::string buffer_;
};

// The float stored for a coordinate: the nearest one, kept below 1 (see point_table.h).
float table_float(double value) {
  float f = static_cast<float>(value);
  if (value < 1.0 && f >= 1.0f) f = std::nextafter(1.0f, 0.0f);
  return f;
}

// The names of a table's columns, one per column ("column c" where the names run short).
std::vector<std::string> column_names(const TableView& table) {
  std::vector<std::string> names;
  std::size_t at = 0;
  while (at < table.column_names.size()) {
    const std::size_t end = std::min(table.column_names.find(' ', at), table.column_names.size());
    if (end > at) names.push_back(table.column_names.substr(at, end - at));
    at = end + 1;
  }
  names.resize(std::max(names.size(), table.columns));
  for (std::size_t c = 0; c < table.columns; ++c)
    if (names[c].empty()) names[c] = "column " + std::to_string(c);
  names.resize(table.columns);
  return names;
}

// Before any byte: a NaN or infinity in a table (a centroid of a broken cell, say) was written as
// it came, and every reader then refused the file or took "nan" for a value.
void check_values(const TableView& table, const std::string& path) {
  for (std::size_t k = 0; k < table.sets; ++k) {
    const std::size_t rows = table.rows(k);
    for (std::size_t i = 0; i < rows; ++i)
      for (std::size_t c = 0; c < table.columns; ++c) {
        const double v = table.value(k, i, c);
        if (std::isfinite(v)) continue;
        throw Error(path + ": set " + std::to_string(k) + ", row " + std::to_string(i) + ": " + column_names(table)[c] + " is " +
                    exact_text(v) + ", not a finite number: no reader would take it back");
      }
  }
}

std::size_t common_rows(const TableView& table, const std::string& path, TableFormat format) {
  if (table.sets == 0) return 0;
  std::size_t rows = table.rows(0);
  for (std::size_t k = 1; k < table.sets; ++k) {
    if (table.rows(k) != rows) {
      throw Error(path + ": set 0 has " + std::to_string(rows) + " points but set " + std::to_string(k) + " has " +
                  std::to_string(table.rows(k)) + ": the " + std::string(table_format_name(format)) +
                  " format needs the same count in every set (text takes any)");
    }
  }
  return rows;
}

template <typename T>
void write_values(ChunkedWriter& out, const TableView& table, std::size_t rows) {
  for (std::size_t k = 0; k < table.sets; ++k)
    for (std::size_t i = 0; i < rows; ++i)
      for (std::size_t c = 0; c < table.columns; ++c) {
        double v = table.value(k, i, c);
        if constexpr (std::is_same_v<T, float>) {
          out.little_endian(table_float(v));
        } else {
          out.little_endian(v);
        }
      }
}

void write_npy(ChunkedWriter& out, const TableView& table, std::size_t rows, bool float32) {
  const std::string type = float32 ? "<f4" : "<f8";
  std::string dict;
  if (table.named_fields) {
    // One record of named floats per row: the same bytes after the header as (K, N, C).
    std::string fields;
    for (const std::string& name : column_names(table)) fields += (fields.empty() ? "" : ", ") + ("('" + name + "', '" + type + "')");
    dict = "{'descr': [" + fields + "], 'fortran_order': False, 'shape': (" + std::to_string(table.sets) + ", " +
           std::to_string(rows) + "), }";
  } else {
    dict = "{'descr': '" + type + "', 'fortran_order': False, 'shape': (" + std::to_string(table.sets) + ", " +
           std::to_string(rows) + ", " + std::to_string(table.columns) + "), }";
  }
  // Version 1.0: magic, 2 version bytes, a 2-byte header length; the data starts at a multiple
  // of 64 bytes and the header ends with a newline.
  std::size_t unpadded = sizeof kNpyMagic + 2 + 2 + dict.size() + 1;
  dict.append((64 - unpadded % 64) % 64, ' ');
  dict += '\n';
  out.write(kNpyMagic, sizeof kNpyMagic);
  out.write("\x01\x00", 2);
  out.little_endian(static_cast<std::uint16_t>(dict.size()));
  out.write(dict);
  if (float32) {
    write_values<float>(out, table, rows);
  } else {
    write_values<double>(out, table, rows);
  }
}

void write_binary(ChunkedWriter& out, const TableView& table, std::size_t rows, bool float32) {
  out.write(kBinaryMagic, sizeof kBinaryMagic);
  out.little_endian(kBinaryVersion);
  out.little_endian(static_cast<std::uint32_t>(float32 ? 4 : 8));
  out.little_endian(static_cast<std::uint32_t>(table.columns));
  out.little_endian(std::uint32_t{0});
  out.little_endian(static_cast<std::uint64_t>(table.sets));
  out.little_endian(static_cast<std::uint64_t>(rows));
  if (float32) {
    write_values<float>(out, table, rows);
  } else {
    write_values<double>(out, table, rows);
  }
}

bool is_identifier(const std::string& name) {
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) return false;
  return std::all_of(name.begin(), name.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

// C23's and C++20's keywords and alternative tokens: a header must compile as both.
bool is_keyword(std::string_view name) {
  static constexpr std::string_view kKeywords[] = {
      "alignas", "alignof", "and", "and_eq", "asm", "auto", "bitand", "bitor", "bool", "break", "case", "catch",
      "char", "char8_t", "char16_t", "char32_t", "class", "compl", "concept", "const", "consteval", "constexpr",
      "constinit", "const_cast", "continue", "co_await", "co_return", "co_yield", "decltype", "default", "delete",
      "do", "double", "dynamic_cast", "else", "enum", "explicit", "export", "extern", "false", "float", "for",
      "friend", "goto", "if", "inline", "int", "long", "mutable", "namespace", "new", "noexcept", "not", "not_eq",
      "nullptr", "operator", "or", "or_eq", "private", "protected", "public", "register", "reinterpret_cast",
      "requires", "restrict", "return", "short", "signed", "sizeof", "static", "static_assert", "static_cast",
      "struct", "switch", "template", "this", "thread_local", "throw", "true", "try", "typedef", "typeid",
      "typename", "typeof", "typeof_unqual", "union", "unsigned", "using", "virtual", "void", "volatile",
      "wchar_t", "while", "xor", "xor_eq", "_Alignas", "_Alignof", "_Atomic", "_BitInt", "_Bool", "_Complex",
      "_Decimal128", "_Decimal32", "_Decimal64", "_Generic", "_Imaginary", "_Noreturn", "_Static_assert",
      "_Thread_local"};
  return std::find(std::begin(kKeywords), std::end(kKeywords), name) != std::end(kKeywords);
}

// A float literal that reads back as exactly `f`: 9 significant digits, with a '.' or an
// exponent so that the 'f' suffix makes a valid literal.
void float_literal(float f, char* text, std::size_t size) {
  const ClassicNumbers classic;
  int len = std::snprintf(text, size, "%.9g", static_cast<double>(f));
  if (!std::strpbrk(text, ".e")) len += std::snprintf(text + len, size - static_cast<std::size_t>(len), ".0");
  std::snprintf(text + len, size - static_cast<std::size_t>(len), "f");
}

void write_header(ChunkedWriter& out, const TableView& table, std::size_t rows, const TableWriteOptions& options,
                  const std::string& path) {
  const std::string name = checked_table_name(path, options.name);
  for (const std::string& line : options.comment) out.write("// " + comment_line(line, true) + "\n");
  out.write("// " + sets_of_points(table.sets, rows) + ", columns " + table.column_names +
            "; coordinates on the unit torus, in [0, 1).\n");
  out.write("#pragma once\n\n");
  out.write("static const float " + name + "[" + std::to_string(table.sets) + "][" + std::to_string(rows) + "][" +
            std::to_string(table.columns) + "] = {\n");
  char literal[32];
  for (std::size_t k = 0; k < table.sets; ++k) {
    out.write("  {  // set " + std::to_string(k) + "\n");
    for (std::size_t i = 0; i < rows; ++i) {
      out.write("    {");
      for (std::size_t c = 0; c < table.columns; ++c) {
        float_literal(table_float(table.value(k, i, c)), literal, sizeof literal);
        if (c) out.write(", ");
        out.write(literal);
      }
      out.write("},\n");
    }
    out.write("  },\n");
  }
  out.write("};\n");
}

// --- reading ---------------------------------------------------------------------------------

// Reads little- or big-endian values out of a byte range, bounds checked by the callers.
template <typename T>
T load(const char* at, bool big_endian) {
  T value;
  std::memcpy(&value, at, sizeof value);
  if (big_endian != (std::endian::native == std::endian::big)) value = ChunkedWriter::byte_swapped(value);
  return value;
}

// Builds point sets from decoded values, checking each (shared by npy and binary).
class SetBuilder {
  // Sets of no points hold no bytes, so a header may claim any number of them: refused before
  // they are allocated.
  static std::size_t checked_set_count(const std::string& name, std::size_t sets, std::size_t rows) {
    if (sets > 0 && rows == 0)
      throw Error(name + ": the table holds " + sets_of_points(sets, 0));
    return sets;
  }

 public:
  SetBuilder(const std::string& name, std::size_t sets, std::size_t rows, std::size_t columns,
             const ReadOptions& options)
      : name_(name), columns_(columns), options_(options), sets_(checked_set_count(name, sets, rows)) {
    for (PointSet& set : sets_) {
      set.points.reserve(rows);
      if (columns == 3) set.levels.reserve(rows);
    }
  }

  void add(std::size_t set, std::size_t row, std::size_t column, double value) {
    auto where = [&] { return name_ + ": set " + std::to_string(set) + ", point " + std::to_string(row) + ": "; };
    if (!std::isfinite(value)) throw Error(where() + "not a finite number '" + format_value(value) + "'");
    if (column == 2) {
      if (value < 0 || value > kMaxTableLevel || value != std::floor(value))
        throw Error(where() + "level must be a whole number in [0, " + std::to_string(kMaxTableLevel) + "], got '" +
                    format_value(value) + "'" + std::string(kThirdColumnIsTheLevel));
      sets_[set].levels.push_back(static_cast<int>(value));
      return;
    }
    if (column == 0) {
      x_ = value;
    } else {
      int outside = -1;
      const Point placed = place_read_point(Point{x_, value}, options_, outside);
      if (outside >= 0)
        throw Error(where() + (outside == 0 ? "x = " : "y = ") + format_value(outside == 0 ? x_ : value) +
                    " is outside " + read_range_text(outside, options_));
      sets_[set].points.push_back(placed);
    }
  }

  std::vector<PointSet> finish() { return std::move(sets_); }

 private:
  static std::string format_value(double value) {
    const ClassicNumbers classic;
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
  }

  const std::string& name_;
  std::size_t columns_;
  ReadOptions options_;
  std::vector<PointSet> sets_;
  double x_ = 0.0;
};

void check_columns(std::size_t columns, const std::string& name) {
  if (columns != 2 && columns != 3)
    throw Error(name + ": " + std::to_string(columns) + (columns == 1 ? " column" : " columns") +
                " per point; expected 2 (x y) or 3 (x y level)");
}

// sets * rows * columns * bytes without overflow, or Error.
std::size_t payload_bytes(std::uint64_t sets, std::uint64_t rows, std::uint64_t columns, std::uint64_t bytes,
                          const std::string& name) {
  std::uint64_t total = bytes;
  for (std::uint64_t factor : {sets, rows, columns}) {
    if (factor != 0 && total > std::numeric_limits<std::uint64_t>::max() / factor)
      throw Error(name + ": sizes " + std::to_string(sets) + " x " + std::to_string(rows) + " x " +
                  std::to_string(columns) + " overflow: a damaged file");
    total *= factor;
  }
  return static_cast<std::size_t>(total);
}

// A small parser for the Python-literal dictionary of an npy header.
class NpyHeader {
 public:
  NpyHeader(std::string_view text, const std::string& name) : text_(text), name_(name) {}

  std::string string_value(std::string_view key) {
    std::size_t at = value_start(key);
    char quote = at < text_.size() ? text_[at] : '\0';
    if (quote != '\'' && quote != '"') fail(std::string(key) + " is not a string");
    std::size_t end = text_.find(quote, at + 1);
    if (end == std::string_view::npos) fail("unterminated string");
    return std::string(text_.substr(at + 1, end - at - 1));
  }

  // Whether the value is a list (a structured dtype's fields: [('x', '<f8'), ...]).
  bool is_list(std::string_view key) {
    std::size_t at = value_start(key);
    return at < text_.size() && text_[at] == '[';
  }

  bool bool_value(std::string_view key) {
    std::size_t at = value_start(key);
    if (text_.substr(at, 4) == "True") return true;
    if (text_.substr(at, 5) == "False") return false;
    fail(std::string(key) + " is not True or False");
  }

  std::vector<std::uint64_t> tuple_value(std::string_view key) {
    std::size_t at = value_start(key);
    if (at >= text_.size() || text_[at] != '(') fail(std::string(key) + " is not a tuple");
    std::size_t end = text_.find(')', at);
    if (end == std::string_view::npos) fail("unterminated tuple");
    std::vector<std::uint64_t> values;
    std::size_t i = at + 1;
    while (i < end) {
      while (i < end && (text_[i] == ' ' || text_[i] == ',')) ++i;
      if (i == end) break;
      std::uint64_t v = 0;
      std::size_t digits = 0;
      while (i < end && std::isdigit(static_cast<unsigned char>(text_[i]))) {
        if (v > (std::numeric_limits<std::uint64_t>::max() - 9) / 10) fail("shape value too large");
        v = v * 10 + static_cast<std::uint64_t>(text_[i] - '0');
        ++i;
        ++digits;
      }
      if (digits == 0) fail("shape holds something other than whole numbers");
      values.push_back(v);
    }
    return values;
  }

  [[noreturn]] void fail(const std::string& what) const { throw Error(name_ + ": bad .npy header: " + what); }

 private:
  std::size_t value_start(std::string_view key) {
    for (char quote : {'\'', '"'}) {
      std::string quoted = quote + std::string(key) + quote;
      std::size_t at = text_.find(quoted);
      if (at == std::string_view::npos) continue;
      at = text_.find(':', at + quoted.size());
      if (at == std::string_view::npos) break;
      ++at;
      while (at < text_.size() && text_[at] == ' ') ++at;
      return at;
    }
    fail("no '" + std::string(key) + "'");
  }

  std::string_view text_;
  const std::string& name_;
};

// Every read checked, out of memory included (input_file.h).
std::string read_bytes(const std::string& path) { return read_input(path); }

bool starts_with(std::string_view bytes, const char* magic, std::size_t size) {
  return bytes.size() >= size && std::memcmp(bytes.data(), magic, size) == 0;
}

// A zip archive's first bytes: NumPy's savez writes one (.npz) of .npy files.
constexpr char kZipMagic[4] = {'P', 'K', '\x03', '\x04'};

[[noreturn]] void refuse_zip(const std::string& name) {
  throw Error(name + ": a zip archive (numpy.savez writes .npz), not a point table: save one array with "
                     "numpy.save('points.npy', a)");
}

}  // namespace

std::string file_extension(const std::string& path) {
  std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  std::size_t dot = name.find_last_of('.');
  if (dot == std::string::npos || dot == 0) return "";
  return lower_case(name.substr(dot));
}

std::span<const std::string_view> table_format_extensions(TableFormat format) {
  static constexpr std::string_view text[] = {".txt", ".dat", ".pts", ""};
  static constexpr std::string_view npy[] = {".npy"};
  static constexpr std::string_view binary[] = {".bpt"};
  static constexpr std::string_view header[] = {".h", ".hpp"};
  static constexpr std::string_view csv[] = {".csv"};
  switch (format) {
    case TableFormat::text: return text;
    case TableFormat::npy: return npy;
    case TableFormat::binary: return binary;
    case TableFormat::header: return header;
    case TableFormat::csv: return csv;
  }
  return text;
}

TableFormat table_format_for(const std::string& path, const std::string& requested) {
  if (!requested.empty()) {
    for (TableFormat f : kTableFormats)
      if (requested == table_format_name(f)) return f;
    throw Error("unknown table format '" + requested + "' (text, npy, binary, header, csv)");
  }
  if (path == "-") return TableFormat::text;
  const std::string ext = file_extension(path);
  for (TableFormat f : kTableFormats)
    for (std::string_view named : table_format_extensions(f))
      if (ext == named) return f;
  throw Error(path + ": unknown extension '" + ext +
              "' (.txt .dat .pts: text, .npy, .bpt: binary, .h .hpp: C header, .csv; or say --format)");
}

std::string_view table_format_name(TableFormat format) {
  switch (format) {
    case TableFormat::text: return "text";
    case TableFormat::npy: return "npy";
    case TableFormat::binary: return "binary";
    case TableFormat::header: return "header";
    case TableFormat::csv: return "csv";
  }
  return "text";
}

std::string_view binary_table_format(TableFormat format) {
  if (format == TableFormat::npy) return "NumPy (.npy)";
  if (format == TableFormat::binary) return "point table (.bpt)";
  return "";
}

TableView point_sets_table(std::span<const PointSet> sets) {
  bool levels = !sets.empty() && sets[0].has_levels();
  for (std::size_t k = 0; k < sets.size(); ++k) {
    if (sets[k].has_levels() != levels)
      throw Error("set " + std::to_string(k) + (levels ? " has no levels" : " has levels") + " but set 0 " +
                  (levels ? "has" : "has none") + ": a table has one set of columns");
    // value() read the level of every row: a shorter column was read past its end.
    check_level_column(sets[k], "set " + std::to_string(k) + ", ");
  }
  TableView view;
  view.sets = sets.size();
  view.columns = levels ? 3 : 2;
  view.column_names = levels ? "x y level" : "x y";
  view.rows = [sets](std::size_t k) { return sets[k].points.size(); };
  view.value = [sets](std::size_t k, std::size_t i, std::size_t c) {
    const PointSet& set = sets[k];
    return c == 0 ? set.points[i].x : c == 1 ? set.points[i].y : static_cast<double>(set.levels[i]);
  };
  return view;
}

namespace {

// The rows of a text or CSV table: a '# set k' line before each set when there are several, values
// with 17 significant digits and `separator` between them (levels, whole numbers, come out "3").
void write_rows(const TableView& table, char separator, const ByteSink& sink) {
  ChunkedWriter out(sink);
  const ClassicNumbers classic;
  char value[32];
  for (std::size_t k = 0; k < table.sets; ++k) {
    if (table.sets > 1) out.write("# set " + std::to_string(k) + "\n");
    const std::size_t rows = table.rows(k);
    for (std::size_t i = 0; i < rows; ++i) {
      for (std::size_t c = 0; c < table.columns; ++c) {
        int len = std::snprintf(value, sizeof value - 1, "%.17g", table.value(k, i, c));
        value[len++] = c + 1 < table.columns ? separator : '\n';
        out.write(value, static_cast<std::size_t>(len));
      }
    }
  }
  out.flush();
}

// CSV as write_table says: the comment lines (checked as a point file's, so that the reader takes
// them back), the column names, then the rows with ',' between values.
void write_csv_table(const TableView& table, const std::vector<std::string>& comment, const std::string& path,
                     const ByteSink& sink) {
  check_values(table, path);
  std::string names = table.column_names;
  std::replace(names.begin(), names.end(), ' ', ',');
  sink(format_points(PointSet{}, comment) + names + "\n");
  write_rows(table, ',', sink);
}

}  // namespace

void write_text_table(const TableView& table, const std::string& path, const ByteSink& sink) {
  check_values(table, path);
  write_rows(table, ' ', sink);
}

void write_table(TableFormat format, const TableView& table, const TableWriteOptions& options, const std::string& path,
                 const ByteSink& sink) {
  if (format == TableFormat::text) throw Error(path + ": text tables are written as point files (point_file.h)");
  if (format == TableFormat::csv) {
    write_csv_table(table, options.comment, path, sink);
    return;
  }
  check_columns(table.columns, path);
  if (format == TableFormat::binary && table.named_fields)
    throw Error(path + ": a bluetile point table's columns are x y or x y level, not " + table.column_names +
                "; write .npy (a field per column), text or a C header");
  const std::size_t rows = common_rows(table, path, format);
  check_values(table, path);
  ChunkedWriter out(sink);
  switch (format) {
    case TableFormat::npy: write_npy(out, table, rows, options.float32); break;
    case TableFormat::binary: write_binary(out, table, rows, options.float32); break;
    case TableFormat::header: write_header(out, table, rows, options, path); break;
    case TableFormat::text:
    case TableFormat::csv: break;
  }
  out.flush();
}

void write_point_table(TableFormat format, std::span<const PointSet> sets, const TableWriteOptions& options,
                       const std::string& path, const ByteSink& sink) {
  // Before any byte: a NaN or infinity was written, and every reader then refused the file.
  for (std::size_t k = 0; k < sets.size(); ++k)
    check_written_points(sets[k], path + ": set " + std::to_string(k) + ", ");
  if (format != TableFormat::text) {
    write_table(format, point_sets_table(sets), options, path, sink);
    return;
  }
  if (sets.size() == 1) {
    sink(format_points(sets[0], options.comment));
    return;
  }
  sink(format_points(PointSet{}, options.comment));
  for (std::size_t k = 0; k < sets.size(); ++k) sink("# set " + std::to_string(k) + "\n" + format_points(sets[k]));
}

std::string checked_table_name(const std::string& path, const std::string& name) {
  if (name.empty()) {
    // Letters outside ASCII cannot be in a C name, and dropping them gave names nobody chose
    // ("ünï.h" -> "n"); punctuation becomes '_' as the header says.
    const std::string file = path.substr(path.find_last_of('/') == std::string::npos ? 0 : path.find_last_of('/') + 1);
    if (std::any_of(file.begin(), file.end(), [](char c) { return static_cast<unsigned char>(c) >= 0x80; }))
      throw Error(path + ": the file name holds letters outside ASCII, which a C name cannot, so the array would be '" +
                  table_name_for_path(path) + "'; name the array (--name, or name= in Python)");
    return table_name_for_path(path);
  }
  if (!is_identifier(name)) throw Error(path + ": '" + name + "' is not a C identifier (letters, digits, '_')");
  if (is_keyword(name)) throw Error(path + ": '" + name + "' is a C or C++ keyword, not a name for the array");
  return name;
}

std::string table_name_for_path(const std::string& path) {
  std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  std::size_t dot = name.find_last_of('.');
  if (dot != std::string::npos && dot > 0) name.resize(dot);
  std::string id;
  for (char c : name) {
    bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    if (ok) {
      id += c;
    } else if (!id.empty() && id.back() != '_') {
      id += '_';
    }
  }
  while (!id.empty() && id.back() == '_') id.pop_back();
  if (id.empty()) return "bluetile_points";
  if (std::isdigit(static_cast<unsigned char>(id[0])) || is_keyword(id)) id = "points_" + id;
  return id;
}

std::vector<PointSet> parse_binary_table(std::string_view bytes, const std::string& name, const ReadOptions& options) {
  if (bytes.size() < sizeof kBinaryMagic || !starts_with(bytes, kBinaryMagic, sizeof kBinaryMagic))
    throw Error(name + ": not a bluetile binary point table (wrong magic)");
  if (bytes.size() < kBinaryHeaderBytes)
    throw Error(name + ": binary point table cut short: " + std::to_string(bytes.size()) + " bytes, the header alone is " +
                std::to_string(kBinaryHeaderBytes));
  const char* h = bytes.data();
  auto version = load<std::uint32_t>(h + 8, false);
  auto value_bytes = load<std::uint32_t>(h + 12, false);
  auto columns = load<std::uint32_t>(h + 16, false);
  auto sets = load<std::uint64_t>(h + 24, false);
  auto rows = load<std::uint64_t>(h + 32, false);
  if (version != kBinaryVersion)
    throw Error(name + ": binary point table version " + std::to_string(version) + ", this reader knows version 1");
  if (value_bytes != 4 && value_bytes != 8)
    throw Error(name + ": " + std::to_string(value_bytes) + " bytes per value; expected 4 (float32) or 8 (float64)");
  check_columns(columns, name);
  std::size_t payload = payload_bytes(sets, rows, columns, value_bytes, name);
  if (bytes.size() - kBinaryHeaderBytes != payload) {
    throw Error(name + ": header says " + sets_of_points(sets, rows) + " (" +
                std::to_string(kBinaryHeaderBytes + payload) + " bytes) but the file has " + std::to_string(bytes.size()) +
                " bytes");
  }
  SetBuilder builder(name, sets, rows, columns, options);
  const char* at = h + kBinaryHeaderBytes;
  for (std::size_t k = 0; k < sets; ++k)
    for (std::size_t i = 0; i < rows; ++i)
      for (std::size_t c = 0; c < columns; ++c, at += value_bytes)
        builder.add(k, i, c, value_bytes == 4 ? load<float>(at, false) : load<double>(at, false));
  return builder.finish();
}

std::vector<PointSet> parse_npy_table(std::string_view bytes, const std::string& name, const ReadOptions& options) {
  if (!starts_with(bytes, kNpyMagic, sizeof kNpyMagic)) throw Error(name + ": not a .npy file (wrong magic)");
  if (bytes.size() < 10) throw Error(name + ": .npy file cut short in its header");
  const int major = static_cast<unsigned char>(bytes[6]);
  std::size_t header_size = 0, header_start = 0;
  if (major == 1) {
    header_size = load<std::uint16_t>(bytes.data() + 8, false);
    header_start = 10;
  } else if (major == 2 || major == 3) {
    if (bytes.size() < 12) throw Error(name + ": .npy file cut short in its header");
    header_size = load<std::uint32_t>(bytes.data() + 8, false);
    header_start = 12;
  } else {
    throw Error(name + ": .npy format version " + std::to_string(major) + " (this reader knows 1 to 3)");
  }
  if (bytes.size() - header_start < header_size) throw Error(name + ": .npy file cut short in its header");
  NpyHeader header(bytes.substr(header_start, header_size), name);
  // A well-formed file of another kind of array is refused saying how NumPy makes the one read
  // here (they were "bad .npy header").
  if (header.is_list("descr")) {
    // `bluetile centroids` writes its cx cy area tables so: name their fields in the hint.
    const std::string_view text = std::string_view(bytes).substr(header_start, header_size);
    const bool centroids = text.find("('cx'") != std::string_view::npos && text.find("('cy'") != std::string_view::npos;
    const char* x = centroids ? "cx" : "x";
    const char* y = centroids ? "cy" : "y";
    throw Error(name + ": a structured array (named fields" + (centroids ? " cx, cy, area: centroids" : "") +
                "); expected plain float64 or float32 values: save numpy.stack([a['" + x + "'], a['" + y +
                "']], axis=-1)");
  }
  const std::string descr = header.string_value("descr");
  const bool fortran = header.bool_value("fortran_order");
  std::vector<std::uint64_t> shape = header.tuple_value("shape");

  if (descr.size() != 3 || (descr[0] != '<' && descr[0] != '>' && descr[0] != '=' && descr[0] != '|') ||
      descr[1] != 'f' || (descr[2] != '4' && descr[2] != '8'))
    throw Error(name + ": values of dtype '" + descr + "'; expected float64 ('<f8') or float32 ('<f4'): save " +
                "a.astype(numpy.float64)");
  const bool big_endian = descr[0] == '>' || (descr[0] != '<' && std::endian::native == std::endian::big);
  const std::size_t value_bytes = descr[2] == '4' ? 4 : 8;
  if (shape.size() == 1)
    throw Error(name + ": shape (" + std::to_string(shape[0]) +
                ",) is one-dimensional; expected (N, 2), (N, 3) or (K, N, C): save a.reshape(-1, 2) for x y pairs");
  const bool one_set = shape.size() == 2;
  if (one_set) shape.insert(shape.begin(), 1);
  if (shape.size() != 3)
    throw Error(name + ": shape of " + std::to_string(shape.size()) + " dimensions; expected (N, C) or (K, N, C)");
  const std::uint64_t sets = shape[0], rows = shape[1], columns = shape[2];
  // x and y as two rows (numpy.array([xs, ys]), or a.T saved by mistake): say so.
  if (columns != 2 && columns != 3 && (rows == 2 || rows == 3))
    throw Error(name + ": shape (" + (one_set ? "" : std::to_string(sets) + ", ") + std::to_string(rows) + ", " +
                std::to_string(columns) + ") holds " + std::to_string(columns) +
                " columns per point; expected 2 (x y) or 3 (x y level): coordinates as rows? save " +
                (one_set ? "a.T" : "a.transpose(0, 2, 1)"));
  check_columns(columns, name);
  std::size_t payload = payload_bytes(sets, rows, columns, value_bytes, name);
  std::size_t data_start = header_start + header_size;
  if (bytes.size() - data_start != payload) {
    throw Error(name + ": shape (" + std::to_string(sets) + ", " + std::to_string(rows) + ", " + std::to_string(columns) +
                ") needs " + std::to_string(payload) + " data bytes but the file has " +
                std::to_string(bytes.size() - data_start));
  }
  SetBuilder builder(name, sets, rows, columns, options);
  const char* data = bytes.data() + data_start;
  for (std::size_t k = 0; k < sets; ++k)
    for (std::size_t i = 0; i < rows; ++i)
      for (std::size_t c = 0; c < columns; ++c) {
        // C order: the last index varies fastest; Fortran order: the first.
        std::size_t index = fortran ? k + sets * (i + rows * c) : (k * rows + i) * columns + c;
        const char* at = data + index * value_bytes;
        builder.add(k, i, c, value_bytes == 4 ? load<float>(at, big_endian) : load<double>(at, big_endian));
      }
  return builder.finish();
}

bool is_rps_path(const std::string& path) { return file_extension(path) == ".rps"; }

PointSet parse_rps_points(std::string_view bytes, const std::string& name, const ReadOptions& options) {
  constexpr std::size_t kPointBytes = 2 * sizeof(float);
  if (bytes.size() % kPointBytes != 0)
    throw Error(name + ": " + std::to_string(bytes.size()) +
                " bytes is not a whole number of points (.rps holds 8-byte pairs of float32 x y)");
  PointSet set;
  const ClassicNumbers classic;  // the values its messages quote
  const std::size_t count = bytes.size() / kPointBytes;
  set.points.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    double value[2];
    for (int axis = 0; axis < 2; ++axis) {
      value[axis] = load<float>(bytes.data() + i * kPointBytes + axis * sizeof(float), false);
      char text[32];
      std::snprintf(text, sizeof text, "%.9g", value[axis]);
      const std::string where = name + ": point " + std::to_string(i) + ": ";
      if (!std::isfinite(value[axis])) throw Error(where + "not a finite number '" + text + "'");
    }
    int outside = -1;
    const Point placed = place_read_point(Point{value[0], value[1]}, options, outside);
    if (outside >= 0) {
      char text[32];
      std::snprintf(text, sizeof text, "%.9g", value[outside]);
      throw Error(name + ": point " + std::to_string(i) + ": " + (outside == 0 ? "x" : "y") + " = " + text +
                  " is outside " + read_range_text(outside, options));
    }
    set.points.push_back(placed);
  }
  return set;
}

PointSet read_rps_file(const std::string& path, const ReadOptions& options) {
  return parse_rps_points(read_bytes(path), input_name(path), options);
}

namespace {

// A text file's sets as one table: the level column in every set or in none, refused when the
// file is read (before any work) rather than when the result is written.
std::vector<PointSet> same_columns(std::vector<PointSet> sets, const std::string& path) {
  for (std::size_t k = 1; k < sets.size(); ++k) {
    if (sets[k].has_levels() != sets[0].has_levels())
      throw Error(input_name(path) + ": set " + std::to_string(k) +
                  (sets[0].has_levels() ? " has no level column but set 0 has one"
                                        : " has a level column but set 0 has none") +
                  ": a table's sets have one set of columns");
  }
  return sets;
}

// Standard input, a FIFO or a device is read once: its first bytes, looked at to tell the
// format, cannot be read again (a second open would wait for another writer).
std::vector<PointSet> parse_stream_table(const std::string& bytes, const std::string& name, const ReadOptions& options) {
  std::string_view head(bytes);
  if (starts_with(head, kNpyMagic, sizeof kNpyMagic)) return parse_npy_table(bytes, name, options);
  if (starts_with(head, kBinaryMagic, 4)) return parse_binary_table(bytes, name, options);
  if (starts_with(head, kZipMagic, sizeof kZipMagic)) refuse_zip(name);
  return same_columns(parse_point_sets(bytes, name, options), name);
}

// A file whose name says nothing of its format, read by its first bytes: an .npy or a .bpt saved
// as points.dat is read as such (read_points_by_extension read it as text: "binary data").
std::vector<PointSet> read_by_content(const std::string& path, const ReadOptions& options) {
  struct stat status {};
  if (path == "-" || (stat(path.c_str(), &status) == 0 && !S_ISREG(status.st_mode) && !S_ISDIR(status.st_mode)))
    return parse_stream_table(read_input(path), input_name(path), options);
  char start[sizeof kBinaryMagic] = {};
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open: " + std::strerror(errno));
    in.read(start, sizeof start);
  }
  std::string_view head(start, sizeof start);
  if (starts_with(head, kNpyMagic, sizeof kNpyMagic)) return parse_npy_table(read_bytes(path), path, options);
  if (starts_with(head, kBinaryMagic, 4)) return parse_binary_table(read_bytes(path), path, options);
  if (starts_with(head, kZipMagic, sizeof kZipMagic)) refuse_zip(path);
  return read_point_sets(path, options);
}

}  // namespace

std::vector<PointSet> read_point_table(const std::string& path, const ReadOptions& options) {
  if (path != "-" && is_rps_path(path)) return {read_rps_file(path, options)};
  // By its extension, as analyze reads it: its lines were text's "expected 'x y'".
  if (path != "-" && file_extension(path) == ".csv")
    return same_columns(parse_csv_points(read_input(path), path, options), path);
  return same_columns(read_by_content(path, options), path);
}

namespace {

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> csv_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(trimmed(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

// A field without the quotes a CSV writer may put around any value (Python's csv.QUOTE_ALL).
std::string_view unquoted(std::string_view field) {
  if (field.size() >= 2 && field.front() == '"' && field.back() == '"') return trimmed(field.substr(1, field.size() - 2));
  return field;
}

// A header field's name: unquoted (R quotes them), lower case.
std::string csv_name(std::string_view field) {
  if (field.size() >= 2 && (field.front() == '"' || field.front() == '\'') && field.back() == field.front())
    field = field.substr(1, field.size() - 2);
  return lower_case(std::string(field));
}

// Whether `fields` name the columns x,y or x,y,level.
bool names_point_columns(std::span<const std::string_view> fields) {
  if (fields.size() != 2 && fields.size() != 3) return false;
  return csv_name(fields[0]) == "x" && csv_name(fields[1]) == "y" && (fields.size() == 2 || csv_name(fields[2]) == "level");
}

// What a first line of a CSV is: the columns x,y[,level]; the same after an unnamed first column
// (the index pandas' to_csv and R's write.csv write by default, skipped in every row); another
// header (a field that is a name, not a number); or data.
enum class CsvFirstLine { columns, index_and_columns, other_header, data };

CsvFirstLine csv_first_line(const std::vector<std::string_view>& fields) {
  if (names_point_columns(fields)) return CsvFirstLine::columns;
  if (fields.size() > 1 && csv_name(fields[0]).empty() && names_point_columns(std::span(fields).subspan(1)))
    return CsvFirstLine::index_and_columns;
  for (std::string_view field : fields) {
    const std::string name = csv_name(field);
    if (name == "nan" || name == "inf" || name == "infinity") continue;  // refused as numbers, with their line
    const std::string_view inner = unquoted(field);  // "0.25" quoted is a number
    if (!inner.empty() && (std::isalpha(static_cast<unsigned char>(inner.front())) || inner.front() == '"' ||
                           inner.front() == '\''))
      return CsvFirstLine::other_header;
  }
  return CsvFirstLine::data;
}

// Whether the lines holding data (before any '#') hold blanks between their values and no ',' or
// ';': bluetile's text points in a file named .csv ('relax -o - > points.csv' writes them, as did
// 'relax --format text -o points.csv' before CSV was written), which no line of a CSV can be.
bool blank_separated(std::string_view text) {
  bool data = false;
  while (!text.empty()) {
    std::string_view line = next_line(text);
    line = trimmed(line.substr(0, line.find('#')));
    if (line.empty()) continue;
    if (line.find_first_of(",;") != std::string_view::npos) return false;
    data = true;
  }
  return data;
}

}  // namespace

std::vector<PointSet> parse_csv_points(std::string_view text, const std::string& name, const ReadOptions& options) {
  // Each line becomes the text format's "x y [level]" and goes through its parser, which checks
  // the numbers, ranges and levels and counts the lines: one reader of points, not two.
  static constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (blank_separated(text)) return parse_point_sets(text, name, options);
  if (text.substr(0, kBom.size()) == kBom) text.remove_prefix(kBom.size());
  PointTextParser parser(name, true, options);
  std::size_t number = 0;
  bool data_seen = false;
  bool index_column = false;  // the header's first column is unnamed: an index, skipped
  bool trailing_comma = false;  // the first line ends with ',': so does every line, no field after it
  while (!text.empty()) {
    const std::string_view line = next_line(text);
    ++number;
    const std::string_view body = trimmed(line);
    if (body.empty() || body.front() == '#') {
      parser.feed(std::string(line) + "\n");
      continue;
    }
    std::vector<std::string_view> fields = csv_fields(body);
    // A ',' ending every line, the first one's included (some spreadsheets write one): no field
    // after it. Where the first line has none, an empty last field is an error as any.
    if (!data_seen) trailing_comma = fields.size() > 1 && body.back() == ',';
    if (trailing_comma && fields.size() > 1 && body.back() == ',') fields.pop_back();
    auto fail = [&](const std::string& what) {
      const std::string shown(body.substr(0, 40));
      throw Error(name + ":" + std::to_string(number) + ": " + what + ", got '" + shown + (body.size() > 40 ? "...'" : "'"));
    };
    // A spreadsheet in a locale with a decimal comma exports "0,5;0,25" (was "not a number '5;0'"); no
    // field of ours holds a ';'.
    if (body.find(';') != std::string_view::npos)
      fail("fields separated by ';' (a spreadsheet's export where the decimal point is a comma); a CSV here has "
           "',' between fields and '.' in numbers");
    if (!data_seen) {
      data_seen = true;
      const CsvFirstLine first = csv_first_line(fields);
      if (first == CsvFirstLine::other_header) {
        // The tables bluetile itself writes as .csv, by their first column: the pandas advice that
        // follows fits them not.
        const std::string column = csv_name(fields[0]);
        const std::string_view own = column == "frequency" ? "bluetile analyze's radial.csv (radial power by frequency)"
                                     : column == "r"       ? "bluetile analyze's rdf.csv (the radial distribution function)"
                                     : column == "iteration"
                                         ? "a --log of bluetile relax or stipple (energy and displacement by iteration)"
                                         : "";
        const std::string header = "header '" + std::string(body.substr(0, 40)) + (body.size() > 40 ? "...'" : "'");
        if (!own.empty())
          throw Error(name + ":" + std::to_string(number) + ": " + header + ": " + std::string(own) +
                      ", not points; give the point file that was analysed or relaxed");
        throw Error(name + ":" + std::to_string(number) + ": " + header +
                    " names other columns: a CSV's header names x,y or x,y,level (an unnamed first column, pandas' "
                    "or R's index, is skipped); in pandas: df[['x', 'y']].to_csv(path, index=False)");
      }
      if (first != CsvFirstLine::data) {
        index_column = first == CsvFirstLine::index_and_columns;
        parser.feed("# " + std::string(body) + "\n");  // the header, as a comment: line numbers stay
        continue;
      }
    }
    if (index_column) {
      if (fields.size() < 2) fail("expected 'index,x,y' or 'index,x,y,level' (the header's first column is unnamed)");
      fields.erase(fields.begin());
    }
    if (fields.size() != 2 && fields.size() != 3)
      fail(index_column ? "expected 'index,x,y' or 'index,x,y,level' (the header's first column is unnamed)"
                        : "expected 'x,y' or 'x,y,level' (comma-separated)");
    std::string converted;
    for (std::string_view field : fields) {
      field = unquoted(field);
      if (field.empty()) fail("an empty field");
      if (field.find_first_of(" \t") != std::string_view::npos) fail("a field holding a blank");
      converted += std::string(field) + " ";
    }
    converted.back() = '\n';
    parser.feed(converted);
  }
  return parser.finish();
}

std::vector<PointSet> read_points_by_extension(const std::string& path, const ReadOptions& options) {
  const std::string extension = path == "-" ? "" : file_extension(path);
  std::vector<PointSet> sets;
  if (extension == ".npy") sets = parse_npy_table(read_input(path), input_name(path), options);
  else if (extension == ".bpt") sets = parse_binary_table(read_input(path), input_name(path), options);
  else if (extension == ".csv") sets = parse_csv_points(read_input(path), input_name(path), options);
  else if (extension == ".rps") sets = {read_rps_file(path, options)};
  else if (extension == ".npz") refuse_zip(path);
  else sets = read_by_content(path, options);
  return same_columns(std::move(sets), path);
}

}  // namespace bluetile
