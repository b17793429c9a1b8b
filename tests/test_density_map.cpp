// Density maps: the transfer from image samples to texels, orientation, file formats, the
// errors for bad images, and bilinear lookup.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "bluetile/core/error.h"
#include "bluetile/io/density_map.h"
#include "test_support.h"

namespace bluetile {
namespace {

using test::error_of;

ImageFile grey_image(int width, int height, std::vector<float> values, bool floating_point = false) {
  ImageFile image;
  image.width = width;
  image.height = height;
  image.channels = 1;
  image.values = std::move(values);
  image.floating_point = floating_point;
  return image;
}

TEST(DensityMap, SrgbCurveAtKnownValues) {
  EXPECT_DOUBLE_EQ(srgb_to_linear(0.0), 0.0);
  EXPECT_DOUBLE_EQ(srgb_to_linear(1.0), 1.0);
  EXPECT_NEAR(srgb_to_linear(0.5), 0.214041140, 1e-9);   // ((0.5 + 0.055) / 1.055)^2.4
  EXPECT_DOUBLE_EQ(srgb_to_linear(0.04), 0.04 / 12.92);  // the linear toe
}

TEST(DensityMap, ImageRowZeroIsTheTopOfThePlane) {
  // 2 x 3 picture: the top row bright, the bottom row dark.
  ImageFile image = grey_image(2, 3, {1.0f, 0.5f, 0.25f, 0.25f, 0.0f, 0.125f});
  DensityTransfer linear;
  linear.curve = TransferCurve::linear;
  DensityGrid grid = density_from_image(image, linear, "picture");
  ASSERT_EQ(grid.width, 2);
  ASSERT_EQ(grid.height, 3);
  EXPECT_EQ(grid.at(0, 2), 1.0f);  // image (0, 0): top left -> grid row 2 (top)
  EXPECT_EQ(grid.at(1, 2), 0.5f);
  EXPECT_EQ(grid.at(0, 1), 0.25f);
  EXPECT_EQ(grid.at(0, 0), 0.0f);  // image (0, 2): bottom left -> grid row 0
  EXPECT_EQ(grid.at(1, 0), 0.125f);
}

TEST(DensityMap, TransferDecodesInvertsAndRaisesToGamma) {
  ImageFile image = grey_image(2, 1, {0.5f, 1.0f});
  DensityTransfer t;  // automatic: integer samples are sRGB
  DensityGrid grid = density_from_image(image, t, "g");
  EXPECT_NEAR(grid.at(0, 0), 0.214041140, 1e-7);
  EXPECT_EQ(grid.at(1, 0), 1.0f);
  // The same samples stored as float are linear under `automatic`.
  image.floating_point = true;
  EXPECT_EQ(density_from_image(image, t, "g").at(0, 0), 0.5f);
  t.curve = TransferCurve::srgb;  // ...unless asked
  EXPECT_NEAR(density_from_image(image, t, "g").at(0, 0), 0.214041140, 1e-7);

  t.curve = TransferCurve::linear;
  t.invert = true;
  t.gamma = 2.0;
  grid = density_from_image(grey_image(2, 1, {0.25f, 0.0f}), t, "g");
  EXPECT_EQ(grid.at(0, 0), 0.5625f);  // (1 - 0.25)^2
  EXPECT_EQ(grid.at(1, 0), 1.0f);
}

TEST(DensityMap, LuminanceOfColourLaidOnWhitePaper) {
  // Samples associated with alpha (as OpenImageIO reads them): each gains 1 - alpha, the white
  // showing through. Transparent pixels were black before (zero samples), the densest ink under
  // --invert.
  ImageFile rgba;
  rgba.width = 4;
  rgba.height = 1;
  rgba.channels = 4;
  rgba.values = {0.5f, 0, 0, 0.5f, 0, 0, 0, 0, 0, 0, 1, 1, 0, 1, 0, 1};
  DensityTransfer linear;
  linear.curve = TransferCurve::linear;
  DensityGrid grid = density_from_image(rgba, linear, "c");
  EXPECT_FLOAT_EQ(grid.at(0, 0), 0.2126f + 0.5f * (0.7152f + 0.0722f));  // half-transparent red: (1, 0.5, 0.5)
  EXPECT_FLOAT_EQ(grid.at(1, 0), 1.0f);                                  // transparent: white
  EXPECT_FLOAT_EQ(grid.at(2, 0), 0.0722f);                               // opaque blue
  EXPECT_FLOAT_EQ(grid.at(3, 0), 0.7152f);                               // opaque green
  ImageFile grey_alpha = grey_image(3, 1, {0.75f, 1.0f, 0.0f, 0.0f, 0.25f, 0.5f});
  grey_alpha.channels = 2;
  DensityGrid ga = density_from_image(grey_alpha, linear, "ga");
  EXPECT_EQ(ga.at(0, 0), 0.75f);
  EXPECT_EQ(ga.at(1, 0), 1.0f);
  EXPECT_EQ(ga.at(2, 0), 0.75f);
  DensityTransfer inverted = linear;
  inverted.invert = true;
  EXPECT_EQ(density_from_image(grey_alpha, inverted, "ga").at(1, 0), 0.0f);  // no ink where transparent
  grey_alpha.values[3] = 1.5f;
  EXPECT_EQ(error_of([&] { density_from_image(grey_alpha, linear, "ga.exr"); }),
            "ga.exr: pixel (1, 0) (column, row from the top) has alpha 1.5: alpha must lie in [0, 1]");
}

TEST(DensityMap, BadSamplesNameTheirPixel) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  DensityTransfer t;
  EXPECT_EQ(error_of([&] { density_from_image(grey_image(3, 2, {1, 1, 1, 1, nan, 1}, true), t, "m.exr"); }),
            "m.exr: pixel (1, 1) (column, row from the top) channel 0 is nan: density samples must be finite and "
            "non-negative");
  EXPECT_NE(error_of([&] { density_from_image(grey_image(1, 1, {-0.5f}, true), t, "m.exr"); }).find("is -0.5"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              density_from_image(grey_image(1, 1, {std::numeric_limits<float>::infinity()}, true), t, "m.exr");
            }).find("is inf"),
            std::string::npos);
  EXPECT_EQ(error_of([&] { density_from_image(grey_image(0, 0, {}), t, "e.png"); }),
            "e.png: the image is empty (0 x 0 pixels)");
  EXPECT_EQ(error_of([&] { density_from_image(grey_image(2, 1, {0, 0}), t, "z.png"); }),
            "z.png: the density is zero everywhere (the image is black everywhere, and its bright parts are the dense "
            "ones)");
  DensityTransfer inverted;
  inverted.invert = true;
  EXPECT_EQ(error_of([&] { density_from_image(grey_image(1, 1, {1.0f}), inverted, "w.png"); }),
            "w.png: the density is zero everywhere (the image is white everywhere, and its dark parts are the dense "
            "ones)");
  // Zero after the gamma alone: no reason guessed.
  DensityTransfer steep;
  steep.gamma = 400.0;
  EXPECT_EQ(error_of([&] { density_from_image(grey_image(1, 1, {0.05f}, true), steep, "s.exr"); }),
            "s.exr: the density is zero everywhere");
  EXPECT_NE(error_of([&] { density_from_image(grey_image(1, 1, {2.5f}, true), inverted, "h.exr"); })
                .find("luminance 2.5, above 1"),
            std::string::npos);
  DensityTransfer bad_gamma;
  bad_gamma.gamma = 0.0;
  EXPECT_NE(error_of([&] { density_from_image(grey_image(1, 1, {1.0f}), bad_gamma, "g.png"); }).find("gamma 0"),
            std::string::npos);
}

