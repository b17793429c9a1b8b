// Output files (see output_file.h for what is promised).
#include "bluetile/core/output_file.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <set>
#include <streambuf>
#include <thread>

#include <fcntl.h>
#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bluetile/core/error.h"
#include "bluetile/core/input_file.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace fs = std::filesystem;
namespace {

// Large enough that write(2) calls cost nothing next to formatting, small enough to ignore.
constexpr std::size_t kBufferSize = 1 << 16;
// Like the kernel's own limit on symbolic links in one path.
constexpr int kMaxLinks = 40;

std::string reason(int err) { return std::strerror(err); }

[[noreturn]] void fail(const std::string& path, const std::string& what, int err) {
  if (err == EPIPE) throw ReaderGone(path + ": " + what + ": " + reason(err));
  throw Error(path + ": " + what + ": " + reason(err));
}

// ---- Staged folders removed on SIGINT, SIGTERM, SIGHUP -----------------------------------

struct StagingRegistry {
  std::mutex mutex;  // held by the watcher while it cleans and by publish() while it renames
  std::vector<std::string> folders;
};

StagingRegistry& registry() {
  static StagingRegistry* r = new StagingRegistry;  // never destroyed: the watcher outlives main
  return *r;
}

// Makes a staging folder and registers it under one hold of the lock: a signal between the two
// would otherwise find the folder made but not listed, and leave it behind. `make` returns false
// with errno set when the folder cannot be made.
template <typename Make>
bool make_registered_staging(const std::string& folder, Make make) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  if (!make()) return false;
  registry().folders.push_back(folder);
  return true;
}

void unregister_staging_locked(const std::string& folder) {
  auto& folders = registry().folders;
  for (std::size_t i = 0; i < folders.size(); ++i) {
    if (folders[i] == folder) {
      folders.erase(folders.begin() + static_cast<std::ptrdiff_t>(i));
      return;
    }
  }
}

