// Numbers on the command line: refused with the option, the value and
// the accepted range, never clamped; whole numbers in scientific notation accepted.
#include <gtest/gtest.h>

#include <sched.h>

#include "bluetile/io/image_file.h"
#include "bluetile/io/pdf.h"
#include "robustness_support.h"
#include "test_support.h"

namespace bluetile::robustness {
namespace {

using test::read_text;
using test::TempDir;

struct Refusal {
  std::vector<std::string> arguments;
  std::string message;  // the whole stderr line after "bluetile: "
};

TEST(Options, OutOfRangeNanAndInfinityAreRefused) {
  TempDir dir;
  const std::string out = dir.file("o.txt");
  const std::string seeds = "expected an integer from 0 to 18446744073709551615 (see --help)";
  const std::vector<Refusal> cases = {
      {{"relax", "-n", "10", "-s", "18446744073709551616", "-o", out}, "--seed 18446744073709551616: out of range; " + seeds},
      {{"relax", "-n", "10", "-s", "99999999999999999999999", "-o", out}, "--seed 99999999999999999999999: out of range; " + seeds},
      {{"relax", "-n", "10", "-s", "-1", "-o", out}, "--seed -1: out of range; " + seeds},
      {{"relax", "-n", "10", "--fixed", "99999999999999999999", "-o", out},
       "--fixed 99999999999999999999: out of range; expected an integer from 0 to 100000000 (see --help)"},
      {{"relax", "-n", "10", "--fixed", "-3", "-o", out},
       "--fixed -3: out of range; expected an integer from 0 to 100000000 (see --help)"},
      {{"relax", "-n", "10", "--tolerance", "nan", "-o", out},
       "--tolerance nan: not a finite number; expected a finite number >= 0 (see --help)"},
      {{"relax", "-n", "10", "--tolerance", "-1e-3", "-o", out},
       "--tolerance -1e-3: out of range; expected a finite number >= 0 (see --help)"},
      {{"progressive", "-n", "10", "--ratio", "nan", "-o", out},
       "--ratio nan: not a finite number; expected a number above 1 and at most 100000000 (see --help)"},
      {{"progressive", "-n", "10", "--ratio", "inf", "-o", out},
       "--ratio inf: not a finite number; expected a number above 1 and at most 100000000 (see --help)"},
      {{"relax", "-n", "1.5", "-o", out}, "--count 1.5: not an integer; expected an integer from 1 to 100000000 (see --help)"},
      {{"relax", "-n", "1e9", "-o", out}, "--count 1e9: out of range; expected an integer from 1 to 100000000 (see --help)"},
      {{"relax", "-n", "ten", "-o", out}, "--count ten: not a number; expected an integer from 1 to 100000000 (see --help)"},
      {{"relax", "-n", "10", "-k", "1e-2", "-o", out},
       "--iterations 1e-2: not an integer; expected an integer from 0 to 100000000 (see --help)"},
      {{"dart", "-n", "10", "--shrink", "1", "-o", out},
       "--shrink 1: out of range; expected a number from 1e-06 to 0.999999 (see --help)"},
      {{"analyze", "-i", out, "-o", dir.file("an"), "--bin-width", "0"},
       "--bin-width 0: out of range; expected a number above 0 and at most 65536 (see --help)"},
      {{"relax", "-n", "10", "--resolution", "15", "-o", out},
       "--resolution 15: out of range; expected an integer from 16 to 65536 (see --help)"},
      // Every command takes numbers the one way.
      {{"tile", "--region", "0", "0", "1", "1", "-s", "-1", "-o", out}, "--seed -1: out of range; " + seeds},
      {{"wang", "-s", "18446744073709551616", "-o", out}, "--seed 18446744073709551616: out of range; " + seeds},
      {{"wang-check", "/dev/null", "-s", "-1"}, "--seed -1: out of range; " + seeds},
      {{"stipple", "--image", "/dev/null", "-n", "10", "-s", "-1", "-o", out}, "--seed -1: out of range; " + seeds},
      {{"wang", "--ratio", "inf", "-o", out},
       "--ratio inf: not a finite number; expected a number above 1 and at most 100000000 (see --help)"},
      {{"wang", "--margin", "nan", "-o", out}, "--margin nan: not a finite number; expected a number from 0 to 0.25 (see --help)"},
      {{"wang", "--lattice-step", "nan", "-o", out},
       "--lattice-step nan: not a finite number; expected a number from 0.0001 to 0.1 (see --help)"},
      {{"wang", "--seam-spacing", "nan", "-o", out},
       "--seam-spacing nan: not a finite number; expected a number from 0.01 to 2 (see --help)"},
      {{"stipple", "--tolerance", "nan"}, "--tolerance nan: not a finite number; expected a finite number >= 0 (see --help)"},
      {{"stipple", "--dot-radius", "nan"}, "--dot-radius nan: not a finite number; expected a number above 0 and at most 1 (see --help)"},
      {{"relax", "-n", "10", "--weight-exponent", "nan", "-o", out},
       "--weight-exponent nan: not a finite number; expected a number from 0 to 8 (see --help)"},
      {{"relax", "-n", "10", "--gamma", "inf", "-o", out},
       "--gamma inf: not a finite number; expected a finite number > 0 (see --help)"},
      {{"tile", "--region", "0", "0", "1", "1", "--threads", "0", "-o", out},
       "--threads 0: out of range; expected an integer from 1 to 1024 (see --help)"},
  };
  for (const Refusal& c : cases) {
    Outcome r = run(c.arguments);
    EXPECT_EQ(r.exit_code, 105) << r.err;  // CLI11's validation exit status
    EXPECT_EQ(r.err, "bluetile: " + c.message + "\n");
  }
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{});
}

TEST(Options, WholeNumbersInScientificNotationAreAccepted) {
  TempDir dir;
  // "-n 1e2" said "not in range".
  Outcome r = run({"relax", "-n", "1e2", "-k", "2.5e1", "-s", "7E0", "--engine", "exact", "-o", dir.file("a.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run({"relax", "-n", "100", "-k", "25", "-s", "7", "--engine", "exact", "-o", dir.file("b.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(dir.file("a.txt")), read_text(dir.file("b.txt")));
  r = run({"relax", "-n", "10", "-k", "1", "-s", "18446744073709551615", "--engine", "exact", "-o", dir.file("c.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_text(dir.file("c.txt")).find("seed 18446744073709551615"), std::string::npos);
}

TEST(Options, WangTakesCountsAsRelaxDoes) {
  TempDir dir;
  // "wang --points 1e3" was refused where "relax -n 1e3" is accepted.
  Outcome r = run({"wang", "-n", "1.3e1", "-k", "0", "--warm", "0", "--lattice-steps", "0", "--seam-steps", "0",
                   "--levels", "2", "--ratio", "+2", "-o", dir.file("a.tiles")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run({"wang", "-n", "13", "-k", "0", "--warm", "0", "--lattice-steps", "0", "--seam-steps", "0", "--levels", "2",
           "-o", dir.file("b.tiles")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(dir.file("a.tiles")), read_text(dir.file("b.tiles")));
}

TEST(Options, RunsTooLargeForTheMachineAreRefusedUpFront) {
  TempDir dir;
  // Nothing bounded --count x --sets.
  Outcome r = run({"relax", "-n", "100000000", "--sets", "10000000", "--engine", "exact", "-o", dir.file("o.txt")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err.rfind("bluetile: --count 100000000 x --sets 10000000 needs about 568.4 PiB of memory, more than the ", 0), 0u)
      << r.err;
  if (!sanitized()) {  // ulimit -v stands in for a small machine
    Invocation limited{{"dart", "-n", "100000000", "-o", dir.file("o.txt")}};
    limited.address_space_bytes = 1L << 30;
    r = run(limited);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err.rfind("bluetile: --count 100000000 needs about 17.9 GiB of memory, more than the ", 0), 0u) << r.err;
    limited.arguments = {"progressive", "-n", "50000000", "--levels", "2", "--engine", "exact", "-o", dir.file("o.txt")};
    r = run(limited);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err.rfind("bluetile: 100000000 points in 2 levels needs about 60.3 GiB of memory, more than the ", 0), 0u)
        << r.err;
  }
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{});
}

TEST(Options, TheDefaultThreadsAreTheCpusTheProcessMayRunOn) {
  // Under taskset, a cpuset or a batch scheduler the machine's CPU count put threads that poll
  // for work on one allowed core, 3-5x slower than one thread; the count is the affinity mask's,
  // as nproc's. analyze's estimate names the count it divides by.
  cpu_set_t allowed;
  ASSERT_EQ(sched_getaffinity(0, sizeof allowed, &allowed), 0);
  int first = 0;
  while (!CPU_ISSET(first, &allowed)) ++first;
  const int count = CPU_COUNT(&allowed);
  TempDir dir;
  const std::string points = dir.write("p.txt", many_points_text(3000));
  Invocation analyze{{"analyze", "-i", points, "-o", dir.file("out"), "--time-limit", "0.0001"}};
  analyze.environment = {{"BLUETILE_THREADS", ""}};  // empty: unset
  Outcome r = run(analyze);
  EXPECT_EQ(r.exit_code, 1);
  const std::string all = count == 1 ? " on 1 thread, " : " on " + std::to_string(count) + " threads, ";
  EXPECT_NE(r.err.find(all), std::string::npos) << r.err;
  analyze.wrapper = {"/usr/bin/taskset", "-c", std::to_string(first)};
  r = run(analyze);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(" on 1 thread, "), std::string::npos) << r.err;
}

TEST(Options, InputsTooLargeToRelaxAreRefusedUpFront) {
  // relax -i and centroids -i checked nothing: a file of 600000 points read into a process with
  // 250 MB of address space ended in "out of memory" after the reading, not with the estimate.
  if (sanitized()) GTEST_SKIP() << "the address sanitizer reserves terabytes: ulimit -v cannot be used";
  TempDir dir;
  const std::string input = dir.write("big.txt", many_points_text(600000));
  for (const std::string command : {"relax", "centroids"}) {
    Invocation limited{{command, "-i", input, "--engine", "exact", "-o", dir.file("o.txt")}};
    limited.address_space_bytes = 250L << 20;
    const Outcome r = run(limited);
    EXPECT_EQ(r.exit_code, 1) << command;
    EXPECT_EQ(r.err.rfind("bluetile: " + command + " of the 600000 points of " + input +
                              " needs about 366.2 MiB of memory, more than the ",
                          0),
              0u)
        << r.err;
  }
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"big.txt"});
}

TEST(Options, TilingsTooLargeAreRefusedUpFront) {
  // A tiled window's count is known before any point is made (cells x points x
  // thinning), and nothing bounded it: 10^12 points were written until the disk was full.
  TempDir dir;
  const std::string map = dir.file("map.png");
  write_image_file(map, 2, 2, 1, std::vector<std::uint8_t>(4, 128));  // uniform: mean = largest
  const std::string limit = ", more than the limit of 100000000 ";
  const std::string too_many = limit + "points: use a smaller region or a lower density";
  const std::vector<Refusal> cases = {
      {{"tile", "--region", "0", "0", "1000000", "1000000", "--density", "1", "-o", dir.file("p.txt")},
       "--region 0 0 1000000 1000000 holds about 1000000000000 points (1 per unit area)" + too_many},
      {{"tile", "--region", "0", "0", "1000000", "1000000", "--density", "1", "-o", dir.file("p.svg")},
       "--region 0 0 1000000 1000000 holds about 1000000000000 points (1 per unit area)" + too_many},
      {{"tile", "--region", "0", "0", "1000000", "1000000", "--density", "1", "-o", dir.file("p.png")},
       "--region 0 0 1000000 1000000 holds about 1000000000000 points (1 per unit area)" + too_many},
      {{"tile", "--region", "0", "0", "1", "1", "--density-map", map, "--count", "1e12", "-o", dir.file("p.txt")},
       "--region 0 0 1 1 holds about 1000000000000 points (1000000000000 per unit area)" + too_many},
      {{"tile", "--region", "0", "0", "1", "1", "--density-map", map, "--max-density", "1e10", "-o", "-"},
       "--region 0 0 1 1 holds about 10000000000 points (10000000000 per unit area)" + too_many},
      {{"tile", "--region", "0", "0", "1000", "1000", "--tile-size", "1e-3", "-o", dir.file("p.txt")},
       "--region 0 0 1000 1000 holds about 2048000000000000 points (2048000000 per unit area)" + too_many},
      // Few points, but 10^12 tiles to visit.
      {{"tile", "--region", "0", "0", "1000", "1000", "--tile-size", "1e-3", "--density", "1", "-o", dir.file("p.txt")},
       "--region 0 0 1000 1000 spans about 1000006000009 tiles of size 0.001" + limit +
           "tiles: use a larger --tile-size or a smaller region"},
  };
  for (const Refusal& c : cases) {
    // Limits that turn a run which does start into a quick failure of this test, not a full disk.
    Invocation limited{c.arguments};
    limited.file_size_bytes = 1L << 20;
    if (!sanitized()) limited.address_space_bytes = 2L << 30;
    Outcome r = run(limited);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(r.err, "bluetile: " + c.message + "\n");
    EXPECT_EQ(r.out, "");
  }
  if (!sanitized() && pdf_unavailable_reason().empty()) {
    // A PDF is built whole (an SVG is streamed): 5 x 10^7 dots do not fit in 1 GiB.
    Invocation limited{{"tile", "--region", "0", "0", "10000", "5000", "--density", "1", "-o", dir.file("p.pdf")}};
    limited.address_space_bytes = 1L << 30;
    limited.file_size_bytes = 1L << 20;
    Outcome r = run(limited);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err.rfind("bluetile: " + dir.file("p.pdf") + ": a PDF of about 50000000 dots needs about 51.2 GiB of memory, "
                          "more than the ", 0), 0u) << r.err;
  }
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"map.png"});
}

TEST(Options, RendersTallerThanAnImageMayBeAreRefusedUpFront) {
  // The render's height went through static_cast<int> of 1.6e10 and came out a
  // 16384 x 1 PNG, exit 0.
  TempDir dir;
  Outcome r = run({"tile", "--region", "0", "0", "1", "1000000", "--density", "1", "--image-size", "16384", "-o",
                   dir.file("p.png")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "bluetile: --image-size 16384: a render of the region 0 0 1 1000000 would be 16384000000 pixels "
                   "tall, more than the limit of 32768: use a smaller --image-size or a wider region\n");
  // stipple's drawing has the image's aspect: a 1 x 100000 image rendered 32768 wide.
  write_image_file(dir.file("tall.png"), 1, 100000, 1, std::vector<std::uint8_t>(100000, 100));
  r = run({"stipple", "--image", dir.file("tall.png"), "-n", "10", "-k", "1", "-o", dir.file("p.txt"), "--png",
           dir.file("p.png"), "--png-width", "32768"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "bluetile: --png-width 32768: a render of the 1 x 100000 image would be 3276800000 pixels tall, "
                   "more than the limit of 32768: use a smaller --png-width\n");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"tall.png"});
}

TEST(Options, StipplesTooLargeForTheMachineAreRefusedUpFront) {
  // stipple -n 1e8 failed after 20 s where relax -n 1e8 is refused at once.
  if (sanitized()) GTEST_SKIP() << "ulimit -v stands in for a small machine, and the sanitizer needs terabytes of it";
  TempDir dir;
  write_image_file(dir.file("map.png"), 2, 2, 1, std::vector<std::uint8_t>(4, 100));
  Invocation limited{{"stipple", "--image", dir.file("map.png"), "-n", "100000000", "-o", dir.file("p.txt")}};
  limited.address_space_bytes = 1L << 30;
  Outcome r = run(limited);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err.rfind("bluetile: --count 100000000 needs about 59.6 GiB of memory, more than the ", 0), 0u) << r.err;
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"map.png"});
}

