// Density maps from images (see density_map.h for the transfer). The sRGB curve is the one of
// IEC 61966-2-1; the luminance weights are those of Rec. ITU-R BT.709.
#include "bluetile/io/density_map.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "bluetile/core/error.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace {

std::string number(double v) {
  char text[32];
  const ClassicNumbers classic;
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

std::string pixel_name(int column, int row_from_top) {
  return "pixel (" + std::to_string(column) + ", " + std::to_string(row_from_top) + ") (column, row from the top)";
}

}  // namespace

double srgb_to_linear(double encoded) {
  if (encoded <= 0.04045) return encoded / 12.92;
  return std::pow((encoded + 0.055) / 1.055, 2.4);
}

DensityGrid density_from_image(const ImageFile& image, const DensityTransfer& transfer, const std::string& name) {
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0)
    throw Error(name + ": the image is empty (" + std::to_string(image.width) + " x " + std::to_string(image.height) +
                " pixels)");
  // The engines index texels with int; a picture this large would not fit in memory anyway.
  if (static_cast<long long>(image.width) * image.height > std::numeric_limits<int>::max())
    throw Error(name + ": the image is too large (" + std::to_string(image.width) + " x " +
                std::to_string(image.height) + " pixels)");
  if (!(transfer.gamma > 0.0) || !std::isfinite(transfer.gamma))
    throw Error(name + ": gamma " + number(transfer.gamma) + " is not a positive number");
  const bool decode_srgb = transfer.curve == TransferCurve::srgb ||
                           (transfer.curve == TransferCurve::automatic && !image.floating_point);
  const std::size_t channels = static_cast<std::size_t>(image.channels);
  const std::size_t colour_channels = channels >= 3 ? 3 : 1;
  // Grey + alpha, or RGBA: the last channel is alpha.
  const bool has_alpha = channels == 2 || channels == 4;

  DensityGrid grid(image.width, image.height);
  bool any_positive = false;
  // Every pixel at the blank end (white when inverted, else black): said so, the usual cause.
  bool all_blank = true;
  for (int r = 0; r < image.height; ++r) {
    const int row = image.height - 1 - r;  // y up
    for (int column = 0; column < image.width; ++column) {
      const float* sample =
          image.values.data() + (static_cast<std::size_t>(r) * static_cast<std::size_t>(image.width) +
                                 static_cast<std::size_t>(column)) * channels;
      double paper = 0.0;  // the white showing through: 1 - alpha
      if (has_alpha) {
        const double alpha = sample[channels - 1];
        if (!(alpha >= 0.0 && alpha <= 1.0))
          throw Error(name + ": " + pixel_name(column, r) + " has alpha " + number(alpha) + ": alpha must lie in [0, 1]");
        paper = 1.0 - alpha;
      }
      double linear[3];
      for (std::size_t c = 0; c < colour_channels; ++c) {
        const double v = sample[c];
        if (!std::isfinite(v) || v < 0.0)
          throw Error(name + ": " + pixel_name(column, r) + " channel " + std::to_string(c) + " is " + number(v) +
                      ": density samples must be finite and non-negative");
        linear[c] = decode_srgb ? srgb_to_linear(v + paper) : v + paper;
      }
      double density = colour_channels == 3 ? 0.2126 * linear[0] + 0.7152 * linear[1] + 0.0722 * linear[2] : linear[0];
      all_blank = all_blank && density == (transfer.invert ? 1.0 : 0.0);
      if (transfer.invert) {
        if (density > 1.0)
          throw Error(name + ": " + pixel_name(column, r) + " has luminance " + number(density) +
                      ", above 1: an inverted map needs values in [0, 1]");
        density = 1.0 - density;
      }
      if (transfer.gamma != 1.0) density = std::pow(density, transfer.gamma);
      const auto texel = static_cast<float>(density);
      if (!std::isfinite(texel))
        throw Error(name + ": " + pixel_name(column, r) + " gives density " + number(density) +
                    ", beyond float range");
      grid.at(column, row) = texel;
      any_positive |= texel > 0.0f;
    }
  }
  if (!any_positive) {
    const char* why = !all_blank       ? ""
                      : transfer.invert ? " (the image is white everywhere, and its dark parts are the dense ones)"
                                        : " (the image is black everywhere, and its bright parts are the dense ones)";
    throw Error(name + ": the density is zero everywhere" + why);
  }
  return grid;
}

DensityGrid load_density_map(const std::string& path, const DensityTransfer& transfer, std::uint64_t max_pixels) {
  return density_from_image(read_image_file(path, max_pixels), transfer, path);
}

}  // namespace bluetile
