// Binary point tables (.npy, .bpt) to "-" when standard output is a terminal (a pseudo-terminal
// made here, never the test's own): refused before any work, as gzip does; text still goes there.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <string>
#include <thread>
#include <vector>

#include "robustness_support.h"
#include "test_support.h"

namespace bluetile::robustness {
namespace {

struct TerminalRun {
  int exit_code = -1;
  std::string terminal;  // what the tool wrote to its stdout and stderr, both the terminal
};

// Runs the tool with stdout and stderr on a new pseudo-terminal, stdin on /dev/null; kills it
// after `seconds`.
TerminalRun run_with_terminal_output(const std::vector<std::string>& arguments, int seconds) {
  int master = -1, slave = -1;
  if (openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) {
    ADD_FAILURE() << "openpty failed";
    return {};
  }
  std::vector<char*> argv;
  std::string program = BLUETILE_BINARY;
  argv.push_back(program.data());
  std::vector<std::string> copies = arguments;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = fork();
  if (pid == 0) {
    close(master);
    int in = open("/dev/null", O_RDONLY);
    dup2(in, STDIN_FILENO);
    dup2(slave, STDOUT_FILENO);
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
  ended = true;
  stop.join();
  waitpid(pid, &status, 0);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

TEST(TerminalOutput, BinaryPointTablesAreRefusedOnATerminalBeforeAnyWork) {
  // A relaxation far longer than the 60 s the child is given: refused at once, or killed.
  for (const char* format : {"npy", "binary"}) {
    TerminalRun refused = run_with_terminal_output(
        {"relax", "--count", "20000", "--iterations", "100000", "--engine", "exact", "--format", format, "-o", "-"}, 60);
    EXPECT_EQ(refused.exit_code, 1) << format << ": " << refused.terminal;
    EXPECT_NE(refused.terminal.find("bluetile: -: standard output is a terminal"), std::string::npos) << refused.terminal;
    EXPECT_NE(refused.terminal.find(std::string(format) == "npy" ? "NumPy (.npy)" : "point table (.bpt)"), std::string::npos)
        << refused.terminal;
    EXPECT_NE(refused.terminal.find("redirect it to a file"), std::string::npos) << refused.terminal;
    EXPECT_EQ(refused.terminal.find("NUMPY"), std::string::npos) << "no binary byte reached the terminal";
  }
  // The same through /dev/stdout, standard output by another name.
  TerminalRun named = run_with_terminal_output(
      {"relax", "--count", "10", "--iterations", "1", "--format", "npy", "-o", "/dev/stdout"}, 60);
  EXPECT_EQ(named.exit_code, 1) << named.terminal;
  EXPECT_NE(named.terminal.find("/dev/stdout: standard output is a terminal"), std::string::npos) << named.terminal;
}

TEST(TerminalOutput, TextStillGoesToATerminalAndBinaryToAPipe) {
  const std::vector<std::string> text = {"relax", "--count", "20", "--iterations", "1", "--engine", "exact", "--seed", "3", "-o", "-"};
  TerminalRun shown = run_with_terminal_output(text, 60);
  EXPECT_EQ(shown.exit_code, 0) << shown.terminal;
  Outcome piped_text = run(text);
  ASSERT_EQ(piped_text.exit_code, 0) << piped_text.err;
  // The terminal turns each "\n" into "\r\n".
  std::string expected;
  for (char c : piped_text.out) {
    if (c == '\n') expected += '\r';
    expected += c;
  }
  // (Around the progress line, which stderr, the same terminal, shows.)
  EXPECT_NE(shown.terminal.find(expected), std::string::npos) << shown.terminal;
  // A pipe takes the binary bytes as before.
  Outcome piped = run({"relax", "--count", "20", "--iterations", "1", "--engine", "exact", "--format", "npy", "-o", "-"});
  EXPECT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_EQ(piped.out.substr(0, 6), "\x93NUMPY") << piped.err;
}

}  // namespace
}  // namespace bluetile::robustness
