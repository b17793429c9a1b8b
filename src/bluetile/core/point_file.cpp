#include "bluetile/core/point_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <memory>
#include <new>

#include "bluetile/core/error.h"
#include "bluetile/core/input_file.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace {

// Values quoted in messages are cut to this many bytes: a message stays one readable line.
constexpr std::size_t kQuoteLength = 40;

// 'value', cut: 'first 40 bytes...' (N bytes).
std::string quote(std::string_view value) {
  // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on a literal + string chain.
  std::string text(1, '\'');
  text.append(value.substr(0, kQuoteLength));
  text += '\'';
  if (value.size() > kQuoteLength) {
    text.insert(text.size() - 1, "...");
    text += " (" + std::to_string(value.size()) + " bytes)";
  }
  return text;
}

// The same without the quotes (a value that parsed as a number).
std::string shortened(std::string_view value) {
  if (value.size() <= kQuoteLength) return std::string(value);
  return std::string(value.substr(0, kQuoteLength)) + "... (" + std::to_string(value.size()) + " bytes)";
}

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// The first tokens of a line (up to kKept) and how many there are in all.
struct Tokens {
  static constexpr std::size_t kKept = 3;
  std::string_view kept[kKept];
  std::size_t count = 0;
};

Tokens split_whitespace(std::string_view line) {
  Tokens tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_blank(line[i])) ++i;
    std::size_t start = i;
    while (i < line.size() && !is_blank(line[i])) ++i;
    if (i > start) {
      if (tokens.count < Tokens::kKept) tokens.kept[tokens.count] = line.substr(start, i - start);
      ++tokens.count;
    }
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

// Said after a text line that holds a comma: a CSV given where text is read.
constexpr std::string_view kCommaHint = " (comma-separated values: a file named .csv is read as CSV)";

// `hint` follows the message of a token that is no number.
double parse_coordinate(std::string_view token, const LineError& fail, std::string_view hint = {}) {
  double value = 0.0;
  // A leading '+', as C, Python and NumPy write and read it (from_chars takes only '-').
  std::string_view digits = token;
  if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-' && digits[1] != '+') digits.remove_prefix(1);
  auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (end != digits.data() + digits.size() || ec == std::errc::invalid_argument)
    fail("not a number " + quote(token) + std::string(hint));
  if (ec == std::errc::result_out_of_range) {
    // Out of range both ways: a number too small for a double (1e-330) is 0, one too large is an
    // error. strtod tells them apart (the tool keeps the C locale's decimal point).
    const ClassicNumbers classic;
    const double nearest = std::strtod(std::string(digits).c_str(), nullptr);
    if (!(std::abs(nearest) < 1.0)) fail("coordinate out of range " + quote(token));
    value = nearest;
  }
  if (!std::isfinite(value)) fail("not a finite number " + quote(token));
  return value == 0.0 ? 0.0 : value;  // "-0" is the torus's 0, written back as "0"
}

