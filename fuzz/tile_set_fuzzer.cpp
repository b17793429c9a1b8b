// libFuzzer target for tile-set files (tiling/tile_set.h): no crash, no undefined behaviour,
// only bluetile::Error; a set that parses is written back bit for bit (the format's promise)
// and passes validate_tile_set.
#include <cstdint>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/tiling/tile_set.h"
#include "bluetile/tiling/tile_set_file.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  bluetile::TileSet set;
  try {
    set = bluetile::parse_tile_set(text, "fuzz");
  } catch (const bluetile::Error&) {
    return 0;
  }
  bluetile::validate_tile_set(set);  // throws (and so crashes here) if reading let a fault through
  const std::string written = bluetile::format_tile_set(set);
  const bluetile::TileSet again = bluetile::parse_tile_set(written, "again");
  BLUETILE_FUZZ_CHECK(bluetile::format_tile_set(again) == written);
  return 0;
}
