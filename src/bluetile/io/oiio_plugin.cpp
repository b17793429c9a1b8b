// The OpenImageIO plugin module: the only code that links OpenImageIO (see image_file.h).
#include "bluetile/io/oiio_plugin.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include <sys/mman.h>
#include <unistd.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace {

// OpenImageIO gathers one line per layer that failed (its own, libpng's, ...), and libpng prints
// its errors on stderr as well: the caller's message is one line. Lines contained in another
// (the same cause, said twice) are dropped; what is left is joined with "; ".
std::string one_line(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    start = end + 1;
    for (const char* prefix : {"libpng error: ", "libpng warning: "})
      if (line.rfind(prefix, 0) == 0) line.erase(0, std::strlen(prefix));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '.')) line.pop_back();
    while (!line.empty() && line.front() == ' ') line.erase(0, 1);
    if (!line.empty()) lines.push_back(line);
  }
  std::string joined;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    bool repeated = false;
    for (std::size_t j = 0; j < lines.size() && !repeated; ++j)
      repeated = j != i && lines[j].find(lines[i]) != std::string::npos && (lines[j] != lines[i] || j < i);
    if (!repeated) joined += (joined.empty() ? "" : "; ") + lines[i];
  }
  return joined;
}

// `silent`: what to say when OpenImageIO and the image libraries said nothing.
int fail(const std::string& message, char* error, size_t error_size,
         const char* silent = "unknown OpenImageIO error") {
  const std::string line = one_line(message);
  std::snprintf(error, error_size, "%s", line.empty() ? silent : line.c_str());
  return 1;
}

// While an image is read, what the image libraries print on standard error (libpng writes its
// errors there besides returning them) goes to a memory file: on failure it joins the message,
// on success it is passed on as it came. Reading happens before a command's work starts, when no
// other thread of ours writes to stderr.
class StderrCapture {
 public:
  StderrCapture() {
    std::fflush(stderr);
    memory_ = memfd_create("bluetile-image-messages", MFD_CLOEXEC);
    if (memory_ < 0) return;
    saved_ = dup(STDERR_FILENO);
    if (saved_ < 0 || dup2(memory_, STDERR_FILENO) < 0) {
      restore();
      return;
    }
  }
  ~StderrCapture() { restore(); }
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  // Ends the capture and returns what was printed.
  std::string finish() {
    std::fflush(stderr);
    std::string text;
    if (memory_ >= 0 && saved_ >= 0) {
      char buffer[4096];
      for (off_t at = 0;;) {
        const ssize_t n = pread(memory_, buffer, sizeof buffer, at);
        if (n <= 0) break;
        text.append(buffer, static_cast<std::size_t>(n));
        at += n;
        if (text.size() > 65536) break;  // enough to say why; never a flood
      }
    }
    restore();
    return text;
  }

 private:
  void restore() {
    if (saved_ >= 0) {
      std::fflush(stderr);
      dup2(saved_, STDERR_FILENO);
      close(saved_);
      saved_ = -1;
    }
    if (memory_ >= 0) close(memory_);
    memory_ = -1;
  }
  int memory_ = -1, saved_ = -1;
};

// Passes on what the libraries printed during a read that succeeded (a warning, say).
void pass_on(const std::string& printed) {
  if (!printed.empty()) std::fwrite(printed.data(), 1, printed.size(), stderr);
}

// The orientation a viewer shows the image in: EXIF's and TIFF's Orientation tag (1 to 8, 1 when
// absent). A phone stores its photographs as the sensor read them and sets the tag; every viewer
// turns them upright, and so does the reader here. A tag outside 1 to 8 means nothing: viewers
// show such a file as stored, and so does the reader, saying so in `warning` where one is given.
int display_orientation(const OIIO::ImageSpec& spec, const char* path = nullptr, std::string* warning = nullptr) {
  const int tag = spec.get_int_attribute("Orientation", 1);
  if (tag >= 1 && tag <= 8) return tag;
  if (warning)
    *warning = std::string("bluetile: warning: ") + path + ": its Orientation tag is " + std::to_string(tag) +
               ", not one of 1 to 8: the image is read as stored\n";
  return 1;
}

// Orientations 5 to 8 turn the image a quarter: width and height change places.
bool quarter_turn(int orientation) { return orientation >= 5; }

