// bluetile stipple: a stipple drawing of an image by weighted Lloyd relaxation (Secord 2002,
// "Weighted Voronoi Stippling"; Deussen, Hiller, van Overveld, Strothotte 2000, "Floating
// Points", which the paper cites as an application). Dots start where the image is dark, drawn in
// proportion to its density, and move to the centres of mass of their cells weighted by that
// density squared, under which a converged set keeps that density (relax/lloyd.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/density_options.h"
#include "cli/engine_options.h"
#include "cli/file_options.h"
#include "cli/numeric_options.h"
#include "cli/option_rules.h"
#include "cli/output_names.h"
#include "cli/point_output.h"
#include "cli/relax_log.h"
#include "cli/stipple_drawing.h"
#include "bluetile/core/error.h"
#include "bluetile/core/memory_budget.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/text.h"
#include "bluetile/io/image.h"
#include "bluetile/io/image_file.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/relax/stipple.h"

namespace bluetile::cli {
namespace {

struct StippleOptions {
  std::string image;
  long long count = 0;
  int iterations = kDefaultStippleIterations;
  std::uint64_t seed = 1;
  double tolerance = 0.0;
  bool periodic = false;
  PointOutputOptions points;
  std::string svg;
  std::string png;
  int png_width = 1024;
  double dot_radius = 0.0;
  std::string log;
  bool verbose = false;
  DensityMapOptions transfer;
  double weight_exponent = kDefaultWeightExponent;
  EngineOptions engine;
  StippleDrawingOptions drawing;
};

// The render's height in pixels, in double: a tall image's does not fit an int.
double render_height(const Domain& domain, int width) {
  const double scale = width / domain.size.x;
  return std::max(1.0, std::round(domain.size.y * scale));
}

// Refuses, before the relaxation, a render taller than an image may be or larger than the memory.
void check_render(const OutputFile& out, const DensityGrid& map, const Domain& domain, int width) {
  const double height = render_height(domain, width);
  if (!(height <= kMaxCanvasSide)) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "--png-width %d: a render of the %d x %d image would be %.0f pixels tall, more than the limit of "
                  "%d: use a smaller --png-width",
                  width, map.width, map.height, height, kMaxCanvasSide);
    throw Error(text);
  }
  check_memory(width * height * kCanvasBytesPerPixel,
               out.path() + ": a render of " + std::to_string(width) + " x " + std::to_string(static_cast<int>(height)) +
                   " pixels");
}

void write_render(OutputFile& out, const std::vector<Point>& points, const std::vector<double>& radii,
                  const Domain& domain, int width) {
  const double scale = width / domain.size.x;
  const int height = static_cast<int>(render_height(domain, width));
  Canvas canvas(width, height, colours::white);
  for (std::size_t i = 0; i < points.size(); ++i)
    canvas.disc({points[i].x * scale, (domain.size.y - points[i].y) * scale}, radii[i] * scale, colours::black);
  write_image(out, canvas);
}

// What --svg writes (--png: kImageFormats).
constexpr OutputFormat kSvgFormats[] = {OutputFormat::svg};

void run_stipple(const StippleOptions& o, const CLI::App& command) {
  if (o.points.output.empty() && o.svg.empty() && o.png.empty())
    throw Error("stipple writes nothing without --output, --svg or --png: say at least one");
  // Refused at once, as relax does, rather than after the start is drawn.
  check_memory(relax_memory_bytes(static_cast<double>(o.count), o.engine.engine), "--count " + std::to_string(o.count));
  // Every output is declared, and so checked, before any work; they appear together at the end.
  // The image plugin is loaded, and the render's format checked, before any output is staged.
  if (!o.svg.empty()) output_format("--svg", o.svg, kSvgFormats);
  if (!o.png.empty()) output_format("--png", o.png, kImageFormats);
  load_image_plugin();
  if (!o.png.empty()) check_image_output(o.png);
  if (!o.drawing.size.empty()) parse_printed_length(o.drawing.size, "--size");
  OutputSet outputs;
  add_declared_inputs(outputs, command);
  std::unique_ptr<PointOutput> points_file =
      o.points.output.empty() ? nullptr : std::make_unique<PointOutput>(outputs, o.points, 1);
  OutputFile* svg_file = o.svg.empty() ? nullptr : &outputs.add(o.svg, {.allow_stdout = true});
  OutputFile* png_file =
      o.png.empty() ? nullptr : &outputs.add(o.png, {.binary_format = binary_output_format(OutputFormat::image)});
  if (!o.log.empty()) check_text_output_name("--log", o.log, "a CSV log");
  OutputFile* log_file = o.log.empty() ? nullptr : &outputs.add(o.log, {.allow_stdout = true});
  auto map = std::make_shared<DensityGrid>(load_density_map(o.image, density_transfer(o.transfer)));
  // The start and the domain Python's stipple() shares (relax/stipple.h).
  const Domain domain = stipple_domain(*map);
  if (png_file) check_render(*png_file, *map, domain, o.png_width);
  const auto count = static_cast<std::size_t>(o.count);
  StippleStart start;
  start.count = count;
  start.seed = o.seed;
  start.periodic = o.periodic;
  start.weight_exponent = o.weight_exponent;
  Scene scene = stipple_scene(*map, start);

  auto engine = make_engine(o.engine);
  note_faster_engine(*engine, static_cast<double>(count) * o.iterations);
  RelaxLog log("stipple", o.iterations, o.verbose, log_file ? &log_file->open() : nullptr);
  LloydResult result = relax_lloyd(*engine, scene, log.lloyd_options(o.iterations, o.tolerance));
  log.finish(result, o.tolerance, o.iterations);
  note_exact_hand_over(*engine);

  const double radius = o.dot_radius > 0.0 ? o.dot_radius : stipple_dot_radius(*map, domain, count);
  char size[64];
  std::snprintf(size, sizeof size, "%.17g x %.17g", domain.size.x, domain.size.y);
  const std::vector<std::string> header = {
      "bluetile stipple: " + counted(static_cast<long long>(count), "point") + ", " +
          counted(result.iterations, "iteration") + ", engine " + engine_text(*engine, o.engine) + ", seed " + std::to_string(o.seed) + ", image " +
          o.image + " (" + transfer_text(o.transfer) + ")",
      // The line analyze reads (point_file.h: "domain bounded" or "domain periodic"), then the region.
      o.periodic ? "domain periodic" : "domain bounded",
      std::string("region ") + size + " (y up: image row 0 at the top)"};
  if (points_file) points_file->write(std::vector<PointSet>{PointSet{scene.sites, {}}}, header);
  const std::vector<double> radii = dot_radii(scene.sites, *map, domain, radius, o.drawing.follow_density);
  if (svg_file) {
    const PenTravel travel = write_stipple_svg(*svg_file, scene.sites, radii, domain, o.drawing);
    if (o.drawing.plot_order)
      std::fprintf(stderr, "bluetile stipple: pen-up travel %.6g %s in plot order (greedy nearest neighbour: %.6g %s)\n",
                   travel.travel, travel.unit.c_str(), travel.greedy, travel.unit.c_str());
  }
  if (png_file) write_render(*png_file, scene.sites, radii, domain, o.png_width);
  if (log_file) log_file->close();
  outputs.publish();
}

}  // namespace

