// How a command's bytes reach its output paths: checked before the work starts, streamed while
// it runs, published together at the end, and never clobbering what they should not.
//
// What a path names decides how it is written:
// - a regular file, or nothing yet: the bytes go to a staged file in a hidden folder
//   (".bluetile-PID-K") beside the target, on the same file system, and are renamed over the
//   target when the outputs are published. A reader sees the old file or the new one, never a
//   part of either. A replaced file's permission bits (rwx of user, group and others; set-id and
//   sticky bits are dropped) and, where the process may set them, its owner and group are kept.
// - a symbolic link: followed (up to 40 links); the file it points to is replaced in its own
//   folder, and the link stays a link. A dangling link creates the file it names.
// - a character or block device, a FIFO, a socket: opened when declared and written directly
//   when the output is written, without any atomicity: what was written before a failure stays
//   written. A FIFO blocks, as for any program, until a reader opens it.
// - /dev/stdout, /dev/stderr, /dev/fd/N, /proc/self/fd/N: that open descriptor, written directly.
// - "-", where the caller allows it (OutputOptions::allow_stdout): standard output, directly.
// Binary bytes (OutputOptions::binary_format) are refused when the output opened directly is a
// terminal: standard output, or any path that names one (/dev/tty, /dev/fd/2, a link to a pty).
// Refused when declared, before any work, with an Error naming the user's path: a folder; a
// missing or unwritable parent folder; an existing file the process may not write; the same file
// as a declared input (add_input) or as another output of the set (by device and inode, through
// links; for files not yet there, by parent folder and name); a pipe or socket (standard output
// or a named FIFO) that another output of the set already writes to, whose bytes would
// interleave (a device such as /dev/null takes any number).
//
// Writers stream: they receive an OutputStream (buffered, every write(2) and the close checked),
// so a 10^8-point file is written with bounded memory. Any failed write throws Error naming the
// user's path; nothing staged is published then.
//
// A command declares all its outputs in one OutputSet, writes each (in any order, each once),
// then calls publish(): every staged file is renamed over its target, all of them or none (a
// replaced file is kept as a hard link until every rename has succeeded, so a failed rename puts
// the earlier ones back; where the file system refuses hard links that rollback is not possible).
// A set destroyed without publish() (an exception, an error) removes everything it staged.
// add_folder() declares a folder of outputs (analyze; "-" is refused, as an output that cannot be
// standard output is): a missing folder is staged whole and appears, with its files, in one rename
// at publish. In a folder that was already there, nothing but the set's own files is touched;
// after publishing, one line on stderr ("bluetile: note: DIR also holds N files this run did not
// write ...") names the visible regular files it holds besides them, which may be outputs of an
// earlier run with other options.
//
// Interrupts: install_interrupt_cleanup(), called first thing by the tool's main, blocks SIGINT,
// SIGTERM and SIGHUP (those the process does not ignore) in the calling thread (threads started
// later inherit that) and hands them to a watcher thread, which removes every staged file and
// folder and then ends the process by the same signal. Call it before starting threads. Then only
// SIGKILL, a crash or a power loss can leave a hidden ".bluetile-PID-K" folder behind. The
// library never calls it itself: signals belong to the program that embeds it (Python turns
// Ctrl-C into KeyboardInterrupt, and a blocked mask would pass to every process it starts), so
// there a signal that ends the process can leave a staging folder, as SIGKILL can.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace bluetile {

// A buffered byte sink over a file descriptor. Every failed write throws Error("<path>: cannot
// write: <reason>") with the user's path.
class OutputStream {
 public:
  OutputStream(int fd, std::string path);
  ~OutputStream();
  OutputStream(const OutputStream&) = delete;
  OutputStream& operator=(const OutputStream&) = delete;

  void write(const void* data, std::size_t size);
  void write(std::string_view text) { write(text.data(), text.size()); }
  void put(char c);
  // printf-style formatting straight into the buffer (C locale, as the tool never sets another).
  void print(const char* format, ...) __attribute__((format(printf, 2, 3)));
  // A std::ostream over the same bytes (for nlohmann::json, operator<<); its failures throw.
  std::ostream& ostream();

  const std::string& path() const { return path_; }  // as the user gave it
  std::uint64_t size() const { return written_ + buffered_; }

  // Flushes and, when `sync`, fsyncs; closes the descriptor; throws Error on any failure.
  void close(bool sync);

