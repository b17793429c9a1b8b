// The output-name rule (src/cli/output_names.h) through the tool: for every output option of every
// command, each refused extension fails before any work with one line naming the option, the file
// and the accepted extensions, and each accepted one writes the format it names (its first bytes).
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <memory>
#include <set>
#include <sstream>

#include "bluetile/io/image_file.h"
#include "cli/app.h"
#include "cli/file_options.h"
#include "cli/numeric_options.h"
#include "robustness_support.h"
#include "test_support.h"

namespace bluetile::robustness {
namespace {

using test::read_text;
using test::TempDir;

// An accepted extension and how a file of its format begins.
struct Accepted {
  std::string extension;
  std::string first_bytes;
};

// One output option: the command (other outputs it needs come first), the option, what it takes
// and what it refuses. `list` is the accepted list as the message gives it.
struct OutputCase {
  std::vector<std::string> command;
  std::string option;
  std::vector<Accepted> accepted;
  std::vector<std::string> refused;
  std::string list;
  // The message's last words, after an extension no format owns (.tsv): --format is refused for
  // one that another format owns (.png).
  std::string alternative;
};

const std::string kPointList =
    ".txt .dat .pts (text points), .npy (NumPy), .bpt (point table), .h .hpp (C header), .csv (CSV)";
const std::string kNpy = std::string("\x93NUMPY", 6);
const std::string kBpt = std::string("\x89" "BTP\r\n\x1a\n", 8);
const std::string kPng = std::string("\x89PNG", 4);

std::vector<Accepted> point_formats(const std::string& text_start, const std::string& header_start) {
  return {{".txt", text_start}, {".pts", text_start}, {".npy", kNpy}, {".bpt", kBpt}, {".h", header_start},
          {".NPY", kNpy}, {".csv", text_start}};
}

// Every output option whose format is picked by its extension. Inputs are made in `dir`.
std::vector<OutputCase> output_cases(const TempDir& dir) {
  const std::string points = dir.write("in.txt", "0.1 0.2\n0.6 0.3\n0.4 0.8\n0.9 0.7\n");
  const std::string map = dir.file("map.png");
  write_image_file(map, 4, 4, 1, std::vector<std::uint8_t>{0, 50, 100, 150, 200, 250, 0, 50, 100, 150, 200, 250,
                                                            0, 50, 100, 150});
  const std::vector<std::string> refused_points = {".svg", ".png", ".pdf", ".bin", ".tiles", ".tsv"};
  const std::vector<std::string> stipple = {"stipple", "--image", map, "-n", "12", "-k", "1"};
  auto with = [](std::vector<std::string> base, std::vector<std::string> more) {
    base.insert(base.end(), more.begin(), more.end());
    return base;
  };
  return {
      {{"relax", "-n", "8", "-k", "1", "--engine", "exact"}, "--output",
       point_formats("# bluetile relax", "// bluetile relax"), refused_points, kPointList, "; or say --format"},
      {{"dart", "-n", "8"}, "--output", point_formats("# bluetile dart", "// bluetile dart"), refused_points,
       kPointList, "; or say --format"},
      {{"progressive", "-n", "4", "-l", "2", "-k", "1", "--engine", "exact"}, "--output",
       point_formats("# bluetile progressive", "// bluetile progressive"), refused_points, kPointList,
       "; or say --format"},
      // cx cy area is no point table: no .bpt, whose third column is the level.
      {{"centroids", "-i", points, "--engine", "exact"}, "--output",
       {{".txt", "# bluetile centroids"}, {".npy", kNpy}, {".h", "//"}, {".NPY", kNpy}, {".csv", "# bluetile centroids"}},
       with(refused_points, {".bpt"}), ".txt .dat .pts (text points), .npy (NumPy), .h .hpp (C header), .csv (CSV)",
       "; or say --format"},
      {stipple, "--output", point_formats("# bluetile stipple", "// bluetile stipple"), refused_points, kPointList,
       "; or say --format"},
      {stipple, "--svg", {{".svg", "<?xml"}, {".SVG", "<?xml"}}, {".png", ".pdf", ".txt", ".npy", ".h"}, ".svg (SVG)"},
      {stipple,
       "--png",
       {{".png", kPng}, {".tif", "II*"}},
       {".svg", ".pdf", ".txt", ".npy", ".gif"},
       ".png .tif .tiff .jpg .jpeg .exr .bmp (image)"},
      {{"relax", "-n", "8", "-k", "1", "--engine", "raster", "--resolution", "32", "-o", dir.file("ids.txt")},
       "--id-image",
       {{".png", kPng}},
       {".svg", ".txt", ".npy"},
       ".png .tif .tiff .jpg .jpeg .exr .bmp (image)"},
      {{"tile", "--region", "0", "0", "2", "1", "--density", "20"},
       "--output",
       {{".txt", "# bluetile tile"}, {".dat", "# bluetile tile"}, {".csv", "# bluetile tile"}, {".bin", ""},
        {".svg", "<?xml"}, {".png", kPng}, {".pdf", "%PDF-"}},
       {".npy", ".bpt", ".h", ".tiles", ".gif"},
       ".txt .dat .pts (text points), .csv (CSV), .bin (raw float64 columns), .svg (SVG), .png .tif .tiff .jpg .jpeg "
       ".exr .bmp (image), .pdf (PDF)"},
      {{"wang", "-n", "4", "-k", "1", "--warm", "0"},
       "--output",
       {{".tiles", "# bluetile tiles 1\n"}, {".txt", "# bluetile tiles 1\n"}},
       {".h", ".npy", ".svg", ".png", ".bpt"},
       ".tiles .txt (tile set)"},
      {with({"analyze", "-i", points, "--no-psa-measures", "--no-discrepancy", "--image-size", "64", "-o"},
            {dir.file("analysis")}),
       "--summary",
       {{".svg", "<?xml"}, {".pdf", "%PDF-"}},
       {".png", ".txt", ".npy"},
       ".pdf (PDF), .svg (SVG)"},
  };
}

// Every output option whose format its extension picks (as the command declares it:
// cli/file_options.h) is tested above; folders and outputs of one format (CSV logs, psa's text)
// are not chosen by name.
TEST(OutputNames, AnAppTakesItsOptionRecordsWithIt) {
  // The records are keyed by option: a destroyed app's stayed, and matched another app's options
  // at reused addresses (the next test failed or passed by the order the tests ran in). The
  // pointers below are only compared as keys once their app is gone.
  const CLI::Option* output = nullptr;
  const CLI::Option* count = nullptr;
  {
    std::unique_ptr<CLI::App> app = cli::make_app();
    CLI::App* relax = app->get_subcommand("relax");
    output = relax->get_option("--output");
    count = relax->get_option("--count");
    ASSERT_NE(cli::find_file_option(output), nullptr);
    ASSERT_NE(cli::find_numeric_option(count), nullptr);
  }
  EXPECT_EQ(cli::find_file_option(output), nullptr);
  EXPECT_EQ(cli::find_numeric_option(count), nullptr);
}

TEST(OutputNames, EveryOutputOptionOfEveryCommandIsCovered) {
  TempDir dir;
  std::set<std::string> covered;
  for (const OutputCase& c : output_cases(dir)) covered.insert(c.command[0] + " " + c.option);
  std::unique_ptr<CLI::App> app = cli::make_app();
  std::size_t by_extension = 0;
  for (const CLI::App* command : app->get_subcommands([](CLI::App*) { return true; })) {
    for (const CLI::Option* option : command->get_options()) {
      const cli::FileOption* file = cli::find_file_option(option);
      if (file == nullptr || file->role != cli::FileOption::Role::output || file->output.formats.empty()) continue;
      ++by_extension;
      const std::string name = command->get_name() + " " + option->get_name();
      EXPECT_TRUE(covered.count(name)) << name << ": an output nobody tests here";
    }
  }
  EXPECT_EQ(by_extension, covered.size());
}

TEST(OutputNames, RefusedExtensionsFailBeforeAnyWorkNamingTheOptionFileAndList) {
  TempDir dir;
  const std::vector<OutputCase> cases = output_cases(dir);
  const std::vector<std::string> inputs = dir.list();
  for (const OutputCase& c : cases) {
    for (const std::string& extension : c.refused) {
      const std::string path = dir.file("out" + extension);
      std::vector<std::string> args = c.command;
      args.insert(args.end(), {c.option, path});
      Outcome r = run(args);
      const std::string name = c.command[0] + " " + c.option + " " + extension;
      EXPECT_EQ(r.exit_code, 1) << name;
      EXPECT_EQ(r.err, "bluetile: " + c.option + " '" + path + "': this output writes " + c.list + ", not '" +
                           extension + "'" + (extension == ".tsv" ? c.alternative : "") + "\n")
          << name;
      EXPECT_EQ(dir.list(), inputs) << name << ": something was written";
    }
  }
}

TEST(OutputNames, AcceptedExtensionsWriteTheFormatTheyName) {
  TempDir dir;
  for (const OutputCase& c : output_cases(dir)) {
    for (const Accepted& a : c.accepted) {
      const std::string path = dir.file("ok-" + c.command[0] + c.option + a.extension);
      std::vector<std::string> args = c.command;
      args.insert(args.end(), {c.option, path});
      Outcome r = run(args);
      const std::string name = c.command[0] + " " + c.option + " " + a.extension;
      ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
      const std::string bytes = read_text(path);
      EXPECT_EQ(bytes.substr(0, a.first_bytes.size()), a.first_bytes) << name;
      if (a.extension == ".bin") {
        // tile's raw columns: x y as float64, 16 bytes a point, no header.
        EXPECT_GT(bytes.size(), 0u);
        EXPECT_EQ(bytes.size() % 16, 0u) << name;
      }
    }
  }
}

// A CSV log takes any name but one that says it is another format the tool writes.
TEST(OutputNames, LogsRefuseAnotherFormatsExtension) {
  TempDir dir;
  for (const std::string command : {"relax", "stipple"}) {
    std::vector<std::string> base = {command, "-n", "10", "-k", "1", "--engine", "exact", "-o", dir.file("p.txt")};
    if (command == "stipple") {
      const std::string map = dir.file("map.png");
      write_image_file(map, 2, 2, 1, std::vector<std::uint8_t>{0, 80, 160, 240});
      base = {command, "--image", map, "-n", "10", "-k", "1", "-o", dir.file("p.txt")};
    }
    const std::vector<std::string> before = dir.list();
    for (const auto& [extension, label] : std::vector<std::pair<std::string, std::string>>{
             {".npy", "NumPy"}, {".png", "image"}, {".SVG", "SVG"}, {".tiles", "tile set"}}) {
      std::vector<std::string> args = base;
      const std::string log = dir.file("log" + extension);
      args.insert(args.end(), {"--log", log});
      Outcome r = run(args);
      EXPECT_EQ(r.exit_code, 1) << command << " " << extension;
      std::string lower = extension;
      for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      EXPECT_EQ(r.err, "bluetile: --log '" + log + "': this output writes a CSV log, not '" + lower + "' (" + label + ")\n")
          << command;
      EXPECT_EQ(dir.list(), before) << command << " " << extension << ": something was written";
    }
    for (const std::string name : {"log.csv", "log.txt", "log.log", "log"}) {
      std::vector<std::string> args = base;
      args.insert(args.end(), {"--log", dir.file(name)});
      Outcome r = run(args);
      EXPECT_EQ(r.exit_code, 0) << command << " " << name << ": " << r.err;
      EXPECT_EQ(read_text(dir.file(name)).rfind("iteration,", 0), 0u) << command << " " << name;
    }
  }
  // psa's point text the same way.
  const std::string points = dir.write("in.txt", "0.1 0.2\n0.6 0.3\n0.4 0.8\n0.9 0.7\n");
  const std::string psa = dir.file("psa.svg");
  Outcome r = run({"analyze", "-i", points, "-o", dir.file("a"), "--psa-points", psa});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "bluetile: --psa-points '" + psa + "': this output writes psa's point text, not '.svg' (SVG)\n");
  EXPECT_FALSE(std::filesystem::exists(dir.file("a")));
}

TEST(OutputNames, StandardOutputAndNamesWithoutExtensionTakeTheFirstFormat) {
  TempDir dir;
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"tile", "--region", "0", "0", "1", "1", "--density", "20", "-o", "-"}, "# bluetile tile"},
      {{"wang", "-n", "4", "-k", "1", "--warm", "0", "-o", "-"}, "# bluetile tiles 1\n"},
      {{"dart", "-n", "8", "-o", "-"}, "# bluetile dart"},
  };
  for (const auto& [args, start] : cases) {
    Outcome r = run(args);
    EXPECT_EQ(r.exit_code, 0) << args[0] << ": " << r.err;
    EXPECT_EQ(r.out.substr(0, start.size()), start) << args[0];
  }
  Outcome r = run({"tile", "--region", "0", "0", "1", "1", "--density", "20", "-o", dir.file("points")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(dir.file("points")).rfind("# bluetile tile", 0), 0u);
}