TEST(DensityMap, FilesOfEveryDepthReadBack) {
  test::TempDir dir;
  DensityTransfer linear;
  linear.curve = TransferCurve::linear;
  const std::vector<float> values = {0.0f, 0.25f, 0.5f, 1.0f, 0.75f, 0.125f};  // 3 x 2, grey
  // 8-bit PNG: samples rounded to 1/255.
  write_image_file(dir.file("m8.png"), 3, 2, 1, values, SampleFormat::uint8);
  DensityGrid g8 = load_density_map(dir.file("m8.png"), linear);
  EXPECT_FLOAT_EQ(g8.at(1, 1), 64.0f / 255.0f);  // image (1, 0) = 0.25 -> 64/255, grid row 1
  EXPECT_FLOAT_EQ(g8.at(0, 0), 1.0f);            // image (0, 1)
  // 16-bit PNG: 1/65535.
  write_image_file(dir.file("m16.png"), 3, 2, 1, values, SampleFormat::uint16);
  DensityGrid g16 = load_density_map(dir.file("m16.png"), linear);
  EXPECT_FLOAT_EQ(g16.at(1, 1), 16384.0f / 65535.0f);
  // EXR and float TIFF keep the value, and count as linear under `automatic`.
  std::vector<float> hdr = values;
  hdr[1] = 3.5f;
  for (const char* name : {"m.exr", "m.tif"}) {
    write_image_file(dir.file(name), 3, 2, 1, hdr, SampleFormat::float32);
    DensityGrid g = load_density_map(dir.file(name), DensityTransfer{});
    EXPECT_EQ(g.at(1, 1), 3.5f) << name;
    EXPECT_EQ(g.at(2, 0), 0.125f) << name;
  }
  // RGB: luminance.
  write_image_file(dir.file("rgb.png"), 1, 1, 3, {0.0f, 1.0f, 0.0f}, SampleFormat::uint8);
  EXPECT_FLOAT_EQ(load_density_map(dir.file("rgb.png"), linear).at(0, 0), 0.7152f);
  // RGBA through the file: a transparent pixel is paper, an opaque black one ink.
  write_image_file(dir.file("rgba.png"), 2, 1, 4, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f}, SampleFormat::uint8);
  DensityTransfer ink = linear;
  ink.invert = true;
  const DensityGrid logo = load_density_map(dir.file("rgba.png"), ink);
  EXPECT_EQ(logo.at(0, 0), 0.0f);
  EXPECT_EQ(logo.at(1, 0), 1.0f);
}

