#include "robustness_support.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include <fcntl.h>
#include <grp.h>
#include <pty.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_support.h"

extern char** environ;

namespace bluetile::robustness {
namespace fs = std::filesystem;

Child::Child(const Invocation& run) {
  char pattern[] = "/tmp/bluetile-capture-XXXXXX";
  if (!mkdtemp(pattern)) throw std::runtime_error("mkdtemp failed");
  capture_dir_ = pattern;
  const std::string out = capture_dir_ + "/out", err = capture_dir_ + "/err";

  // Everything the child needs is prepared before fork: it only calls async-signal-safe functions.
  std::vector<std::string> args = run.wrapper;
  args.push_back(BLUETILE_BINARY);
  args.insert(args.end(), run.arguments.begin(), run.arguments.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) {
    std::string entry(*e);
    bool replaced = false;
    for (const auto& [name, value] : run.environment) replaced |= entry.rfind(name + "=", 0) == 0;
    if (!replaced) env.push_back(entry);
  }
  for (const auto& [name, value] : run.environment) env.push_back(name + "=" + value);
  std::vector<char*> envp;
  for (std::string& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);

  pid_ = fork();
  if (pid_ < 0) throw std::runtime_error("fork failed");
  if (pid_ == 0) {
    int in = open(run.stdin_path.c_str(), O_RDONLY);
    int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (in < 0 || o < 0 || e < 0) _exit(126);
    dup2(in, 0);
    dup2(o, 1);
    dup2(e, 2);
    if (!run.working_directory.empty() && chdir(run.working_directory.c_str()) != 0) _exit(124);
    // The parent (a test thread) may block these for its own reasons; the child starts clean.
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    signal(SIGPIPE, SIG_DFL);
    if (run.address_space_bytes > 0) {
      rlimit limit{static_cast<rlim_t>(run.address_space_bytes), static_cast<rlim_t>(run.address_space_bytes)};
      setrlimit(RLIMIT_AS, &limit);
    }
    if (run.file_size_bytes >= 0) {
      rlimit limit{static_cast<rlim_t>(run.file_size_bytes), static_cast<rlim_t>(run.file_size_bytes)};
      setrlimit(RLIMIT_FSIZE, &limit);
    }
    if (run.unprivileged && geteuid() == 0) {
      const gid_t nobody_group = 65534;
      if (setgroups(0, nullptr) != 0 || setgid(nobody_group) != 0 || setuid(65534) != 0) _exit(125);
    }
    execve(argv[0], argv.data(), envp.data());
    _exit(127);
  }
}

Child::~Child() {
  if (!waited_ && pid_ > 0) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  std::error_code ignored;
  fs::remove_all(capture_dir_, ignored);
}

Outcome Child::wait() {
  Outcome outcome;
  int status = 0;
  rusage usage{};
  while (wait4(pid_, &status, 0, &usage) < 0) {
  }
  waited_ = true;
  outcome.max_resident_kib = usage.ru_maxrss;
  if (WIFEXITED(status)) outcome.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) outcome.signal = WTERMSIG(status);
  outcome.out = test::read_text(capture_dir_ + "/out");
  outcome.err = test::read_text(capture_dir_ + "/err");
  return outcome;
}

Outcome run(const Invocation& r) { return Child(r).wait(); }

std::vector<std::string> entries(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    std::string name = entry.path().lexically_relative(folder).string();
    struct stat st {};
    lstat(entry.path().c_str(), &st);
    if (S_ISLNK(st.st_mode)) name += "@";
    else if (S_ISFIFO(st.st_mode)) name += "|";
    else if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) name += "%";
    else if (S_ISDIR(st.st_mode)) name += "/";
    names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

bool sanitized() {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#else
  return false;
#endif
}

std::string find_program(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::string folders = path ? path : "/usr/bin:/bin";
  for (std::size_t start = 0; start <= folders.size();) {
    const std::size_t end = std::min(folders.find(':', start), folders.size());
    const std::string candidate = folders.substr(start, end - start) + "/" + name;
    if (end > start && access(candidate.c_str(), X_OK) == 0) return candidate;
    start = end + 1;
  }
  return "";
}

TerminalRun run_on_terminal(const std::vector<std::string>& arguments, const std::string& folder, int seconds,
                            unsigned short columns,
                            const std::vector<std::pair<std::string, std::string>>& environment,
                            bool stdout_on_terminal, const std::string& terminal_link) {
  int master = -1, slave = -1;
  winsize size{};
  size.ws_row = 24;
  size.ws_col = columns;
  if (openpty(&master, &slave, nullptr, nullptr, columns > 0 ? &size : nullptr) != 0)
    throw std::runtime_error("openpty failed");
  if (!terminal_link.empty()) {
    const char* name = ttyname(slave);
    if (name == nullptr || symlink(name, terminal_link.c_str()) != 0) {
      close(master);
      close(slave);
      throw std::runtime_error("cannot link " + terminal_link + " to the pseudo-terminal");
    }
  }
  std::vector<char*> argv;
  std::string program = BLUETILE_BINARY;
  argv.push_back(program.data());
  std::vector<std::string> copies = arguments;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string out_path = folder + "/stdout.txt", in_path = folder + "/stdin.txt";
  pid_t pid = fork();
  if (pid == 0) {
    close(master);
    int in = open(in_path.c_str(), O_RDONLY | O_CREAT, 0600);
    int out = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    dup2(in, STDIN_FILENO);
    dup2(stdout_on_terminal ? slave : out, STDOUT_FILENO);
    dup2(slave, STDERR_FILENO);
    for (const auto& [name, value] : environment) {
      if (value.empty()) unsetenv(name.c_str());
      else setenv(name.c_str(), value.c_str(), 1);
    }
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(slave);
  std::atomic<bool> ended{false};
  std::thread stop([pid, seconds, &ended] {
    for (int tenths = 0; tenths < 10 * seconds && !ended; ++tenths)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (!ended) kill(pid, SIGKILL);  // not yet collected, so the pid is still the child's
  });
  TerminalRun result;
  char buffer[4096];
  for (;;) {
    ssize_t n = read(master, buffer, sizeof buffer);
    if (n > 0) result.terminal.append(buffer, static_cast<std::size_t>(n));
    else if (n < 0 && errno == EINTR) continue;
    else break;  // EIO once the child has closed the terminal
  }
  close(master);
  int status = 0;
  ended = true;  // the terminal closed: the child has exited or is exiting
  stop.join();
  waitpid(pid, &status, 0);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string many_points_text(int count) {
  // (i mod 997, i mod 991) on their grids: distinct for i < 997 * 991, as the coprime moduli make them.
  std::string text;
  for (int i = 0; i < count; ++i)
    text += std::to_string((i % 997) / 997.0) + " " + std::to_string((i % 991) / 991.0) + "\n";
  return text;
}

}  // namespace bluetile::robustness
