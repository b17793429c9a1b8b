// Checks that come before the work, and smaller findings: a run that would take hours
// (-k 100000000) is refused in seconds with one line naming the file or option, and leaves
// nothing behind.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bluetile/core/point_file.h"
#include "bluetile/core/rng.h"
#include "bluetile/io/image_file.h"
#include "bluetile/io/pdf.h"
#include "robustness_support.h"
#include "test_support.h"

namespace bluetile::robustness {
namespace {

using test::read_text;
using test::TempDir;
using Names = std::vector<std::string>;

// Runs `invocation`, killing it after a minute: a check that comes only after the work ends so,
// with signal 9, instead of holding the suite for hours.
Outcome run_or_kill(const Invocation& invocation) {
  Child child(invocation);
  std::atomic<bool> done{false};
  std::thread guard([&] {
    for (int tenths = 0; tenths < 600 && !done; ++tenths) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (!done) kill(child.pid(), SIGKILL);
  });
  Outcome outcome = child.wait();
  done = true;
  guard.join();
  return outcome;
}

// `count` points of a jittered grid, as text, and its path.
std::string point_file(const TempDir& dir, const std::string& name, int side) {
  std::string text;
  char line[64];
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      std::snprintf(line, sizeof line, "%.6f %.6f\n", (i + 0.25 + 0.5 * ((i * 7 + j * 3) % 5) / 5.0) / side,
                    (j + 0.25 + 0.5 * ((i * 3 + j * 7) % 5) / 5.0) / side);
      text += line;
    }
  return dir.write(name, text);
}

TEST(ChecksFirst, AnUnknownImageFormatIsRefusedBeforeTheRelaxation) {
  // --id-image a.xyz was found unknown after the relaxation (5 s there).
  TempDir dir;
  Outcome r = run_or_kill({{"relax", "-n", "200", "-k", "100000000", "--engine", "exact", "-o", dir.file("a.txt"),
                            "--id-image", dir.file("a.xyz")}});
  EXPECT_EQ(r.signal, 0) << "not refused before the relaxation";
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err, "bluetile: --id-image '" + dir.file("a.xyz") +
                       "': this output writes .png .tif .tiff .jpg .jpeg .exr .bmp (image), not '.xyz'\n");
  // stipple's --png the same.
  write_image_file(dir.file("map.png"), 2, 2, 1, std::vector<std::uint8_t>(4, 100));
  r = run_or_kill({{"stipple", "--image", dir.file("map.png"), "-n", "200", "-k", "100000000", "-o", dir.file("s.txt"),
                    "--png", dir.file("s.xyz")}});
  EXPECT_EQ(r.signal, 0) << "not refused before the relaxation";
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err, "bluetile: --png '" + dir.file("s.xyz") +
                       "': this output writes .png .tif .tiff .jpg .jpeg .exr .bmp (image), not '.xyz'\n");
  EXPECT_EQ(entries(dir.path()), Names{"map.png"});
}

TEST(ChecksFirst, MixedLevelColumnsAreRefusedWhenTheFileIsRead) {
  // Found when the result was written, after the relaxation, naming no file.
  TempDir dir;
  const std::string mixed = dir.write("mixed.txt", "0.1 0.2 0\n0.3 0.4 1\n#\n0.5 0.6\n0.7 0.8\n");
  Outcome r = run_or_kill({{"relax", "-i", mixed, "-k", "100000000", "--engine", "exact", "-o", dir.file("o.txt")}});
  EXPECT_EQ(r.signal, 0) << "not refused before the relaxation";
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "bluetile: " + mixed + ": set 1 has no level column but set 0 has one: a table's sets have one set "
                   "of columns\n");
  dir.write("other.txt", "0.1 0.2\n0.3 0.4\n#\n0.5 0.6 0\n0.7 0.8 1\n");
  r = run_or_kill({{"centroids", "-i", dir.file("other.txt"), "--engine", "exact", "-o", dir.file("o.txt")}});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "bluetile: " + dir.file("other.txt") +
                       ": set 1 has a level column but set 0 has none: a table's sets have one set of columns\n");
  EXPECT_EQ(entries(dir.path()), (Names{"mixed.txt", "other.txt"}));
}

