#include "bluetile/io/image_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include <dlfcn.h>
#include <link.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bluetile/core/error.h"
#include "bluetile/core/input_file.h"
#include "bluetile/core/process_limits.h"
#include "bluetile/io/oiio_plugin.h"

namespace bluetile {
namespace {

struct Plugin {
  bluetile_oiio_encode_fn encode = nullptr;
  bluetile_oiio_write_fn write = nullptr;
  bluetile_oiio_read_fn read = nullptr;
  bluetile_oiio_check_fn check = nullptr;
  bluetile_oiio_info_fn info = nullptr;
};

// The static initialisers of OpenImageIO and its dependencies start thread pools while the module
// is being loaded. Where the memory or thread limit (ulimit -v, -u) leaves no room for them, the
// exception they throw cannot pass through dlopen and ends the process in std::terminate (an
// abort, exit status 134). While dlopen runs, that end says why on one line instead; callers load
// the plugin before they stage any output (load_image_plugin), so nothing is left behind. The
// address-space check below keeps most runs from getting there at all.
[[noreturn]] void plugin_load_terminated() {
  std::string why = "no reason given";
  if (std::exception_ptr failure = std::current_exception()) {
    try {
      std::rethrow_exception(failure);
    } catch (const std::exception& e) {
      why = e.what();
    } catch (...) {
    }
  }
  std::fprintf(stderr,
               "bluetile: cannot load the image plugin " BLUETILE_OIIO_PLUGIN_NAME
               ": OpenImageIO could not start (%s): out of memory or threads (ulimit -v, ulimit -u)\n",
               why.c_str());
  std::_Exit(1);
}

// The worker threads OpenBLAS (loaded by OpenImageIO's dependencies) starts as it loads: one per
// thread it is told to use (OPENBLAS_NUM_THREADS, GOTO_NUM_THREADS, OMP_NUM_THREADS, the first
// one set) or per core, the calling thread aside.
std::uint64_t openblas_workers(std::uint64_t cores) {
  for (const char* name : {"OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS"}) {
    const char* value = std::getenv(name);
    if (value == nullptr) continue;
    char* end = nullptr;
    const long threads = std::strtol(value, &end, 10);
    if (end != value && threads > 0) return std::min<std::uint64_t>(static_cast<std::uint64_t>(threads), cores) - 1;
  }
  return cores - 1;
}

// Address space that loading the plugin takes: OpenImageIO's some 250 libraries, and the thread
// pools their initialisers start, a stack and a malloc arena per hardware thread, and a buffer
// per OpenBLAS worker (128 MiB on AVX-512 processors, less on others). Measured on 2 cores, 17 MB
// of it before the plugin loads: a stipple of 100 dots needs a 540 MB ulimit -v on an AMD EPYC;
// on an Intel Xeon with AVX-512, relax --id-image took 616 MB with OpenBLAS's worker, 480 MB
// without it (OPENBLAS_NUM_THREADS=1, which the tool sets: cli/main.cpp).
std::uint64_t plugin_address_space_needed() {
  constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;
  const std::uint64_t cores = std::max(1u, std::thread::hardware_concurrency());
  return (448 + 40 * cores + 128 * openblas_workers(cores)) * kMiB;
}

// Under it, those initialisers fail in ways no caller can catch (an abort, a deadlock in a
// logging library's thread pool, a crash): refused before dlopen instead.
void check_plugin_address_space() {
  const std::optional<ProcessLimit> limit = address_space_limit();
  const std::uint64_t needed = plugin_address_space_needed();
  if (!limit || limit->left() >= needed) return;
  throw Error("cannot load the image plugin " BLUETILE_OIIO_PLUGIN_NAME ": OpenImageIO needs about " +
              std::to_string(needed >> 20) + " MiB of address space to start, but the limit (ulimit -v " +
              std::to_string(limit->limit >> 10) + ") leaves " + std::to_string(limit->left() >> 20) +
              " MiB: out of memory for it; raise the limit");
}

void* open_plugin(const std::string& path) {
  const std::terminate_handler previous = std::set_terminate(plugin_load_terminated);
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  std::set_terminate(previous);
  return handle;
}

// The folders the dynamic loader searches for libraries of the object holding this code (the
// program when the library is linked statically, libbluetile_images.so when shared): its RUNPATH,
// which linking bluetile::images (CMake, in a build tree or installed) or bluetile-images
// (pkg-config) points at the plugin's folder, then LD_LIBRARY_PATH and the system folders.
// Asked of the loader (dlinfo) rather than left to a bare-name dlopen because a dlopen
// interposed by a sanitizer runtime searches the runtime's path instead of ours.
std::vector<std::string> loader_search_folders() {
  void* self = nullptr;
  Dl_info where{};
  if (dladdr(reinterpret_cast<void*>(&loader_search_folders), &where) && where.dli_fname)
    self = dlopen(where.dli_fname, RTLD_LAZY | RTLD_NOLOAD);
  if (!self) self = dlopen(nullptr, RTLD_LAZY);  // the program itself
  std::vector<std::string> folders;
  Dl_serinfo size{};
  if (!self || dlinfo(self, RTLD_DI_SERINFOSIZE, &size) != 0) return folders;
  // Dl_serinfo is followed by its strings: storage of whole Dl_serinfo keeps it aligned.
  std::vector<Dl_serinfo> storage(size.dls_size / sizeof(Dl_serinfo) + 1);
  Dl_serinfo* info = storage.data();
  *info = size;
  if (dlinfo(self, RTLD_DI_SERINFO, info) != 0) return folders;
  for (unsigned i = 0; i < info->dls_cnt; ++i) {
    const char* name = info->dls_serpath[i].dls_name;
    if (name && *name) folders.emplace_back(name);
  }
  return folders;
}

// Where the module may be: only BLUETILE_OIIO_PLUGIN when it is set (a wrong value is an error,
// not a silent fall-back); else in the loader's search folders of the object holding this code,
// else by bare name (the loader's cache).
std::vector<std::string> plugin_candidates() {
  std::vector<std::string> paths;
  if (const char* env = std::getenv("BLUETILE_OIIO_PLUGIN")) return {env};
  for (const std::string& folder : loader_search_folders()) {
    const std::string path = folder + "/" BLUETILE_OIIO_PLUGIN_NAME;
    if (access(path.c_str(), F_OK) == 0) paths.push_back(path);
  }
  paths.push_back(BLUETILE_OIIO_PLUGIN_NAME);
  return paths;
}

const Plugin& plugin() {
  static Plugin loaded;
  static std::string failure;
  static std::once_flag once;
  std::call_once(once, [] {
    // One line: the first candidate's reason (the one a user fixes), then what else was tried.
    try {
      check_plugin_address_space();
    } catch (const Error& e) {
      failure = e.what();
      return;
    }
    std::string first_reason, others;
    const std::vector<std::string> candidates = plugin_candidates();
    for (const std::string& path : candidates) {
      std::string why;
      if (void* handle = open_plugin(path)) {
        loaded.encode = reinterpret_cast<bluetile_oiio_encode_fn>(dlsym(handle, "bluetile_oiio_encode"));
        loaded.write = reinterpret_cast<bluetile_oiio_write_fn>(dlsym(handle, "bluetile_oiio_write"));
        loaded.read = reinterpret_cast<bluetile_oiio_read_fn>(dlsym(handle, "bluetile_oiio_read"));
        loaded.check = reinterpret_cast<bluetile_oiio_check_fn>(dlsym(handle, "bluetile_oiio_check"));
        loaded.info = reinterpret_cast<bluetile_oiio_info_fn>(dlsym(handle, "bluetile_oiio_info"));
        if (loaded.encode && loaded.write && loaded.read && loaded.check && loaded.info) return;
        loaded = Plugin{};
        why = path + ": not a bluetile OpenImageIO plugin (or one of another version)";
      } else {
        why = dlerror();
      }
      if (first_reason.empty()) first_reason = why;
      else others += (others.empty() ? "" : ", ") + path;
    }
    failure = std::getenv("BLUETILE_OIIO_PLUGIN")
                  ? "cannot load the image plugin named by BLUETILE_OIIO_PLUGIN: " + first_reason
                  : "cannot load the image plugin " BLUETILE_OIIO_PLUGIN_NAME
                    " (a program linked to bluetile::images finds it through its RUNPATH;"
                    " BLUETILE_OIIO_PLUGIN names the file): " +
                        first_reason + (others.empty() ? "" : "; also tried " + others);
  });
  if (!loaded.write) throw Error(failure);
  return loaded;
}

// The name OpenImageIO is given for an output path: PNG for a path without an extension
// (/dev/stdout).
std::string format_name(const std::string& path) {
  return std::filesystem::path(path).extension().empty() ? path + ".png" : path;
}

// Encodes in memory and streams through the output's checked writes; formats OpenImageIO writes
// only to files go through a file, with messages naming the user's path.
void write_samples(OutputFile& out, int width, int height, int channels, int bits, const void* samples,
                   std::size_t count) {
  const std::string& path = out.path();
  if (count != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * static_cast<std::size_t>(channels))
    throw Error(path + ": image size does not match its pixels");
  const Plugin& p = plugin();
  const std::string name = format_name(path);
  char error[512];
  unsigned char* bytes = nullptr;
  std::size_t size = 0;
  int status = p.encode(name.c_str(), width, height, channels, bits, samples, &bytes, &size, error, sizeof error);
  if (status == 0) {
    std::unique_ptr<unsigned char, decltype(&std::free)> owned(bytes, &std::free);
    out.write(std::string_view(reinterpret_cast<const char*>(bytes), size));
    return;
  }
  if (status != 2) throw Error(path + ": cannot write image: " + error);
  out.write_through_path([&](const std::string& file) {
    if (p.write(file.c_str(), width, height, channels, bits, samples, error, sizeof error) != 0) {
      std::string message = error;
      for (std::size_t at = message.find(file); at != std::string::npos; at = message.find(file, at + path.size()))
        message.replace(at, file.size(), path);
      throw Error(path + ": cannot write image: " + message);
    }
  });
}

}  // namespace

void load_image_plugin() { plugin(); }

void check_image_output(const std::string& path) {
  char error[512];
  if (plugin().check(format_name(path).c_str(), error, sizeof error) != 0)
    throw Error(path + ": cannot write image: " + error);
}

void write_image_file(OutputFile& out, int width, int height, int channels, const std::vector<std::uint8_t>& pixels) {
  write_samples(out, width, height, channels, 8, pixels.data(), pixels.size());
}

void write_image_file(const std::string& path, int width, int height, int channels,
                      const std::vector<std::uint8_t>& pixels) {
  OutputSet outputs;
  write_image_file(outputs.add(path), width, height, channels, pixels);
  outputs.publish();
}

void write_image_file(OutputFile& out, int width, int height, int channels, const std::vector<float>& values,
                      SampleFormat format) {
  if (format == SampleFormat::float32) {
    write_samples(out, width, height, channels, 32, values.data(), values.size());
    return;
  }
  const double top = format == SampleFormat::uint16 ? 65535.0 : 255.0;
  auto quantise = [top](float v) { return std::lround(std::clamp(static_cast<double>(v), 0.0, 1.0) * top); };
  if (format == SampleFormat::uint16) {
    std::vector<std::uint16_t> samples(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) samples[i] = static_cast<std::uint16_t>(quantise(values[i]));
    write_samples(out, width, height, channels, 16, samples.data(), samples.size());
  } else {
    std::vector<std::uint8_t> samples(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) samples[i] = static_cast<std::uint8_t>(quantise(values[i]));
    write_samples(out, width, height, channels, 8, samples.data(), samples.size());
  }
}

void write_image_file(const std::string& path, int width, int height, int channels, const std::vector<float>& values,
                      SampleFormat format) {
  OutputSet outputs;
  write_image_file(outputs.add(path), width, height, channels, values, format);
  outputs.publish();
}

namespace {

// A regular file holding `bytes`, named like `like` (its extension tells OpenImageIO the format),
// removed with the object.
class TemporaryCopy {
 public:
  TemporaryCopy(const std::string& folder, const std::string& bytes, const std::string& like) {
    const std::string extension = std::filesystem::path(like).extension().string();
    std::string pattern = (std::filesystem::path(folder) / "bluetile-image-XXXXXX").string() + extension;
    const int fd = mkstemps(pattern.data(), static_cast<int>(extension.size()));
    if (fd < 0)
      throw Error(like + ": cannot copy the image to a temporary file in '" + folder + "': " + std::strerror(errno));
    path_ = pattern;
    std::size_t written = 0;
    while (written < bytes.size()) {
      const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        const int e = errno;
        ::close(fd);
        std::remove(path_.c_str());
        throw Error(like + ": cannot copy the image to " + path_ + ": " + std::strerror(e));
      }
      written += static_cast<std::size_t>(n);
    }
    ::close(fd);
  }
  ~TemporaryCopy() { std::remove(path_.c_str()); }
  TemporaryCopy(const TemporaryCopy&) = delete;
  TemporaryCopy& operator=(const TemporaryCopy&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// The image at `file`, named `path` in messages.
ImageFile read_regular_image(const std::string& file, const std::string& path, std::uint64_t max_pixels) {
  const Plugin& p = plugin();
  ImageFile image;
  char error[512];
  auto named = [&](std::string text) {  // the plugin's messages quote the file it opened
    for (std::size_t at; file != path && (at = text.find(file)) != std::string::npos;) text.replace(at, file.size(), path);
    return text;
  };
  // The header first: a file that claims more pixels than allowed is refused before any buffer
  // for them is allocated (a few bytes of PNG header can claim 2^62 samples).
  if (p.info(file.c_str(), &image.width, &image.height, &image.channels, error, sizeof error) != 0)
    throw Error(path + ": cannot read image: " + named(error));
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0)
    throw Error(path + ": cannot read image: it is empty (" + std::to_string(image.width) + " x " +
                std::to_string(image.height) + " pixels, " + std::to_string(image.channels) + " channels)");
  const std::uint64_t pixels = static_cast<std::uint64_t>(image.width) * static_cast<std::uint64_t>(image.height);
  if (pixels > max_pixels)
    throw Error(path + ": the image is too large (" + std::to_string(image.width) + " x " +
                std::to_string(image.height) + " pixels, more than " + std::to_string(max_pixels) + ")");
  float* values = nullptr;
  int is_float = 0;
  if (p.read(file.c_str(), &image.width, &image.height, &image.channels, &is_float, &values, error, sizeof error) != 0)
    throw Error(path + ": cannot read image: " + named(error));
  std::unique_ptr<float, decltype(&std::free)> owned(values, &std::free);
  // The file may have changed between the two opens.
  if (static_cast<std::uint64_t>(image.width) * static_cast<std::uint64_t>(image.height) > max_pixels)
    throw Error(path + ": the image is too large (" + std::to_string(image.width) + " x " +
                std::to_string(image.height) + " pixels, more than " + std::to_string(max_pixels) + ")");
  image.floating_point = is_float != 0;
  image.values.assign(values, values + static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) *
                                           static_cast<std::size_t>(image.channels));
  return image;
}

}  // namespace

