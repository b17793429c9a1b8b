#include "bluetile/core/input_file.h"

#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <new>
#include <system_error>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bluetile/core/error.h"

namespace bluetile {
namespace {

// Large enough that system calls cost nothing next to parsing.
constexpr std::size_t kChunkSize = 1 << 16;

std::string name_of(const std::string& path) { return path == "-" ? "stdin" : path; }

int open_input(const std::string& path) {
  struct stat status {};
  if (stat(path.c_str(), &status) != 0 || !S_ISFIFO(status.st_mode)) return ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  return open_fifo_saying_so(path, O_RDONLY | O_CLOEXEC, "a writer");
}

}  // namespace

int open_fifo_saying_so(const std::string& path, int flags, const char* partner) {
  std::mutex mutex;
  std::condition_variable opened_signal;
  bool opened = false;
  std::thread notice;
  try {
    notice = std::thread([&] {
      std::unique_lock<std::mutex> lock(mutex);
      if (!opened_signal.wait_for(lock, std::chrono::seconds(1), [&] { return opened; }))
        std::fprintf(stderr, "bluetile: %s: waiting for %s to open this FIFO\n", path.c_str(), partner);
    });
  } catch (const std::system_error&) {
    // No thread to spare: open without the notice.
  }
  const int fd = ::open(path.c_str(), flags);
  const int saved = errno;
  {
    std::lock_guard<std::mutex> lock(mutex);
    opened = true;
  }
  opened_signal.notify_one();
  if (notice.joinable()) notice.join();
  errno = saved;
  return fd;
}

void for_each_chunk(const std::string& path, const std::function<void(std::string_view)>& consume) {
  const std::string name = name_of(path);
  const int fd = path == "-" ? STDIN_FILENO : open_input(path);
  if (fd < 0) throw Error(name + ": cannot open: " + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() {
      if (fd != STDIN_FILENO) ::close(fd);
    }
  } closer{fd};
  std::unique_ptr<char[]> chunk(new char[kChunkSize]);
  for (std::size_t total = 0;;) {
    ssize_t n = ::read(fd, chunk.get(), kChunkSize);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      if (errno == EISDIR) throw Error(name + ": is a folder");
      throw Error(name + ": read failed after " + std::to_string(total) + " bytes: " + std::strerror(errno));
    }
    if (n == 0) return;
    total += static_cast<std::size_t>(n);
    consume(std::string_view(chunk.get(), static_cast<std::size_t>(n)));
  }
}

std::string read_input(const std::string& path) {
  std::string text;
  try {
    for_each_chunk(path, [&](std::string_view chunk) { text.append(chunk); });
  } catch (const std::bad_alloc&) {
    throw Error(name_of(path) + ": out of memory after " + std::to_string(text.size()) + " bytes");
  }
  return text;
}

}  // namespace bluetile
