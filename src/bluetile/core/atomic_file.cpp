#include "bluetile/core/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "bluetile/core/error.h"

namespace bluetile {
namespace {

std::string temporary_path_for(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path target(path);
  // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on a literal + string chain here.
  std::string name(".");
  name += target.stem().string();
  name += ".tmp";
  name += std::to_string(getpid());
  name += '-';
  name += std::to_string(counter++);
  name += target.extension().string();
  return (target.parent_path() / name).string();
}

}  // namespace

void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  std::string temporary = temporary_path_for(path);
  try {
    write(temporary);
  } catch (...) {
    std::remove(temporary.c_str());
    throw;
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    int err = errno;
    std::remove(temporary.c_str());
    throw Error(path + ": cannot write: " + std::strerror(err));
  }
}

void write_text_atomically(const std::string& path, const std::string& content) {
  write_atomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    if (!out) throw Error(path + ": cannot write: " + std::strerror(errno));
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.close();
    if (!out) throw Error(path + ": write failed (disk full?)");
  });
}

}  // namespace bluetile
