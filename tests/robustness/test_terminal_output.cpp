// Binary point tables (.npy, .bpt) to "-" when standard output is a terminal (a pseudo-terminal
// made here, never the test's own): refused before any work, as gzip does; text still goes there.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "robustness_support.h"
#include "test_support.h"

namespace bluetile::robustness {
namespace {

// The tool with stdout and stderr on a new pseudo-terminal; killed after `seconds`.
TerminalRun run_with_terminal_output(const std::vector<std::string>& arguments, int seconds) {
  test::TempDir folder;
  return run_on_terminal(arguments, folder.path(), seconds, 0, {}, true);
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