// SIGINT, SIGTERM and SIGHUP, but those the process inherited as ignored (a background job of a
// script ignores SIGINT, nohup SIGHUP): they stay ignored.
sigset_t cleanup_signals() {
  sigset_t set;
  sigemptyset(&set);
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction current {};
    if (sigaction(signal_number, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
    sigaddset(&set, signal_number);
  }
  return set;
}

// Removes a staged folder that other threads may still be writing in: a file they create while
// remove_all lists the folder makes its last step (rmdir) fail, so it is tried again until the
// folder is gone; once it is, nothing more can be created in it. Bounded, for a folder that
// cannot be removed at all.
void remove_while_written(const std::string& folder) {
  for (int attempt = 0; attempt < 1000; ++attempt) {
    std::error_code ignored;
    fs::remove_all(folder, ignored);
    struct stat st {};
    if (lstat(folder.c_str(), &st) != 0 && errno == ENOENT) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

[[noreturn]] void watch_signals(sigset_t set) {
  int signal_number = 0;
  while (sigwait(&set, &signal_number) != 0) {
  }
  {
    std::lock_guard<std::mutex> lock(registry().mutex);
    for (const std::string& folder : registry().folders) remove_while_written(folder);
    registry().folders.clear();
    // Keep the lock: no thread may stage anything more. End the process by the same signal,
    // so that the parent sees what happened (a shell prints nothing, exit status 128 + n).
    std::signal(signal_number, SIG_DFL);
    sigset_t just_this;
    sigemptyset(&just_this);
    sigaddset(&just_this, signal_number);
    pthread_sigmask(SIG_UNBLOCK, &just_this, nullptr);
    raise(signal_number);
    std::_Exit(128 + signal_number);  // not reached
  }
}

// ---- Path resolution -----------------------------------------------------------------------

// The descriptor a path names directly (/dev/stdout, /dev/fd/N, /proc/self/fd/N), or -1.
int named_descriptor(const std::string& path) {
  if (path == "/dev/stdout") return 1;
  if (path == "/dev/stderr") return 2;
  const std::string pid_prefix = "/proc/" + std::to_string(getpid()) + "/fd/";
  for (const std::string& prefix : {std::string("/dev/fd/"), std::string("/proc/self/fd/"),
                                    std::string("/proc/thread-self/fd/"), pid_prefix}) {
    if (path.size() <= prefix.size() || path.compare(0, prefix.size(), prefix) != 0) continue;
    int fd = -1;
    const char* begin = path.data() + prefix.size();
    const char* end = path.data() + path.size();
    auto [stop, ec] = std::from_chars(begin, end, fd);
    if (ec == std::errc() && stop == end && fd >= 0) return fd;
  }
  return -1;
}

struct Resolved {
  enum class Type { absent, regular, folder, special, descriptor } type = Type::absent;
  std::string path;  // after following links
  struct stat status {};
  int descriptor = -1;
};

// Follows symbolic links from `user_path`. Throws Error naming user_path on failure.
Resolved resolve(const std::string& user_path) {
  Resolved r;
  r.path = user_path;
  for (int links = 0;; ++links) {
    int fd = named_descriptor(fs::path(r.path).lexically_normal().string());
    if (fd >= 0) {
      r.type = Resolved::Type::descriptor;
      r.descriptor = fd;
      return r;
    }
    if (lstat(r.path.c_str(), &r.status) != 0) {
      if (errno == ENOENT) return r;  // absent; the parent is checked by the caller
      fail(user_path, "cannot write", errno);
    }
    if (!S_ISLNK(r.status.st_mode)) break;
    if (links == kMaxLinks) fail(user_path, "cannot write", ELOOP);
    std::string target(PATH_MAX + 1, '\0');
    ssize_t n = readlink(r.path.c_str(), target.data(), target.size());
    if (n < 0) fail(user_path, "cannot follow link", errno);
    if (static_cast<std::size_t>(n) == target.size()) fail(user_path, "cannot follow link", ENAMETOOLONG);
    target.resize(static_cast<std::size_t>(n));
    fs::path next(target);
    r.path = next.is_absolute() ? next.string() : (fs::path(r.path).parent_path() / next).string();
  }
  if (S_ISREG(r.status.st_mode)) r.type = Resolved::Type::regular;
  else if (S_ISDIR(r.status.st_mode)) r.type = Resolved::Type::folder;
  else r.type = Resolved::Type::special;
  return r;
}

std::string parent_of(const std::string& path) {
  fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

// A folder we may create files in; throws Error naming user_path otherwise.
struct stat writable_folder(const std::string& folder, const std::string& user_path) {
  struct stat st {};
  if (stat(folder.c_str(), &st) != 0) {
    if (errno == ENOENT) throw Error(user_path + ": folder '" + folder + "' does not exist");
    fail(user_path, "cannot write in '" + folder + "'", errno);
  }
  if (!S_ISDIR(st.st_mode)) throw Error(user_path + ": '" + folder + "' is not a folder");
  if (access(folder.c_str(), W_OK | X_OK) != 0) fail(user_path, "cannot write in folder '" + folder + "'", errno);
  return st;
}

int open_descriptor_for_writing(int fd, const std::string& user_path) {
  int flags = fcntl(fd, F_GETFL);
  if (flags < 0) fail(user_path, "cannot write", errno);
  if ((flags & O_ACCMODE) == O_RDONLY) throw Error(user_path + ": descriptor " + std::to_string(fd) + " is not open for writing");
  int copy = fcntl(fd, F_DUPFD_CLOEXEC, 3);
  if (copy < 0) fail(user_path, "cannot write", errno);
  return copy;
}

std::string unique_suffix() {
  static std::atomic<unsigned> counter{0};
  return std::to_string(getpid()) + "-" + std::to_string(counter++);
}

}  // namespace

// ---- OutputStream --------------------------------------------------------------------------

struct OutputStream::StreamAdapter : std::streambuf {
  explicit StreamAdapter(OutputStream& out) : out_(out), stream_(this) {
    stream_.exceptions(std::ios::badbit | std::ios::failbit);  // rethrows our Error
  }
  int_type overflow(int_type c) override {
    if (c != traits_type::eof()) out_.put(static_cast<char>(c));
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    out_.write(s, static_cast<std::size_t>(n));
    return n;
  }
  OutputStream& out_;
  std::ostream stream_;
};

OutputStream::OutputStream(int fd, std::string path)
    : fd_(fd), path_(std::move(path)), buffer_(new char[kBufferSize]) {}

OutputStream::~OutputStream() {
  if (fd_ >= 0) ::close(fd_);  // abandoned (an exception): the caller discards the output
}

void OutputStream::flush() {
  std::size_t done = 0;
  while (done < buffered_) {
    ssize_t n = ::write(fd_, buffer_.get() + done, buffered_ - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(path_, "cannot write", errno);
    }
    if (n == 0) fail(path_, "cannot write", EIO);
    done += static_cast<std::size_t>(n);
  }
  written_ += buffered_;
  buffered_ = 0;
}

void OutputStream::write(const void* data, std::size_t size) {
  if (fd_ < 0) throw Error(path_ + ": write after close");
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    if (buffered_ == kBufferSize) flush();
    std::size_t n = std::min(size, kBufferSize - buffered_);
    std::memcpy(buffer_.get() + buffered_, bytes, n);
    buffered_ += n;
    bytes += n;
    size -= n;
  }
}

void OutputStream::put(char c) {
  if (buffered_ == kBufferSize) flush();
  buffer_[buffered_++] = c;
}

void OutputStream::print(const char* format, ...) {
  // Room for any one formatted line of ours; longer text takes the slow path below.
  constexpr std::size_t kRoom = 512;
  if (kBufferSize - buffered_ < kRoom) flush();
  const ClassicNumbers classic;  // "0.5", whatever locale a program embedding the library set
  va_list args;
  va_start(args, format);
  int n = std::vsnprintf(buffer_.get() + buffered_, kBufferSize - buffered_, format, args);
  va_end(args);
  if (n < 0) throw Error(path_ + ": cannot format output");
  if (static_cast<std::size_t>(n) < kBufferSize - buffered_) {
    buffered_ += static_cast<std::size_t>(n);
    return;
  }
  std::string text(static_cast<std::size_t>(n) + 1, '\0');
  va_start(args, format);
  std::vsnprintf(text.data(), text.size(), format, args);
  va_end(args);
  write(text.data(), static_cast<std::size_t>(n));
}

std::ostream& OutputStream::ostream() {
  if (!adapter_) adapter_ = std::make_unique<StreamAdapter>(*this);
  return adapter_->stream_;
}

void OutputStream::close(bool sync) {
  if (fd_ < 0) return;
  flush();
  if (sync && fsync(fd_) != 0 && errno != EINVAL && errno != EROFS) fail(path_, "cannot write", errno);
  int fd = fd_;
  fd_ = -1;
  // close() reports deferred errors (NFS, quotas); EINTR leaves the descriptor closed on Linux.
  if (::close(fd) != 0 && errno != EINTR) fail(path_, "cannot write", errno);
}

// ---- OutputFile ----------------------------------------------------------------------------

OutputStream& OutputFile::open() {
  if (written_ || stream_) throw Error(path_ + ": output written twice");
  int fd = -1;
  if (kind_ == Kind::staged) {
    fd = ::open(staged_.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC | O_NOFOLLOW);
    if (fd < 0) fail(path_, "cannot write", errno);
  } else {
    fd = descriptor_;
    descriptor_ = -1;
  }
  stream_ = std::make_unique<OutputStream>(fd, path_);
  return *stream_;
}

void OutputFile::close() {
  if (!stream_) throw Error(path_ + ": output closed before it was opened");
  // Staged files are not fsynced: ext4, XFS and btrfs write a file renamed over another before
  // the rename, and a sync per file would cost a 4096-file batch a minute on a disk.
  stream_->close(false);
  stream_.reset();
  written_ = true;
}

void OutputFile::write(const OutputWriter& writer) {
  OutputStream& out = open();
  writer(out);
  close();
}

void OutputFile::write(std::string_view text) {
  write([&](OutputStream& out) { out.write(text); });
}

void OutputFile::write_through_path(const std::function<void(const std::string&)>& writer) {
  if (kind_ == Kind::staged) {
    if (written_) throw Error(path_ + ": output written twice");
    writer(staged_);
    written_ = true;
    return;
  }
  // A device or descriptor: write a private temporary file, then copy its bytes.
  const std::string folder =
      temporary_folder(path_ + ": written to a temporary file first (its format is written to files only)");
  std::string pattern = (fs::path(folder) / ("bluetile-" + unique_suffix() + "-XXXXXX")).string();
  if (!make_registered_staging(pattern, [&] { return mkdtemp(pattern.data()) != nullptr; }))
    fail(path_, "cannot make a temporary folder in '" + folder + "'", errno);
  auto remove_temporary = [&] {
    std::error_code ignored;
    fs::remove_all(pattern, ignored);
    std::lock_guard<std::mutex> lock(registry().mutex);
    unregister_staging_locked(pattern);
  };
  try {
    std::string temporary = pattern + "/" + fs::path(path_).filename().string();
    writer(temporary);
    int in = ::open(temporary.c_str(), O_RDONLY | O_CLOEXEC);
    if (in < 0) fail(path_, "cannot read back the temporary file", errno);
    OutputStream& out = open();
    std::unique_ptr<char[]> chunk(new char[kBufferSize]);
    for (;;) {
      ssize_t n = ::read(in, chunk.get(), kBufferSize);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        int err = errno;
        ::close(in);
        fail(path_, "cannot read back the temporary file", err);
      }
      if (n == 0) break;
      out.write(chunk.get(), static_cast<std::size_t>(n));
    }
    ::close(in);
    close();
  } catch (...) {
    remove_temporary();
    throw;
  }
  remove_temporary();
}

std::string temporary_folder(const std::string& why) {
  const char* value = std::getenv("TMPDIR");
  if (value == nullptr || *value == '\0') return "/tmp";
  struct stat status {};
  const int err = stat(value, &status) == 0 ? (S_ISDIR(status.st_mode) ? 0 : ENOTDIR) : errno;
  if (err != 0)
    throw Error(why + ", but TMPDIR '" + std::string(value) + "' is not a folder (" + reason(err) +
                "): set TMPDIR to a writable folder, or unset it for /tmp");
  return value;
}

// ---- OutputSet -----------------------------------------------------------------------------

// What "the same file" means: device and inode of an existing regular file or folder, or, for
// a file not yet there, its parent folder's device and inode and its name.
struct OutputSet::Identity {
  dev_t device = 0;
  ino_t inode = 0;
  std::string name;  // empty for an existing file
  bool operator==(const Identity&) const = default;
};

// A hidden folder holding the staged files of one target folder.
struct OutputSet::Folder {
  std::string target;      // the folder the files are published into
  std::string staging;     // where they wait; empty until the first file
  bool creates = false;    // target does not exist: staging becomes it at publish
  std::string ancestor;    // creates: the nearest existing ancestor, where staging lives
  dev_t device = 0;        // !creates: identity of target
  ino_t inode = 0;
  std::vector<OutputFile*> files;
};

OutputSet::OutputSet() = default;

OutputSet::~OutputSet() {
  if (!published_) discard();
}

void OutputSet::discard() noexcept {
  for (auto& output : outputs_) {
    output->stream_.reset();
    if (output->descriptor_ >= 0) ::close(output->descriptor_);
    output->descriptor_ = -1;
  }
  std::lock_guard<std::mutex> lock(registry().mutex);
  for (auto& folder : folders_) {
    if (folder->staging.empty()) continue;
    std::error_code ignored;
    fs::remove_all(folder->staging, ignored);
    unregister_staging_locked(folder->staging);
    folder->staging.clear();
  }
}

struct OutputSet::Known {
  Identity id;
  std::string path;
  bool is_input;
};

// Refuses `path` if it is the same file as one declared before, else remembers it.
void OutputSet::remember(const Identity& id, const std::string& path, bool is_input) {
  for (const auto& known : known_) {
    if (!(known->id == id)) continue;
    if (is_input && known->is_input) return;  // one input given twice: harmless
    const std::string& output = is_input ? known->path : path;
    const std::string& other = is_input ? path : known->path;
    if (is_input || known->is_input) throw Error(output + ": is the same file as the input " + other);
    if (output == "-" && other == "-")
      throw Error("-: two outputs go to standard output, where their bytes would interleave: write one of them to a file");
    throw Error(output + ": is the same file as the output " + other);
  }
  known_.push_back(std::make_unique<Known>(Known{id, path, is_input}));
}

void OutputSet::add_input(const std::string& path) {
  if (path == "-") return;
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) fail(path, "cannot open", errno);
  if (!S_ISREG(st.st_mode)) return;  // devices and FIFOs: reading and writing one is legitimate
  remember(Identity{st.st_dev, st.st_ino, {}}, path, true);
}

