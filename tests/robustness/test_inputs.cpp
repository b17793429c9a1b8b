// The tool against bad inputs: one clear line, exit status 1, and
// nothing left behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "bluetile/io/image_file.h"
#include "robustness_support.h"
#include "test_support.h"

namespace bluetile::robustness {
namespace {

namespace fs = std::filesystem;
using test::read_text;
using test::TempDir;
using Names = std::vector<std::string>;

void expect_failure(const Outcome& r, const std::string& message) {
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err, "bluetile: " + message + "\n");
}

TEST(Inputs, StandardInputAndByteOrderMark) {
  TempDir dir;
  dir.write("bom.txt", "\xEF\xBB\xBF" "0.25 0.5\n0.75 0.5\n");
  // A byte-order mark was "not a number".
  Outcome r = run({"centroids", "-i", dir.file("bom.txt"), "--engine", "exact", "-o", "-"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\n0.25 0.5 0.5\n0.75 0.5 0.5\n"), std::string::npos) << r.out;
  Invocation from_stdin{{"centroids", "-i", "-", "--engine", "exact", "-o", "-"}};
  from_stdin.stdin_path = dir.file("bom.txt");
  Outcome s = run(from_stdin);
  EXPECT_EQ(s.exit_code, 0) << s.err;
  EXPECT_EQ(s.out.substr(s.out.find('\n')), r.out.substr(r.out.find('\n')));  // the header names the input
  EXPECT_EQ(s.out.rfind("# bluetile centroids of stdin,", 0), 0u) << s.out;
  dir.write("bad.txt", "0.1 0.2\n0.3 nan\n");
  from_stdin.stdin_path = dir.file("bad.txt");
  expect_failure(run(from_stdin), "stdin:2: not a finite number 'nan'");
  EXPECT_EQ(entries(dir.path()), (Names{"bad.txt", "bom.txt"}));
}

TEST(Inputs, LongLinesAreQuotedShort) {
  TempDir dir;
  // A 10 MB bad line was quoted whole.
  std::string line = "0.5 " + std::string(10 << 20, '7') + "x\n";
  dir.write("long.txt", "0.1 0.2\n" + line);
  Outcome r = run({"relax", "-i", dir.file("long.txt"), "-k", "1", "--engine", "exact", "-o", dir.file("o.txt")});
  expect_failure(r, dir.file("long.txt") + ":2: not a number '" + std::string(40, '7') + "...' (10485761 bytes)");
  EXPECT_EQ(entries(dir.path()), Names{"long.txt"});
}

TEST(Inputs, ReadErrorsAreErrors) {
  TempDir dir;
  fs::create_directory(dir.file("folder"));
  Outcome r = run({"relax", "-i", dir.file("folder"), "-k", "1", "--engine", "exact", "-o", dir.file("o.txt")});
  expect_failure(r, dir.file("folder") + ": is a folder");
  // /proc/self/mem reads fail with EIO at offset 0: an I/O error, deterministically.
  r = run({"relax", "-i", "/proc/self/mem", "-k", "1", "--engine", "exact", "-o", dir.file("o.txt")});
  expect_failure(r, "/proc/self/mem: read failed after 0 bytes: Input/output error");
  r = run({"centroids", "-i", dir.file("missing.txt"), "--engine", "exact", "-o", dir.file("o.txt")});
  expect_failure(r, dir.file("missing.txt") + ": cannot open: No such file or directory");
  EXPECT_EQ(entries(dir.path()), Names{"folder/"});
}

TEST(Inputs, RunningOutOfMemoryWhileReadingIsAnError) {
  if (sanitized()) GTEST_SKIP() << "the address sanitizer reserves terabytes of address space: ulimit -v cannot apply";
  // Under ulimit -v the file was silently cut short (3,355,485 of 5,000,000
  // points read, exit status 0). Ten million points take 160 MB, twice that while growing.
  TempDir dir;
  {
    std::ofstream big(dir.file("big.txt"), std::ios::binary);
    std::string block;
    for (int i = 0; i < 100000; ++i) block += "0 0\n";
    for (int k = 0; k < 100; ++k) big << block;
  }
  Invocation r{{"relax", "-i", dir.file("big.txt"), "-k", "0", "--engine", "exact", "-o", dir.file("o.txt")}};
  r.address_space_bytes = 200L << 20;
  Outcome o = run(r);
  EXPECT_EQ(o.exit_code, 1) << o.err;
  EXPECT_EQ(o.err.rfind("bluetile: " + dir.file("big.txt") + ":", 0), 0u) << o.err;
  EXPECT_NE(o.err.find(": out of memory after "), std::string::npos) << o.err;
  EXPECT_EQ(entries(dir.path()), Names{"big.txt"});
}

TEST(Inputs, ProgressiveLevelsStayReadable) {
  TempDir dir;
  // A level the reader rejects was written, and an empty base accepted.
  dir.write("top.txt", "0.1 0.1 0\n0.6 0.6 1000000\n");
  Outcome r = run({"progressive", "-i", dir.file("top.txt"), "--add", "2", "-k", "1", "--engine", "exact", "-o",
                   dir.file("o.txt")});
  expect_failure(r, dir.file("top.txt") +
                        ": the base already has levels up to 1000000, and a point file holds levels up to 1000000 only");
  dir.write("empty.txt", "# no points\n");
  for (std::string command : {"progressive", "relax", "centroids"}) {
    std::vector<std::string> args = {command, "-i", dir.file("empty.txt"), "--engine", "exact", "-o", dir.file("o.txt")};
    if (command == "progressive") args.insert(args.end(), {"--add", "2"});
    expect_failure(run(args), dir.file("empty.txt") + ": no points");
  }
  dir.write("over.txt", "0.1 0.1 1000001\n");
  r = run({"relax", "-i", dir.file("over.txt"), "--engine", "exact", "-o", dir.file("o.txt")});
  expect_failure(r, dir.file("over.txt") + ":1: level must be an integer from 0 to 1000000, got '1000001' (a point file's third column is the level; a table such as centroids' cx cy area is no point file)");
  EXPECT_EQ(entries(dir.path()), (Names{"empty.txt", "over.txt", "top.txt"}));
}

TEST(Inputs, EnvironmentIsCheckedNotIgnored) {
  TempDir dir;
  // BLUETILE_THREADS=2x was silently ignored.
  Invocation r{{"relax", "-n", "10", "-k", "1", "--engine", "exact", "-o", dir.file("o.txt")}};
  r.environment = {{"BLUETILE_THREADS", "2x"}};
  expect_failure(run(r), "BLUETILE_THREADS='2x': expected an integer from 1 to 1024");
  r.environment = {{"BLUETILE_THREADS", "0"}};
  expect_failure(run(r), "BLUETILE_THREADS='0': expected an integer from 1 to 1024");
  r.environment = {{"BLUETILE_THREADS", "2"}};
  EXPECT_EQ(run(r).exit_code, 0);
  // ...but only where it is used: --help and --version work whatever it holds, an explicit
  // --threads wins over it, and empty is unset (it stopped every command, --help included).
  for (const std::vector<std::string>& unused :
       {std::vector<std::string>{"--help"}, {"--version"}, {"relax", "--help"}, {"help"}, {"help", "relax"},
        {"relax", "-n", "10", "-k", "1", "--engine", "exact", "--threads", "2", "-o", dir.file("t.txt")},
        {"relax", "-n", "10", "-k", "1", "--engine", "exact", "--threads=1", "-o", dir.file("t1.txt")}}) {
    Invocation bad{unused};
    bad.environment = {{"BLUETILE_THREADS", "x"}};
    const Outcome o = run(bad);
    EXPECT_EQ(o.exit_code, 0) << unused[0] << ": " << o.err;
  }
  r.environment = {{"BLUETILE_THREADS", ""}};
  EXPECT_EQ(run(r).exit_code, 0);
  // ...and a garbage Vulkan driver manifest was "out of memory".
  dir.write("icd.json", "garbage{");
  Invocation raster{{"relax", "-n", "10", "-k", "1", "--engine", "raster", "-o", dir.file("r.txt")}};
  raster.environment = {{"VK_ICD_FILENAMES", dir.file("icd.json")}, {"VK_DRIVER_FILES", dir.file("icd.json")}};
  Outcome o = run(raster);
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.err.find("malformed driver manifest"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find(dir.file("icd.json")), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find("--resolution"), std::string::npos) << o.err;
  EXPECT_EQ(entries(dir.path()), (Names{"icd.json", "o.txt", "t.txt", "t1.txt"}));
}

TEST(Inputs, CsvFromPandasIsReadByEveryCommand) {
  TempDir dir;
  // pandas' to_csv (index and all, CRLF as on Windows) and the same points as text: relax -i read
  // the .csv as text ("expected 'x y' ..., got ',x,y'"); analyze refused the index ("an empty field").
  dir.write("pandas.csv", ",x,y\r\n0,0.25,0.5\r\n1,0.75,0.5\r\n2,0.5,0.875\r\n");
  dir.write("same.txt", "0.25 0.5\n0.75 0.5\n0.5 0.875\n");
  auto points_of = [&](const std::string& command, const std::string& input) {
    Outcome r = run({command, "-i", dir.file(input), "--engine", "exact", "-o", "-"});
    EXPECT_EQ(r.exit_code, 0) << command << " " << input << ": " << r.err;
    return r.out.substr(r.out.find('\n') + 1);  // the header names the input
  };
  for (const char* command : {"relax", "centroids"}) {
    const std::string from_csv = points_of(command, "pandas.csv");
    EXPECT_EQ(from_csv, points_of(command, "same.txt")) << command;
    EXPECT_FALSE(from_csv.empty()) << command;
  }
  Outcome a = run({"analyze", "-i", dir.file("pandas.csv"), "-o", dir.file("a"), "--no-centroids"});
  EXPECT_EQ(a.exit_code, 0) << a.err;
  // A CSV under another name says how it would be read.
  dir.write("comma.txt", "x,y\n0.25,0.5\n");
  expect_failure(run({"relax", "-i", dir.file("comma.txt"), "--engine", "exact", "-o", dir.file("o.txt")}),
                 dir.file("comma.txt") +
                     ":1: expected 'x y' or 'x y level', got 'x,y' (comma-separated values: a file named .csv is read "
                     "as CSV)");
  EXPECT_EQ(entries(dir.path()).size(), 4u + 12u);  // the inputs, a/ and its 11 files
}

TEST(Inputs, AnalyzeFromReadsWhatInputReads) {
  // analyze --from read every file as text: an .npy was "binary data (NUL byte)", a pandas CSV
  // "expected 'x y'".
  TempDir dir;
  dir.write("p.csv", ",x,y\n0,0.25,0.5\n1,0.75,0.5\n2,0.5,0.875\n3,0.125,0.125\n");
  dir.write("q.txt", "0.25 0.5\n0.75 0.5\n0.5 0.875\n0.125 0.125\n");
  for (const char* from : {"p.csv", "q.txt"}) {
    Outcome r = run({"analyze", "-i", dir.file("q.txt"), "--from", dir.file(from), "-o", dir.file(std::string("a-") + from),
                     "--no-centroids", "--no-psa-measures", "--no-discrepancy"});
    EXPECT_EQ(r.exit_code, 0) << from << ": " << r.err;
  }
  dir.write("two.csv", "x,y\n0.25,0.5\n0.75,0.5\n# set 1\n0.5,0.875\n0.125,0.125\n");
  expect_failure(run({"analyze", "-i", dir.file("q.txt"), "--from", dir.file("two.csv"), "-o", dir.file("b")}),
                 dir.file("two.csv") + ": holds 2 sets; --from needs one");
}

TEST(Inputs, AnalyzeReadsATableUnderAGenericNameByItsContent) {
  // An .npy or .bpt saved as points.dat or points.bin was "binary data (NUL byte): not a point
  // file" for analyze, where relax -i read it by its content.
  TempDir dir;
  for (const char* format : {"npy", "binary"}) {
    const std::string table = dir.file(std::string("p-") + format + (format == std::string("npy") ? ".npy" : ".bpt"));
    Outcome made = run({"dart", "-n", "16", "--seed", "3", "-o", table});
    ASSERT_EQ(made.exit_code, 0) << made.err;
    for (const char* name : {"points.dat", "points.bin", "points"}) {
      const std::string renamed = dir.file(std::string(format) + "-" + name);
      std::filesystem::copy_file(table, renamed);
      Outcome r = run({"analyze", "-i", renamed, "-o", dir.file(std::string("a-") + format + "-" + name), "--no-centroids",
                       "--no-psa-measures", "--no-discrepancy"});
      EXPECT_EQ(r.exit_code, 0) << format << " as " << name << ": " << r.err;
      EXPECT_NE(read_text(dir.file(std::string("a-") + format + "-" + name + "/report.txt")).find("16 points"), std::string::npos);
    }
  }
}

TEST(Inputs, AnUnusableTmpdirIsNamed) {
  // An image that is no regular file (a pipe here) is copied to a temporary file: a TMPDIR naming
  // no folder was "internal error: filesystem error: temp_directory_path: No such file or
  // directory", and an empty one the same (empty is unset, as for BLUETILE_THREADS).
  TempDir dir;
  write_image_file(dir.file("map.png"), 2, 2, 1, std::vector<std::uint8_t>{50, 100, 150, 200});
  Invocation piped{{"relax", "-n", "20", "-k", "1", "--engine", "exact", "--density-map", "/dev/stdin", "-o",
                    dir.file("o.txt")}};
  piped.wrapper = {"/bin/sh", "-c", "cat \"$MAP\" | \"$0\" \"$@\""};
  piped.environment = {{"MAP", dir.file("map.png")}, {"TMPDIR", dir.file("gone")}};
  expect_failure(run(piped), "/dev/stdin: not a regular file, so read into a temporary copy, but TMPDIR '" +
                                 dir.file("gone") +
                                 "' is not a folder (No such file or directory): set TMPDIR to a writable folder, or "
                                 "unset it for /tmp");
  piped.environment = {{"MAP", dir.file("map.png")}, {"TMPDIR", dir.file("map.png")}};
  EXPECT_NE(run(piped).err.find("' is not a folder (Not a directory)"), std::string::npos);
  EXPECT_EQ(entries(dir.path()), Names{"map.png"});
  piped.environment = {{"MAP", dir.file("map.png")}, {"TMPDIR", ""}};
  Outcome r = run(piped);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  fs::create_directory(dir.file("tmp"));
  piped.environment = {{"MAP", dir.file("map.png")}, {"TMPDIR", dir.file("tmp")}};
  r = run(piped);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(entries(dir.path()), (Names{"map.png", "o.txt", "tmp/"}));  // the copy removed
}

// A tile-grid header (what `tile --normalize` writes for analyze's drawing) with its origin far off,
// as a hand edit can leave it: analyze's grid lines were a loop whose index stood still, and it
// added the same line until memory ran out ("out of memory" under this limit, all memory without).
TEST(Inputs, AFarTileGridOriginEndsItsGridLines) {
  TempDir dir;
  std::string text = "# tile grid 1e20 1e20 0.01 0.01\n";
  for (int i = 0; i < 40; ++i) text += std::to_string((i * 37 % 40 + 0.5) / 40.0) + " " + std::to_string((i + 0.5) / 40.0) + "\n";
  dir.write("far.txt", text);
  Invocation analyze{{"analyze", "-i", dir.file("far.txt"), "-o", dir.file("out"), "--no-psa-measures"}};
  // The limit ends a regression in seconds; the address sanitizer's reservation cannot run under it.
  if (!sanitized()) analyze.address_space_bytes = 3L << 30;
  const Outcome r = run(analyze);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir.file("out/points.svg")));
}

}  // namespace
}  // namespace bluetile::robustness