// Where the pixel at column x, row y of the upright image (width w, height h) lies in the stored
// image, for each orientation (the tag names where the stored row 0 and column 0 are shown:
// 2 mirrored, 3 turned half, 4 flipped, 5 transposed, 6 turned a quarter clockwise to be
// upright, 7 transverse, 8 a quarter counter-clockwise).
void stored_position(int orientation, long x, long y, long w, long h, long* sx, long* sy) {
  switch (orientation) {
    case 2: *sx = w - 1 - x; *sy = y; break;
    case 3: *sx = w - 1 - x; *sy = h - 1 - y; break;
    case 4: *sx = x; *sy = h - 1 - y; break;
    case 5: *sx = y; *sy = x; break;
    case 6: *sx = y; *sy = w - 1 - x; break;
    case 7: *sx = h - 1 - y; *sy = w - 1 - x; break;
    case 8: *sx = h - 1 - y; *sy = x; break;
    default: *sx = x; *sy = y; break;
  }
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int bluetile_oiio_encode(const char* name, int width, int height,
                                                                           int channels, int bits, const void* pixels,
                                                                           unsigned char** bytes, size_t* size,
                                                                           char* error, size_t error_size) {
  const OIIO::TypeDesc type = bits == 8 ? OIIO::TypeDesc::UINT8 : bits == 16 ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::FLOAT;
  if (bits != 8 && bits != 16 && bits != 32) return fail("unsupported sample size", error, error_size);
  // The name only chooses the format; nothing is written under it.
  auto out = OIIO::ImageOutput::create(name);
  if (!out) return fail(OIIO::geterror(), error, error_size);
  if (!out->supports("ioproxy")) {
    fail(std::string(out->format_name()) + " cannot be written to memory", error, error_size);
    return 2;
  }
  OIIO::Filesystem::IOVecOutput memory;
  OIIO::ImageSpec spec(width, height, channels, type);
  if (!out->set_ioproxy(&memory) || !out->open(name, spec) || !out->write_image(type, pixels) ||
      !out->close())
    return fail(out->geterror(), error, error_size);
  const std::vector<unsigned char>& buffer = memory.buffer();
  *bytes = static_cast<unsigned char*>(std::malloc(buffer.size() ? buffer.size() : 1));
  if (!*bytes) return fail("out of memory", error, error_size);
  std::memcpy(*bytes, buffer.data(), buffer.size());
  *size = buffer.size();
  return 0;
}

extern "C" __attribute__((visibility("default"))) int bluetile_oiio_check(const char* name, char* error,
                                                                          size_t error_size) {
  if (!OIIO::ImageOutput::create(name)) return fail(OIIO::geterror(), error, error_size);
  return 0;
}

extern "C" __attribute__((visibility("default"))) int bluetile_oiio_write(const char* path, int width, int height,
                                                                          int channels, int bits, const void* pixels,
                                                                          char* error, size_t error_size) {
  const OIIO::TypeDesc type = bits == 32 ? OIIO::TypeDesc::FLOAT : bits == 16 ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8;
  if (bits != 8 && bits != 16 && bits != 32) return fail("unsupported sample size", error, error_size);
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return fail(OIIO::geterror(), error, error_size);
  OIIO::ImageSpec spec(width, height, channels, type);
  if (!out->open(path, spec) || !out->write_image(type, pixels) || !out->close())
    return fail(out->geterror(), error, error_size);
  return 0;
}

extern "C" __attribute__((visibility("default"))) int bluetile_oiio_info(const char* path, int* width, int* height,
                                                                         int* channels, char* error,
                                                                         size_t error_size) {
  StderrCapture capture;
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    const std::string why = OIIO::geterror();
    return fail(why + "\n" + capture.finish(), error, error_size);
  }
  const bool turned = quarter_turn(display_orientation(in->spec()));
  *width = turned ? in->spec().height : in->spec().width;
  *height = turned ? in->spec().width : in->spec().height;
  *channels = in->spec().nchannels;
  in->close();
  pass_on(capture.finish());
  return 0;
}

extern "C" __attribute__((visibility("default"))) int bluetile_oiio_read(const char* path, int* width, int* height,
                                                                         int* channels, int* is_float, float** values,
                                                                         char* error, size_t error_size) {
  StderrCapture capture;
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    const std::string why = OIIO::geterror();
    return fail(why + "\n" + capture.finish(), error, error_size);
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    return fail("the image is empty (" + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " pixels, " +
                    std::to_string(spec.nchannels) + " channels)\n" + capture.finish(),
                error, error_size);
  size_t count = static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height) * static_cast<size_t>(spec.nchannels);
  auto* data = static_cast<float*>(std::malloc(count * sizeof(float)));
  if (!data) {
    // Whole tenths in integers: %.1f would write "1,5" under an embedding program's comma locale,
    // and the module does not link the library's ClassicNumbers.
    const auto tenths = static_cast<unsigned long long>(
        std::llround(static_cast<double>(count) * sizeof(float) * 10.0 / (1024.0 * 1024.0 * 1024.0)));
    char gib[48];
    std::snprintf(gib, sizeof gib, "%llu.%llu", tenths / 10, tenths % 10);
    return fail("out of memory: its " + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " pixels of " +
                    std::to_string(spec.nchannels) + (spec.nchannels == 1 ? " channel needs " : " channels need ") + gib +
                    " GiB as 4-byte samples",
                error, error_size);
  }
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data)) {
    std::free(data);
    const std::string why = in->geterror();
    // A PNM cut short fails here without a word from OpenImageIO.
    return fail(why + "\n" + capture.finish(), error, error_size,
                "its pixels could not be read: the file is cut short or damaged");
  }
  std::string warning;
  const int orientation = display_orientation(spec, path, &warning);
  long w = spec.width, h = spec.height;
  if (quarter_turn(orientation)) std::swap(w, h);
  if (orientation != 1) {
    auto* upright = static_cast<float*>(std::malloc(count * sizeof(float)));
    if (!upright) {
      std::free(data);
      return fail("out of memory: turning its " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                      " pixels upright (EXIF orientation " + std::to_string(orientation) + ") needs a second copy",
                  error, error_size);
    }
    const long c = spec.nchannels;
    for (long y = 0; y < h; ++y)
      for (long x = 0; x < w; ++x) {
        long sx = 0, sy = 0;
        stored_position(orientation, x, y, w, h, &sx, &sy);
        std::memcpy(upright + (y * w + x) * c, data + (sy * spec.width + sx) * c, static_cast<size_t>(c) * sizeof(float));
      }
    std::free(data);
    data = upright;
  }
  *width = static_cast<int>(w);
  *height = static_cast<int>(h);
  *channels = spec.nchannels;
  *is_float = spec.format.is_floating_point() ? 1 : 0;
  *values = data;
  in->close();
  pass_on(capture.finish() + warning);
  return 0;
}
