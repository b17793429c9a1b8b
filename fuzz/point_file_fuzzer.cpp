// libFuzzer target for point files (core/point_file.h). Beyond "no crash, no leak, no undefined
// behaviour, only bluetile::Error", it checks two properties:
// - cutting the text into pieces anywhere (as the 64 KiB file chunks do) changes nothing: the
//   same sets or the same message;
// - what parses, written back with write's %.17g, reads back bit for bit.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "bluetile/core/error.h"
#include "bluetile/core/point_file.h"
#include "fuzz_support.h"

namespace {

struct Parsed {
  std::vector<bluetile::PointSet> sets;
  std::string error;  // empty when it parsed
};

template <typename Parse>
Parsed attempt(Parse parse) {
  Parsed result;
  try {
    result.sets = parse();
  } catch (const bluetile::Error& e) {
    result.error = e.what();
  }
  return result;
}

bool same(const Parsed& a, const Parsed& b) {
  if (a.error != b.error || a.sets.size() != b.sets.size()) return false;
  for (std::size_t k = 0; k < a.sets.size(); ++k)
    if (a.sets[k].points != b.sets[k].points || a.sets[k].levels != b.sets[k].levels) return false;
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  for (bool several : {false, true}) {
    Parsed whole = attempt([&] {
      if (several) return bluetile::parse_point_sets(text, "fuzz");
      return std::vector<bluetile::PointSet>{bluetile::parse_points(text, "fuzz")};
    });
    // Piece sizes from the input's first byte: 1 to 256 bytes, so cuts fall everywhere.
    const std::size_t step = size ? 1 + data[0] : 1;
    Parsed pieces = attempt([&] {
      bluetile::PointTextParser parser("fuzz", several);
      for (std::size_t at = 0; at < size; at += step) parser.feed(text.substr(at, step));
      return parser.finish();
    });
    BLUETILE_FUZZ_CHECK(same(whole, pieces));
    if (!whole.error.empty() || several) continue;
    const bluetile::PointSet& set = whole.sets[0];
    for (const auto& p : set.points) BLUETILE_FUZZ_CHECK(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0);
    Parsed again = attempt([&] {
      return std::vector<bluetile::PointSet>{bluetile::parse_points(bluetile::format_points(set, {"round trip"}), "again")};
    });
    BLUETILE_FUZZ_CHECK(same(whole, again));
  }
  return 0;
}
