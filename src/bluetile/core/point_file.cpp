#include "bluetile/core/point_file.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "bluetile/core/atomic_file.h"
#include "bluetile/core/error.h"

namespace bluetile {
namespace {

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

class LineError {
 public:
  LineError(const std::string& name, std::size_t line) : name_(name), line_(line) {}
  [[noreturn]] void operator()(const std::string& what) const {
    throw Error(name_ + ":" + std::to_string(line_) + ": " + what);
  }

 private:
  const std::string& name_;
  std::size_t line_;
};

double parse_coordinate(std::string_view token, const LineError& fail) {
  double value = 0.0;
  auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec == std::errc::result_out_of_range) fail("coordinate out of range '" + std::string(token) + "'");
  if (ec != std::errc() || end != token.data() + token.size())
    fail("not a number '" + std::string(token) + "'");
  if (!std::isfinite(value)) fail("not a finite number '" + std::string(token) + "'");
  return value;
}

bool parse_integer(std::string_view token, long long& value) {
  auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

// Incrementally builds one set, checking each line.
class SetParser {
 public:
  SetParser(const std::string& name, const ReadOptions& options) : name_(name), options_(options) {}

  void declare(std::optional<Boundary> boundary) { set_.declared_boundary = boundary; }

  void data_line(std::string_view line, std::size_t number) {
    LineError fail(name_, number);
    auto tokens = split_whitespace(line);
    if (tokens.empty()) return;
    if (tokens.size() == 1) {
      long long count = 0;
      if (set_.points.empty() && count_line_ == 0 && parse_integer(tokens[0], count)) {
        if (count < 0) fail("negative point count '" + std::string(tokens[0]) + "'");
        declared_count_ = static_cast<std::size_t>(count);
        count_line_ = number;
        return;
      }
      fail("expected 'x y' or 'x y level', got '" + std::string(line) + "'");
    }
    if (tokens.size() > 3) fail("expected 'x y' or 'x y level', got " + std::to_string(tokens.size()) +
                                " columns: '" + std::string(line) + "'");
    Point p{parse_coordinate(tokens[0], fail), parse_coordinate(tokens[1], fail)};
    bool has_level = tokens.size() == 3;
    if (set_.points.empty()) {
      levels_seen_ = has_level;
    } else if (has_level != levels_seen_) {
      fail(has_level ? "level column appears here but not on earlier lines"
                     : "level column missing (earlier lines have one)");
    }
    if (has_level) {
      long long level = 0;
      if (!parse_integer(tokens[2], level) || level < 0 || level > 1000000)
        fail("level must be a non-negative integer, got '" + std::string(tokens[2]) + "'");
      set_.levels.push_back(static_cast<int>(level));
    }
    if (!options_.wrap) {
      for (int axis = 0; axis < 2; ++axis) {
        if (!(p[axis] >= 0.0 && p[axis] < 1.0))
          fail(std::string(axis == 0 ? "x" : "y") + " = " + std::string(tokens[static_cast<std::size_t>(axis)]) +
               " is outside [0, 1)");
      }
    }
    set_.points.push_back(wrap_point(p, Domain{}));
  }

  bool empty() const { return set_.points.empty() && count_line_ == 0; }

  PointSet finish() {
    if (count_line_ != 0 && declared_count_ != set_.points.size()) {
      LineError(name_, count_line_)("count line says " + std::to_string(declared_count_) +
                                    " points but " + std::to_string(set_.points.size()) + " follow");
    }
    PointSet result = std::move(set_);
    set_ = PointSet{};
    set_.declared_boundary = result.declared_boundary;  // a "# domain" line holds for later sets
    levels_seen_ = false;
    declared_count_ = 0;
    count_line_ = 0;
    return result;
  }

 private:
  std::string name_;
  ReadOptions options_;
  PointSet set_;
  bool levels_seen_ = false;
  std::size_t declared_count_ = 0;
  std::size_t count_line_ = 0;
};

std::string read_whole_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open: " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(path + ": read failed");
  return text.str();
}

// The boundary a comment declares ("domain periodic" / "domain bounded"), if it is such a line.
std::optional<Boundary> declared_boundary(std::string_view comment) {
  auto words = split_whitespace(comment);
  if (words.size() != 2 || words[0] != "domain") return std::nullopt;
  if (words[1] == "periodic") return Boundary::periodic;
  if (words[1] == "bounded") return Boundary::bounded;
  return std::nullopt;
}

// Calls on_line(content without comment, line number, starts_with_hash, comment text after '#')
// for every line.
template <typename OnLine>
void for_each_line(const std::string& text, const std::string& name, OnLine on_line) {
  std::size_t number = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + start, end - start);
    ++number;
    if (line.find('\0') != std::string_view::npos)
      LineError(name, number)("binary data (NUL byte): not a point file");
    std::size_t hash = line.find('#');
    bool comment_line = split_whitespace(line.substr(0, hash)).empty() && hash != std::string_view::npos;
    on_line(line.substr(0, hash), number, comment_line,
            hash == std::string_view::npos ? std::string_view() : line.substr(hash + 1));
    start = end + 1;
  }
}

}  // namespace

PointSet parse_points(const std::string& text, const std::string& name, const ReadOptions& options) {
  SetParser parser(name, options);
  for_each_line(text, name, [&](std::string_view line, std::size_t number, bool comment_line, std::string_view comment) {
    if (comment_line && parser.empty())
      if (auto boundary = declared_boundary(comment)) parser.declare(boundary);
    parser.data_line(line, number);
  });
  return parser.finish();
}

PointSet read_point_file(const std::string& path, const ReadOptions& options) {
  return parse_points(read_whole_file(path), path, options);
}

std::vector<PointSet> read_point_sets(const std::string& path, const ReadOptions& options) {
  std::string text = read_whole_file(path);
  std::vector<PointSet> sets;
  SetParser parser(path, options);
  for_each_line(text, path, [&](std::string_view line, std::size_t number, bool comment_line, std::string_view comment) {
    if (comment_line) {
      if (!parser.empty()) sets.push_back(parser.finish());
      if (auto boundary = declared_boundary(comment)) parser.declare(boundary);
      return;
    }
    parser.data_line(line, number);
  });
  if (!parser.empty()) sets.push_back(parser.finish());
  return sets;
}

std::string format_points(const PointSet& set, const std::vector<std::string>& header) {
  std::string text;
  text.reserve(set.points.size() * 42 + 64);
  for (const auto& line : header) text += "# " + line + "\n";
  char buffer[96];
  for (std::size_t i = 0; i < set.points.size(); ++i) {
    int n = set.has_levels()
                ? std::snprintf(buffer, sizeof buffer, "%.17g %.17g %d\n", set.points[i].x,
                                set.points[i].y, set.levels[i])
                : std::snprintf(buffer, sizeof buffer, "%.17g %.17g\n", set.points[i].x, set.points[i].y);
    text.append(buffer, static_cast<std::size_t>(n));
  }
  return text;
}

void write_point_file(const std::string& path, const PointSet& set, const std::vector<std::string>& header) {
  write_text_atomically(path, format_points(set, header));
}

}  // namespace bluetile