 private:
  void flush();

  int fd_;
  std::string path_;
  std::unique_ptr<char[]> buffer_;
  std::size_t buffered_ = 0;
  std::uint64_t written_ = 0;
  struct StreamAdapter;
  std::unique_ptr<StreamAdapter> adapter_;
};

using OutputWriter = std::function<void(OutputStream&)>;

struct OutputOptions {
  bool allow_stdout = false;  // "-" means standard output
  // Not empty for binary bytes (a format name, "NumPy (.npy)"): an output that is a terminal
  // (standard output, /dev/tty, any path naming one) is refused when declared, as gzip does,
  // rather than spilling them onto the screen.
  std::string_view binary_format;
};

// One declared output of an OutputSet.
class OutputFile {
 public:
  const std::string& path() const { return path_; }  // as the user gave it
  // Whether this output is the process's standard output ("-", /dev/stdout, /dev/fd/1).
  bool is_stdout() const { return stdout_; }

  // Writes the whole output: opens it, calls writer, flushes, closes; throws Error on failure.
  void write(const OutputWriter& writer);
  void write(std::string_view text);
  // For writers that need a path (an external library): writer(path) writes a file there; for a
  // staged output that is the staged file, else a private temporary copied to the target.
  // Messages of the writer that name that path should be rewritten to path() by the caller.
  void write_through_path(const std::function<void(const std::string&)>& writer);
  // For an output written piece by piece over a run (a log): open() once, write, close().
  OutputStream& open();
  void close();

 private:
  friend class OutputSet;
  enum class Kind { staged, descriptor };
  std::string path_;
  Kind kind_ = Kind::staged;
  int descriptor_ = -1;    // Kind::descriptor: open fd (ours, closed after writing)
  bool stdout_ = false;     // Kind::descriptor: a copy of descriptor 1
  std::string name_;        // Kind::staged: file name in the staging folder and the target's
  std::string target_;      // Kind::staged: the resolved target path
  std::string staged_;      // Kind::staged: the staged file
  bool replaces_ = false;   // Kind::staged: a file exists at target_
  std::unique_ptr<OutputStream> stream_;
  bool written_ = false;
};

class OutputSet {
 public:
  OutputSet();
  ~OutputSet();  // if not published: removes everything staged, closes descriptors
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // An input of the command ("-" = standard input): no output may be the same file.
  void add_input(const std::string& path);
  // Declares and checks an output; the reference stays valid for the set's life.
  OutputFile& add(const std::string& path, OutputOptions options = {});
  // Declares a folder of outputs, created at publish if missing (with missing parents); files in
  // it are then add()ed as folder/name.
  void add_folder(const std::string& path);
  // Renames every staged output over its target, all or none; every output must be written.
  void publish();

 private:
  struct Folder;
  struct Identity;
  struct Known;
  void remember(const Identity& id, const std::string& path, bool is_input);
  std::size_t staging_folder_for(const std::string& directory, const std::string& user_path);
  void discard() noexcept;
  void note_files_of_earlier_runs() const;

  std::vector<std::unique_ptr<Folder>> folders_;
  std::vector<std::unique_ptr<OutputFile>> outputs_;
  std::vector<std::unique_ptr<Known>> known_;  // declared inputs and outputs, by identity
  std::vector<std::string> new_folders_;  // add_folder() paths not yet there, lexically normal
  std::vector<std::pair<std::string, std::string>> reused_folders_;  // add_folder() of a folder already there: user's path, resolved
  bool published_ = false;
};

// The folder for private temporary files (an image read from a FIFO, a format written through a
// path to a device): $TMPDIR when it is set and not empty, else /tmp. Throws Error("<why>, but
// TMPDIR '<value>' is not a folder (<reason>): ...") when it names anything else (a stale TMPDIR
// was "internal error: filesystem error: temp_directory_path: No such file or directory").
std::string temporary_folder(const std::string& why);

// One output on its own: declares it, writes it, publishes it.
void write_output(const std::string& path, const OutputWriter& writer, OutputOptions options = {});
void write_output(const std::string& path, std::string_view text, OutputOptions options = {});

// See the header comment; for a program's main, not for a library; idempotent. Throws Error if
// the watcher thread cannot start.
void install_interrupt_cleanup();

}  // namespace bluetile