TEST(OutputNames, StippleNeedsNoPointFileForADrawingButSomeOutput) {
  TempDir dir;
  const std::string map = dir.file("map.png");
  write_image_file(map, 4, 4, 1, std::vector<std::uint8_t>(16, 100));
  Outcome r = run({"stipple", "--image", map, "-n", "12", "-k", "1", "--svg", dir.file("only.svg")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(dir.list(), (std::vector<std::string>{"map.png", "only.svg"}));
  r = run({"stipple", "--image", map, "-n", "12", "-k", "1"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "bluetile: stipple writes nothing without --output, --svg or --png: say at least one\n");
  // Every point format, the same points: the text and the table agree to the last bit.
  r = run({"stipple", "--image", map, "-n", "12", "-k", "1", "-o", dir.file("s.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run({"stipple", "--image", map, "-n", "12", "-k", "1", "-o", dir.file("s.bpt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string table = read_text(dir.file("s.bpt"));
  ASSERT_EQ(table.size(), 40u + 12u * 2u * 8u);
  std::istringstream text(read_text(dir.file("s.txt")));
  std::string line;
  std::size_t value = 0;
  while (std::getline(text, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream xy(line);
    double x = 0.0, y = 0.0;
    xy >> x >> y;
    for (double v : {x, y}) {
      double stored = 0.0;
      std::memcpy(&stored, table.data() + 40 + 8 * value++, 8);
      EXPECT_EQ(stored, v) << "value " << value - 1;
    }
  }
  EXPECT_EQ(value, 24u);
}

}  // namespace
}  // namespace bluetile::robustness
