#include "bluetile/io/image_file.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <mutex>

#include <dlfcn.h>

#include "bluetile/core/atomic_file.h"
#include "bluetile/core/error.h"
#include "bluetile/io/oiio_plugin.h"

namespace bluetile {
namespace {

struct Plugin {
  bluetile_oiio_write_fn write = nullptr;
  bluetile_oiio_read_fn read = nullptr;
};

// Where the module may be: BLUETILE_OIIO_PLUGIN, else by bare name, which the dynamic loader
// looks up in the RUNPATH of the object holding this code: the program when the library is
// linked statically, libbluetile_images.so when shared. Linking bluetile::images (CMake, in a
// build tree or installed) or bluetile-images (pkg-config) puts the plugin's folder there.
std::vector<std::string> plugin_candidates() {
  std::vector<std::string> paths;
  if (const char* env = std::getenv("BLUETILE_OIIO_PLUGIN")) paths.push_back(env);
  paths.push_back(BLUETILE_OIIO_PLUGIN_NAME);
  return paths;
}

const Plugin& plugin() {
  static Plugin loaded;
  static std::string failure;
  static std::once_flag once;
  std::call_once(once, [] {
    std::string tried;
    for (const std::string& path : plugin_candidates()) {
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        tried += "\n  " + std::string(dlerror());
        continue;
      }
      loaded.write = reinterpret_cast<bluetile_oiio_write_fn>(dlsym(handle, "bluetile_oiio_write"));
      loaded.read = reinterpret_cast<bluetile_oiio_read_fn>(dlsym(handle, "bluetile_oiio_read"));
      if (loaded.write && loaded.read) return;
      tried += "\n  " + path + ": not a bluetile OpenImageIO plugin";
    }
    failure = "cannot load the image plugin " BLUETILE_OIIO_PLUGIN_NAME
              " (a program linked to bluetile::images finds it through its RUNPATH;"
              " BLUETILE_OIIO_PLUGIN names the file):" + tried;
  });
  if (!loaded.write) throw Error(failure);
  return loaded;
}

void write_samples(const std::string& path, int width, int height, int channels, int bits, const void* samples,
                   std::size_t count) {
  if (count != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * static_cast<std::size_t>(channels))
    throw Error(path + ": image size does not match its pixels");
  const Plugin& p = plugin();
  write_atomically(path, [&](const std::string& temporary) {
    char error[512];
    if (p.write(temporary.c_str(), width, height, channels, bits, samples, error, sizeof error) != 0)
      throw Error(path + ": cannot write image: " + error);
  });
}

}  // namespace

void write_image_file(const std::string& path, int width, int height, int channels,
                      const std::vector<std::uint8_t>& pixels) {
  write_samples(path, width, height, channels, 8, pixels.data(), pixels.size());
}

void write_image_file(const std::string& path, int width, int height, int channels, const std::vector<float>& values,
                      SampleFormat format) {
  if (format == SampleFormat::float32) {
    write_samples(path, width, height, channels, 32, values.data(), values.size());
    return;
  }
  const double top = format == SampleFormat::uint16 ? 65535.0 : 255.0;
  auto quantise = [top](float v) { return std::lround(std::clamp(static_cast<double>(v), 0.0, 1.0) * top); };
  if (format == SampleFormat::uint16) {
    std::vector<std::uint16_t> samples(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) samples[i] = static_cast<std::uint16_t>(quantise(values[i]));
    write_samples(path, width, height, channels, 16, samples.data(), samples.size());
  } else {
    std::vector<std::uint8_t> samples(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) samples[i] = static_cast<std::uint8_t>(quantise(values[i]));
    write_samples(path, width, height, channels, 8, samples.data(), samples.size());
  }
}

ImageFile read_image_file(const std::string& path) {
  const Plugin& p = plugin();
  ImageFile image;
  float* values = nullptr;
  int is_float = 0;
  char error[512];
  if (p.read(path.c_str(), &image.width, &image.height, &image.channels, &is_float, &values, error, sizeof error) != 0)
    throw Error(path + ": cannot read image: " + error);
  image.floating_point = is_float != 0;
  image.values.assign(values, values + static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) *
                                           static_cast<std::size_t>(image.channels));
  std::free(values);
  return image;
}

}  // namespace bluetile
