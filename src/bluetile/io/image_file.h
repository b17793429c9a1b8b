// Image files through OpenImageIO, loaded on first use.
//
// Debian's OpenImageIO pulls in some 250 shared libraries (OpenCV, FFmpeg, GStreamer, ...),
// whose relocation cost about 0.3 s of CPU at every start of a program linked to it. The
// library therefore reaches OpenImageIO only through a small plugin module
// (libbluetile_oiio.so, built from oiio_plugin.cpp), which is opened the first time an image is
// written or read: commands that write no image start in milliseconds.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bluetile/core/output_file.h"

namespace bluetile {

// Loads the image plugin now instead of at the first image: a command that reads or writes
// images calls it before it declares any output, so that a plugin that cannot load (not found, or
// no memory or threads left for OpenImageIO to start) fails before anything is staged. Throws
// Error saying why; where OpenImageIO itself cannot start, prints that on one line and ends the
// process with status 1 (its failure cannot be caught).
void load_image_plugin();

// Throws Error("<path>: cannot write image: <why>") when OpenImageIO knows no format to write for
// the path's extension (PNG when it has none, as for /dev/stdout). Nothing is written; loads the
// plugin. Commands call it when they declare an image output, before any work.
void check_image_output(const std::string& path);

// Writes 8-bit pixels (row 0 at the top, `channels` interleaved) in the format named by the
// output path's extension (PNG when it has none, as /dev/stdout), encoded in memory and streamed
// through output_file.h. Throws Error naming the user's path on failure.
void write_image_file(OutputFile& out, int width, int height, int channels, const std::vector<std::uint8_t>& pixels);
// The same as an output of its own (write_output).
void write_image_file(const std::string& path, int width, int height, int channels,
                      const std::vector<std::uint8_t>& pixels);

enum class SampleFormat { uint8, uint16, float32 };

// Writes float samples (row 0 at the top, `channels` interleaved) stored in the file as
// `format`: integer formats take values in [0, 1] (rounded; others are clamped), float32 keeps
// them as they are (EXR, TIFF). Streamed through output_file.h like the 8-bit writer.
void write_image_file(OutputFile& out, int width, int height, int channels, const std::vector<float>& values,
                      SampleFormat format);
void write_image_file(const std::string& path, int width, int height, int channels, const std::vector<float>& values,
                      SampleFormat format);

struct ImageFile {
  int width = 0, height = 0, channels = 0;
  // `channels` interleaved, row 0 at the top, turned upright as the file's orientation tag (EXIF,
  // TIFF) says, as viewers show it (width and height as shown): integer samples scaled to
  // [0, 1], float samples (EXR, HDR, float TIFF) as stored, which may be anything, NaN included.
  std::vector<float> values;
  bool floating_point = false;  // the file stores floating-point samples
};

// The most pixels an image may have by default: the engines index texels with int.
inline constexpr std::uint64_t kMaxImagePixels = 2147483647;

// Reads any image OpenImageIO knows. Throws Error("<path>: ...") on one line when the file cannot
// be opened or decoded (what the image libraries print goes into the message, not on stderr),
// when it is empty, and when its header claims more than `max_pixels` pixels (before anything is
// decoded). "-" is standard input (named "stdin" in messages).
ImageFile read_image_file(const std::string& path, std::uint64_t max_pixels = kMaxImagePixels);

}  // namespace bluetile