// A 3 x 2 grey TIFF of 8-bit samples 10 20 30 / 40 50 60 (rows top first, as stored), its
// Orientation tag `orientation`, written byte by byte (little-endian, one uncompressed strip).
std::string oriented_tiff(int orientation) {
  std::string bytes = "II";
  auto u16 = [&](unsigned v) {
    bytes.push_back(static_cast<char>(v & 0xff));
    bytes.push_back(static_cast<char>(v >> 8));
  };
  auto u32 = [&](unsigned v) {
    u16(v & 0xffff);
    u16(v >> 16);
  };
  u16(42);
  u32(8);  // the directory follows the header
  const unsigned width = 3, height = 2, entries = 10, pixels_at = 8 + 2 + entries * 12 + 4;
  u16(entries);
  const unsigned short_type = 3, long_type = 4;
  for (auto [tag, type, value] : {std::array<unsigned, 3>{256, short_type, width}, {257, short_type, height},
                                  {258, short_type, 8}, {259, short_type, 1}, {262, short_type, 1},
                                  {273, long_type, pixels_at}, {274, short_type, static_cast<unsigned>(orientation)},
                                  {277, short_type, 1}, {278, short_type, height}, {279, long_type, width * height}}) {
    u16(tag);
    u16(type);
    u32(1);
    u32(value);  // a SHORT sits in the first two bytes of the field
  }
  u32(0);  // no next directory
  for (int sample : {10, 20, 30, 40, 50, 60}) bytes.push_back(static_cast<char>(sample));
  return bytes;
}

TEST(DensityMap, PhotographsAreTurnedUprightAsTheirOrientationTagSays) {
  // A phone stores its photographs as the sensor read them and tags how to show them: a portrait
  // was stippled lying on its side (the tag was ignored). Stored a b c / d e f; each orientation's
  // upright picture by hand (EXIF 2.3, tag 274: where the stored row 0 and column 0 are shown).
  struct Case {
    int orientation, width, height;
    std::string upright;  // rows top first
  };
  const std::vector<Case> cases = {{1, 3, 2, "abcdef"}, {2, 3, 2, "cbafed"}, {3, 3, 2, "fedcba"}, {4, 3, 2, "defabc"},
                                   {5, 2, 3, "adbecf"}, {6, 2, 3, "daebfc"}, {7, 2, 3, "fcebda"}, {8, 2, 3, "cfbead"}};
  test::TempDir dir;
  for (const Case& c : cases) {
    const std::string path = dir.write(std::to_string(c.orientation) + "-oriented.tif", oriented_tiff(c.orientation));
    const ImageFile image = read_image_file(path);
    ASSERT_EQ(image.width, c.width) << c.orientation;
    ASSERT_EQ(image.height, c.height) << c.orientation;
    ASSERT_EQ(image.channels, 1);
    for (std::size_t k = 0; k < c.upright.size(); ++k)
      EXPECT_FLOAT_EQ(image.values[k], static_cast<float>(10 * (c.upright[k] - 'a' + 1)) / 255.0f)
          << "orientation " << c.orientation << ", pixel " << k;
  }
  // The density map of a tagged photograph is the map of the same picture stored upright.
  DensityTransfer linear;
  linear.curve = TransferCurve::linear;
  const std::vector<float> upright = {40 / 255.0f, 10 / 255.0f, 50 / 255.0f, 20 / 255.0f, 60 / 255.0f, 30 / 255.0f};
  write_image_file(dir.file("upright.png"), 2, 3, 1, upright, SampleFormat::uint8);
  const DensityGrid tagged = load_density_map(dir.file("6-oriented.tif"), linear);
  const DensityGrid plain = load_density_map(dir.file("upright.png"), linear);
  ASSERT_EQ(tagged.width, plain.width);
  ASSERT_EQ(tagged.height, plain.height);
  for (int y = 0; y < plain.height; ++y)
    for (int x = 0; x < plain.width; ++x) EXPECT_EQ(tagged.at(x, y), plain.at(x, y)) << x << ", " << y;
}

