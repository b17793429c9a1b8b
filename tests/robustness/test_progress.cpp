// Progress on stderr: shown with totals and the time left when stderr is a terminal (a
// pseudo-terminal here), absent otherwise.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <thread>
#include <regex>
#include <string>
#include <vector>

#include "robustness_support.h"
#include "test_support.h"

namespace bluetile::robustness {
namespace {

struct TerminalRun {
  int exit_code = -1;
  std::string terminal;  // what the tool wrote to its stderr, a terminal
};

// Runs the tool with stderr on a new pseudo-terminal and stdin, stdout on files; kills it after
// `seconds`.
TerminalRun run_on_terminal(const std::vector<std::string>& arguments, const std::string& folder, int seconds) {
  int master = -1, slave = -1;
  if (openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) ADD_FAILURE() << "openpty failed";
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
    dup2(out, STDOUT_FILENO);
    dup2(slave, STDERR_FILENO);
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

TEST(Progress, ATerminalSeesTotalsAndTheTimeLeft) {
  test::TempDir dir;
  // A relaxation far longer than the test, killed after 4 s: the time left shows once a second
  // has passed, whatever the machine's speed.
  TerminalRun terminal = run_on_terminal(
      {"relax", "--count", "20000", "--iterations", "100000", "--engine", "exact", "-o", dir.file("points.txt")},
      dir.path(), 4);
  EXPECT_TRUE(std::regex_search(terminal.terminal,
                                std::regex(R"(relax [0-9]+/100000, about [0-9.]+ (s|min|h|days) left)")))
      << terminal.terminal;
  // A short run draws its last step on a terminal, and nothing when stderr is not one.
  const std::vector<std::string> job = {"relax", "--count", "300", "--iterations", "6", "--engine", "exact",
                                        "-o", dir.file("small.txt")};
  TerminalRun short_run = run_on_terminal(job, dir.path(), 60);
  EXPECT_EQ(short_run.exit_code, 0) << short_run.terminal;
  EXPECT_NE(short_run.terminal.find("relax 6/6"), std::string::npos) << short_run.terminal;
  Outcome piped = run(job);
  EXPECT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_EQ(piped.err, "") << "progress is for terminals only";
}

}  // namespace
}  // namespace bluetile::robustness