TEST(Options, WangSetsTooLargeAreRefusedUpFront) {
  // The levels' counts are known before any relaxation; --ratio 1e7 (1.3e8
  // points per tile) and --levels 32 ran on.
  TempDir dir;
  const std::vector<Refusal> cases = {
      {{"wang", "--points", "13", "--levels", "2", "--ratio", "1e7", "-o", dir.file("t.txt")},
       "--points 13 --levels 2 --ratio 10000000 makes about 130000000 points per tile (1040000000 in the 8 tiles), "
       "more than the limit of 1000000 per tile: use fewer levels or a smaller ratio"},
      {{"wang", "--levels", "32", "--set", "wang16", "-o", dir.file("t.txt")},
       "--points 52 --levels 32 --ratio 2 makes about 111669149696 points per tile (1786706395136 in the 16 tiles), "
       "more than the limit of 1000000 per tile: use fewer levels or a smaller ratio"},
  };
  for (const Refusal& c : cases) {
    Invocation limited{c.arguments};
    if (!sanitized()) limited.address_space_bytes = 2L << 30;  // without the check: out of memory, not hours
    Outcome r = run(limited);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(r.err, "bluetile: " + c.message + "\n");
  }
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{});
}

TEST(Options, WangCheckPlanesTooLargeAreRefusedWithoutAnOutputFolder) {
  // The plane's memory was checked only for the spectrum image (-o): without it, a 1024 x 1024
  // tiling of 600 points a tile was measured until memory ran out.
  TempDir dir;
  const std::string tiles = dir.file("tiles.txt");
  Outcome r = run({"wang", "-n", "600", "-k", "0", "--warm", "0", "--lattice-steps", "0", "--seam-steps", "0", "-o", tiles});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Invocation limited{{"wang-check", tiles, "--period", "1024"}};
  if (!sanitized()) limited.address_space_bytes = 2L << 30;
  r = run(limited);
  EXPECT_EQ(r.exit_code, 1);
  // 1024^2 x 600 points and their periodogram (F = 2 (ceil(1.6 sqrt(N)) + 2) = 80270: about 145 GiB,
  // a little more per thread).
  EXPECT_EQ(r.err.rfind("bluetile: the spectrum of the 629145600-point plane needs about 14", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(" GiB of memory, more than the "), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"tiles.txt"});
}

}  // namespace
}  // namespace bluetile::robustness
