#include "cli/seam_report.h"

#include <cstdio>
#include <sstream>

namespace bluetile::cli {
namespace {

std::string relation_name(TileRelation relation) {
  switch (relation) {
    case TileRelation::east: return "east of";
    case TileRelation::north: return "north of";
    case TileRelation::north_east: return "north-east of";
    case TileRelation::north_west: return "north-west of";
  }
  return "?";
}

}  // namespace

std::string seam_report(const SeamCheck& check) {
  std::ostringstream out;
  out << "seam check: " << check.blocks << " admissible 2x2 blocks, " << check.tile_pairs << " tile pairs\n";
  char row[256];
  std::snprintf(row, sizeof row, "  %-6s %8s %10s %10s %8s %8s %6s  %s\n", "levels", "n/tile", "across", "within",
                "seamX", "within", "X/W", "closest pair across a seam");
  out << row;
  for (const SeamLevel& l : check.levels) {
    std::string pair = "tile " + std::to_string(l.closest.second_tile) + " point " +
                       std::to_string(l.closest.second_point) + " " + relation_name(l.closest.relation) + " tile " +
                       std::to_string(l.closest.first_tile) + " point " + std::to_string(l.closest.first_point);
    std::snprintf(row, sizeof row, "  0-%-4d %8zu %10.6f %10.6f %8.4f %8.4f %6.3f  %s\n", l.level, l.points_per_tile,
                  l.cross_min, l.within_min, l.cross_relative(), l.within_relative(), l.ratio(), pair.c_str());
    out << row;
  }
  out << "  (across: minimum distance between points of different tiles over every admissible block, tile units;\n"
         "   seamX and within: in hexagonal spacings of the tile's count; X/W = across / within)\n";
  return out.str();
}

}  // namespace bluetile::cli
