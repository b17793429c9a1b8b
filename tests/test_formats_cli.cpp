// Sample tables through the tool: --format and extensions, multi-set inputs kept apart,
// --sets for dart and progressive, '{}' in output names, damaged tables refused.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include <sys/stat.h>

#include "bluetile/core/point_table.h"
#include "test_support.h"

namespace bluetile {
namespace {

using test::read_text;
using test::run_bluetile;
using test::TempDir;

void expect_same_points(const PointSet& a, const PointSet& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) ASSERT_EQ(a.points[i], b.points[i]) << "point " << i;
  EXPECT_EQ(a.levels, b.levels);
}

// The data lines of a text table, one string per '#'-separated block (empty blocks skipped).
std::vector<std::string> data_blocks(const std::string& text) {
  std::vector<std::string> blocks(1);
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    std::string line = text.substr(start, end - start);
    if (line.rfind('#', 0) == 0) {
      if (!blocks.back().empty()) blocks.emplace_back();
    } else {
      blocks.back() += line + "\n";
    }
    start = end == std::string::npos ? text.size() : end + 1;
  }
  if (blocks.back().empty()) blocks.pop_back();
  return blocks;
}

// Runs bluetile and requires success.
void ok(const std::vector<std::string>& arguments) {
  auto r = run_bluetile(arguments);
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

TEST(FormatsCli, EveryFormatHoldsTheSamePoints) {
  TempDir dir;
  const std::vector<std::string> relax = {"relax", "-n", "16", "--sets", "6", "-k", "3", "--engine", "exact"};
  auto run = [&](const std::string& name, std::vector<std::string> more = {}) {
    std::vector<std::string> args = relax;
    args.insert(args.end(), {"-o", dir.file(name)});
    args.insert(args.end(), more.begin(), more.end());
    ok(args);
  };
  run("t.txt");
  run("t.npy");
  run("t.bpt");
  run("t.data", {"--format", "npy"});
  run("t32.npy", {"--float32"});
  run("t.h", {"--name", "table"});
  run("t.csv");
  run("csv-points", {"--format", "csv"});
  auto text = read_point_table(dir.file("t.txt"));
  ASSERT_EQ(text.size(), 6u);
  for (const char* name : {"t.npy", "t.bpt", "t.data", "t.csv"}) {
    auto sets = read_point_table(dir.file(name));
    ASSERT_EQ(sets.size(), 6u) << name;
    for (std::size_t k = 0; k < 6; ++k) expect_same_points(sets[k], text[k]);
  }
  auto f32 = read_point_table(dir.file("t32.npy"));
  EXPECT_EQ(f32[5].points[15].x, static_cast<double>(static_cast<float>(text[5].points[15].x)));
  std::string header = read_text(dir.file("t.h"));
  EXPECT_NE(header.find("static const float table[6][16][2] = {"), std::string::npos);
  EXPECT_NE(header.find("// bluetile relax: 6 sets of 16 points"), std::string::npos) << header.substr(0, 200);
  // CSV (written since it was read): the provenance, the column names, the sets apart.
  const std::string csv = read_text(dir.file("t.csv"));
  EXPECT_EQ(csv.rfind("# bluetile relax: 6 sets of 16 points, 3 iterations, engine exact, seed 1\nx,y\n# set 0\n", 0), 0u)
      << csv.substr(0, 200);
  EXPECT_EQ(read_text(dir.file("csv-points")), csv);
}

TEST(FormatsCli, StandardInputIsRecognisedByContentLikeAFile) {
  // -i - reads NumPy and point-table bytes as a file of any name would be read: by their magic.
  TempDir dir;
  ok({"relax", "-n", "12", "--sets", "2", "-k", "2", "--engine", "exact", "-o", dir.file("t.npy")});
  ok({"relax", "-n", "12", "--sets", "2", "-k", "2", "--engine", "exact", "-o", dir.file("t.bpt")});
  ok({"relax", "-n", "12", "--sets", "2", "-k", "2", "--engine", "exact", "-o", dir.file("t.txt")});
  ok({"centroids", "--engine", "exact", "-i", dir.file("t.txt"), "-o", dir.file("from-file.txt")});
  // The first line names the input; the rest are the centroids.
  auto body = [](const std::string& text) { return text.substr(text.find('\n')); };
  const std::string expected = body(read_text(dir.file("from-file.txt")));
  // stdin from the file inside the inner shell (run_command gives the outer one /dev/null).
  auto from_stdin = [&](const std::string& command, const std::string& input) {
    return test::run_command("sh -c '\"$0\" " + command + " < \"$1\"' '" BLUETILE_BINARY "' '" + input + "'");
  };
  for (const char* name : {"t.npy", "t.bpt", "t.txt"}) {
    const std::string out = dir.file(std::string("centroids-") + name + ".txt");
    auto r = from_stdin("centroids --engine exact -i - -o " + out, dir.file(name));
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    EXPECT_EQ(body(read_text(out)), expected) << name;
    r = from_stdin("analyze -i - -o " + dir.file(std::string("a-") + name) + " --no-discrepancy --average", dir.file(name));
    EXPECT_EQ(r.exit_code, 0) << name << ": " << r.err << r.out;
  }
  // Damaged bytes on stdin are named as stdin.
  const std::string truncated = dir.write("cut.npy", read_text(dir.file("t.npy")).substr(0, 100));
  auto r = from_stdin("centroids --engine exact -i - -o " + dir.file("never.txt"), truncated);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err.rfind("bluetile: stdin: ", 0), 0u) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("never.txt")));
}