TEST(ChecksFirst, TextThatIsNotUtf8IsWrittenWithReplacementCharacters) {
  // A title not in UTF-8 failed the PDF after the whole analysis, and a
  // file name or label not in UTF-8 failed stats.json with the JSON library's message.
  TempDir dir;
  const std::string input = point_file(dir, "p\xff.txt", 12);
  std::vector<std::string> args = {"analyze", "-i", input, "-o", dir.file("a"), "--no-centroids", "--title", "t\xfe"};
  const bool pdf = pdf_unavailable_reason().empty();
  if (pdf) args.insert(args.end(), {"--summary", dir.file("s.pdf")});
  Outcome r = run(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::string stats = read_text(dir.file("a/stats.json"));
  EXPECT_NE(stats.find("\"label\": \"p\xEF\xBF\xBD\""), std::string::npos) << stats;
  EXPECT_NE(stats.find("p\xEF\xBF\xBD.txt\""), std::string::npos) << stats;
  if (pdf) {
    EXPECT_EQ(read_text(dir.file("s.pdf")).rfind("%PDF", 0), 0u);
  }
  r = run({"analyze", "-i", input, "-o", dir.file("b"), "--no-centroids", "--label", "l\xc3"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_text(dir.file("b/stats.json")).find("\"label\": \"l\xEF\xBF\xBD\""), std::string::npos);
  // wang-check's stats.json names its tile-set file.
  r = run({"wang", "--points", "8", "-k", "2", "-o", dir.file("w\xff.txt")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run({"wang-check", dir.file("w\xff.txt"), "--period", "2", "-o", dir.file("c")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_text(dir.file("c/stats.json")).find("w\xEF\xBF\xBD.txt\","), std::string::npos);
}

TEST(ChecksFirst, AnnulusWidthsAreCheckedAgainstTheLimitAndTheMemory) {
  // --bin-width 1e-6 took 7 GB before failing; 1e-300 was "wider than half the
  // periodogram size". 144 points: F = 2 floor(5 sqrt(144)) = 120.
  TempDir dir;
  const std::string input = point_file(dir, "p.txt", 12);
  Outcome r = run({"analyze", "-i", input, "-o", dir.file("a"), "--bin-width", "1e-300"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "bluetile: --bin-width 1e-300 is too narrow: 6e+301 annuli (F / 2 = 60 over the width), more than "
                   "the limit of 1e+09\n");
  r = run({"analyze", "-i", input, "-o", dir.file("a"), "--bin-width", "100"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "bluetile: --bin-width 100 is wider than half the periodogram size F / 2 = 60: no annulus fits\n");
  if (!sanitized()) {  // ulimit -v stands in for a small machine; the sanitizer needs terabytes of it
    Invocation limited{{"analyze", "-i", input, "-o", dir.file("a"), "--bin-width", "1e-6"}};
    limited.address_space_bytes = 1L << 30;
    r = run_or_kill(limited);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err.rfind("bluetile: --bin-width 1e-06 (60000000 annuli) needs about 22.4 GiB of memory, more than the ",
                          0),
              0u)
        << r.err;
  }
  EXPECT_EQ(entries(dir.path()), Names{"p.txt"});
}

TEST(ChecksFirst, ALongAnalysisSaysSoAsItStarts) {
  // analyze of 10^6 points ran for hours with no word off a terminal; past --time-limit it is now
  // refused (test_analysis.cpp), and a run within it but long says how long as it starts (3 x
  // 10^5 points: some minutes, psa's measures and the discrepancies being O(N^2); interrupted
  // once that is said).
  TempDir dir;
  PointSet set;
  Rng rng(5);
  for (int i = 0; i < 300000; ++i) set.points.push_back(rng.point(Domain{}));
  const std::string input = dir.write("large.txt", format_points(set));
  Child child({{"analyze", "-i", input, "-o", dir.file("a"), "--threads", "2"}});
  std::this_thread::sleep_for(std::chrono::seconds(2));
  kill(child.pid(), SIGINT);
  Outcome r = child.wait();
  EXPECT_EQ(r.signal, SIGINT) << r.err;
  EXPECT_EQ(r.err.rfind("bluetile: note: analyze of 300000 points should take about ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(" min on 2 threads\n"), std::string::npos) << r.err;
  // Short runs say nothing.
  r = run({"analyze", "-i", point_file(dir, "small.txt", 12), "-o", dir.file("b"), "--no-centroids"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(entries(dir.path()), (Names{"b/", "b/points.png", "b/points.svg", "b/radial.csv", "b/radial.png",
                                        "b/radial.svg", "b/rdf.csv", "b/rdf.png", "b/rdf.svg", "b/report.txt",
                                        "b/spectrum.png", "b/spectrum.svg", "b/stats.json", "large.txt", "small.txt"}));
}

TEST(ChecksFirst, AnalyzeAndWangCheckLoadTheImagePluginBeforeTheirWork) {
  // Their PNGs are drawn at the end, and the plugin was loaded only then: under a limit too small
  // for it, analyze of 50000 points ended in a bare "out of memory" during the analysis (or, with
  // more room, said the plugin's limit after it), and wang-check printed its seam report first.
  if (sanitized()) GTEST_SKIP() << "the address sanitizer reserves terabytes of address space: ulimit -v cannot apply";
  TempDir dir;
  const std::string points = dir.write("points.txt", many_points_text(50000));
  const std::string plugin = "bluetile: cannot load the image plugin libbluetile_oiio.so: OpenImageIO needs about ";
  Invocation analyze{{"analyze", "-i", points, "-o", dir.file("a"), "--no-psa-measures"}};
  analyze.address_space_bytes = 200L << 20;
  Outcome r = run_or_kill(analyze);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err.rfind(plugin, 0), 0u) << r.err;
  TempDir made;  // a small set (4 points a tile) from the tool itself
  const std::string tiles = made.file("tiles.txt");
  r = run({"wang", "-n", "4", "-k", "1", "--warm", "0", "--lattice-steps", "0", "--lattice-steps-per-iteration", "0",
           "--strategy", "rounds", "-o", tiles});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Invocation check{{"wang-check", tiles, "--period", "4", "-o", dir.file("w")}};
  check.address_space_bytes = 200L << 20;
  r = run_or_kill(check);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err.rfind(plugin, 0), 0u) << r.err;
  EXPECT_EQ(r.out, "") << "the seam report came before the refusal";
  EXPECT_EQ(entries(dir.path()), Names{"points.txt"});
}

TEST(ChecksFirst, TooLittleMemoryForTheImagePluginOrThreadsIsSaid) {
  // Under ulimit -v 400000-450000 KiB stipple aborted (rc 134) while the image
  // plugin loaded, leaving its staging folder; under 30 MB tile said "internal error: Resource
  // temporarily unavailable" (45 MB now: reading the built-in corner81 set, 7.7 MB of text, needs
  // more than 30 before the threads start).
  if (sanitized()) GTEST_SKIP() << "the address sanitizer reserves terabytes of address space: ulimit -v cannot apply";
  TempDir dir;
  write_image_file(dir.file("map.png"), 2, 2, 1, std::vector<std::uint8_t>(4, 100));
  for (long kib : {300000L, 420000L, 450000L}) {
    Invocation limited{{"stipple", "--image", dir.file("map.png"), "-n", "100", "-k", "2", "-o", dir.file("s.txt")}};
    limited.address_space_bytes = kib << 10;
    Outcome r = run_or_kill(limited);
    EXPECT_EQ(r.exit_code, 1) << kib << " KiB: " << r.err;
    EXPECT_EQ(r.err.rfind("bluetile: cannot load the image plugin libbluetile_oiio.so: OpenImageIO needs about ", 0), 0u)
        << r.err;
    EXPECT_NE(r.err.find("(ulimit -v " + std::to_string(kib) + ")"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("out of memory"), std::string::npos) << r.err;
  }
  Invocation tile{{"tile", "--region", "0", "0", "4", "4", "-o", dir.file("t.txt")}};
  tile.address_space_bytes = 45L << 20;
  tile.environment = {{"BLUETILE_THREADS", "4"}};
  Outcome r = run_or_kill(tile);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err.rfind("bluetile: ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("out of memory or threads (ulimit -v, ulimit -u)"), std::string::npos) << r.err;
  EXPECT_EQ(entries(dir.path()), Names{"map.png"});
}

TEST(ChecksFirst, AnImageTooLargeForTheMemoryLimitSaysWhatItNeeds) {
  // A PNG whose header claims 40000 x 40000 pixels, under ulimit -v 4 GB: "out of memory for
  // 1600000000 samples", which left the user to work out why.
  if (sanitized()) GTEST_SKIP() << "the address sanitizer reserves terabytes of address space: ulimit -v cannot apply";
  TempDir dir;
  write_image_file(dir.file("small.png"), 2, 2, 1, std::vector<std::uint8_t>(4, 100));
  dir.write("huge.png", test::with_png_size(read_text(dir.file("small.png")), 40000, 40000));
  Invocation limited{{"stipple", "--image", dir.file("huge.png"), "-n", "10", "-o", dir.file("s.txt")}};
  limited.address_space_bytes = 4000000L << 10;
  Outcome r = run_or_kill(limited);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err, "bluetile: " + dir.file("huge.png") +
                       ": cannot read image: out of memory: its 40000 x 40000 pixels of 1 channel needs 6.0 GiB as "
                       "4-byte samples\n");
  EXPECT_EQ(entries(dir.path()), (Names{"huge.png", "small.png"}));
}

TEST(ChecksFirst, HeaderArrayNamesAreCheckedBeforeTheWork) {
  // A C keyword was accepted as the array name, and a name that is no C name
  // was found only when the header was written, after the relaxation.
  TempDir dir;
  Outcome r = run_or_kill({{"relax", "-n", "50", "-k", "100000000", "--engine", "exact", "-o", dir.file("p.h"),
                            "--name", "while"}});
  EXPECT_EQ(r.signal, 0) << "not refused before the relaxation";
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "bluetile: " + dir.file("p.h") + ": 'while' is a C or C++ keyword, not a name for the array\n");
  r = run_or_kill({{"relax", "-n", "50", "-k", "100000000", "--engine", "exact", "-o", dir.file("p.h"), "--name", "2x"}});
  EXPECT_EQ(r.signal, 0) << "not refused before the relaxation";
  EXPECT_EQ(r.err, "bluetile: " + dir.file("p.h") + ": '2x' is not a C identifier (letters, digits, '_')\n");
  // A name taken from the file name is made a name, as one starting with a digit already was.
  r = run({"relax", "-n", "50", "-k", "1", "--engine", "exact", "-o", dir.file("int.h")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_text(dir.file("int.h")).find("static const float points_int[1][50][2] = {"), std::string::npos);
  EXPECT_EQ(entries(dir.path()), Names{"int.h"});
}

TEST(ChecksFirst, TwoOutputsIntoOnePipeAreRefused) {
  // Two outputs into one pipe interleaved their bytes, where two into one
  // regular standard output are refused.
  TempDir dir;
  const std::string fifo = dir.file("pipe");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const int reader = open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // lets the tool open its end
  ASSERT_GE(reader, 0);
  Outcome r = run_or_kill({{"relax", "-n", "50", "-k", "100000000", "--engine", "exact", "-o", fifo, "--log", fifo}});
  close(reader);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "bluetile: " + fifo + ": is the same file as the output " + fifo + "\n");
  EXPECT_EQ(entries(dir.path()), Names{"pipe|"});
  // Standard output a pipe: -o - --log - as for a regular standard output.
  test::CommandResult piped = test::run_command(
      "(timeout 60 '" BLUETILE_BINARY "' relax -n 50 -k 100000000 --engine exact -o - --log - | cat)");
  EXPECT_EQ(piped.out, "");
  EXPECT_EQ(piped.err,
            "bluetile: -: two outputs go to standard output, where their bytes would interleave: write one of them to "
            "a file\n");
}

TEST(ChecksFirst, SmallWordingsAndMinusZero) {
  // "0 point"; "-0" written back as it was read.
  TempDir dir;
  dir.write("zero.txt", "0\n");
  Outcome r = run({"analyze", "-i", dir.file("zero.txt"), "-o", dir.file("a")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "bluetile: " + dir.file("zero.txt") + ": 0 points; analysis needs at least 2 points per set\n");
  dir.write("minus.txt", "-0 0.5\n0.25 -0.0\n");
  r = run({"relax", "-i", dir.file("minus.txt"), "-k", "0", "--engine", "exact", "-o", dir.file("o.txt")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::string text = read_text(dir.file("o.txt"));
  EXPECT_NE(text.find("\n0 0.5\n0.25 0\n"), std::string::npos) << text;
  // The points only: the header names the input, whose temporary folder's random name can hold
  // "-0" (bluetile-test-0...), one run in about sixty.
  const std::string points = text.substr(text.find('\n') + 1);
  EXPECT_EQ(points.find("-0"), std::string::npos) << text;
}

TEST(ChecksFirst, AFifoInputWithoutAWriterIsSaidAndThenRead) {
  // An input FIFO nobody writes to held the run without a word; and its first
  // bytes, read to tell the format, were lost to a second open, which then waited for ever.
  TempDir dir;
  const std::string fifo = dir.file("in");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::thread writer([&] {
    // The tool waits in open() meanwhile and says so after a second; 8 s leave a slow start
    // (a sanitizer build on a loaded machine) time to get there first.
    std::this_thread::sleep_for(std::chrono::seconds(8));
    std::ofstream out(fifo);
    out << "0.1 0.2\n0.6 0.7\n0.3 0.9\n";
  });
  Outcome r = run_or_kill({{"relax", "-i", fifo, "-k", "1", "--engine", "exact", "-o", dir.file("o.txt")}});
  const int release = open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // a writer still waiting for a reader
  writer.join();
  if (release >= 0) close(release);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "bluetile: " + fifo + ": waiting for a writer to open this FIFO\n");
  EXPECT_NE(read_text(dir.file("o.txt")).find("3 points, 1 iteration,"), std::string::npos);
}

TEST(ChecksFirst, AFifoOutputWithoutAReaderIsSaidAndThenWritten) {
  // The output side of the test above: an output FIFO nobody reads held the run without a word.
  TempDir dir;
  const std::string fifo = dir.file("out");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] {
    std::this_thread::sleep_for(std::chrono::seconds(8));  // as above: the note first
    std::ifstream in(fifo);
    received.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  });
  Outcome r = run_or_kill({{"dart", "-n", "10", "-o", fifo}});
  const int release = open(fifo.c_str(), O_WRONLY | O_NONBLOCK);  // a reader still waiting for a writer
  reader.join();
  if (release >= 0) close(release);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "bluetile: " + fifo + ": waiting for a reader to open this FIFO\n");
  EXPECT_NE(received.find("# bluetile dart"), std::string::npos) << received;
}

TEST(ChecksFirst, AnImageThroughAFifoIsReadOnceAsAFileWouldBe) {
  // A density map or stipple image given as a FIFO (or a process substitution's pipe) hung for
  // ever without a word: the image library opens an image twice and probes it by reading. Now it
  // is read once, with the waiting note, and gives the points the same image as a file gives.
  TempDir dir;
  Outcome made = run({"tile", "--region", "0", "0", "1", "1", "--density", "200", "--image-size", "48", "-o",
                      dir.file("map.png")});
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const std::string image = read_text(dir.file("map.png"));
  const std::string fifo = dir.file("pipe.png");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::thread writer([&] {
    std::this_thread::sleep_for(std::chrono::seconds(8));  // as above: the note first
    std::ofstream out(fifo, std::ios::binary);
    out << image;
  });
  const std::vector<std::string> tile = {"tile", "--region", "0", "0", "2", "1", "--count", "300", "--density-map"};
  std::vector<std::string> through_fifo = tile;
  through_fifo.insert(through_fifo.end(), {fifo, "-o", dir.file("fifo.txt")});
  Outcome r = run_or_kill({through_fifo});
  const int release = open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  writer.join();
  if (release >= 0) close(release);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "bluetile: " + fifo + ": waiting for a writer to open this FIFO\n");
  std::vector<std::string> from_file = tile;
  from_file.insert(from_file.end(), {dir.file("map.png"), "-o", dir.file("file.txt")});
  ASSERT_EQ(run(from_file).exit_code, 0);
  auto points = [](const std::string& text) { return text.substr(text.find("\n0") + 1); };  // after the header
  EXPECT_EQ(points(read_text(dir.file("fifo.txt"))), points(read_text(dir.file("file.txt"))));
  EXPECT_GT(points(read_text(dir.file("file.txt"))).size(), 1000u);
  // A FIFO of no image is refused by the image's name, and no temporary copy stays.
  std::thread junk([&] {
    std::ofstream out(fifo, std::ios::binary);
    out << "not an image\n";
  });
  r = run_or_kill({{"stipple", "--image", fifo, "-n", "10", "-k", "1", "-o", dir.file("s.txt")}});
  junk.join();
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err.rfind("bluetile: " + fifo + ": cannot read image: ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find("bluetile-image-"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("s.txt")));
}

// A long raster job on a CPU device says, before it starts, how long it should
// take and how long the exact engine would (killed once the line had time to appear).
TEST(ChecksFirst, ALongRasterJobOnACpuDeviceNamesTheFasterEngine) {
  TempDir dir;
  Child child({{"relax", "-n", "20000", "-k", "1000", "-o", dir.file("a.txt")}});
  std::this_thread::sleep_for(std::chrono::seconds(8));
  kill(child.pid(), SIGKILL);
  Outcome r = child.wait();
  if (r.err.find("no Vulkan") != std::string::npos || r.exit_code == 1) GTEST_SKIP() << "no raster engine: " << r.err;
  // 2e7 cells at 2.5 us: 50 s and a rounding, said as 51 (durations are rounded up); the exact
  // engine 16 times less (3.1 s, said as 4).
  EXPECT_NE(r.err.find("bluetile: note: about 51 s on the raster engine on "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("a CPU device; --engine exact computes the same cells (to 1e-12 of area coverage) in about 4 s"),
            std::string::npos)
      << r.err;
  // Short jobs, and the exact engine, say nothing.
  Outcome small = run({"relax", "-n", "200", "-k", "5", "-o", dir.file("b.txt")});
  EXPECT_EQ(small.exit_code, 0) << small.err;
  EXPECT_EQ(small.err, "");
  Outcome exact = run({"relax", "-n", "20000", "-k", "3", "--engine", "exact", "-o", dir.file("c.txt")});
  EXPECT_EQ(exact.err, "");
}

}  // namespace
}  // namespace bluetile::robustness
