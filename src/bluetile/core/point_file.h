// Point files (DESIGN section 6): UTF-8 text, one point per line "x y" with an optional third
// column holding the point's level; '#' starts a comment; a first data line holding a single
// integer is a point count (psa's convention) and is checked. Coordinates outside [0,1) are
// wrapped onto the unit torus (or refused, see ReadOptions); NaN, infinity and malformed lines
// are errors naming the file and line. A comment line "# domain periodic" or "# domain bounded"
// says how the sets after it were made (analysis measures bounded sets in the plain square).
// Written with 17 significant digits so every double round-trips.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile {

struct PointSet {
  std::vector<Point> points;
  // Level of each point (hierarchical sets), or empty when the file had no level column.
  std::vector<int> levels;

  // What a "# domain ..." line before the set declared, if any.
  std::optional<Boundary> declared_boundary;

  bool has_levels() const { return !levels.empty(); }
};

struct ReadOptions {
  // false: a coordinate outside [0, 1) is an error naming the file, line and value, instead of
  // being wrapped onto the torus.
  bool wrap = true;
};

// Reads one point set. Throws Error("<path>:<line>: <what>") on bad input.
PointSet read_point_file(const std::string& path, const ReadOptions& options = {});

// Parses point-file text; `name` is used in error messages in place of a path.
PointSet parse_points(const std::string& text, const std::string& name, const ReadOptions& options = {});

// Several sets in one file, separated by lines starting with '#' (UTK's convention), as
// `relax --sets` writes them. Empty sets between consecutive '#' lines are skipped.
std::vector<PointSet> read_point_sets(const std::string& path, const ReadOptions& options = {});

// Text of a point file: optional header comment lines (each gets "# "), then one point a line.
std::string format_points(const PointSet& set, const std::vector<std::string>& header = {});

// Writes atomically (temporary file, then rename).
void write_point_file(const std::string& path, const PointSet& set,
                      const std::vector<std::string>& header = {});

}  // namespace bluetile
