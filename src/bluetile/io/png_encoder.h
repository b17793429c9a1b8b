// The PNG encoder behind the images SvgDocument embeds; internal to the library (and its tests).
#pragma once

#include <cstdint>
#include <vector>

#include "bluetile/io/svg.h"

namespace bluetile {

// The PNG encoding of an 8-bit grey or RGB image (uncompressed deflate blocks: no zlib needed;
// the periodograms it embeds are noise and would not compress much anyway). Throws Error unless
// the pixel count matches width x height x channels (1 or 3).
std::vector<std::uint8_t> encode_png(const SvgImage& image);

}  // namespace bluetile
