#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <langinfo.h>
#include <locale.h>

#include "bluetile/analysis/radial_power.h"
#include "bluetile/core/error.h"
#include "bluetile/core/memory_budget.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/point_table.h"
#include "bluetile/core/text.h"
#include "test_support.h"

namespace bluetile {
namespace {

using test::TempDir;

// The message of the Error that parse_points throws for `text`, or "" when it parses.
std::string parse_error(const std::string& text) {
  try {
    parse_points(text, "pts.txt");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(PointFile, ReadsCommentsCountAndLevels) {
  PointSet set = parse_points("# made by hand\n3\n0.1 0.2 0\n0.3 0.4 1 # trailing comment\n\n0.5 0.6 1\n", "x");
  ASSERT_EQ(set.points.size(), 3u);
  EXPECT_EQ(set.points[1], Point(0.3, 0.4));
  EXPECT_EQ(set.levels, (std::vector<int>{0, 1, 1}));
  PointSet plain = parse_points("0.1 0.2\r\n0.3\t0.4\r\n", "x");
  EXPECT_EQ(plain.points.size(), 2u);
  EXPECT_FALSE(plain.has_levels());
}

TEST(PointFile, TheCommentLinesBeforeTheFirstPointAreKeptAsTheHeader) {
  PointSet set = parse_points("# made by hand\n#tile grid 0 0 0.5 0.5\n3\n#  after the count\n0.1 0.2\n# later\n0.3 0.4 "
                              "# trailing\n0.5 0.6\n",
                              "x");
  EXPECT_EQ(set.header, (std::vector<std::string>{" made by hand", "tile grid 0 0 0.5 0.5", "  after the count"}));
  // Each set of a file of several has its own; a long header keeps its first lines.
  std::string text = "# a\n0.1 0.1\n# b\n#  \n# c\n0.2 0.2\n#\n";
  for (int i = 0; i < 40; ++i) text += "# " + std::to_string(i) + "\n";
  text += "0.3 0.3\n";
  TempDir dir;
  const std::vector<PointSet> sets = read_point_sets(dir.write("sets.txt", text));
  ASSERT_EQ(sets.size(), 3u);
  EXPECT_EQ(sets[0].header, (std::vector<std::string>{" a"}));
  EXPECT_EQ(sets[1].header, (std::vector<std::string>{" b", " c"}));
  ASSERT_EQ(sets[2].header.size(), PointSet::kHeaderLines);  // blank comments ('#' between sets) not kept
  EXPECT_EQ(sets[2].header.front(), " 0");
  EXPECT_EQ(sets[2].header.back(), " 31");
}

TEST(PointFile, WrapsCoordinatesOntoTheTorus) {
  PointSet set = parse_points("-0.25 1.5\n1 0\n-1e-20 0.5\n", "x");
  EXPECT_EQ(set.points[0], Point(0.75, 0.5));
  EXPECT_EQ(set.points[1], Point(0.0, 0.0));
  EXPECT_EQ(set.points[2].x, 0.0);  // would round to 1.0, which is outside [0,1)
}

TEST(PointFile, OutOfRangeRefusedWhenAskedAndDomainDeclared) {
  ReadOptions strict;
  strict.wrap = false;
  try {
    parse_points("0.1 0.2\n0.5 1.25\n", "pts.txt", strict);
    ADD_FAILURE() << "accepted y = 1.25";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "pts.txt:2: y = 1.25 is outside [0, 1)");
  }
  EXPECT_THROW(parse_points("-0.0001 0.5\n", "x", strict), Error);
  EXPECT_THROW(parse_points("1 0.5\n", "x", strict), Error);
  EXPECT_EQ(parse_points("0 0.999\n", "x", strict).points.size(), 1u);
  // "# domain bounded" before a set says how it was made; it holds for later sets of the file.
  EXPECT_FALSE(parse_points("0.1 0.2\n", "x").declared_boundary);
  EXPECT_EQ(parse_points("# domain bounded\n0.1 0.2\n", "x").declared_boundary, Boundary::bounded);
  EXPECT_EQ(parse_points("# made by scipy\n#  domain   periodic \n0.1 0.2\n", "x").declared_boundary,
            Boundary::periodic);
  EXPECT_FALSE(parse_points("# domain square\n0.1 0.2\n", "x").declared_boundary);
  TempDir dir;
  auto sets = read_point_sets(dir.write("s.txt", "# domain bounded\n# set 0\n0.1 0.2\n# set 1\n0.3 0.4\n"));
  ASSERT_EQ(sets.size(), 2u);
  EXPECT_EQ(sets[0].declared_boundary, Boundary::bounded);
  EXPECT_EQ(sets[1].declared_boundary, Boundary::bounded);
}

TEST(PointFile, BoundedSetsAreNotWrapped) {
  // A set declared bounded lies in its square: a point outside it was wrapped into the square
  // (1.5 to 0.5) and relaxed or measured there without a word.
  const std::string bounded = " (the set is declared '# domain bounded': its points lie in the square, and are not wrapped "
                              "onto a torus)";
  EXPECT_EQ(parse_error("# domain bounded\n0.5 0.5\n1.5 0.25\n"), "pts.txt:3: x = 1.5 is outside [0, 1)" + bounded);
  EXPECT_EQ(parse_error("# domain bounded\n0.5 -0.25\n"), "pts.txt:2: y = -0.25 is outside [0, 1)" + bounded);
  // The line holds for the later sets of the file; a periodic or undeclared set is wrapped as before.
  EXPECT_THROW(parse_point_sets("# domain bounded\n# set 0\n0.1 0.2\n# set 1\n1 0.4\n", "x"), Error);
  EXPECT_EQ(parse_points("# domain periodic\n1.5 -0.25\n", "x").points, std::vector<Point>{Point(0.5, 0.75)});
  EXPECT_EQ(parse_points("1.5 -0.25\n", "x").points, std::vector<Point>{Point(0.5, 0.75)});
  // Inside, a bounded set reads as before; a CSV's domain line counts the same.
  EXPECT_EQ(parse_points("# domain bounded\n0 0.999\n", "x").points, std::vector<Point>{Point(0.0, 0.999)});
  EXPECT_THROW(parse_csv_points("# domain bounded\nx,y\n1.5,0.25\n", "p.csv"), Error);
}

TEST(PointFile, ACoordinateJustInsideTheDomainsEndStaysAtThatEnd) {
  // (0.9999999999999999 + 1) / 2 rounds to 1: the point read at the right side of a [-1, 1) box
  // was placed at 0, the left side, which a bounded set's analysis took as written there.
  const double below_one = std::nextafter(1.0, 0.0);
  const ReadOptions box{.wrap = true, .domain = CoordinateBox{-1, -1, 1, 1}};
  for (const char* header : {"", "# domain bounded\n", "# domain periodic\n"}) {
    const PointSet set = parse_points(std::string(header) + "0.9999999999999999 -1\n0 0.9999999999999999\n", "x", box);
    EXPECT_EQ(set.points, (std::vector<Point>{{below_one, 0.0}, {0.5, below_one}})) << header;
  }
  // Outside the box a periodic set still wraps: the box's end is its start.
  EXPECT_EQ(parse_points("1 3\n", "x", box).points, (std::vector<Point>{{0.0, 0.0}}));
}

TEST(PointFile, DomainLinesWithATypoAreRefusedNotTakenForComments) {
  // "# domain bounde" was a comment: the set was analysed on the torus without a word.
  const std::string fix =
      " is not a domain line: write '# domain periodic' or '# domain bounded' alone on the line (or reword the "
      "comment)";
  EXPECT_EQ(parse_error("# domain bounde\n0.1 0.2\n"), "pts.txt:1: '# domain bounde'" + fix);
  EXPECT_EQ(parse_error("# made by hand\n#  domain periodic extra \n0.1 0.2\n"),
            "pts.txt:2: '# domain periodic extra'" + fix);
  EXPECT_EQ(parse_error("# Domain: Bounded\n0.1 0.2\n"), "pts.txt:1: '# Domain: Bounded'" + fix);
  EXPECT_EQ(parse_error("0.1 0.2\n# domain periodc\n"), "pts.txt:2: '# domain periodc'" + fix);
  // The boundary followed by punctuation and more words was prose: a bounded set went on the torus.
  EXPECT_EQ(parse_error("# domain bounded, unit square\n0.1 0.2\n"), "pts.txt:1: '# domain bounded, unit square'" + fix);
  EXPECT_EQ(parse_error("# domain periodic; psa's convention\n0.1 0.2\n"),
            "pts.txt:1: '# domain periodic; psa's convention'" + fix);
  EXPECT_EQ(parse_error("0.1 0.2 # domain boundd\n"), "");  // after a point: a comment on the point
  // Prose about the domain stays a comment.
  for (const char* prose : {"# domain square\n", "# domain bounds 0 0 64 64\n", "# domain [0, 64)^2\n", "# domain\n",
                            "# the domain is bounded\n"}) {
    PointSet set = parse_points(std::string(prose) + "0.1 0.2\n", "x");
    EXPECT_FALSE(set.declared_boundary) << prose;
    EXPECT_EQ(set.points.size(), 1u) << prose;
  }
  // In a file of several sets too, where a '#' line also ends a set.
  EXPECT_THROW(parse_point_sets("# set 0\n0.1 0.2\n# domain bounded.\n0.3 0.4\n", "x"), Error);
}

TEST(PointFile, WritersRefuseACommentTheReaderRefuses) {
  // save_table(comment=['domain: bounded']) wrote a file that load_table then refused.
  const PointSet set{{{0.25, 0.5}}, {}, {}};
  const std::string fix =
      ", and reading the file back would fail on it: write 'domain periodic' or 'domain bounded' alone (the writer "
      "adds the '#') to declare the domain, or reword the comment";
  auto write_error = [&](const std::vector<std::string>& header) -> std::string {
    try {
      format_points(set, header);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(write_error({"made by hand", "domain: bounded"}),
            "comment line 2: '# domain: bounded' is not a domain line" + fix);
  EXPECT_EQ(write_error({"Domain Bounded"}), "comment line 1: '# Domain Bounded' is not a domain line" + fix);
  EXPECT_EQ(write_error({" domain periodc "}), "comment line 1: '# domain periodc' is not a domain line" + fix);
  // What the reader takes is written and read back: domain lines, prose, a '#' of its own.
  for (const std::string line : {"domain bounded", "domain periodic", "domain torus", "domain aperiodic",
                                 "domain [0, 64)^2", "the domain is bounded", "# domain: bounded", ""}) {
    const PointSet back = parse_points(format_points(set, {line}), "x");
    EXPECT_EQ(back.points.size(), 1u) << line;
  }
  EXPECT_EQ(parse_points(format_points(set, {"domain bounded"}), "x").declared_boundary, Boundary::bounded);
  // The streaming writer and the table writer check before any byte.
  TempDir dir;
  const std::string path = dir.file("c.txt");
  EXPECT_THROW(write_point_file(path, set, {"domain: bounded"}), Error);
  EXPECT_FALSE(std::filesystem::exists(path));
  std::string bytes;
  EXPECT_THROW(write_point_table(TableFormat::text, std::vector<PointSet>{set}, {.float32 = false, .name = {},
                                 .comment = {"domain bounde"}}, "c.txt", [&](std::string_view b) { bytes += b; }),
               Error);
  EXPECT_EQ(bytes, "");
  // A C header's '//' comment is not read back: any line goes.
  write_point_table(TableFormat::header, std::vector<PointSet>{set}, {.float32 = false, .name = {},
                    .comment = {"domain: bounded"}}, "c.h", [&](std::string_view b) { bytes += b; });
  EXPECT_NE(bytes.find("// domain: bounded\n"), std::string::npos);
}

TEST(PointFile, CommaSeparatedLinesSayHowCsvIsRead) {
  // A CSV given as text was "expected 'x y' or 'x y level'" and no more.
  const std::string hint = " (comma-separated values: a file named .csv is read as CSV)";
  EXPECT_EQ(parse_error("0.5,0.25\n"), "pts.txt:1: expected 'x y' or 'x y level', got '0.5,0.25'" + hint);
  EXPECT_EQ(parse_error("x,y\n0.5,0.25\n"), "pts.txt:1: expected 'x y' or 'x y level', got 'x,y'" + hint);
  EXPECT_EQ(parse_error("0.5, 0.25\n"), "pts.txt:1: not a number '0.5,'" + hint);
  EXPECT_EQ(parse_error("0, 0.5, 0.25, 1\n"),
            "pts.txt:1: expected 'x y' or 'x y level', got 4 columns: '0, 0.5, 0.25, 1'" + hint);
  EXPECT_EQ(parse_error("0.5 x\n"), "pts.txt:1: not a number 'x'");  // no comma, no hint
}

// A locale whose decimal point is a comma: one the system has, else de_DE made with localedef in
// `folder`; 0 when neither can be had.
locale_t comma_locale(const std::string& folder) {
  auto comma = [](locale_t l) { return l != static_cast<locale_t>(0) && std::string(nl_langinfo_l(RADIXCHAR, l)) == ","; };
  for (const char* name : {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "fr_FR.utf8", "de_DE", "fr_FR"}) {
    locale_t l = newlocale(LC_ALL_MASK, name, static_cast<locale_t>(0));
    if (comma(l)) return l;
    if (l) freelocale(l);
  }
  if (test::run_command("localedef -i de_DE -f UTF-8 '" + folder + "/de_DE.UTF-8' 2>/dev/null").exit_code != 0)
    return static_cast<locale_t>(0);
  setenv("LOCPATH", folder.c_str(), 1);
  locale_t l = newlocale(LC_ALL_MASK, "de_DE.UTF-8", static_cast<locale_t>(0));
  unsetenv("LOCPATH");
  if (comma(l)) return l;
  if (l) freelocale(l);
  return static_cast<locale_t>(0);
}

TEST(PointFile, NumbersAreWrittenAndReadWithAPointWhateverTheLocale) {
  // Under a program's German locale (Python's locale.setlocale(LC_ALL, '')), point files were
  // written "0,5 0,25", which no reader took back, and CSV fields "0,5" split in two.
  TempDir dir;
  const locale_t comma = comma_locale(dir.path());
  if (comma == static_cast<locale_t>(0)) GTEST_SKIP() << "no locale with a decimal comma, and localedef cannot make one";
  const locale_t before = uselocale(comma);
  char check[16];
  std::snprintf(check, sizeof check, "%.1f", 0.5);
  const std::string seen = check;
  const PointSet set{{{0.5, 0.25}, {0.125, 0.75}}, {0, 1}, {}};
  const std::string text = format_points(set);
  write_point_file(dir.file("p.txt"), set);
  const std::string written = test::read_text(dir.file("p.txt"));
  std::string table;
  write_point_table(TableFormat::header, std::vector<PointSet>{set}, {}, "t.h", [&](std::string_view b) { table += b; });
  const std::string csv = csv_number(0.5, 6), exact = exact_text(0.5), fixed = fixed_text(0.5, 2);
  const std::string range = read_range_text(0, ReadOptions{.wrap = false, .domain = CoordinateBox{0.5, 0, 1.5, 1}});
  const PointSet tiny = parse_points("1.5e-330 0.5\n", "x");
  uselocale(before);
  freelocale(comma);
  ASSERT_EQ(seen, "0,5") << "the locale made has no decimal comma";
  EXPECT_EQ(text, "0.5 0.25 0\n0.125 0.75 1\n");
  EXPECT_EQ(written, text);
  EXPECT_NE(table.find("{0.5f, 0.25f, 0.0f},"), std::string::npos) << table;
  EXPECT_EQ(csv + " " + exact + " " + fixed, "0.5 0.5 0.50");
  EXPECT_EQ(range, "[0.5, 1.5)");
  EXPECT_EQ(tiny.points, (std::vector<Point>{{0.0, 0.5}}));  // 1.5e-330 is 0, not "out of range"
}

TEST(PointFile, DomainCommentsOfWordsNearABoundaryStayComments) {
  // "# domain aperiodic" (a tiling of the plane), "# domain unbounded" and "# domain bounds" are
  // words of their own a letter or two from "periodic" or "bounded"; they were refused as typos.
  for (const char* prose : {"# domain aperiodic\n", "# domain Unbounded\n", "# domain bounds\n", "# domain rounded\n",
                            "# domain founded\n", "# domain bound\n", "# domain period\n"}) {
    EXPECT_EQ(parse_error(std::string(prose) + "0.1 0.2\n"), "") << prose;
    PointSet set = parse_points(std::string(prose) + "0.1 0.2\n", "x");
    EXPECT_FALSE(set.declared_boundary) << prose;
  }
  EXPECT_NE(parse_error("# domain aperiodc\n0.1 0.2\n"), "");  // a typo of neither word is still one
}

TEST(PointFile, ACHeaderSaysItIsOneNotCommaSeparatedValues) {
  // A .h that --format header writes, given as points, was "got 15 columns: ... (comma-separated
  // values: a file named .csv is read as CSV)".
  const std::string fix =
      ": a C header (bluetile writes one for --format header) is compiled in, not read back; read the points from the "
      "text, .npy or .bpt file it was made from";
  EXPECT_EQ(parse_error("// bluetile dart: 4 points, seed 1\nstatic const double p[1][1][2] = {{{0.5, 0.5}}};\n"),
            "pts.txt:1: a C or C++ source line '// bluetile dart: 4 points, seed 1'" + fix);
  EXPECT_EQ(parse_error("/* points */\n"), "pts.txt:1: a C or C++ source line '/* points */'" + fix);
}

TEST(PointFile, MessagesWriteNumbersWithAPointWhateverTheLocale) {
  // Messages formatted with printf under the program's comma locale said "1,5 MiB" and
  // "annulus width 10,5".
  TempDir dir;
  const locale_t comma = comma_locale(dir.path());
  if (comma == static_cast<locale_t>(0)) GTEST_SKIP() << "no locale with a decimal comma, and localedef cannot make one";
  const locale_t before = uselocale(comma);
  const std::string bytes = format_bytes(1.5 * 1024 * 1024);
  std::string annulus;
  try {
    radial_power(Periodogram{8, std::vector<double>(64, 1.0)}, 10.5);
  } catch (const Error& e) {
    annulus = e.what();
  }
  uselocale(before);
  freelocale(comma);
  EXPECT_EQ(bytes, "1.5 MiB");
  EXPECT_EQ(annulus, "annulus width 10.5 is wider than half the periodogram size (4)");
}

TEST(PointFile, MalformedLinesNameFileLineAndValue) {
  EXPECT_EQ(parse_error("0.1 0.2\n0.3 nan\n"), "pts.txt:2: not a finite number 'nan'");
  EXPECT_EQ(parse_error("0.1 0.2\ninf 0.3\n"), "pts.txt:2: not a finite number 'inf'");
  EXPECT_EQ(parse_error("0.1 zero\n"), "pts.txt:1: not a number 'zero'");
  EXPECT_EQ(parse_error("0.1 0.2x\n"), "pts.txt:1: not a number '0.2x'");
  EXPECT_EQ(parse_error("1e999 0.2\n"), "pts.txt:1: coordinate out of range '1e999'");
  EXPECT_EQ(parse_error("-1e999 0.2\n"), "pts.txt:1: coordinate out of range '-1e999'");
  EXPECT_EQ(parse_error("+-0.2 0.2\n"), "pts.txt:1: not a number '+-0.2'");
  EXPECT_EQ(parse_error("++0.2 0.2\n"), "pts.txt:1: not a number '++0.2'");
  EXPECT_EQ(parse_error("+ 0.2\n"), "pts.txt:1: not a number '+'");
  // A leading '+' (C, Python and NumPy write it) and a number too small for a double (0, as C's
  // strtod reads it) were refused as "not a number" and "out of range".
  EXPECT_EQ(parse_points("+0.25 0.5\n1e-330 +.75\n", "pts.txt").points,
            (std::vector<Point>{{0.25, 0.5}, {0.0, 0.75}}));
  EXPECT_EQ(parse_error("0.1 0.2\n0.5\n"), "pts.txt:2: expected 'x y' or 'x y level', got '0.5'");
  EXPECT_EQ(parse_error("0.1 0.2 0 7\n"), "pts.txt:1: expected 'x y' or 'x y level', got 4 columns: '0.1 0.2 0 7'");
  EXPECT_EQ(parse_error("0.1 0.2 0\n0.3 0.4\n"), "pts.txt:2: level column missing (earlier lines have one)");
  EXPECT_EQ(parse_error("0.1 0.2\n0.3 0.4 1\n"), "pts.txt:2: level column appears here but not on earlier lines");
  EXPECT_EQ(parse_error("0.1 0.2 -1\n"), "pts.txt:1: level must be an integer from 0 to 1000000, got '-1' (a point file's third column is the level; a table such as centroids' cx cy area is no point file)");
  EXPECT_EQ(parse_error("0.1 0.2 1.5\n"), "pts.txt:1: level must be an integer from 0 to 1000000, got '1.5' (a point file's third column is the level; a table such as centroids' cx cy area is no point file)");
  EXPECT_EQ(parse_error("# c\n3\n0.1 0.2\n0.3 0.4\n"), "pts.txt:2: count line says 3 points but 2 follow");
  EXPECT_EQ(parse_error("-2\n"), "pts.txt:1: negative point count '-2'");
  EXPECT_EQ(parse_error(std::string("0.1 0.2\n\0\n", 10)), "pts.txt:2: binary data (NUL byte): not a point file");
  EXPECT_EQ(parse_error(""), "");
}

TEST(PointFile, ByteOrderMarkIsSkippedAtTheStartOnly) {
  // "\xEF\xBB\xBF0.1 0.2" was "not a number '\xEF\xBB\xBF0.1'".
  PointSet set = parse_points("\xEF\xBB\xBF" "0.1 0.2\n0.3 0.4\n", "x");
  EXPECT_EQ(set.points, (std::vector<Point>{{0.1, 0.2}, {0.3, 0.4}}));
  EXPECT_EQ(parse_error("0.1 0.2\n\xEF\xBB\xBF" "0.3 0.4\n"), "pts.txt:2: not a number '\xEF\xBB\xBF" "0.3'");
  EXPECT_TRUE(parse_points("\xEF\xBB\xBF", "x").points.empty());
  EXPECT_EQ(parse_error("\xEF\xBB"), "pts.txt:1: expected 'x y' or 'x y level', got '\xEF\xBB'");
}

TEST(PointFile, Utf16TextSaysHowToSaveItAsUtf8) {
  // Windows PowerShell's "> points.txt" writes UTF-16: it was "binary data (NUL byte)".
  const std::string fix = "pts.txt: UTF-16 text (Windows PowerShell's '>' and Out-File write it); point files are "
                          "UTF-8: save it with Out-File -Encoding utf8 (or Set-Content)";
  const std::string little("\xFF\xFE" "0\0.\0" "5\0 \0" "0\0\r\0\n\0", 16);
  EXPECT_EQ(parse_error(little), fix);
  EXPECT_EQ(parse_error(std::string("\xFE\xFF\0" "0\0.\0" "5", 8)), fix);
  for (std::size_t step : {1, 2, 3}) {  // cut anywhere, as read from a pipe
    PointTextParser parser("pts.txt", false);
    std::string message;
    try {
      for (std::size_t at = 0; at < little.size(); at += step) parser.feed(std::string_view(little).substr(at, step));
      parser.finish();
    } catch (const Error& e) {
      message = e.what();
    }
    EXPECT_EQ(message, fix) << step;
  }
  EXPECT_EQ(parse_error("\xFF"), "pts.txt:1: expected 'x y' or 'x y level', got '\xFF'");  // too short to tell
}

TEST(PointFile, PiecesCutAnywhereParseAsTheWhole) {
  const std::string text = "\xEF\xBB\xBF# set 0\r\n3\n0.1 0.2 0\n0.3 0.4 1 # c\n\n0.5 0.6 1\n# set 1\n0.7 0.8 2";
  const std::vector<PointSet> whole = parse_point_sets(text, "x");
  ASSERT_EQ(whole.size(), 2u);
  ASSERT_EQ(whole[0].points.size(), 3u);
  EXPECT_EQ(whole[1].points, (std::vector<Point>{{0.7, 0.8}}));
  for (std::size_t step : {1, 2, 3, 5, 7, 64}) {
    PointTextParser parser("x", true);
    for (std::size_t at = 0; at < text.size(); at += step) parser.feed(std::string_view(text).substr(at, step));
    std::vector<PointSet> pieces = parser.finish();
    ASSERT_EQ(pieces.size(), whole.size()) << step;
    for (std::size_t k = 0; k < whole.size(); ++k) {
      EXPECT_EQ(pieces[k].points, whole[k].points) << step;
      EXPECT_EQ(pieces[k].levels, whole[k].levels) << step;
    }
  }
}

TEST(PointFile, ALoneCarriageReturnEndsALineAsCrLfDoes) {
  // Classic Mac OS line ends: the file was one line ("got 4 columns: '0.1 0.20.3 0.4'").
  const std::string mac = "# by hand\r3\r0.1 0.2 0\r0.3 0.4 1\r\r0.5 0.6 1\r";
  const std::string unix_text = "# by hand\n3\n0.1 0.2 0\n0.3 0.4 1\n\n0.5 0.6 1\n";
  const std::string windows = "# by hand\r\n3\r\n0.1 0.2 0\r\n0.3 0.4 1\r\n\r\n0.5 0.6 1\r\n";
  const PointSet expected = parse_points(unix_text, "x");
  ASSERT_EQ(expected.points.size(), 3u);
  for (const std::string& text : {mac, windows}) {
    for (std::size_t step : {1, 2, 3, 7, 64}) {  // a "\r\n" cut between chunks is one line end
      PointTextParser parser("x", false);
      for (std::size_t at = 0; at < text.size(); at += step) parser.feed(std::string_view(text).substr(at, step));
      std::vector<PointSet> sets = parser.finish();
      ASSERT_EQ(sets.size(), 1u);
      EXPECT_EQ(sets[0].points, expected.points) << step;
      EXPECT_EQ(sets[0].levels, expected.levels) << step;
      EXPECT_EQ(parser.lines(), 6u) << step;
    }
  }
  // Lines are counted as an editor shows them, whichever ends they have.
  EXPECT_EQ(parse_error("0.1 0.2\r0.3 x\r"), "pts.txt:2: not a number 'x'");
  EXPECT_EQ(parse_error("0.1 0.2\r\n0.3 x\r\n"), "pts.txt:2: not a number 'x'");
}

TEST(PointFile, QuotedValuesAreCut) {
  // A 10 MB bad line was quoted whole.
  const std::string long_token(1000, 'z');
  EXPECT_EQ(parse_error("0.1 " + long_token + "\n"), "pts.txt:1: not a number '" + std::string(40, 'z') + "...' (1000 bytes)");
  EXPECT_EQ(parse_error("0.1 0.2 3 " + long_token + "\n"),
            "pts.txt:1: expected 'x y' or 'x y level', got 4 columns: '0.1 0.2 3 " + std::string(30, 'z') +
                "...' (1010 bytes)");
  EXPECT_EQ(parse_error("0.1 1e999\n"), "pts.txt:1: coordinate out of range '1e999'");
  EXPECT_EQ(parse_error("0.1 " + std::string(400, '9') + "x\n"),
            "pts.txt:1: not a number '" + std::string(40, '9') + "...' (401 bytes)");
}

TEST(PointFile, MissingFileIsAnError) {
  EXPECT_THROW(read_point_file("/nonexistent/points.txt"), Error);
  TempDir dir;
  try {
    read_point_file(dir.path());
    ADD_FAILURE() << "a folder was read as a point file";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), dir.path() + ": is a folder");
  }
}

TEST(PointFile, CommentsCannotAddLines) {
  // A header holding a line break (a file name, a Python comment) stays one comment line: no
  // point, no code line in a C header, and a // comment never continues onto the next line.
  EXPECT_EQ(comment_line("input nl\n0.25 0.75\r\x1b[31m\ttab"), "input nl\\n0.25 0.75\\r\\x1b[31m\ttab");
  EXPECT_EQ(comment_line("back\\"), "back\\");
  EXPECT_EQ(comment_line("back\\", true), "back\\x5c");
  EXPECT_EQ(comment_line("caf\xc3\xa9 \x7f"), "caf\xc3\xa9 \\x7f");  // UTF-8 kept, DEL escaped
  test::TempDir dir;
  PointSet set;
  set.points = {{0.1, 0.2}, {0.6, 0.7}};
  write_point_file(dir.file("p.txt"), set, {"made from nl\n0.25 0.75"});
  EXPECT_EQ(read_point_file(dir.file("p.txt")).points.size(), 2u);
  EXPECT_EQ(test::read_text(dir.file("p.txt")).rfind("# made from nl\\n0.25 0.75\n", 0), 0u);
  EXPECT_EQ(format_points(set, {"a\nb"}).rfind("# a\\nb\n0.1", 0), 0u);

  // The tool copies the input's name into its header.
  const std::string odd = dir.write("nl\n0.25 0.75", "0.1 0.2\n0.6 0.7\n");
  auto r = test::run_bluetile({"relax", "-i", odd, "--iterations", "0", "--engine", "exact", "-o", dir.file("o.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_point_file(dir.file("o.txt")).points.size(), 2u);
  r = test::run_bluetile({"relax", "-i", odd, "--iterations", "0", "--engine", "exact", "-o", dir.file("o.h")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string header = test::read_text(dir.file("o.h"));
  EXPECT_NE(header.find("input " + dir.file("nl") + "\\n0.25 0.75\n"), std::string::npos) << header.substr(0, 300);
}

TEST(PointFile, RoundTripsEveryBit) {
  TempDir dir;
  PointSet set;
  set.points = test::uniform_points(1000, 42);
  set.points.push_back({std::nextafter(1.0, 0.0), 5e-324});
  for (std::size_t i = 0; i < set.points.size(); ++i) set.levels.push_back(static_cast<int>(i % 4));
  write_point_file(dir.file("p.txt"), set, {"a header"});
  PointSet back = read_point_file(dir.file("p.txt"));
  ASSERT_EQ(back.points.size(), set.points.size());
  for (std::size_t i = 0; i < set.points.size(); ++i) ASSERT_EQ(back.points[i], set.points[i]) << i;
  EXPECT_EQ(back.levels, set.levels);
  EXPECT_EQ(dir.list(), std::vector<std::string>{"p.txt"});  // no temporary left behind
}

TEST(PointFile, SeveralSetsSeparatedByHashLines) {
  TempDir dir;
  std::string path = dir.write("sets.txt", "# header\n# set 0\n0.1 0.1\n0.2 0.2\n# set 1\n0.3 0.3\n#\n");
  auto sets = read_point_sets(path);
  ASSERT_EQ(sets.size(), 2u);
  EXPECT_EQ(sets[0].points.size(), 2u);
  EXPECT_EQ(sets[1].points[0], Point(0.3, 0.3));
}

}  // namespace
}  // namespace bluetile
