// The command line as a user runs it: outputs, determinism, and bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "bluetile/core/point_file.h"
#include "bluetile/io/image_file.h"
#include "bluetile/voronoi/exact_engine.h"
#include "test_support.h"

namespace bluetile {
namespace {

using test::read_text;
using test::run_bluetile;
using test::TempDir;

TEST(Cli, HelpOnEverySubcommand) {
  // This covered 2 of the subcommands.
  for (std::string sub : {"relax", "centroids", "analyze", "dart", "progressive", "devices", "stipple"}) {
    auto r = run_bluetile({sub, "--help"});
    EXPECT_EQ(r.exit_code, 0) << sub;
    EXPECT_NE(r.out.find("Usage: "), std::string::npos) << sub << ": " << r.out;
    EXPECT_EQ(r.out.find("--output") != std::string::npos, sub != "devices") << sub;
  }
  const std::string commands =
      "(commands: relax, centroids, analyze, dart, progressive, devices, wang, wang-check, tile, stipple";
  // No command was CLI11's "A subcommand is required", which named none.
  auto none = run_bluetile({});
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_EQ(none.err, "bluetile: a command is required " + commands + "; see --help)\n");
  // "bluetile help" was an unknown command; now the help of the tool or of the command, as --help.
  auto main_help = run_bluetile({"--help"});
  EXPECT_NE(main_help.out.find("A command's options: bluetile help COMMAND"), std::string::npos) << main_help.out;
  auto help = run_bluetile({"help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_EQ(help.out, main_help.out);
  auto relax_help = run_bluetile({"relax", "--help"});
  help = run_bluetile({"help", "relax"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_EQ(help.out, relax_help.out);
  EXPECT_EQ(relax_help.out.find("bluetile help COMMAND"), std::string::npos) << "the footer is the tool's only";
  help = run_bluetile({"help", "frobnicate"});
  EXPECT_EQ(help.exit_code, 2);
  EXPECT_EQ(help.err, "bluetile: unknown command 'frobnicate' " + commands + "; see --help)\n");
  help = run_bluetile({"help", "relax", "tile"});
  EXPECT_EQ(help.exit_code, 2);
  EXPECT_EQ(help.err, "bluetile: help takes one command, got 'relax' and 'tile' " + commands + ")\n");
  EXPECT_EQ(help.out, "");
  // An unknown command was "A subcommand is required", and with --help after it the main help
  // and status 0.
  for (auto arguments : {std::vector<std::string>{"frobnicate"}, std::vector<std::string>{"compare", "--help"}}) {
    auto r = run_bluetile(arguments);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "bluetile: unknown command '" + arguments[0] +
                         "' (commands: relax, centroids, analyze, dart, progressive, devices, wang, wang-check, tile, "
                         "stipple; see --help)\n");
    EXPECT_EQ(r.out, "");
  }
}

TEST(Cli, AFileGivenWithoutItsOptionIsNamed) {
  // "analyze points.txt -o out" said only "--input is required".
  TempDir dir;
  auto r = run_bluetile({"analyze", "points.txt", "-o", dir.file("out")});
  EXPECT_EQ(r.exit_code, 106);
  EXPECT_EQ(r.err,
            "bluetile: --input is required; 'points.txt' was given without an option: --input points.txt? (see "
            "--help)\n");
  r = run_bluetile({"relax", "-n", "10", "p.txt"});
  EXPECT_EQ(r.err, "bluetile: --output is required; 'p.txt' was given without an option: --output p.txt? (see --help)\n");
  // Nothing stray: CLI11's words alone.
  r = run_bluetile({"analyze", "-o", dir.file("out")});
  EXPECT_EQ(r.err, "bluetile: --input is required (see --help)\n");
  EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}

TEST(Cli, RelaxIsDeterministicAcrossThreadCounts) {
  TempDir dir;
  auto a = run_bluetile({"relax", "-n", "500", "-k", "20", "--seed", "9", "--engine", "exact", "--threads", "1",
                         "-o", dir.file("a.txt")});
  auto b = run_bluetile({"relax", "-n", "500", "-k", "20", "--seed", "9", "--engine", "exact", "--threads", "2",
                         "-o", dir.file("b.txt")});
  auto c = run_bluetile({"relax", "-n", "500", "-k", "20", "--seed", "10", "--engine", "exact", "-o", dir.file("c.txt")});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(read_text(dir.file("a.txt")), read_text(dir.file("b.txt")));
  EXPECT_NE(read_text(dir.file("a.txt")), read_text(dir.file("c.txt")));
  EXPECT_EQ(read_point_file(dir.file("a.txt")).points.size(), 500u);
}

TEST(Cli, RelaxLogAndFixedSites) {
  TempDir dir;
  auto r = run_bluetile({"relax", "-n", "300", "-k", "5", "--engine", "exact", "-o", dir.file("p.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_bluetile({"relax", "-i", dir.file("p.txt"), "-k", "7", "--fixed", "100", "--engine", "exact",
                    "-o", dir.file("q.txt"), "--log", dir.file("log.csv"), "--verbose"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  PointSet before = read_point_file(dir.file("p.txt")), after = read_point_file(dir.file("q.txt"));
  for (std::size_t i = 0; i < 100; ++i) ASSERT_EQ(before.points[i], after.points[i]);
  EXPECT_NE(before.points[150], after.points[150]);
  std::string log = read_text(dir.file("log.csv"));
  EXPECT_EQ(log.rfind("iteration,energy,max_displacement,mean_displacement", 0), 0u);
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 8);
  EXPECT_NE(r.err.find("iteration 7: energy"), std::string::npos);
}

TEST(Cli, RelaxSetsInOneFileAndOneFileEach) {
  TempDir dir;
  auto r = run_bluetile({"relax", "-n", "64", "--sets", "3", "-k", "5", "--engine", "exact", "-o", dir.file("all.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto sets = read_point_sets(dir.file("all.txt"));
  ASSERT_EQ(sets.size(), 3u);
  r = run_bluetile({"relax", "-n", "64", "--sets", "3", "-k", "5", "--engine", "exact", "-o", dir.file("set-{}.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_point_file(dir.file("set-2.txt")).points, sets[2].points);
  // Set 0 of a batch is the single set of the same seed.
  r = run_bluetile({"relax", "-n", "64", "-k", "5", "--engine", "exact", "-o", dir.file("one.txt")});
  EXPECT_EQ(read_point_file(dir.file("one.txt")).points, sets[0].points);
}

TEST(Cli, RasterRelaxOfSitesOnALineSaysTheExactEngineMeasuredThem) {
  // 1000 sites on y = 0.5: sliver cells, handed over to the exact engine, and the run says so;
  // the same points as the exact engine's. A uniform start says nothing.
  TempDir dir;
  std::string text;
  for (int i = 0; i < 1000; ++i) text += std::to_string((i + 0.5) / 1000.0) + " 0.5\n";
  std::ofstream(dir.file("line.txt")) << text;
  auto raster = run_bluetile({"relax", "-i", dir.file("line.txt"), "-k", "3", "--engine", "raster", "-o", dir.file("r.txt")});
  auto exact = run_bluetile({"relax", "-i", dir.file("line.txt"), "-k", "3", "--engine", "exact", "-o", dir.file("e.txt")});
  ASSERT_EQ(raster.exit_code, 0) << raster.err;
  ASSERT_EQ(exact.exit_code, 0) << exact.err;
  EXPECT_NE(raster.err.find("measured 3 of 3 scene computations with the exact engine"), std::string::npos) << raster.err;
  EXPECT_EQ(read_point_file(dir.file("r.txt")).points, read_point_file(dir.file("e.txt")).points);
  auto uniform = run_bluetile({"relax", "-n", "1000", "-k", "3", "--engine", "raster", "-o", dir.file("u.txt")});
  ASSERT_EQ(uniform.exit_code, 0) << uniform.err;
  EXPECT_EQ(uniform.err.find("exact engine"), std::string::npos) << uniform.err;
}

TEST(Cli, CentroidsWritesOneLinePerPointInOrder) {
  TempDir dir;
  std::string in = dir.write("in.txt", "0.25 0.5\n0.75 0.5\n");
  auto r = run_bluetile({"centroids", "-i", in, "-o", dir.file("c.txt"), "--engine", "exact"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string text = read_text(dir.file("c.txt"));
  EXPECT_NE(text.find("\n0.25 0.5 0.5\n0.75 0.5 0.5\n"), std::string::npos) << text;
}

struct BadInput {
  std::string name;
  std::string content;
  std::string message;  // expected in stderr
};

TEST(Cli, BadInputFilesFailCleanlyAndWriteNothing) {
  const std::vector<BadInput> cases = {
      {"nan.txt", "0.1 0.2\n0.3 nan\n", "nan.txt:2: not a finite number 'nan'"},
      {"inf.txt", "0.1 -inf\n", "inf.txt:1: not a finite number '-inf'"},
      {"text.txt", "hello world\n", "text.txt:1: not a number 'hello'"},
      {"count.txt", "5\n0.1 0.2\n", "count.txt:1: count line says 5 points but 1 follow"},
      {"columns.txt", "0.1 0.2 0.3 0.4\n", "columns.txt:1: expected 'x y' or 'x y level'"},
      {"empty.txt", "# nothing\n", "empty.txt: no points"},
      // A count line of 0 is a set with no points: refused, not relaxed into a header-only file.
      {"zero.txt", "0\n", "zero.txt: 0 points; "},
      {"second.txt", "0.1 0.2\n# set 1\n0\n", "second.txt (set 1 of 2): 0 points; "},
  };
  for (const auto& bad : cases) {
    for (std::string sub : {"relax", "centroids"}) {
      TempDir dir;
      std::string in = dir.write(bad.name, bad.content);
      auto r = run_bluetile({sub, "-i", in, "-o", dir.file("out.txt"), "--engine", "exact"});
      EXPECT_NE(r.exit_code, 0) << sub << " " << bad.name;
      EXPECT_NE(r.err.find(bad.message), std::string::npos) << sub << ": " << r.err;
      EXPECT_EQ(r.err.rfind("bluetile: ", 0), 0u) << r.err;
      EXPECT_EQ(dir.list(), std::vector<std::string>{bad.name}) << sub << " left output behind";
    }
  }
}

TEST(Cli, BadOptionsFailWithAMessage) {
  TempDir dir;
  std::string out = dir.file("o.txt");
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"relax", "-n", "0", "-o", out}, "--count"},
      {{"relax", "-n", "-5", "-o", out}, "--count"},
      {{"relax", "-n", "100", "-k", "-1", "-o", out}, "--iterations"},
      {{"relax", "-o", out}, "--count or --input"},
      {{"relax", "-n", "100"}, "--output"},
      {{"relax", "-n", "10", "--fixed", "11", "-o", out, "--engine", "exact"}, "--fixed 11 is more than the 10 points"},
      {{"relax", "-n", "10", "-i", BLUETILE_TEST_DATA "/../test_cli.cpp", "-o", out}, "excludes"},
      {{"relax", "-i", dir.file("missing.txt"), "-o", out}, "missing.txt"},
      {{"relax", "-n", "10", "--engine", "magic", "-o", out}, "--engine"},
      {{"relax", "-n", "10", "--coverage", "blur", "-o", out}, "--coverage"},
      {{"relax", "-n", "10", "--tolerance", "-1", "-o", out}, "--tolerance"},
      {{"relax", "-n", "10", "-o", dir.file("no/such/dir/o.txt"), "--engine", "exact"}, "no/such/dir/o.txt"},
  };
  for (const auto& c : cases) {
    auto r = run_bluetile(c.args);
    EXPECT_NE(r.exit_code, 0) << c.args[1] << " " << c.args[2];
    EXPECT_NE(r.err.find(c.message), std::string::npos) << "expected '" << c.message << "' in: " << r.err;
  }
  EXPECT_EQ(dir.list(), std::vector<std::string>{});
}

TEST(Cli, OptionsARunWouldNotUseAreRefused) {
  // Raster settings on the exact engine, and relaxation or engine options with the fill order,
  // were accepted and changed nothing (an absent device included).
  TempDir dir;
  const std::string out = dir.file("o.txt");
  const std::string raster_setting = ": a raster engine setting, and this run uses the exact engine";
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"relax", "-n", "64", "--engine", "exact", "--device", "7", "-o", out}, "--device 7" + raster_setting + ";"},
      {{"relax", "-n", "64", "--bounded", "--pixel-work", "device", "-o", out},
       "--pixel-work device" + raster_setting + ", the default with --bounded; --engine raster uses it"},
      {{"centroids", "-i", BLUETILE_TEST_DATA "/ranks_square.txt", "--engine", "exact", "--coverage", "point", "-o", out},
       "--coverage point" + raster_setting},
      {{"progressive", "-n", "64", "--levels", "2", "--engine", "exact", "--resolution", "100", "-o", out},
       "--resolution 100" + raster_setting},
      {{"wang", "-n", "4", "-k", "1", "--cone", "fan", "-o", out}, "--cone fan" + raster_setting + ", the default for wang"},
      {{"progressive", "-n", "64", "--levels", "3", "--rank-order", "fill", "-k", "5", "-o", out},
       "--iterations 5: --rank-order fill relaxes nothing and runs no engine"},
      {{"progressive", "-n", "64", "--levels", "3", "--rank-order", "fill", "--placement", "random", "-o", out},
       "--placement random: --rank-order fill"},
      {{"progressive", "-n", "64", "--levels", "3", "--rank-order", "fill", "--device", "7", "-o", out},
       "--device 7: --rank-order fill"},
      {{"relax", "-i", BLUETILE_TEST_DATA "/ranks_square.txt", "--seed", "7", "--engine", "exact", "-o", out},
       "--seed 7: only with --count (it draws the random start; the input is the start)\n"},
      {{"relax", "-n", "5", "--weight-exponent", "3", "--engine", "exact", "-o", out},
       "--weight-exponent 3 weights the cells by a --density-map: give one\n"},
  };
  for (const auto& c : cases) {
    auto r = run_bluetile(c.args);
    EXPECT_EQ(r.exit_code, 1) << c.args[0] << ": " << r.err;
    EXPECT_EQ(r.err.rfind("bluetile: " + c.message, 0), 0u) << r.err;
  }
  EXPECT_EQ(dir.list(), std::vector<std::string>{});
  // An ID image is drawn by a raster engine made from them: taken with the exact engine.
  auto r = run_bluetile({"relax", "-n", "64", "-k", "1", "--engine", "exact", "--resolution", "64", "--id-image",
                         dir.file("id.png"), "-o", out});
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(Cli, SettingsOfPartsARunDoesNotHaveAreRefused) {
  // wang's level, strategy, order and step settings, stipple's and tile's drawing settings were
  // accepted where the run had no such part, and changed nothing (--void-sigma with the fill
  // order, --png-width without --png, --image-size without a render).
  TempDir dir;
  write_image_file(dir.file("map.png"), 4, 4, 1, std::vector<float>(16, 0.5f), SampleFormat::uint8);
  const std::string tiles = dir.file("t.tiles"), points = dir.file("p.txt"), map = dir.file("map.png");
  const std::vector<std::string> wang = {"wang", "-n", "8", "-k", "1", "--warm", "0", "-o", tiles};
  const std::vector<std::string> stipple = {"stipple", "--image", map, "-n", "20", "-k", "1", "-o", points};
  const std::vector<std::string> tile = {"tile", "--region", "0", "0", "1", "1", "--density", "50"};
  struct Case {
    std::vector<std::string> base, more;
    std::string message;
  };
  const std::vector<Case> cases = {
      {wang, {"--ratio", "3"}, "--ratio 3: only with --levels 2 or more (this run: --levels 1)"},
      {wang, {"--period", "6"}, "--period 6: only with --strategy instances (this run: --strategy auto, exact for wang8)"},
      {wang, {"--strategy", "rounds", "--period", "6"},
       "--period 6: only with --strategy instances (this run: --strategy rounds)"},
      {wang, {"--void-sigma", "0.7"}, "--void-sigma 0.7: only with --rank-order voids (this run: --rank-order fill)"},
      {wang, {"--lattice-steps", "0", "--lattice-steps-per-iteration", "0", "--lattice-step", "0.01"},
       "--lattice-step 0.01: only with --lattice-steps or --lattice-steps-per-iteration above 0 (this run: "
       "--lattice-steps 0, --lattice-steps-per-iteration 0)"},
      {wang, {"--seam-steps", "0", "--seam-spacing", "0.7"},
       "--seam-spacing 0.7: only with --seam-steps above 0 (this run: --seam-steps 0)"},
      {wang, {"--levels", "2", "--level-seam-spacing", "0.7"},
       "--level-seam-spacing 0.7: only with --seam-steps above 0, --levels 2 or more and --rank-order farthest or "
       "voids, whose later levels are relaxed, not filled (this run: --seam-steps 20, --levels 2, --rank-order fill)"},
      {wang, {"--rank-order", "voids", "--level-seam-spacing", "0.7"},
       "--level-seam-spacing 0.7: only with --seam-steps above 0, --levels 2 or more and --rank-order farthest or "
       "voids, whose later levels are relaxed, not filled (this run: --seam-steps 20, --levels 1, --rank-order voids)"},
      {wang, {"--filled-lattice-steps", "9"},
       "--filled-lattice-steps 9: only with --rank-order fill and --levels 2 or more (this run: --rank-order fill, "
       "--levels 1)"},
      {wang, {"--levels", "2", "--rank-order", "voids", "--filled-lattice-steps", "9"},
       "--filled-lattice-steps 9: only with --rank-order fill and --levels 2 or more (this run: --rank-order voids, "
       "--levels 2)"},
      {wang, {"--levels", "2", "--filled-lattice-steps", "0", "--filled-lattice-up-to", "64"},
       "--filled-lattice-up-to 64: only with --rank-order fill, --levels 2 or more and --filled-lattice-steps above 0 "
       "(this run: --rank-order fill, --levels 2, --filled-lattice-steps 0)"},
      {wang, {"--filled-lattice-spacing", "0.5"},
       "--filled-lattice-spacing 0.5: only with --rank-order fill, --levels 2 or more and --filled-lattice-steps "
       "above 0 (this run: --rank-order fill, --levels 1, --filled-lattice-steps 150)"},
      {stipple, {"--png-width", "64"}, "--png-width 64: only with --png, the render it sizes"},
      {stipple, {"--size", "10cm"}, "--size 10cm: only with --svg, the drawing it shapes"},
      {stipple, {"--png", dir.file("s.png"), "--dot-shape", "stroke"}, "--dot-shape stroke: only with --svg, the drawing it shapes"},
      {stipple, {"--plot-order"}, "--plot-order: only with --svg, the drawing it shapes"},
      {stipple, {"--dot-radius", "0.01"}, "--dot-radius 0.01: only with --svg or --png, whose dots it sizes"},
      {stipple, {"--dots-follow-density"}, "--dots-follow-density: only with --svg or --png, whose dots it sizes"},
      {tile, {"-o", points, "--image-size", "64"},
       "--image-size 64: only with a render output (.png .tif .tiff .jpg .jpeg .exr .bmp)"},
      {tile, {"-o", dir.file("t.svg"), "--image-size", "64"},
       "--image-size 64: only with a render output (.png .tif .tiff .jpg .jpeg .exr .bmp)"},
      {tile, {"-o", points, "--dot-radius", "0.1"},
       "--dot-radius 0.1: only with a drawing or render output (.svg .pdf .png .tif .tiff .jpg .jpeg .exr .bmp)"},
      {tile, {"-o", "-", "--dots-follow-density"},
       "--dots-follow-density: only with a drawing or render output (.svg .pdf .png .tif .tiff .jpg .jpeg .exr .bmp)"},
      {tile, {"-o", dir.file("t.png"), "--columns", "x,y,rank"},
       "--columns x,y,rank: only with a point-file output (.txt .dat .pts .csv .bin, no extension, or -)"},
      {tile, {"-o", dir.file("t.svg"), "--normalize"},
       "--normalize: only with a point-file output (.txt .dat .pts .csv .bin, no extension, or -)"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = c.base;
    args.insert(args.end(), c.more.begin(), c.more.end());
    const auto r = run_bluetile(args);
    EXPECT_EQ(r.exit_code, 1) << c.message;
    EXPECT_EQ(r.err, "bluetile: " + c.message + "\n");
    EXPECT_EQ(r.out, "");
  }
  EXPECT_EQ(dir.list(), std::vector<std::string>{"map.png"});

  // Where the run has the part, each is taken.
  const std::vector<std::vector<std::string>> taken = {
      {"--levels", "2", "--ratio", "3", "--filled-lattice-steps", "2", "--filled-lattice-spacing", "0.5",
       "--filled-lattice-up-to", "64", "--lattice-step", "0.01", "--seam-spacing", "0.7"},
      {"--levels", "2", "--rank-order", "voids", "--void-sigma", "0.7", "--level-seam-spacing", "0.7"},
      {"--levels", "2", "--rank-order", "farthest", "--level-seam-spacing", "0.7", "--strategy", "instances",
       "--period", "4"},
      {"--set", "corner81", "--period", "4"},  // auto is instances for corner81
  };
  for (const auto& more : taken) {
    std::vector<std::string> args = wang;
    args.insert(args.end(), more.begin(), more.end());
    const auto r = run_bluetile(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
  }
  auto r = run_bluetile({"stipple", "--image", map, "-n", "20", "-k", "1", "--svg", dir.file("s.svg"), "--size", "5cm",
                         "--dot-shape", "stroke", "--plot-order", "--dot-radius", "0.01", "--dots-follow-density"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run_bluetile({"stipple", "--image", map, "-n", "20", "-k", "1", "--png", dir.file("s.png"), "--png-width", "32",
                    "--dot-radius", "0.01"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run_bluetile({"tile", "--region", "0", "0", "1", "1", "--density", "50", "-o", dir.file("t.bin"), "-o",
                    dir.file("t.png"), "--columns", "x,y,rank", "--normalize", "--image-size", "32", "--dot-radius",
                    "0.05", "--dots-follow-density"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(Cli, WangMadeByLinesRunAsWritten) {
  // The tile set's second line names the options that shaped it, each where the run used it, so
  // that it is accepted as written and makes the same set (it named --level-seam-spacing with
  // the fill order, which fills the later levels and takes no seam steps there).
  TempDir dir;
  const std::vector<std::vector<std::string>> runs = {
      {"--levels", "3"},
      {"--levels", "2", "--rank-order", "voids", "--strategy", "instances", "--period", "4", "--margin", "0.05"},
      {"--levels", "2", "--rank-order", "farthest", "--seam-steps", "0", "--lattice-steps", "0",
       "--lattice-steps-per-iteration", "0"},
      {"--levels", "3", "--filled-lattice-steps", "0"},
  };
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const std::string first = dir.file("first" + std::to_string(k) + ".tiles");
    std::vector<std::string> args = {"wang", "-n", "8", "-k", "2", "--warm", "1", "-o", first};
    args.insert(args.end(), runs[k].begin(), runs[k].end());
    auto r = run_bluetile(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string text = read_text(first);
    const std::string prefix = "# bluetile tiles 1\n# made by: bluetile ";
    ASSERT_EQ(text.rfind(prefix, 0), 0u) << text.substr(0, 200);
    const std::string line = text.substr(prefix.size(), text.find('\n', prefix.size()) - prefix.size());
    std::vector<std::string> again;
    std::istringstream words(line);
    for (std::string word; words >> word;) again.push_back(word);
    const std::string second = dir.file("second" + std::to_string(k) + ".tiles");
    again.insert(again.end(), {"-o", second});
    r = run_bluetile(again);
    ASSERT_EQ(r.exit_code, 0) << line << ": " << r.err;
    EXPECT_EQ(read_text(second), text) << line;
  }
}

TEST(Cli, BoundedSetsAreNotWrappedIntoTheSquare) {
  // relax --bounded (or a file declaring '# domain bounded') moved a point at x = 1.5 to 0.5 and
  // relaxed it there; analyze --bounded --wrap did the same before measuring in the square.
  TempDir dir;
  const std::string plain = dir.write("plain.txt", "0.5 0.5\n1.5 0.25\n0.2 0.8\n");
  const std::string declared = dir.write("declared.txt", "# domain bounded\n0.5 0.5\n1.5 0.25\n0.2 0.8\n");
  const std::string out = dir.file("o.txt");
  const std::string square = " is outside [0, 1) (the set is declared '# domain bounded': its points lie in the square, "
                             "and are not wrapped onto a torus)\n";
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"relax", "-i", plain, "--bounded", "-k", "1", "-o", out},
       plain + ":2: x = 1.5 is outside [0, 1) (--bounded: the points lie in the unit square, and are not wrapped onto a "
               "torus)\n"},
      {{"relax", "-i", declared, "-k", "1", "-o", out}, declared + ":3: x = 1.5" + square},
      {{"centroids", "-i", declared, "--engine", "exact", "-o", out}, declared + ":3: x = 1.5" + square},
      {{"analyze", "-i", declared, "-o", dir.file("a")}, declared + ":3: x = 1.5" + square},
      {{"analyze", "-i", declared, "--wrap", "-o", dir.file("a")}, declared + ":3: x = 1.5" + square},
      {{"analyze", "-i", plain, "--bounded", "-o", dir.file("a")},
       plain + ":2: x = 1.5 is outside [0, 1) (--domain X0 Y0 X1 Y1 rescales points made in another rectangle)\n"},
      {{"analyze", "-i", plain, "--bounded", "--wrap", "-o", dir.file("a")},
       "--wrap wraps points onto the torus, and --bounded measures them in the square: give one\n"},
  };
  for (const Case& c : cases) {
    const auto r = run_bluetile(c.args);
    EXPECT_EQ(r.exit_code, 1) << c.message;
    EXPECT_EQ(r.err, "bluetile: " + c.message);
  }
  EXPECT_EQ(dir.list(), (std::vector<std::string>{"declared.txt", "plain.txt"}));
  // On the torus a point outside is still wrapped: relax as before, analyze with --wrap.
  auto r = run_bluetile({"relax", "-i", plain, "-k", "1", "--engine", "exact", "-o", out});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run_bluetile({"analyze", "-i", plain, "--wrap", "--no-psa-measures", "--no-discrepancy", "-o", dir.file("a")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(Cli, BoundedSetsSayTheirDomainAndStayBounded) {
  // relax --bounded and stipple wrote no line that analyze reads ("# domain bounded"), so their
  // sets were analysed, relaxed and measured on the torus unless told again.
  TempDir dir;
  auto r = run_bluetile({"relax", "-n", "50", "-k", "3", "--bounded", "-o", dir.file("b.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string made = read_text(dir.file("b.txt"));
  EXPECT_NE(made.find("\n# domain bounded\n"), std::string::npos) << made.substr(0, 200);
  EXPECT_EQ(read_point_file(dir.file("b.txt")).declared_boundary, Boundary::bounded);
  // Relaxed again: bounded (and on the exact engine) as with --bounded.
  r = run_bluetile({"relax", "-i", dir.file("b.txt"), "-k", "2", "-o", dir.file("again.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_bluetile({"relax", "-i", dir.file("b.txt"), "-k", "2", "--bounded", "--engine", "exact", "-o", dir.file("told.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_point_file(dir.file("again.txt")).points, read_point_file(dir.file("told.txt")).points);
  // Its cells end at the square's border: the areas sum to 1 with no wrap-around.
  r = run_bluetile({"centroids", "-i", dir.file("b.txt"), "--engine", "exact", "-o", dir.file("c.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_text(dir.file("c.txt")).find("bounded"), std::string::npos);
  const Scene scene = [&] {
    Scene s = make_scene(read_point_file(dir.file("b.txt")).points);
    s.boundary = Boundary::bounded;
    return s;
  }();
  std::ifstream table(dir.file("c.txt"));
  std::string line;
  std::getline(table, line);  // the header
  const SceneCells cells = ExactEngine().compute(scene);
  for (const Cell& cell : cells.cells) {
    double cx = 0.0, cy = 0.0, area = 0.0;
    table >> cx >> cy >> area;
    EXPECT_EQ(cx, cell.centroid.x);
    EXPECT_EQ(cy, cell.centroid.y);
    EXPECT_EQ(area, cell.area);
  }
  // stipple's output declares it too, and analyze then measures Euclidean distances.
  write_image_file(dir.file("map.png"), 4, 4, 1, std::vector<float>(16, 0.5f), SampleFormat::uint8);
  r = run_bluetile({"stipple", "--image", dir.file("map.png"), "-n", "40", "-k", "2", "-o", dir.file("s.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_point_file(dir.file("s.txt")).declared_boundary, Boundary::bounded);
  r = run_bluetile({"analyze", "-i", dir.file("s.txt"), "-o", dir.file("an"), "--no-psa-measures"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_text(dir.file("an/report.txt")).find("bounded (Euclidean distances in the unit square)"),
            std::string::npos);
  // progressive builds on the torus: a bounded base is refused, not made periodic.
  r = run_bluetile({"progressive", "-i", dir.file("b.txt"), "--add", "10", "-o", dir.file("p.txt")});
  EXPECT_EQ(r.err, "bluetile: " + dir.file("b.txt") +
                       ": declares '# domain bounded'; progressive builds its levels on the torus\n");
  EXPECT_FALSE(std::filesystem::exists(dir.file("p.txt")));
}

TEST(Cli, IdImagesTakeTheSetIndexAsTheOutputDoes) {
  // --id-image 'id-{}.png' with --sets 3 wrote one file literally named "id-{}.png".
  TempDir dir;
  auto r = run_bluetile({"relax", "-n", "64", "-k", "1", "--sets", "3", "--engine", "exact", "--resolution", "64",
                         "--id-image", dir.file("id-{}.png"), "-o", dir.file("p.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(dir.list().size(), 4u);
  for (const char* name : {"id-0.png", "id-1.png", "id-2.png"})
    EXPECT_TRUE(std::filesystem::exists(dir.file(name))) << name;
  EXPECT_NE(read_text(dir.file("id-0.png")), read_text(dir.file("id-2.png")));  // each set's own cells
}

}  // namespace
}  // namespace bluetile
