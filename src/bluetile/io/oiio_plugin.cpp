// The OpenImageIO plugin module: the only code that links OpenImageIO (see image_file.h).
#include "bluetile/io/oiio_plugin.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace {

int fail(const std::string& message, char* error, size_t error_size) {
  std::snprintf(error, error_size, "%s", message.empty() ? "unknown OpenImageIO error" : message.c_str());
  return 1;
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

extern "C" __attribute__((visibility("default"))) int bluetile_oiio_read(const char* path, int* width, int* height,
                                                                         int* channels, int* is_float, float** values,
                                                                         char* error, size_t error_size) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return fail(OIIO::geterror(), error, error_size);
  const OIIO::ImageSpec& spec = in->spec();
  size_t count = static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height) * static_cast<size_t>(spec.nchannels);
  auto* data = static_cast<float*>(std::malloc(count * sizeof(float)));
  if (!data) return fail("out of memory", error, error_size);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data)) {
    std::free(data);
    return fail(in->geterror(), error, error_size);
  }
  *width = spec.width;
  *height = spec.height;
  *channels = spec.nchannels;
  *is_float = spec.format.is_floating_point() ? 1 : 0;
  *values = data;
  return 0;
}