TEST(FormatsCli, UnknownExtensionsAreRefusedBeforeAnyWork) {
  TempDir dir;
  auto r = run_bluetile({"relax", "-n", "10", "--engine", "exact", "-o", dir.file("points.png")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err, "bluetile: --output '" + dir.file("points.png") +
                       "': this output writes .txt .dat .pts (text points), .npy (NumPy), .bpt (point table), .h .hpp "
                       "(C header), .csv (CSV), not '.png'\n");
  r = run_bluetile({"relax", "-n", "10", "--engine", "exact", "-o", dir.file("points.data")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err, "bluetile: --output '" + dir.file("points.data") +
                       "': this output writes .txt .dat .pts (text points), .npy (NumPy), .bpt (point table), .h .hpp "
                       "(C header), .csv (CSV), not '.data'; or say --format\n");
  EXPECT_TRUE(dir.list().empty());
}

TEST(FormatsCli, CentroidsAreANamedTableNotPoints) {
  // centroids -o c.npy wrote cx cy area as (K, N, 3), the shape of x y level points: now NumPy
  // fields named cx, cy and area; .bpt, which cannot name them, is refused before any work.
  TempDir dir;
  const std::string points = dir.write("p.txt", "0.1 0.2\n0.6 0.3\n0.4 0.8\n0.9 0.7\n");
  ok({"centroids", "-i", points, "--engine", "exact", "-o", dir.file("c.npy")});
  const std::string npy = read_text(dir.file("c.npy"));
  EXPECT_NE(npy.find("{'descr': [('cx', '<f8'), ('cy', '<f8'), ('area', '<f8')], 'fortran_order': False, 'shape': (1, 4), }"),
            std::string::npos)
      << npy.substr(0, 128);
  // The same values as the text table.
  ok({"centroids", "-i", points, "--engine", "exact", "-o", dir.file("c.txt")});
  const std::string text = read_text(dir.file("c.txt"));
  std::vector<double> from_text;
  for (std::size_t at = text.find("\n0"); at != std::string::npos && at + 1 < text.size(); at = text.find('\n', at + 1)) {
    if (text[at + 1] == '#') continue;
    char* end = nullptr;
    const char* p = text.c_str() + at + 1;
    for (int c = 0; c < 3; ++c, p = end) from_text.push_back(std::strtod(p, &end));
  }
  ASSERT_EQ(from_text.size(), 12u) << text;
  std::vector<double> from_npy(12);
  std::memcpy(from_npy.data(), npy.data() + npy.size() - 12 * sizeof(double), 12 * sizeof(double));
  EXPECT_EQ(from_npy, from_text);
  for (const std::vector<std::string>& more : {std::vector<std::string>{"-o", dir.file("c.bpt")},
                                               std::vector<std::string>{"--format", "binary", "-o", dir.file("c.data")}}) {
    std::vector<std::string> args = {"centroids", "-i", points, "--engine", "exact"};
    args.insert(args.end(), more.begin(), more.end());
    auto r = run_bluetile(args);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find(more[0] == "-o" ? "': this output writes .txt .dat .pts (text points), .npy (NumPy), .h .hpp (C header), .csv (CSV), not "
                                           "'.bpt'\n"
                                           : "--format binary: a bluetile point table (.bpt) holds x y or x y level"),
              std::string::npos)
        << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("c.bpt")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("c.data")));
  // A CSV names the columns.
  ok({"centroids", "-i", points, "--engine", "exact", "-o", dir.file("c.csv")});
  const std::string csv = read_text(dir.file("c.csv"));
  EXPECT_EQ(csv.substr(csv.find('\n') + 1, 11), "cx,cy,area\n") << csv;
  // Read back, it is refused as no point table.
  auto r = run_bluetile({"analyze", "-i", dir.file("c.npy"), "-o", dir.file("a")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "bluetile: " + dir.file("c.npy") +
                      ": a structured array (named fields cx, cy, area: centroids); expected plain float64 or float32 "
                      "values: save numpy.stack([a['cx'], a['cy']], axis=-1)\n");
}

TEST(FormatsCli, AFormatTheNameContradictsIsRefusedBeforeAnyWork) {
  // --format text -o f.npy wrote text into f.npy (NumPy then refused it); a name another format
  // owns is refused with --format, a name no format owns, none, the generic .dat and .bin, "-"
  // and a FIFO take any.
  TempDir dir;
  struct Case {
    std::string name, format, message;
  };
  const std::vector<Case> cases = {
      {"f.npy", "text", "is named as NumPy ('.npy'); give it .txt, .dat, .pts or no extension for text"},
      {"f.txt", "npy", "is named as text points ('.txt'); give it .npy for npy"},
      {"f.H", "binary", "is named as C header ('.h'); give it .bpt for binary"},
      {"f.bpt", "header", "is named as point table ('.bpt'); give it .h or .hpp for header"},
      {"f.png", "text", "is named as image ('.png'); give it .txt, .dat, .pts or no extension for text"},
      {"f.tiles", "npy", "is named as tile set ('.tiles'); give it .npy for npy"},
      // A .csv is CSV since it is written: text points in one were read back as blank-separated text.
      {"f.csv", "text", "is named as CSV ('.csv'); give it .txt, .dat, .pts or no extension for text"},
      {"f.txt", "csv", "is named as text points ('.txt'); give it .csv for csv"},
  };
  for (const Case& c : cases) {
    auto r = run_bluetile({"dart", "-n", "10", "--format", c.format, "-o", dir.file(c.name)});
    EXPECT_EQ(r.exit_code, 1) << c.name;
    EXPECT_EQ(r.err, "bluetile: --format " + c.format + ": --output '" + dir.file(c.name) + "' " + c.message +
                         ", or leave --format out\n");
  }
  EXPECT_TRUE(dir.list().empty());
  ok({"dart", "-n", "10", "--format", "npy", "-o", dir.file("f.data")});
  ok({"dart", "-n", "10", "--format", "npy", "-o", dir.file("npy-points")});
  ok({"dart", "-n", "10", "--format", "npy", "-o", dir.file("f.NPY")});
  EXPECT_EQ(read_text(dir.file("f.data")).substr(0, 6), "\x93NUMPY");
  EXPECT_EQ(read_text(dir.file("npy-points")).substr(0, 6), "\x93NUMPY");
  // .dat and .bin are generic names (they were refused for npy and binary, which worked before
  // the check): written as asked, and read back by their content.
  ok({"dart", "-n", "10", "--format", "npy", "-o", dir.file("f.dat")});
  ok({"dart", "-n", "10", "--format", "binary", "-o", dir.file("f.bin")});
  EXPECT_EQ(read_text(dir.file("f.dat")).substr(0, 6), "\x93NUMPY");
  EXPECT_EQ(read_text(dir.file("f.bin")).substr(0, 4), "\x89" "BTP");
  for (const char* name : {"f.dat", "f.bin"})
    ok({"analyze", "-i", dir.file(name), "-o", dir.file(std::string("a-") + name), "--no-centroids", "--no-psa-measures",
        "--no-discrepancy"});
  auto r = run_bluetile({"dart", "-n", "10", "--format", "npy", "-o", "-"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, 6), "\x93NUMPY");
  // A FIFO named as text takes npy bytes: its name describes nothing.
  const std::string fifo = dir.file("pipe.txt");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  r = test::run_command("cat '" + fifo + "' > '" + dir.file("from-fifo") + "' & '" BLUETILE_BINARY
                        "' dart -n 10 --format npy -o '" + fifo + "'; status=$?; wait; exit $status");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(dir.file("from-fifo")).substr(0, 6), "\x93NUMPY");
}