void OutputSet::add_folder(const std::string& path) {
  // "-" is standard output to every other output; a folder of that name is "./-".
  if (path == "-") throw Error("-: this output cannot be standard output");
  Resolved r = resolve(path);
  if (r.type == Resolved::Type::folder) {
    writable_folder(r.path, path);
    reused_folders_.push_back({path, r.path});
    return;
  }
  if (r.type != Resolved::Type::absent) throw Error(path + ": exists and is not a folder");
  // Missing: find the nearest existing ancestor, which must be a writable folder.
  fs::path ancestor = fs::path(r.path).lexically_normal();
  if (!ancestor.has_filename()) ancestor = ancestor.parent_path();
  std::error_code ec;
  do {
    ancestor = ancestor.parent_path();
  } while (!ancestor.empty() && !fs::exists(ancestor, ec));
  writable_folder(ancestor.empty() ? "." : ancestor.string(), path);
  auto folder = std::make_unique<Folder>();
  folder->target = fs::path(r.path).lexically_normal().string();
  if (!folder->target.empty() && folder->target.back() == '/') folder->target.pop_back();
  folder->creates = true;
  folder->ancestor = ancestor.empty() ? "." : ancestor.string();
  folders_.push_back(std::move(folder));
}

std::size_t OutputSet::staging_folder_for(const std::string& directory, const std::string& user_path) {
  const std::string normal = fs::path(directory).lexically_normal().string();
  for (std::size_t i = 0; i < folders_.size(); ++i)
    if (folders_[i]->creates && folders_[i]->target == normal) return i;
  struct stat st = writable_folder(directory, user_path);
  for (std::size_t i = 0; i < folders_.size(); ++i)
    if (!folders_[i]->creates && folders_[i]->device == st.st_dev && folders_[i]->inode == st.st_ino) return i;
  auto folder = std::make_unique<Folder>();
  folder->target = directory;
  folder->device = st.st_dev;
  folder->inode = st.st_ino;
  folders_.push_back(std::move(folder));
  return folders_.size() - 1;
}

