// Density maps from images: any picture OpenImageIO reads (PNG, TIFF, EXR, ...; grey or RGB;
// 8-bit, 16-bit or float samples) becomes a DensityGrid of non-negative float texels, one per
// pixel, through a documented transfer:
//   1. decode each sample to linear light: the sRGB curve (IEC 61966-2-1) or none ("linear");
//      `automatic` decodes integer samples (PNG, 8/16-bit TIFF: sRGB by convention) and keeps
//      float samples (EXR: linear by convention) as they are;
//   2. luminance Y = 0.2126 R + 0.7152 G + 0.0722 B (Rec. 709, the sRGB primaries) for three
//      or more channels; the first channel of a grey image; an image with alpha (channel 2 of
//      grey + alpha, channel 4 of RGBA) is first laid on white paper, as a viewer shows it:
//      each sample (associated with alpha, as OpenImageIO reads it) gains 1 - alpha before
//      decoding, so a transparent pixel is white, not the black its zero samples would be
//      (under --invert, stipple's default, that made the background the densest ink);
//   3. `invert`: density 1 - Y, for maps where dark means dense (Y must then lie in [0, 1]);
//   4. `gamma`: density^gamma (1 keeps it).
// Orientation: the image's row 0 is the top of the picture as a viewer shows it (a photograph's
// EXIF or TIFF orientation tag applied, read_image_file) and the plane's y is up, so image row r
// becomes grid row height - 1 - r (density_grid.h); columns keep their order.
#pragma once

#include <string>

#include "bluetile/core/density_grid.h"
#include "bluetile/io/image_file.h"

namespace bluetile {

enum class TransferCurve { automatic, srgb, linear };

struct DensityTransfer {
  TransferCurve curve = TransferCurve::automatic;
  bool invert = false;
  double gamma = 1.0;  // > 0, finite
};

// The sRGB decoding curve (encoded value to linear light), continued as the same power law
// above 1.
double srgb_to_linear(double encoded);

// The grid of `image` under `transfer`. `name` stands for the image in error messages.
// Throws Error("<name>: <what>") for an empty image, a sample that is NaN, infinite or negative
// (naming its pixel as column, row from the top), a luminance above 1 under `invert`, a bad
// gamma, and a density that is zero everywhere.
DensityGrid density_from_image(const ImageFile& image, const DensityTransfer& transfer, const std::string& name);

// Reads the image at `path` and converts it as above. Throws Error naming the path when the file
// cannot be read or its content is refused, or when it has more than `max_pixels` pixels
// (read_image_file; checked on the header, before decoding).
DensityGrid load_density_map(const std::string& path, const DensityTransfer& transfer,
                             std::uint64_t max_pixels = kMaxImagePixels);

}  // namespace bluetile
