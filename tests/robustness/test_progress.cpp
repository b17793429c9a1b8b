// Progress on stderr: shown with totals and the time left when stderr is a terminal (a
// pseudo-terminal here), absent otherwise.
#include <gtest/gtest.h>

#include <cstdint>
#include <regex>
#include <string>
#include <vector>

#include "robustness_support.h"
#include "test_support.h"

namespace bluetile::robustness {
namespace {

TEST(Progress, ATerminalSeesTotalsAndTheTimeLeft) {
  test::TempDir dir;
  // A relaxation far longer than the test, killed after 4 s: the time left shows once a second
  // has passed, whatever the machine's speed.
  TerminalRun terminal = run_on_terminal(
      {"relax", "--count", "20000", "--iterations", "100000", "--engine", "exact", "-o", dir.file("points.txt")},
      dir.path(), 4, 0, {{"COLUMNS", ""}});  // 80 columns, whatever the test's own terminal
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

// A filled level's lattice steps come after its last fill round: the line names them (it showed
// the fill's last round while they ran, which at 2048 points per tile would be minutes).
TEST(Progress, AWangRunShowsTheFilledLevelsLatticeSteps) {
  test::TempDir dir;
  TerminalRun wang = run_on_terminal({"wang", "--set", "wang8", "--points", "8", "--iterations", "2", "--warm", "1",
                                      "--levels", "3", "--engine", "exact", "-o", dir.file("set.tiles")},
                                     dir.path(), 60);
  EXPECT_EQ(wang.exit_code, 0) << wang.terminal;
  EXPECT_NE(wang.terminal.find("level 2: lattice steps 150/150"), std::string::npos) << wang.terminal;
}

// The lines drawn on a terminal: what lies between carriage returns and line feeds.
std::vector<std::string> drawn_lines(const std::string& terminal) {
  std::vector<std::string> lines;
  std::string line;
  for (char c : terminal) {
    if (c == '\r' || c == '\n') {
      if (!line.empty()) lines.push_back(line);
      line.clear();
    } else {
      line += c;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

TEST(Progress, TheLineFitsTheTerminalAndADumbOneGetsNoEscapes) {
  // The line was as long as its text: on a terminal narrower than that it wrapped, and every
  // redraw left a row behind; under TERM=dumb (Emacs' shell) each redraw showed "^[[K".
  test::TempDir dir;
  const std::vector<std::string> job = {"relax", "--count", "300", "--iterations", "6", "--engine", "exact",
                                        "-o", dir.file("small.txt")};
  for (const unsigned short columns : {std::uint16_t{20}, std::uint16_t{0}}) {
    TerminalRun narrow = run_on_terminal(job, dir.path(), 60, columns, {{"TERM", "dumb"}, {"COLUMNS", "30"}});
    EXPECT_EQ(narrow.exit_code, 0) << narrow.terminal;
    EXPECT_EQ(narrow.terminal.find('\033'), std::string::npos) << narrow.terminal;
    const std::size_t width = columns > 0 ? columns : 30;  // the window's size, else COLUMNS
    const std::vector<std::string> lines = drawn_lines(narrow.terminal);
    EXPECT_NE(narrow.terminal.find("relax 6/6"), std::string::npos) << narrow.terminal;
    for (const std::string& line : lines) EXPECT_LT(line.size(), width) << "'" << line << "'";
  }
  // A terminal that takes escapes still gets the erase-line sequence, and the width holds too.
  TerminalRun xterm = run_on_terminal(job, dir.path(), 60, 20, {{"TERM", "xterm"}});
  EXPECT_NE(xterm.terminal.find("\r\033[Krelax 6/6"), std::string::npos) << xterm.terminal;
  for (std::string line : drawn_lines(xterm.terminal)) {
    if (line.rfind("\033[K", 0) == 0) line.erase(0, 3);
    EXPECT_LT(line.size(), 20u) << "'" << line << "'";
  }
}

}  // namespace
}  // namespace bluetile::robustness
