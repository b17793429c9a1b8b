// Point files (DESIGN section 6): UTF-8 text, one point per line "x y" with an optional third
// column holding the point's level; '#' starts a comment; a first data line holding a single
// integer is a point count (psa's convention) and is checked. Coordinates outside [0,1) are
// wrapped onto the unit torus (or refused, see ReadOptions); NaN, infinity and malformed lines
// are errors naming the file and line. A comment line "# domain periodic" or "# domain bounded"
// says how the sets after it were made (analysis measures bounded sets in the plain square); a
// comment that looks meant as one but is not ("# domain bounde", "# Domain: bounded", "# domain
// periodic extra") is an error naming the line. A UTF-8 byte-order mark at the start is skipped; a
// line that is no point and holds a comma is refused with a hint that a .csv is read as CSV. Written with 17 significant digits so every
// double round-trips.
//
// Reading streams the file in chunks (memory: the points, not the text). Any failure, a
// malformed line, a read error, running out of memory, is an Error naming the file (and the
// line where there is one); a file is never silently cut short. Values quoted in messages are
// cut to a few dozen characters.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bluetile/core/output_file.h"
#include "bluetile/core/torus.h"

namespace bluetile {

struct PointSet {
  std::vector<Point> points;
  // Level of each point (hierarchical sets), or empty when the file had no level column.
  std::vector<int> levels;

  // What a "# domain ..." line before the set declared, if any.
  std::optional<Boundary> declared_boundary;
  // A text file's comment lines before the set's first point, the text after '#' (the first
  // kHeaderLines that are not blank): what a writer declared there, such as `bluetile tile`'s
  // tile grid. Read in the one pass over the file: a FIFO or standard input declares as much.
  std::vector<std::string> header;
  static constexpr std::size_t kHeaderLines = 32;

  bool has_levels() const { return !levels.empty(); }
};

// The rectangle [x0, x1) x [y0, y1) a file's coordinates lie in (ReadOptions::domain).
struct CoordinateBox {
  double x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0;
};

struct ReadOptions {
  // false: a coordinate outside [0, 1) (outside `domain` when there is one) is an error naming
  // the file, line and value, instead of being wrapped onto the torus. A set after a "# domain
  // bounded" line is never wrapped: it lies in its square, and a point outside is an error, said
  // with kBoundedNotWrapped.
  bool wrap = true;
  // The domain the set was made in: every coordinate is mapped linearly from [x0, x1) x [y0, y1)
  // onto the unit torus (a non-square box is stretched). None: the file is on the unit torus.
  std::optional<CoordinateBox> domain{};
};

inline constexpr std::string_view kBoundedNotWrapped =
    " (the set is declared '# domain bounded': its points lie in the square, and are not wrapped onto a torus)";

// A point as read, placed on the unit torus as `options` says. `outside` is set to the axis
// (0 x, 1 y) of a coordinate outside the domain when options.wrap is false (the point is then
// not placed), else -1.
Point place_read_point(Point read, const ReadOptions& options, int& outside);

// "[0, 1)", or the domain's range of that axis ("[0, 64)"), for messages.
std::string read_range_text(int axis, const ReadOptions& options);

// The largest level a point file may hold: writers must not go beyond what readers accept.
inline constexpr int kMaxLevel = 1000000;
// Said after a bad level: a three-column table of another kind (centroids' cx cy area) is the
// usual cause.
inline constexpr std::string_view kThirdColumnIsTheLevel =
    " (a point file's third column is the level; a table such as centroids' cx cy area is no point file)";

// The name used in messages for a path: "stdin" for "-", else the path.
std::string input_name(const std::string& path);

// Reads one point set from `path`, or from standard input when path is "-".
// Throws Error("<path>:<line>: <what>") on bad input, Error("<path>: <what>") on read failure.
PointSet read_point_file(const std::string& path, const ReadOptions& options = {});

// Several sets in one file, separated by lines starting with '#' (UTK's convention), as
// `relax --sets` writes them. Empty sets between consecutive '#' lines are skipped.
std::vector<PointSet> read_point_sets(const std::string& path, const ReadOptions& options = {});

// The same, from text in memory; `name` is used in error messages in place of a path.
PointSet parse_points(std::string_view text, const std::string& name, const ReadOptions& options = {});
std::vector<PointSet> parse_point_sets(std::string_view text, const std::string& name, const ReadOptions& options = {});

// Point-file text fed in pieces cut anywhere (the readers above feed 64 KiB chunks): the result,
// or the error, does not depend on where the cuts fall.
class PointTextParser {
 public:
  // `several_sets`: '#' lines separate sets (read_point_sets); else one set (read_point_file).
  PointTextParser(std::string name, bool several_sets, const ReadOptions& options = {});
  ~PointTextParser();
  PointTextParser(const PointTextParser&) = delete;
  PointTextParser& operator=(const PointTextParser&) = delete;

  void feed(std::string_view piece);  // throws Error on a bad line
  std::vector<PointSet> finish();     // throws Error; one set unless several_sets
  std::size_t lines() const;          // complete lines seen so far
  std::size_t points() const;         // points parsed so far

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

// Throws Error("<what>: '# domain: bounded' is not a domain line, ...") when `line`, written as a
// comment ("# " + line, as the writers below write it), is one the readers above refuse: a line
// that looks meant as "domain periodic" or "domain bounded" but is not. Every other line passes
// ("domain bounded" itself, prose). `what` names the line for the user (Python's "comment").
void check_comment_line(std::string_view line, const std::string& what);

// Streams a point file: optional header comment lines (each gets "# "), then one point a line.
// A header line the readers refuse (check_comment_line) throws Error before any byte.
// Throws Error, as check_written_points does (naming the output), before any byte.
void write_points(OutputStream& out, const PointSet& set, const std::vector<std::string>& header = {});

// The same text as a string (small sets; large ones stream through write_points).
// Throws Error as check_written_points does.
std::string format_points(const PointSet& set, const std::vector<std::string>& header = {});

// Throws Error("<what>levels: 1 for 2 points") for a level column whose length is neither 0 nor the
// number of points (what reads a level per point read it past its end).
void check_level_column(const PointSet& set, const std::string& what);

// Throws Error unless a reader would take `set` back: "<what>point 2 (nan, 0.5) is not finite: no
// reader would take it back", the same for a level outside 0 to kMaxLevel, and "<what>levels: 1
// for 2 points" for a level column as long as no set (it was read past its end). `what` begins
// the message ("out.txt: set 1, "; "" for none). The text writers wrote "nan" where they were given one.
void check_written_points(const PointSet& set, const std::string& what);

// Writes a point file through output_file.h ("-" is standard output).
void write_point_file(const std::string& path, const PointSet& set,
                      const std::vector<std::string>& header = {});

}  // namespace bluetile