bool parse_integer(std::string_view token, long long& value) {
  auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

// Incrementally builds one set, checking each line.
class SetParser {
 public:
  SetParser(const std::string& name, const ReadOptions& options) : name_(name), options_(options), bounded_(options) {
    bounded_.wrap = false;
  }

  void declare(std::optional<Boundary> boundary) { set_.declared_boundary = boundary; }
  // A comment line before the set's first point. A bare '#' (between the sets of a file of
  // several: UTK's files have one before each) says nothing and costs nothing.
  void header_line(std::string_view comment) {
    if (split_whitespace(comment).count == 0) return;
    if (set_.points.empty() && set_.header.size() < PointSet::kHeaderLines) set_.header.emplace_back(comment);
  }

  void data_line(std::string_view line, std::size_t number) {
    LineError fail(name_, number);
    const std::string_view hint = line.find(',') != std::string_view::npos ? kCommaHint : std::string_view{};
    Tokens tokens = split_whitespace(line);
    if (tokens.count == 0) return;
    // A C header (--format header, save_table's .h) begins with a '//' comment; its commas drew the
    // CSV hint, which fits it not.
    if (tokens.kept[0].substr(0, 2) == "//" || tokens.kept[0].substr(0, 2) == "/*")
      fail("a C or C++ source line " + quote(line) +
           ": a C header (bluetile writes one for --format header) is compiled in, not read back; read the points from "
           "the text, .npy or .bpt file it was made from");
    if (tokens.count == 1) {
      long long count = 0;
      if (set_.points.empty() && count_line_ == 0 && parse_integer(tokens.kept[0], count)) {
        if (count < 0) fail("negative point count " + quote(tokens.kept[0]));
        declared_count_ = static_cast<std::size_t>(count);
        count_line_ = number;
        return;
      }
      fail("expected 'x y' or 'x y level', got " + quote(line) + std::string(hint));
    }
    if (tokens.count > 3)
      fail("expected 'x y' or 'x y level', got " + std::to_string(tokens.count) + " columns: " + quote(line) +
           std::string(hint));
    Point p{parse_coordinate(tokens.kept[0], fail, hint), parse_coordinate(tokens.kept[1], fail, hint)};
    bool has_level = tokens.count == 3;
    if (set_.points.empty()) {
      levels_seen_ = has_level;
    } else if (has_level != levels_seen_) {
      fail(has_level ? "level column appears here but not on earlier lines"
                     : "level column missing (earlier lines have one)");
    }
    if (has_level) {
      long long level = 0;
      if (!parse_integer(tokens.kept[2], level) || level < 0 || level > kMaxLevel)
        fail("level must be an integer from 0 to " + std::to_string(kMaxLevel) + ", got " + quote(tokens.kept[2]) +
             std::string(kThirdColumnIsTheLevel));
      set_.levels.push_back(static_cast<int>(level));
    }
    // A set declared bounded lies in its square, not on a torus: a point outside it is refused, not
    // wrapped (it was moved into the square without a word).
    const bool bounded = set_.declared_boundary == Boundary::bounded;
    int outside = -1;
    const Point placed = place_read_point(p, bounded ? bounded_ : options_, outside);
    if (outside >= 0)
      fail(std::string(outside == 0 ? "x" : "y") + " = " + shortened(tokens.kept[outside]) + " is outside " +
           read_range_text(outside, options_) + (bounded ? std::string(kBoundedNotWrapped) : ""));
    set_.points.push_back(placed);
  }

  bool empty() const { return set_.points.empty() && count_line_ == 0; }
  std::size_t size() const { return set_.points.size(); }

  PointSet finish() {
    if (count_line_ != 0 && declared_count_ != set_.points.size()) {
      LineError(name_, count_line_)("count line says " + std::to_string(declared_count_) + " points but " +
                                    std::to_string(set_.points.size()) + " follow");
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
  ReadOptions bounded_;  // options_ for a set declared bounded: nothing wrapped
  PointSet set_;
  bool levels_seen_ = false;
  std::size_t declared_count_ = 0;
  std::size_t count_line_ = 0;
};

// Single-character edits between a and b (Levenshtein), for telling a typo from prose.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// What a comment (the text after '#') says about the domain. A comment that looks meant as a
// domain line but is not ("domain bounde", "Domain Bounded", "domain periodic extra", "domain
// bounded, unit square") is `malformed`: read as a comment, it left the set on the default torus
// without a word. Prose that merely starts with "domain" ("domain [0, 64)^2") is `none`, a comment.
enum class DomainComment { none, periodic, bounded, malformed };

DomainComment classify_comment(std::string_view comment) {
  Tokens words = split_whitespace(comment);
  if (words.count == 0) return DomainComment::none;
  if (words.count == 2 && words.kept[0] == "domain") {
    if (words.kept[1] == "periodic") return DomainComment::periodic;
    if (words.kept[1] == "bounded") return DomainComment::bounded;
  }
  // Any case, a ':' after "domain", words after the boundary, or one word that is a typo of one
  // or two letters ("bounde", "periodc"; "domain bounds 0 0 64 64" is prose).
  std::string first = lower_case(std::string(words.kept[0]));
  if (!first.empty() && first.back() == ':') first.pop_back();
  if (first != "domain" || words.count < 2) return DomainComment::none;
  const std::string second = lower_case(std::string(words.kept[1]));
  constexpr std::size_t kTypoEdits = 2;
  // The boundary with punctuation after it ("bounded,") is the boundary too.
  std::string bare = second;
  while (!bare.empty() && std::string_view(",;.:").find(bare.back()) != std::string_view::npos) bare.pop_back();
  const bool boundary_word = bare == "periodic" || bare == "bounded";
  // Words a letter or two from a boundary that mean something of their own ("# domain aperiodic":
  // a tiling of the plane; "# domain unbounded") are prose, not typos.
  constexpr std::string_view kWords[] = {"aperiodic", "unbounded", "bounds", "rounded", "founded", "bound", "period"};
  const bool word = std::find(std::begin(kWords), std::end(kWords), second) != std::end(kWords);
  const bool typo = words.count == 2 && !word &&
                    (edit_distance(second, "periodic") <= kTypoEdits || edit_distance(second, "bounded") <= kTypoEdits);
  return boundary_word || typo ? DomainComment::malformed : DomainComment::none;
}

// "'# domain: bounded' is not a domain line", the line as the reader sees it, for both the
// reader's message and the writers'.
std::string not_a_domain_line(std::string_view comment) {
  while (!comment.empty() && is_blank(comment.front())) comment.remove_prefix(1);
  while (!comment.empty() && is_blank(comment.back())) comment.remove_suffix(1);
  return quote("# " + std::string(comment)) + " is not a domain line";
}

// The boundary a comment declares, if it is a domain line; Error for a malformed one.
std::optional<Boundary> declared_boundary(std::string_view comment, const LineError& fail) {
  switch (classify_comment(comment)) {
    case DomainComment::periodic: return Boundary::periodic;
    case DomainComment::bounded: return Boundary::bounded;
    case DomainComment::none: return std::nullopt;
    case DomainComment::malformed: break;
  }
  fail(not_a_domain_line(comment) +
       ": write '# domain periodic' or '# domain bounded' alone on the line (or reword the comment)");
}

}  // namespace

Point place_read_point(Point read, const ReadOptions& options, int& outside) {
  outside = -1;
  const CoordinateBox box = options.domain.value_or(CoordinateBox{});
  const double low[2] = {box.x0, box.y0}, high[2] = {box.x1, box.y1};
  Point unit = read;
  for (int axis = 0; axis < 2; ++axis) {
    if (!options.wrap && !(read[axis] >= low[axis] && read[axis] < high[axis])) {
      outside = axis;
      return read;
    }
    if (!options.domain) continue;
    unit[axis] = (read[axis] - low[axis]) / (high[axis] - low[axis]);
    // A coordinate just below the box's end may round to 1, which the wrap below would take to 0,
    // the other side of a bounded square: it stays at the end.
    if (unit[axis] == 1.0 && read[axis] < high[axis]) unit[axis] = std::nextafter(1.0, 0.0);
  }
  return wrap_point(unit, Domain{});
}

std::string read_range_text(int axis, const ReadOptions& options) {
  const CoordinateBox box = options.domain.value_or(CoordinateBox{});
  const ClassicNumbers classic;
  char text[80];
  std::snprintf(text, sizeof text, "[%.17g, %.17g)", axis == 0 ? box.x0 : box.y0, axis == 0 ? box.x1 : box.y1);
  return text;
}

// Splits text fed in arbitrary chunks into lines and hands them to one set parser (or, with
// `several`, one per '#'-separated set).
class PointTextParser::Impl {
 public:
  Impl(std::string name, bool several, const ReadOptions& options)
      : name_(std::move(name)), several_(several), parser_(name_, options) {}

  void feed(std::string_view chunk) {
    if (at_start_) {
      // A UTF-8 byte-order mark (some editors write one) is not part of the first line.
      static constexpr std::string_view kBom = "\xEF\xBB\xBF";
      // UTF-16's, either byte order: Windows PowerShell's '>' and Out-File write it. Its NUL bytes
      // were "binary data (NUL byte): not a point file".
      static constexpr std::string_view kUtf16Little = "\xFF\xFE", kUtf16Big = "\xFE\xFF";
      carry_.append(chunk);
      if (carry_.size() < kBom.size() && kBom.substr(0, carry_.size()) == carry_) return;  // undecided yet
      if (carry_.size() < kUtf16Little.size() && (carry_ == kUtf16Little.substr(0, 1) || carry_ == kUtf16Big.substr(0, 1)))
        return;
      const std::string_view head(carry_);
      if (head.substr(0, 2) == kUtf16Little || head.substr(0, 2) == kUtf16Big)
        throw Error(name_ + ": UTF-16 text (Windows PowerShell's '>' and Out-File write it); point files are UTF-8: "
                            "save it with Out-File -Encoding utf8 (or Set-Content)");
      at_start_ = false;
      std::string text = std::move(carry_);
      carry_.clear();
      std::string_view rest(text);
      if (rest.substr(0, kBom.size()) == kBom) rest.remove_prefix(kBom.size());
      feed_lines(rest);
      return;
    }
    feed_lines(chunk);
  }

  std::vector<PointSet> finish() {
    if (at_start_) {  // fewer bytes than a byte-order mark
      at_start_ = false;
      std::string text = std::move(carry_);
      carry_.clear();
      feed_lines(text);
    }
    if (!carry_.empty()) {  // last line without a newline
      std::string last = std::move(carry_);
      carry_.clear();
      line(last);
    }
    if (!several_ || !parser_.empty()) sets_.push_back(parser_.finish());
    return std::move(sets_);
  }

  std::size_t line_number() const { return number_; }
  std::size_t points_read() const {
    std::size_t n = parser_.size();
    for (const PointSet& s : sets_) n += s.points.size();
    return n;
  }

 private:
  // A line ends at "\n", "\r\n" or a lone "\r" (classic Mac OS; its files were one long line).
  void feed_lines(std::string_view chunk) {
    while (!chunk.empty()) {
      if (after_cr_) {  // the "\n" of a "\r\n", perhaps in the next chunk
        after_cr_ = false;
        if (chunk.front() == '\n') {
          chunk.remove_prefix(1);
          continue;
        }
      }
      std::size_t end = chunk.find_first_of("\r\n");
      if (end == std::string_view::npos) {
        carry_.append(chunk);
        return;
      }
      if (carry_.empty()) {
        line(chunk.substr(0, end));
      } else {
        carry_.append(chunk.substr(0, end));
        std::string whole = std::move(carry_);
        carry_.clear();
        line(whole);
      }
      after_cr_ = chunk[end] == '\r';
      chunk.remove_prefix(end + 1);
    }
  }

  void line(std::string_view text) {
    ++number_;
    if (text.find('\0') != std::string_view::npos)
      LineError(name_, number_)("binary data (NUL byte): not a point file");
    std::size_t hash = text.find('#');
    std::string_view data = text.substr(0, hash);
    const bool comment_line = hash != std::string_view::npos && split_whitespace(data).count == 0;
    if (comment_line) {
      const std::string_view comment = text.substr(hash + 1);
      const std::optional<Boundary> boundary = declared_boundary(comment, LineError(name_, number_));
      // In a file of several sets a '#' line ends a set (UTK's convention): it speaks for the next.
      if (several_ && !parser_.empty()) sets_.push_back(parser_.finish());
      if (boundary && parser_.empty()) parser_.declare(boundary);
      parser_.header_line(comment);
      return;
    }
    parser_.data_line(data, number_);
  }

  std::string name_;
  bool several_;
  SetParser parser_;
  std::vector<PointSet> sets_;
  std::string carry_;  // an incomplete line (or, at the start, bytes that may be a byte-order mark)
  bool at_start_ = true;
  bool after_cr_ = false;  // the last line ended at a "\r"
  std::size_t number_ = 0;
};

PointTextParser::PointTextParser(std::string name, bool several_sets, const ReadOptions& options)
    : impl_(std::make_unique<Impl>(std::move(name), several_sets, options)) {}
PointTextParser::~PointTextParser() = default;
void PointTextParser::feed(std::string_view piece) { impl_->feed(piece); }
std::vector<PointSet> PointTextParser::finish() { return impl_->finish(); }
std::size_t PointTextParser::lines() const { return impl_->line_number(); }
std::size_t PointTextParser::points() const { return impl_->points_read(); }

namespace {

std::vector<PointSet> parse(std::string_view text, const std::string& name, bool several, const ReadOptions& options) {
  PointTextParser parser(name, several, options);
  parser.feed(text);
  return parser.finish();
}

std::vector<PointSet> read(const std::string& path, bool several, const ReadOptions& options) {
  const std::string name = input_name(path);
  PointTextParser parser(name, several, options);
  try {
    for_each_chunk(path, [&](std::string_view chunk) { parser.feed(chunk); });
    return parser.finish();
  } catch (const std::bad_alloc&) {
    throw Error(name + ":" + std::to_string(parser.lines()) + ": out of memory after " + std::to_string(parser.points()) +
                " points");
  }
}

}  // namespace

std::string input_name(const std::string& path) { return path == "-" ? "stdin" : path; }

PointSet parse_points(std::string_view text, const std::string& name, const ReadOptions& options) {
  return std::move(parse(text, name, false, options).front());
}

std::vector<PointSet> parse_point_sets(std::string_view text, const std::string& name, const ReadOptions& options) {
  return parse(text, name, true, options);
}

PointSet read_point_file(const std::string& path, const ReadOptions& options) {
  return std::move(read(path, false, options).front());
}

std::vector<PointSet> read_point_sets(const std::string& path, const ReadOptions& options) {
  return read(path, true, options);
}

void check_comment_line(std::string_view line, const std::string& what) {
  // As written: the reader sees the escaped text after the "#".
  const std::string written = comment_line(line);
  if (classify_comment(written) != DomainComment::malformed) return;
  throw Error(what + ": " + not_a_domain_line(written) +
              ", and reading the file back would fail on it: write 'domain periodic' or 'domain bounded' alone "
              "(the writer adds the '#') to declare the domain, or reword the comment");
}

namespace {

// Before any byte: a header line the reader refuses made a file nobody could read back.
void check_header(const std::vector<std::string>& header) {
  for (std::size_t i = 0; i < header.size(); ++i) check_comment_line(header[i], "comment line " + std::to_string(i + 1));
}

}  // namespace

void check_level_column(const PointSet& set, const std::string& what) {
  if (set.has_levels() && set.levels.size() != set.points.size())
    throw Error(what + "levels: " + std::to_string(set.levels.size()) + " for " + std::to_string(set.points.size()) +
                " points");
}

void check_written_points(const PointSet& set, const std::string& what) {
  check_level_column(set, what);
  for (std::size_t i = 0; i < set.points.size(); ++i) {
    const Point p = set.points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y))
      throw Error(what + "point " + std::to_string(i) + " (" + exact_text(p.x) + ", " + exact_text(p.y) +
                  ") is not finite: no reader would take it back");
    if (set.has_levels() && (set.levels[i] < 0 || set.levels[i] > kMaxLevel))
      throw Error(what + "point " + std::to_string(i) + ": level " + std::to_string(set.levels[i]) + " is outside 0 to " +
                  std::to_string(kMaxLevel) + ": no reader would take it back");
  }
}

