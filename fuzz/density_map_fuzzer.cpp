// libFuzzer target for density-map images (io/density_map.h, through io/image_file.h and the
// OpenImageIO plugin): whatever the bytes, reading them as a map never crashes, leaks or hangs;
// it gives a grid of finite non-negative texels of the image's size with some texel positive, or
// one bluetile::Error of one line naming the file. The first byte picks the file's extension
// (OpenImageIO chooses its reader by it, then tries the others) and the transfer; the rest is
// the file. OpenImageIO and the codecs are not instrumented: libFuzzer steers by our code only,
// and the seeds (fuzz/corpus/density_map) carry it into each format. While OpenImageIO reads,
// standard error goes into the error message (image_file.h), so a crash report from inside a read
// is lost from the log: run the crash-* input under gdb to see it.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#include <unistd.h>

#include "bluetile/core/error.h"
#include "bluetile/io/density_map.h"
#include "fuzz_support.h"

namespace {

// The formats the tool's documentation names for --density-map, and PGM, the simplest.
constexpr std::array<const char*, 6> kExtensions = {".png", ".pgm", ".tif", ".exr", ".hdr", ".bmp"};
// Enough for any seed and a mutation of it; a header claiming more is refused before decoding
// (read_image_file's limit), which is what the check exercises.
constexpr std::uint64_t kMaxPixels = 1 << 18;

// A folder of this process for the file, removed at exit. Plain characters: they outlive every
// destructor that runs before the exit handler.
char scratch[] = "/tmp/bluetile-fuzz-density-XXXXXX";

const char* scratch_folder() {
  static const bool made = [] {
    if (!mkdtemp(scratch)) std::abort();
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(scratch, ignored);
    });
    return true;
  }();
  (void)made;
  return scratch;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::uint8_t choice = data[0];
  const std::string path = std::string(scratch_folder()) + "/map" + kExtensions[choice % kExtensions.size()];
  {
    std::FILE* file = std::fopen(path.c_str(), "wb");
    BLUETILE_FUZZ_CHECK(file != nullptr);
    BLUETILE_FUZZ_CHECK(std::fwrite(data + 1, 1, size - 1, file) == size - 1);
    BLUETILE_FUZZ_CHECK(std::fclose(file) == 0);
  }
  bluetile::DensityTransfer transfer;
  const std::size_t curve = (choice / kExtensions.size()) % 3;
  transfer.curve = curve == 0 ? bluetile::TransferCurve::automatic
                   : curve == 1 ? bluetile::TransferCurve::srgb
                                : bluetile::TransferCurve::linear;
  transfer.invert = (choice / (kExtensions.size() * 3)) % 2 == 1;
  transfer.gamma = choice >= 128 ? 2.2 : 1.0;
  bluetile::DensityGrid grid;
  try {
    grid = bluetile::load_density_map(path, transfer, kMaxPixels);
  } catch (const bluetile::Error& e) {
    const std::string message = e.what();
    BLUETILE_FUZZ_CHECK(message.rfind(path + ": ", 0) == 0);
    BLUETILE_FUZZ_CHECK(message.find('\n') == std::string::npos);
    return 0;
  }
  BLUETILE_FUZZ_CHECK(grid.width > 0 && grid.height > 0);
  BLUETILE_FUZZ_CHECK(static_cast<std::uint64_t>(grid.width) * static_cast<std::uint64_t>(grid.height) <= kMaxPixels);
  BLUETILE_FUZZ_CHECK(grid.texels.size() == static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height));
  bool any_positive = false;
  for (float texel : grid.texels) {
    BLUETILE_FUZZ_CHECK(std::isfinite(texel) && texel >= 0.0f);
    any_positive |= texel > 0.0f;
  }
  BLUETILE_FUZZ_CHECK(any_positive);
  return 0;
}
