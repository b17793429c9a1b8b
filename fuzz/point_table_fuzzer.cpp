// libFuzzer target for the binary point tables (core/point_table.h: npy, .bpt, CSV, psa's .rps): no crash, no
// undefined behaviour, no allocation beyond what the bytes can hold, only bluetile::Error; every
// value read is finite.
#include <cmath>
#include <cstdint>
#include <string_view>

#include "bluetile/core/error.h"
#include "bluetile/core/point_table.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // Through pointers the default ReadOptions must be given.
  for (auto parse : {&bluetile::parse_npy_table, &bluetile::parse_binary_table, &bluetile::parse_csv_points}) {
    try {
      for (const bluetile::PointSet& set : parse(bytes, "fuzz", bluetile::ReadOptions{}))
        for (const auto& p : set.points) BLUETILE_FUZZ_CHECK(std::isfinite(p.x) && std::isfinite(p.y));
    } catch (const bluetile::Error&) {
    }
  }
  for (bool wrap : {true, false}) {
    try {
      for (const auto& p : bluetile::parse_rps_points(bytes, "fuzz", {.wrap = wrap}).points)
        BLUETILE_FUZZ_CHECK(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0);
    } catch (const bluetile::Error&) {
    }
  }
  return 0;
}
