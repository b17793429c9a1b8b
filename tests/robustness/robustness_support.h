// The robustness group's harness: runs the bluetile binary as a child process with a chosen
// stdin, environment and resource limits, and looks at what it left behind.
#pragma once

#include <sys/types.h>

#include <string>
#include <utility>
#include <vector>

namespace bluetile::robustness {

struct Invocation {
  std::vector<std::string> arguments;           // after the program name
  std::string stdin_path = "/dev/null";
  std::vector<std::pair<std::string, std::string>> environment;  // added to (or replacing in) ours
  long address_space_bytes = 0;                 // RLIMIT_AS when > 0 (ulimit -v)
  long file_size_bytes = -1;                    // RLIMIT_FSIZE when >= 0 (ulimit -f)
  // Run as the unprivileged user "nobody" (65534) when the test runs as root, so that
  // permissions apply; the folders it works in must then be open to it.
  bool unprivileged = false;
  // A program (absolute path, then its arguments) that the tool's command line is given to, as
  // `unshare ... sh -c SCRIPT sh` takes it: the tool then runs inside what the program sets up.
  std::vector<std::string> wrapper;
  // The folder the tool runs in ("": the test's own), so that a relative path it makes up (a
  // folder named "-") lands where the test looks.
  std::string working_directory;
};

struct Outcome {
  int exit_code = -1;  // -1 when ended by a signal
  int signal = 0;      // the signal that ended it, or 0
  long max_resident_kib = 0;  // its peak resident memory (getrusage's ru_maxrss)
  std::string out, err;
};

// A started child; wait() collects it.
class Child {
 public:
  explicit Child(const Invocation& run);
  ~Child();
  pid_t pid() const { return pid_; }
  Outcome wait();

 private:
  pid_t pid_ = -1;
  std::string capture_dir_;
  bool waited_ = false;
};

Outcome run(const Invocation& run);
inline Outcome run(std::vector<std::string> arguments) { return run(Invocation{std::move(arguments)}); }

struct TerminalRun {
  int exit_code = -1;    // -1 when killed
  std::string terminal;  // what the tool wrote to the terminal
};

// Runs the tool with stderr (and, with `stdout_on_terminal`, stdout) on a new pseudo-terminal
// `columns` wide (0: size unset), stdin an empty file in `folder` and stdout otherwise
// `folder`/stdout.txt, with `environment` set (an empty value unsets); kills it after `seconds`.
// `terminal_link`: a symbolic link made there to the pseudo-terminal (/dev/pts/N), for a path
// argument that names it.
TerminalRun run_on_terminal(const std::vector<std::string>& arguments, const std::string& folder, int seconds,
                            unsigned short columns = 0,
                            const std::vector<std::pair<std::string, std::string>>& environment = {},
                            bool stdout_on_terminal = false, const std::string& terminal_link = "");

// Every entry under `folder` (hidden ones and subfolders too), relative, sorted; "name@" for a
// symbolic link, "name|" for a FIFO, "name%" for a device, "name/" for a folder.
std::vector<std::string> entries(const std::string& folder);

// Whether this binary and the tool were built with the address sanitizer (which reserves
// terabytes of address space, so ulimit -v cannot be used).
bool sanitized();

// A point file of `count` distinct points (up to 988027), for runs sized by their input.
std::string many_points_text(int count);

// The absolute path of `name` on PATH, or "" when there is none.
std::string find_program(const std::string& name);

}  // namespace bluetile::robustness