ImageFile read_image_file(const std::string& path, std::uint64_t max_pixels) {
  // OpenImageIO opens an image twice (its header, then its pixels) and reads a little to probe
  // its format: a FIFO or pipe (a process substitution's /dev/fd/N) would be empty the second
  // time, or wait for a writer gone, without a word. Such an input is read once (read_input says
  // when it waits for a writer) into a regular temporary copy. So is standard input ("-", named
  // "stdin" as the point readers name it), a pipe or a file; OpenImageIO finds the format from
  // the bytes.
  const bool standard_input = path == "-";
  struct stat status {};
  const bool found = !standard_input && stat(path.c_str(), &status) == 0;
  // OpenImageIO would say it knows no format for a folder's name.
  if (found && S_ISDIR(status.st_mode)) throw Error(path + ": is a folder, not an image");
  if (standard_input || (found && !S_ISREG(status.st_mode))) {
    const std::string name = standard_input ? "stdin" : path;
    // Before the input is read: a FIFO's bytes are not lost to a TMPDIR that cannot take them.
    const std::string folder = temporary_folder(name + ": not a regular file, so read into a temporary copy");
    const TemporaryCopy copy(folder, read_input(path), name);
    return read_regular_image(copy.path(), name, max_pixels);
  }
  return read_regular_image(path, path, max_pixels);
}

}  // namespace bluetile
