// Binary point tables (.npy, .bpt) to "-" when standard output is a terminal, or to a path that
// names one (a pseudo-terminal made here, never the test's own): refused before any work, as gzip
// does; text still goes there.
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

TEST(TerminalOutput, BinaryPointTablesAreRefusedOnATerminalNamedByAPath) {
  // -o /dev/tty --format npy dumped the bytes onto the terminal: only "-" was asked. Here a link
  // in a temporary folder names the pseudo-terminal; stdout is a file.
  test::TempDir folder;
  const std::string link = folder.file("tty");
  TerminalRun refused = run_on_terminal(
      {"relax", "--count", "20000", "--iterations", "100000", "--engine", "exact", "--format", "npy", "-o", link},
      folder.path(), 60, 0, {}, false, link);
  EXPECT_EQ(refused.exit_code, 1) << refused.terminal;
  EXPECT_NE(refused.terminal.find("bluetile: " + link + ": is a terminal, and NumPy (.npy) data is binary: write it "
                                  "to a file or pipe it to a program"),
            std::string::npos)
      << refused.terminal;
  EXPECT_EQ(refused.terminal.find("NUMPY"), std::string::npos) << "no binary byte reached the terminal";
  EXPECT_EQ(test::read_text(folder.file("stdout.txt")), "");
  EXPECT_EQ(entries(folder.path()), (std::vector<std::string>{"stdin.txt", "stdout.txt", "tty@"}));
  // Text to the same path still goes there.
  test::TempDir other;
  const std::string text_link = other.file("tty");
  TerminalRun shown = run_on_terminal({"relax", "--count", "20", "--iterations", "1", "--engine", "exact", "-o", text_link},
                                      other.path(), 60, 0, {}, false, text_link);
  EXPECT_EQ(shown.exit_code, 0) << shown.terminal;
  EXPECT_NE(shown.terminal.find("# bluetile relax: 20 points"), std::string::npos) << shown.terminal;
}

TEST(TerminalOutput, ImagesAndBinaryColumnsAreRefusedOnATerminalNamedByAPath) {
  // An ID image, tile's raw columns and a stipple's PNG went onto the terminal as bytes.
  struct Case {
    std::vector<std::string> arguments;  // "{}" stands for the link
    std::string link_name, words;
  };
  const std::vector<Case> cases = {
      {{"relax", "--count", "20", "--iterations", "0", "--engine", "exact", "--id-image", "{}", "-o", "{folder}/p.txt"},
       "tty",
       "image"},
      {{"tile", "--region", "0", "0", "1", "1", "--density", "4", "-o", "{}"}, "tty.bin", "raw float64 columns"},
      {{"stipple", "--image", "{image}", "-n", "20", "--iterations", "0", "--png", "{}"}, "tty", "image"},
  };
  test::TempDir inputs;  // a 2 x 2 grey image for the stipple
  const std::string image = inputs.write("grey.pgm", std::string("P5 2 2 255\n") + std::string(4, '\x80'));
  for (const Case& c : cases) {
    test::TempDir folder;
    const std::string link = folder.file(c.link_name);
    std::vector<std::string> arguments;
    for (const std::string& a : c.arguments)
      arguments.push_back(a == "{}" ? link : a == "{folder}/p.txt" ? folder.file("p.txt") : a == "{image}" ? image : a);
    TerminalRun refused = run_on_terminal(arguments, folder.path(), 60, 0, {}, false, link);
    EXPECT_EQ(refused.exit_code, 1) << refused.terminal;
    EXPECT_NE(refused.terminal.find("bluetile: " + link + ": is a terminal, and " + c.words + " data is binary"),
              std::string::npos)
        << refused.terminal;
    EXPECT_EQ(entries(folder.path()), (std::vector<std::string>{"stdin.txt", "stdout.txt", c.link_name + "@"}));
  }
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