namespace {

// Binary bytes on a terminal are garbage to the reader and can leave the terminal in a strange
// state (gzip and zstd refuse the same); text goes there as it would to a file. Asked of the
// descriptor, whatever its name: /dev/tty, /dev/pts/N or a link to one is as much a terminal.
void refuse_binary_on_terminal(int fd, const std::string& path, bool is_stdout, const OutputOptions& options) {
  if (options.binary_format.empty() || isatty(fd) != 1) return;
  ::close(fd);
  const std::string binary = std::string(options.binary_format) + " data is binary: ";
  if (is_stdout)
    throw Error(path + ": standard output is a terminal, and " + binary +
                "redirect it to a file (> FILE) or pipe it to a program (| ...)");
  throw Error(path + ": is a terminal, and " + binary + "write it to a file or pipe it to a program (| ...)");
}

}  // namespace

OutputFile& OutputSet::add(const std::string& path, OutputOptions options) {
  if (published_) throw Error(path + ": output added after publishing");
  if (path.empty()) throw Error("empty output path");
  auto output = std::make_unique<OutputFile>();
  output->path_ = path;
  auto direct = [&](int fd, const struct stat* st) -> OutputFile& {
    output->kind_ = OutputFile::Kind::descriptor;
    output->descriptor_ = fd;
    // A descriptor open on a regular file (a shell's > file), or a pipe or socket, where two
    // outputs would interleave their bytes; a device (a terminal, /dev/null) takes any number.
    if (st && (S_ISREG(st->st_mode) || S_ISFIFO(st->st_mode) || S_ISSOCK(st->st_mode))) {
      remember(Identity{st->st_dev, st->st_ino, {}}, path, false);
    }
    outputs_.push_back(std::move(output));
    return *outputs_.back();
  };
  if (path == "-") {
    if (!options.allow_stdout) throw Error("-: this output cannot be standard output");
    int fd = open_descriptor_for_writing(1, "standard output");
    output->stdout_ = true;
    refuse_binary_on_terminal(fd, path, true, options);
    struct stat st {};
    fstat(fd, &st);
    return direct(fd, &st);
  }

  // Outputs inside a folder staged whole (add_folder of a missing folder).
  const std::string normal_parent = parent_of(fs::path(path).lexically_normal().string());
  Resolved r;
  bool in_new_folder = false;
  for (const auto& folder : folders_)
    if (folder->creates && folder->target == normal_parent) in_new_folder = true;
  if (in_new_folder) {
    r.path = fs::path(path).lexically_normal().string();
  } else {
    r = resolve(path);
  }

  switch (r.type) {
    case Resolved::Type::descriptor: {
      int fd = open_descriptor_for_writing(r.descriptor, path);
      output->stdout_ = r.descriptor == 1;
      refuse_binary_on_terminal(fd, path, output->stdout_, options);
      struct stat st {};
      fstat(fd, &st);
      return direct(fd, &st);
    }
    case Resolved::Type::special: {
      struct stat target {};
      const bool fifo = stat(r.path.c_str(), &target) == 0 && S_ISFIFO(target.st_mode);
      int fd = fifo ? open_fifo_saying_so(r.path, O_WRONLY | O_NOCTTY | O_CLOEXEC, "a reader")
                    : ::open(r.path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
      if (fd < 0) fail(path, "cannot write", errno);
      refuse_binary_on_terminal(fd, path, false, options);
      struct stat st {};
      fstat(fd, &st);
      return direct(fd, &st);
    }
    case Resolved::Type::folder:
      throw Error(path + ": is a folder");
    case Resolved::Type::regular:
      if (access(r.path.c_str(), W_OK) != 0) fail(path, "cannot replace", errno);
      output->replaces_ = true;
      break;
    case Resolved::Type::absent:
      break;
  }

  const std::string directory = parent_of(r.path);
  const std::size_t index = staging_folder_for(directory, path);
  Folder& folder = *folders_[index];
  output->name_ = fs::path(r.path).filename().string();
  output->target_ = (fs::path(folder.target) / output->name_).string();
  Identity id;
  if (output->replaces_) {
    id = {r.status.st_dev, r.status.st_ino, {}};
  } else if (folder.creates) {
    id = {0, 0, output->target_};
  } else {
    id = {folder.device, folder.inode, output->name_};
  }
  remember(id, path, false);

  if (folder.staging.empty()) {
    if (folder.creates) {
      // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on a literal + string chain.
      std::string name(".");
      name += fs::path(folder.target).filename().string();
      name += ".bluetile-";
      name += unique_suffix();
      const std::string staging = (fs::path(folder.ancestor) / name).string();
      if (!make_registered_staging(staging, [&] { return mkdir(staging.c_str(), 0777) == 0; }))
        fail(path, "cannot create a folder in '" + folder.ancestor + "'", errno);
      folder.staging = staging;
    } else {
      const std::string staging = (fs::path(folder.target) / (".bluetile-" + unique_suffix())).string();
      if (!make_registered_staging(staging, [&] { return mkdir(staging.c_str(), 0700) == 0; }))
        fail(path, "cannot write in folder '" + folder.target + "'", errno);
      folder.staging = staging;
    }
  }
  output->kind_ = OutputFile::Kind::staged;
  output->staged_ = folder.staging + "/" + output->name_;
  int fd = ::open(output->staged_.c_str(), O_CREAT | O_EXCL | O_WRONLY | O_CLOEXEC, 0666);
  if (fd < 0) fail(path, "cannot write", errno);
  if (output->replaces_) {
    // Keep owner and group where allowed (root, or a group we belong to), then the mode.
    if (r.status.st_uid != geteuid() || r.status.st_gid != getegid()) {
      if (fchown(fd, r.status.st_uid, r.status.st_gid) != 0 && fchown(fd, static_cast<uid_t>(-1), r.status.st_gid) != 0) {
      }
    }
    if (fchmod(fd, r.status.st_mode & 0777) != 0) {
      int err = errno;
      ::close(fd);
      fail(path, "cannot keep the permissions of the file it replaces", err);
    }
  }
  ::close(fd);
  folder.files.push_back(output.get());
  outputs_.push_back(std::move(output));
  return *outputs_.back();
}

void OutputSet::publish() {
  if (published_) return;
  for (const auto& output : outputs_) {
    if (!output->written_) throw Error(output->path_ + ": output declared but never written (internal error)");
  }
  struct Step {
    enum class What { replaced, created, folder } what;
    std::string target;
    std::string backup;  // replaced: a hard link to the old file, or empty when none could be made
    std::string staging;  // folder: where it came from
  };
  std::vector<Step> done;
  auto roll_back = [&] {
    for (auto step = done.rbegin(); step != done.rend(); ++step) {
      if (step->what == Step::What::folder) {
        if (rename(step->target.c_str(), step->staging.c_str()) != 0) {
        }
      } else if (step->what == Step::What::created) {
        unlink(step->target.c_str());
      } else if (!step->backup.empty()) {
        if (rename(step->backup.c_str(), step->target.c_str()) != 0) {
        }
      }
    }
  };

  std::unique_lock<std::mutex> lock(registry().mutex);
  for (const auto& folder : folders_) {
    if (folder->staging.empty()) continue;
    if (folder->creates) {
      std::error_code ec;
      fs::create_directories(fs::path(folder->target).parent_path(), ec);
      if (rename(folder->staging.c_str(), folder->target.c_str()) != 0) {
        int err = errno;
        roll_back();
        lock.unlock();
        discard();
        // Made (and filled) by another run while this one worked: this run's folder cannot replace
        // it, and is not merged into a folder that was never checked. "Directory not empty" said
        // none of that.
        struct stat now {};
        if ((err == ENOTEMPTY || err == EEXIST) && stat(folder->target.c_str(), &now) == 0 && S_ISDIR(now.st_mode))
          throw Error(folder->target + ": the folder was made by another process while this run worked; nothing was "
                      "written to it (run again to write into it)");
        fail(folder->target, "cannot create the folder", err);
      }
      done.push_back({Step::What::folder, folder->target, {}, folder->staging});
      continue;
    }
    for (OutputFile* file : folder->files) {
      const std::string staged = folder->staging + "/" + file->name_;
      Step step{Step::What::created, file->target_, {}, {}};
      struct stat st {};
      if (lstat(file->target_.c_str(), &st) == 0) {
        step.what = Step::What::replaced;
        std::string backup = folder->staging + "/.replaced-" + file->name_;
        if (link(file->target_.c_str(), backup.c_str()) == 0) step.backup = backup;
      }
      if (rename(staged.c_str(), file->target_.c_str()) != 0) {
        int err = errno;
        roll_back();
        lock.unlock();
        discard();
        fail(file->path_, "cannot replace", err);
      }
      done.push_back(step);
    }
  }
  published_ = true;
  for (const auto& folder : folders_) {
    if (folder->staging.empty()) continue;
    if (!folder->creates) {
      std::error_code ignored;
      fs::remove_all(folder->staging, ignored);  // the staging folder and the kept old files
    }
    unregister_staging_locked(folder->staging);
  }
  lock.unlock();
  note_files_of_earlier_runs();
}

void OutputSet::note_files_of_earlier_runs() const {
  constexpr std::size_t kNamesShown = 4;  // enough to recognise them; the count says the rest
  for (const auto& [user_path, resolved] : reused_folders_) {
    struct stat folder {};
    if (stat(resolved.c_str(), &folder) != 0) continue;
    // The set's files in it, by the folder's identity (the paths may be spelled differently).
    std::set<std::string> written;
    for (const auto& output : outputs_) {
      if (output->target_.empty()) continue;
      const fs::path target(output->target_);
      struct stat parent {};
      const std::string parent_path = target.has_parent_path() ? target.parent_path().string() : ".";
      if (stat(parent_path.c_str(), &parent) == 0 && parent.st_dev == folder.st_dev && parent.st_ino == folder.st_ino)
        written.insert(target.filename().string());
    }
    std::vector<std::string> others;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(resolved, ec)) {
      const std::string name = entry.path().filename().string();
      std::error_code type_error;
      // Hidden files and folders are no output of ours; staging folders are hidden too.
      if (name.empty() || name[0] == '.' || !entry.is_regular_file(type_error) || written.count(name)) continue;
      others.push_back(name);
    }
    if (others.empty()) continue;
    std::sort(others.begin(), others.end());
    std::string list;
    for (std::size_t i = 0; i < others.size() && i < kNamesShown; ++i) list += (i ? ", " : "") + others[i];
    if (others.size() > kNamesShown) list += " and " + std::to_string(others.size() - kNamesShown) + " more";
    // Said as what they are, not guessed at: the files of an earlier run with other options, or
    // another command's (the demo's relax outputs, beside its analysis).
    const bool one = others.size() == 1;
    std::fprintf(stderr, "bluetile: note: %s also holds %zu file%s this run did not write, left as %s: %s\n",
                 user_path.c_str(), others.size(), one ? "" : "s", one ? "it is" : "they are", list.c_str());
  }
}

void write_output(const std::string& path, const OutputWriter& writer, OutputOptions options) {
  OutputSet outputs;
  outputs.add(path, options).write(writer);
  outputs.publish();
}

void write_output(const std::string& path, std::string_view text, OutputOptions options) {
  write_output(path, [&](OutputStream& out) { out.write(text); }, options);
}

void install_interrupt_cleanup() {
  static std::once_flag once;
  std::call_once(once, [] {
    sigset_t set = cleanup_signals();
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
    try {
      std::thread(watch_signals, set).detach();
    } catch (const std::system_error& e) {
      // EAGAIN or ENOMEM: its stack did not fit the memory or thread limit.
      throw Error("cannot start the interrupt watcher (" + e.code().message() +
                  "): out of memory or threads (ulimit -v, ulimit -u)");
    }
  });
}

}  // namespace bluetile
