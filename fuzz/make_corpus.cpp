// Writes the seed corpus of the fuzz targets (fuzz/corpus/): real files as the library writes
// them, small enough to mutate quickly. Built with the fuzzers (bluetile_fuzz_make_corpus);
//   build-fuzz/bluetile_fuzz_make_corpus fuzz/corpus
// rewrites them (the point-file seeds from the tool, `relax --sets`, `progressive`, come from
// fuzz/corpus/README.md's commands).
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "bluetile/core/point_file.h"
#include "bluetile/core/point_table.h"
#include "bluetile/core/rng.h"
#include "bluetile/tiling/tile_set.h"
#include "bluetile/tiling/tile_set_file.h"
#if BLUETILE_FUZZ_IMAGES
#include "bluetile/io/image_file.h"
#endif

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

// Seeds of tile_set_semantics_fuzzer.cpp: a kind byte, then per tile a shape byte and a damage
// byte (see there). All zeros: a sound set of 2 points a tile.
std::string semantics_seed(std::uint8_t kind, std::size_t tiles, std::size_t tile, std::uint8_t shape,
                           std::uint8_t damage) {
  std::string bytes(1 + 2 * tiles, '\0');
  bytes[0] = static_cast<char>(kind);
  for (std::size_t id = 0; id < tiles; ++id) bytes[2 + 2 * id] = static_cast<char>(0x40);  // 3 points, no damage
  bytes[1 + 2 * tile] = static_cast<char>(shape);
  bytes[2 + 2 * tile] = static_cast<char>(damage);
  return bytes;
}

#if BLUETILE_FUZZ_IMAGES
// A seed of density_map_fuzzer.cpp: the extension's index (its kExtensions), then the file that
// write_image_file makes for a small map.
void save_image(const std::string& root, const std::string& name, std::uint8_t extension, int width, int height,
                int channels, SampleFormat format) {
  const std::string scratch = root + "/density_map/scratch-" + name;
  std::vector<float> values(static_cast<std::size_t>(width * height * channels));
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<float>((i * 5) % 7) / 6.0f;
  write_image_file(scratch, width, height, channels, values, format);
  std::ifstream in(scratch, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::remove(scratch.c_str());
  save(root + "/density_map/" + name, std::string(1, static_cast<char>(extension)) + bytes);
}
#endif

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
  save(root + "/tile_set_semantics/wang8-sound.bin", semantics_seed(0, 8, 0, 0x40, 0xFF));
  save(root + "/tile_set_semantics/wang16-empty-tile.bin", semantics_seed(1, 16, 3, 5, 0xFF));
  save(root + "/tile_set_semantics/corner16-levels-fall.bin", semantics_seed(2, 16, 5, 0x40, 4));
#if BLUETILE_FUZZ_IMAGES
  save_image(root, "grey8.png", 0, 4, 3, 1, SampleFormat::uint8);
  save_image(root, "rgba16.png", 0, 2, 2, 4, SampleFormat::uint16);
  save_image(root, "grey.pgm", 1, 3, 2, 1, SampleFormat::uint8);
  save_image(root, "float.tif", 2, 2, 2, 1, SampleFormat::float32);
  save_image(root, "float.exr", 3, 2, 2, 1, SampleFormat::float32);
  save_image(root, "rgb.hdr", 4, 2, 2, 3, SampleFormat::float32);
  save_image(root, "rgb.bmp", 5, 2, 2, 3, SampleFormat::uint8);
#endif
  return 0;
}
