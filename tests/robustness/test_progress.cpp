// Progress on stderr: shown with totals and the time left when stderr is a terminal (a
// pseudo-terminal here), absent otherwise.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
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

// Runs the tool with stderr on a new pseudo-terminal and stdin, stdout on files.
TerminalRun run_on_terminal(const std::vector<std::string>& arguments, const std::string& folder) {
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
  waitpid(pid, &status, 0);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

TEST(Progress, ATerminalSeesTotalsAndTheTimeLeft) {
  test::TempDir dir;
  // A relaxation of a few seconds: the time left shows once a second has passed.
  const std::vector<std::string> job = {"relax", "--count", "30000", "--iterations", "60", "--engine", "exact",
                                        "-o", dir.file("points.txt")};
  TerminalRun terminal = run_on_terminal(job, dir.path());
  ASSERT_EQ(terminal.exit_code, 0) << terminal.terminal;
  EXPECT_TRUE(std::regex_search(terminal.terminal, std::regex(R"(relax [0-9]+/60, about [0-9.]+ (s|min|h) left)")))
      << terminal.terminal;
  EXPECT_NE(terminal.terminal.find("relax 60/60"), std::string::npos) << terminal.terminal;

  Outcome piped = run(job);
  EXPECT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_EQ(piped.err, "") << "progress is for terminals only";
}

}  // namespace
}  // namespace bluetile::robustness