void write_points(OutputStream& out, const PointSet& set, const std::vector<std::string>& header) {
  check_header(header);
  check_written_points(set, out.path() + ": ");
  for (const auto& line : header) {
    out.write("# ");
    out.write(comment_line(line));
    out.put('\n');
  }
  // %.17g: 17 significant digits make every double round-trip.
  for (std::size_t i = 0; i < set.points.size(); ++i) {
    if (set.has_levels()) {
      out.print("%.17g %.17g %d\n", set.points[i].x, set.points[i].y, set.levels[i]);
    } else {
      out.print("%.17g %.17g\n", set.points[i].x, set.points[i].y);
    }
  }
}

std::string format_points(const PointSet& set, const std::vector<std::string>& header) {
  check_header(header);
  check_written_points(set, "");
  std::string text;
  for (const auto& line : header) text += "# " + comment_line(line) + "\n";
  const ClassicNumbers classic;
  char buffer[96];
  for (std::size_t i = 0; i < set.points.size(); ++i) {
    int n = set.has_levels() ? std::snprintf(buffer, sizeof buffer, "%.17g %.17g %d\n", set.points[i].x, set.points[i].y,
                                             set.levels[i])
                             : std::snprintf(buffer, sizeof buffer, "%.17g %.17g\n", set.points[i].x, set.points[i].y);
    text.append(buffer, static_cast<std::size_t>(n));
  }
  return text;
}

void write_point_file(const std::string& path, const PointSet& set, const std::vector<std::string>& header) {
  write_output(path, [&](OutputStream& out) { write_points(out, set, header); }, {.allow_stdout = true});
}

}  // namespace bluetile