// `jpeg` with an Exif segment (APP1) after its start marker whose one tag is Orientation
// `orientation`: how a camera tags its photographs.
std::string with_exif_orientation(const std::string& jpeg, int orientation) {
  std::string exif = std::string("Exif\0\0", 6) + "II";
  auto u16 = [&](unsigned v) {
    exif.push_back(static_cast<char>(v & 0xff));
    exif.push_back(static_cast<char>(v >> 8));
  };
  u16(42);
  u16(8), u16(0);  // the directory follows the header
  u16(1);          // one entry: tag 274, SHORT, count 1
  u16(274), u16(3), u16(1), u16(0), u16(static_cast<unsigned>(orientation)), u16(0);
  u16(0), u16(0);  // no next directory
  const std::size_t length = exif.size() + 2;
  return jpeg.substr(0, 2) + "\xff\xe1" + static_cast<char>(length >> 8) + static_cast<char>(length & 0xff) + exif +
         jpeg.substr(2);
}

TEST(DensityMap, AnOrientationTagOutsideOneToEightIsNamedAndTheImageReadAsStored) {
  // Such a tag means nothing, and viewers show the file as stored; it was read that way without a
  // word, as if it had said 1. (libtiff drops such a tag from a TIFF itself: a JPEG's Exif keeps it.)
  test::TempDir dir;
  write_image_file(dir.file("plain.jpg"), 3, 2, 1, {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f}, SampleFormat::uint8);
  std::ifstream stream(dir.file("plain.jpg"), std::ios::binary);
  const std::string jpeg((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
  const ImageFile plain = read_image_file(dir.file("plain.jpg"));
  for (int tag : {0, 9, 300}) {
    const std::string path = dir.write(std::to_string(tag) + ".jpg", with_exif_orientation(jpeg, tag));
    testing::internal::CaptureStderr();
    const ImageFile image = read_image_file(path);
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "bluetile: warning: " + path + ": its Orientation tag is " +
                                                          std::to_string(tag) +
                                                          ", not one of 1 to 8: the image is read as stored\n");
    EXPECT_EQ(image.width, 3) << tag;
    EXPECT_EQ(image.height, 2) << tag;
    EXPECT_EQ(image.values, plain.values) << tag;
  }
  // A tag in range says nothing, and is followed (the segment is read).
  const std::string turned = dir.write("6.jpg", with_exif_orientation(jpeg, 6));
  testing::internal::CaptureStderr();
  const ImageFile upright = read_image_file(turned);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(upright.width, 2);
  EXPECT_EQ(upright.height, 3);
}

TEST(DensityMap, BadFilesGiveOneClearError) {
  test::TempDir dir;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  write_image_file(dir.file("nan.exr"), 2, 2, 1, {1.0f, 1.0f, nan, 1.0f}, SampleFormat::float32);
  EXPECT_EQ(error_of([&] { load_density_map(dir.file("nan.exr"), DensityTransfer{}); }),
            dir.file("nan.exr") + ": pixel (0, 1) (column, row from the top) channel 0 is nan: density samples must "
                                  "be finite and non-negative");
  std::string missing = error_of([&] { load_density_map(dir.file("missing.png"), DensityTransfer{}); });
  EXPECT_EQ(missing.rfind(dir.file("missing.png") + ": cannot read image", 0), 0u) << missing;
  std::string garbage = dir.write("garbage.png", "not a picture");
  EXPECT_EQ(error_of([&] { load_density_map(garbage, DensityTransfer{}); }).rfind(garbage + ": cannot read image", 0),
            0u);
  std::string empty = dir.write("empty.png", "");
  EXPECT_EQ(error_of([&] { load_density_map(empty, DensityTransfer{}); }).rfind(empty + ": cannot read image", 0), 0u);
  // A PNM cut short gave "unknown OpenImageIO error", and a folder "could not find a format reader".
  std::string cut = dir.write("cut.pgm", "P5\n100 100\n255\n abc");
  EXPECT_EQ(error_of([&] { load_density_map(cut, DensityTransfer{}); }),
            cut + ": cannot read image: its pixels could not be read: the file is cut short or damaged");
  std::filesystem::create_directory(dir.file("folder.png"));
  EXPECT_EQ(error_of([&] { load_density_map(dir.file("folder.png"), DensityTransfer{}); }),
            dir.file("folder.png") + ": is a folder, not an image");
}

TEST(DensityMap, DamagedPngsGiveOneLineAndPrintNothingElse) {
  test::TempDir dir;
  std::vector<float> values(64 * 64);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<float>((i * 37) % 101) / 100.0f;
  write_image_file(dir.file("good.png"), 64, 64, 1, values, SampleFormat::uint8);
  const std::string good = test::read_text(dir.file("good.png"));
  ASSERT_EQ(good.substr(12, 4), "IHDR");
  const std::string truncated = dir.write("truncated.png", good.substr(0, good.size() / 2));
  const std::string zero = dir.write("zero.png", test::with_png_size(good, 0, 0));
  const std::string huge = dir.write("huge.png", test::with_png_size(good, 60000, 60000));
  for (const std::string& path : {truncated, zero, huge}) {
    testing::internal::CaptureStderr();
    const std::string message = error_of([&] { load_density_map(path, DensityTransfer{}); });
    const std::string printed = testing::internal::GetCapturedStderr();
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(printed, "") << path;  // libpng printed "libpng error: ..." lines here
  }
  // A header claiming 3.6e9 pixels is refused from the header, before 14 GB of samples are asked for.
  EXPECT_EQ(error_of([&] { load_density_map(huge, DensityTransfer{}); }),
            huge + ": the image is too large (60000 x 60000 pixels, more than 2147483647)");
  // The limit is the caller's: 64 x 64 = 4096 pixels.
  EXPECT_EQ(error_of([&] { load_density_map(dir.file("good.png"), DensityTransfer{}, 4095); }),
            dir.file("good.png") + ": the image is too large (64 x 64 pixels, more than 4095)");
  EXPECT_EQ(load_density_map(dir.file("good.png"), DensityTransfer{}, 4096).width, 64);
}

TEST(DensityGrid, BilinearLookupAtCentresBetweenAndBeyond) {
  DensityGrid grid(2, 2);
  grid.at(0, 0) = 1.0f;
  grid.at(1, 0) = 3.0f;
  grid.at(0, 1) = 5.0f;
  grid.at(1, 1) = 7.0f;
  EXPECT_DOUBLE_EQ(sample_bilinear(grid, {0.25, 0.25}), 1.0);  // texel centres
  EXPECT_DOUBLE_EQ(sample_bilinear(grid, {0.75, 0.75}), 7.0);
  EXPECT_DOUBLE_EQ(sample_bilinear(grid, {0.5, 0.25}), 2.0);   // halfway along a row
  EXPECT_DOUBLE_EQ(sample_bilinear(grid, {0.5, 0.5}), 4.0);    // the middle
  EXPECT_DOUBLE_EQ(sample_bilinear(grid, {0.375, 0.625}), 4.5);  // 1 + 2 * 0.25 + 4 * 0.75
  // Clamp continues the edge texels; wrap repeats the grid.
  EXPECT_DOUBLE_EQ(sample_bilinear(grid, {0.0, 0.25}), 1.0);
  EXPECT_DOUBLE_EQ(sample_bilinear(grid, {-3.0, 2.0}), 5.0);
  EXPECT_DOUBLE_EQ(sample_bilinear(grid, {0.0, 0.25}, GridEdge::wrap), 2.0);  // between texel 1 (left copy) and 0
  EXPECT_DOUBLE_EQ(sample_bilinear(grid, {1.25, 0.25}, GridEdge::wrap), 1.0);
  EXPECT_DOUBLE_EQ(grid.mean(), 4.0);
}

}  // namespace
}  // namespace bluetile