void add_stipple_command(CLI::App& app) {
  auto o = std::make_shared<StippleOptions>();
  o->engine.engine = "exact";  // the raster engine weights cells too, 5x slower here (docs/BENCHMARKS.md)
  CLI::App* cmd = app.add_subcommand(
      "stipple", "Stipple an image: dots whose density follows its darkness, relaxed by weighted Lloyd (Secord 2002)");
  add_input_option(cmd, "--image", o->image, InputKind::image,
                   "Image to stipple (PNG, TIFF, EXR, ...: anything OpenImageIO reads; '-': standard input)")
      ->required();
  add_integer_option(cmd, "-n,--count", o->count, 1LL, kMaxCount, "Number of dots")->required();
  add_integer_option(cmd, "-k,--iterations", o->iterations, 0, kMaxIterations, "Lloyd iterations");
  add_seed_option(cmd, o->seed, "Seed of the density-proportional start");
  add_real_option(cmd, "--tolerance", o->tolerance, {}, "Stop early once no dot moves more than this (domain units)");
  cmd->add_flag("--periodic", o->periodic, "Cells wrap around the picture's edges (default: they end at the border)");
  add_point_output_options(cmd, o->points,
                           "Output points (optional when --svg or --png is given): the picture's longer side spans "
                           "[0, 1), y up (image row 0 is the top)",
                           false, /*several_sets=*/false);
  add_output_option(cmd, "--svg", o->svg, {.formats = kSvgFormats, .standard_output = true},
                    "Write the drawing as SVG (.svg; one black disc per dot)");
  add_output_option(cmd, "--png", o->png, {.formats = kImageFormats},
                    "Render the drawing as an image (.png .tif .tiff .jpg .jpeg .exr .bmp)");
  add_integer_option(cmd, "--png-width", o->png_width, 16, 32768, "Width of the --png render in pixels");
  // At most the domain's side: a huge one hung the PDF writer or came out as r="0" in SVG.
  add_real_option(cmd, "--dot-radius", o->dot_radius, {0.0, 1.0, true, false},
                  "Dot radius in domain units (default: dots just touch where the image is darkest)")
      ->default_str("");
  add_output_option(cmd, "--log", o->log, kCsvLog, "Write a CSV log of energy and displacement per iteration");
  cmd->add_flag("-v,--verbose", o->verbose, "Print energy and displacement of every iteration on stderr");
  o->transfer.invert = true;  // dark means dense by default, as ink on paper
  add_density_transfer_options(cmd, o->transfer);
  add_weight_exponent_option(cmd, o->weight_exponent);
  add_engine_options(cmd, o->engine);
  add_stipple_drawing_options(cmd, o->drawing);
  cmd->callback([o, cmd] {
    refuse_unused_raster_options(*cmd, o->engine, cmd->count("--engine") ? "" : ", the default for stipple");
    // The drawing's settings need the drawing they shape: the render's width, the SVG's print size,
    // dot shape and pen order, and the dots' size in either.
    refuse_unless_used(*cmd, "--png-width", !o->png.empty(), "--png, the render it sizes");
    for (const char* name : {"--size", "--dot-shape", "--plot-order"})
      refuse_unless_used(*cmd, name, !o->svg.empty(), "--svg, the drawing it shapes");
    for (const char* name : {"--dot-radius", "--dots-follow-density"})
      refuse_unless_used(*cmd, name, !o->svg.empty() || !o->png.empty(), "--svg or --png, whose dots it sizes");
    run_stipple(*o, *cmd);
  });
}

}  // namespace bluetile::cli
