// Writes the seed corpus of the fuzz targets (fuzz/corpus/): real files as the library writes
// them, small enough to mutate quickly. Built with the fuzzers (bluetile_fuzz_make_corpus);
//   build-fuzz/bluetile_fuzz_make_corpus fuzz/corpus
// rewrites them (the point-file seeds from the tool, `relax --sets`, `progressive`, come from
// fuzz/corpus/README.md's commands).
#include <cstdio>
#include <fstream>
#include <string>

#include "bluetile/core/point_file.h"
#include "bluetile/core/point_table.h"
#include "bluetile/core/rng.h"
#include "bluetile/tiling/tile_set.h"

using namespace bluetile;

namespace {

void save(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
  std::printf("%s: %zu bytes\n", path.c_str(), bytes.size());
}

PointSet random_set(std::size_t n, std::uint64_t seed, bool levels) {
  Rng rng(seed);
  PointSet set;
  for (std::size_t i = 0; i < n; ++i) {
    set.points.push_back(rng.point(Domain{}));
    if (levels) set.levels.push_back(static_cast<int>(i * 3 / n));
  }
  return set;
}

// A tile set of `kind` with `per_tile` points a tile, ranks in order, levels 0 then 1.
TileSet tile_set(TileSetKind kind, std::size_t per_tile) {
  TileRules rules(kind);
  TileSet set;
  set.kind = kind;
  set.header = {"fuzz seed: " + std::string(tile_set_kind_name(kind))};
  for (int id = 0; id < rules.tile_count(); ++id) {
    Tile tile;
    tile.colours = rules.colours(id);
    PointSet points = random_set(per_tile, 100 + static_cast<std::uint64_t>(id), false);
    for (std::size_t k = 0; k < per_tile; ++k) {
      tile.points.push_back(points.points[k]);
      tile.levels.push_back(k < per_tile / 2 ? 0 : 1);
      tile.ranks.push_back(static_cast<std::uint32_t>(k));
    }
    set.tiles.push_back(tile);
  }
  return set;
}

std::string table_bytes(TableFormat format, const std::vector<PointSet>& sets, bool float32) {
  std::string bytes;
  TableWriteOptions options;
  options.float32 = float32;
  write_table(format, point_sets_table(sets), options, "seed", [&](std::string_view piece) { bytes.append(piece); });
  return bytes;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string root = argc > 1 ? argv[1] : "fuzz/corpus";
  for (TileSetKind kind : tile_set_kinds())
    save(root + "/tile_set/" + std::string(tile_set_kind_name(kind)) + ".txt", format_tile_set(tile_set(kind, 3)));
  const std::vector<PointSet> two = {random_set(5, 1, false), random_set(5, 2, false)};
  const std::vector<PointSet> levels = {random_set(6, 3, true)};
  save(root + "/point_table/two-sets.npy", table_bytes(TableFormat::npy, two, false));
  save(root + "/point_table/levels-float32.npy", table_bytes(TableFormat::npy, levels, true));
  save(root + "/point_table/two-sets.bpt", table_bytes(TableFormat::binary, two, false));
  save(root + "/point_table/levels-float32.bpt", table_bytes(TableFormat::binary, levels, true));
  save(root + "/point_file/levels.txt", format_points(levels[0], {"made by bluetile_fuzz_make_corpus"}));
  return 0;
}