TEST(FormatsCli, OptionsOfAnotherFormatAreRefusedBeforeAnyWork) {
  // --float32 on a text file and --name on anything but a header were ignored without a word.
  TempDir dir;
  auto r = run_bluetile({"relax", "-n", "10", "--engine", "exact", "-o", dir.file("p.txt"), "--float32"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "bluetile: --float32: --output '" + dir.file("p.txt") +
                       "' is text; 4-byte floats are for npy and binary outputs\n");
  r = run_bluetile({"dart", "-n", "10", "--sets", "2", "-o", dir.file("p{}.npy"), "--name", "table"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "bluetile: --name 'table': --output '" + dir.file("p0.npy") +
                       "' is npy; the array name is for header outputs (.h, .hpp)\n");
  r = run_bluetile({"dart", "-n", "10", "-o", dir.file("p.h"), "--float32"});
  EXPECT_EQ(r.err, "bluetile: --float32: --output '" + dir.file("p.h") +
                       "' is header; 4-byte floats are for npy and binary outputs\n");
  r = run_bluetile({"dart", "-n", "10", "-o", dir.file("p.csv"), "--name", "table"});
  EXPECT_EQ(r.err, "bluetile: --name 'table': --output '" + dir.file("p.csv") +
                       "' is csv; the array name is for header outputs (.h, .hpp)\n");
  EXPECT_TRUE(dir.list().empty());
  ok({"dart", "-n", "10", "-o", dir.file("p.bpt"), "--float32"});
  ok({"dart", "-n", "10", "-o", dir.file("p.h"), "--name", "table"});
}

TEST(FormatsCli, EveryBraceInAnOutputNameIsTheSetIndex) {
  TempDir dir;
  ok({"dart", "-n", "20", "--sets", "11", "-o", dir.file("{}-of-11_{}.npy")});
  auto names = dir.list();
  ASSERT_EQ(names.size(), 11u);
  EXPECT_TRUE(std::filesystem::exists(dir.file("00-of-11_00.npy")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("10-of-11_10.npy")));
  EXPECT_EQ(read_point_table(dir.file("07-of-11_07.npy")).size(), 1u);
  // A text file of one set said "11 sets of 20 points" and not which set it held.
  ok({"relax", "-n", "16", "--sets", "3", "-k", "2", "--engine", "exact", "-o", dir.file("rs-{}.txt")});
  ok({"relax", "-n", "16", "--sets", "3", "-k", "2", "--engine", "exact", "-o", dir.file("all.txt")});
  const std::string one = read_text(dir.file("rs-1.txt"));
  EXPECT_EQ(one.substr(0, one.find('\n', one.find('\n') + 1) + 1),
            "# bluetile relax: 3 sets of 16 points, 2 iterations, engine exact, seed 1\n"
            "# this file: set 1 of 3\n")
      << one;
  EXPECT_EQ(read_point_file(dir.file("rs-1.txt")).points, read_point_table(dir.file("all.txt"))[1].points);
}

TEST(FormatsCli, MultiSetInputsAreKeptApart) {
  TempDir dir;
  // Three sets of different sizes in UTK's text convention.
  ok({"dart", "-n", "30", "--seed", "1", "-o", dir.file("a.txt")});
  ok({"dart", "-n", "40", "--seed", "2", "-o", dir.file("b.txt")});
  ok({"dart", "-n", "50", "--seed", "3", "-o", dir.file("c.txt")});
  std::string all = "# three sets\n# set 0\n" + read_text(dir.file("a.txt")) + "# set 1\n" + read_text(dir.file("b.txt")) +
                    "# set 2\n" + read_text(dir.file("c.txt"));
  std::string multi = dir.write("multi.txt", all);
  ok({"relax", "-i", multi, "-k", "4", "--engine", "exact", "-o", dir.file("relaxed.txt")});
  ok({"centroids", "-i", multi, "--engine", "exact", "-o", dir.file("cells.txt")});
  auto relaxed = read_point_table(dir.file("relaxed.txt"));
  auto cells = data_blocks(read_text(dir.file("cells.txt")));
  ASSERT_EQ(relaxed.size(), 3u);
  ASSERT_EQ(cells.size(), 3u);
  const char* names[] = {"a.txt", "b.txt", "c.txt"};
  for (std::size_t k = 0; k < 3; ++k) {
    // Each set relaxes and measures exactly as it does alone.
    ok({"relax", "-i", dir.file(names[k]), "-k", "4", "--engine", "exact", "-o", dir.file("alone.txt")});
    expect_same_points(relaxed[k], read_point_file(dir.file("alone.txt")));
    ok({"centroids", "-i", dir.file(names[k]), "--engine", "exact", "-o", dir.file("alone-cells.txt")});
    auto alone = data_blocks(read_text(dir.file("alone-cells.txt")));
    ASSERT_EQ(alone.size(), 1u);
    EXPECT_EQ(cells[k], alone[0]) << "set " << k;
  }
  // .npy and .bpt inputs too.
  ok({"relax", "-n", "20", "--sets", "2", "-k", "0", "--engine", "exact", "-o", dir.file("start.bpt")});
  ok({"relax", "-i", dir.file("start.bpt"), "-k", "3", "--engine", "exact", "-o", dir.file("from-bpt.npy")});
  ok({"relax", "-n", "20", "--sets", "2", "-k", "3", "--engine", "exact", "-o", dir.file("direct.npy")});
  auto from_bpt = read_point_table(dir.file("from-bpt.npy"));
  auto direct = read_point_table(dir.file("direct.npy"));
  ASSERT_EQ(from_bpt.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) expect_same_points(from_bpt[k], direct[k]);
}

TEST(FormatsCli, SetsOfDartAndProgressiveAreTheirSeedsAlone) {
  TempDir dir;
  ok({"dart", "-n", "25", "--seed", "5", "--sets", "3", "-o", dir.file("darts.txt")});
  ok({"dart", "-n", "25", "--seed", "7", "-o", dir.file("dart7.txt")});
  auto darts = read_point_table(dir.file("darts.txt"));
  ASSERT_EQ(darts.size(), 3u);
  expect_same_points(darts[2], read_point_file(dir.file("dart7.txt")));
  ok({"progressive", "-n", "10", "--levels", "2", "-k", "3", "--seed", "5", "--sets", "2", "--engine", "exact", "-o",
      dir.file("levels.npy")});
  ok({"progressive", "-n", "10", "--levels", "2", "-k", "3", "--seed", "6", "--engine", "exact", "-o",
      dir.file("levels6.txt")});
  auto levels = read_point_table(dir.file("levels.npy"));
  ASSERT_EQ(levels.size(), 2u);
  expect_same_points(levels[1], read_point_file(dir.file("levels6.txt")));
  EXPECT_EQ(levels[1].levels.back(), 1);
}

TEST(FormatsCli, DamagedTablesAreRefusedWithTheirFileName) {
  TempDir dir;
  ok({"relax", "-n", "8", "-k", "0", "--engine", "exact", "-o", dir.file("good.bpt")});
  std::string bytes = read_text(dir.file("good.bpt"));
  std::string short_file = dir.write("short.bpt", bytes.substr(0, bytes.size() - 3));
  auto r = run_bluetile({"relax", "-i", short_file, "--engine", "exact", "-o", dir.file("out.txt")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err, "bluetile: " + short_file + ": header says 1 set of 8 points (168 bytes) but the file has 165 bytes\n");
  EXPECT_FALSE(std::filesystem::exists(dir.file("out.txt")));
}

}  // namespace
}  // namespace bluetile
