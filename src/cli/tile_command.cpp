// bluetile tile: the points of any window of an aperiodic tiling of the plane by a tile set
// (Hiller, Deussen, Keller 2001, section 3), at a uniform density or following a density map
// (thinning by rank, tiling/density_thinning.h). Point files and SVG drawings are streamed; a PDF
// of dots and a render are made whole, then written.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>

#include "cli/commands.h"
#include "cli/density_options.h"
#include "cli/file_options.h"
#include "cli/numeric_options.h"
#include "cli/option_rules.h"
#include "cli/output_names.h"
#include "cli/progress.h"
#include "bluetile/core/error.h"
#include "bluetile/core/memory_budget.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/text.h"
#include "bluetile/io/density_map.h"
#include "bluetile/io/image.h"
#include "bluetile/io/image_file.h"
#include "bluetile/io/pdf.h"
#include "bluetile/tiling/default_tile_set.h"
#include "bluetile/tiling/tile_set_file.h"
#include "bluetile/drawing/tiled_drawing.h"
#include "bluetile/tiling/tiled_output.h"
#include "bluetile/tiling/tiler.h"
#include "bluetile/tiling/tiling_plan.h"

namespace bluetile::cli {
namespace {

// Peak memory per dot of a PDF drawing, which is built whole before cairo draws it (an SVG is
// streamed): the document, then cairo's page. Measured (peak RSS of `tile -o x.pdf` at 3 and 6 x
// 10^5 dots: 980 bytes a dot between them) and rounded up.
constexpr double kPdfBytesPerDot = 1100.0;

struct TileOptions {
  std::string tiles;
  std::vector<double> region;
  double tile_size = 0.0;
  double density = 0.0;
  double max_density = 0.0;
  double count = 0.0;
  std::uint64_t seed = 1;
  std::vector<std::string> outputs;
  std::string columns = "x,y";
  bool normalize = false;
  std::string density_map;
  std::string fit = "contain";
  DensityMapOptions transfer;
  double dot_radius = 0.0;
  bool dots_follow_density = false;
  int image_size = 1024;
  int threads = 0;
  bool verbose = false;
};

// What -o writes, by the output-name rule (cli/output_names.h): "-" and names without an
// extension are point files.
constexpr OutputFormat kTileFormats[] = {OutputFormat::points_text, OutputFormat::points_csv, OutputFormat::raw_columns,
                                         OutputFormat::svg, OutputFormat::image, OutputFormat::pdf};

OutputFormat output_kind(const std::string& path) { return output_format("--output", path, kTileFormats); }

// The tiling, thinning and window the options describe (tiling/tiling_plan.h), and the set's name.
struct Plan : TilingPlan {
  std::string tiles_name;
};

// The tool's names for a request's fields, in the library's messages.
constexpr TilingNames kOptionNames{"--tile-size", "--density", "--max-density", "--count", "--density-map", " "};

TilingRequest tiling_request(const TileOptions& o) {
  TilingRequest request;
  request.window = {o.region[0], o.region[1], o.region[2], o.region[3]};
  request.tile_size = o.tile_size;
  request.density = o.density;
  request.max_density = o.max_density;
  request.count = o.count;
  request.seed = o.seed;
  request.fit = parse_map_fit(o.fit);
  return request;
}

Plan make_plan(const TileOptions& o) {
  const TilingRequest request = tiling_request(o);
  DensityGrid grid;
  if (!o.density_map.empty()) grid = load_density_map(o.density_map, density_transfer(o.transfer));
  TileSet set = o.tiles.empty() ? default_tile_set() : read_tile_set(o.tiles);
  Plan plan;
  static_cast<TilingPlan&>(plan) =
      plan_tiling(std::move(set), o.density_map.empty() ? nullptr : &grid, request, kOptionNames);
  plan.tiles_name = o.tiles.empty() ? std::string("default (") + kDefaultTileSetName + ")" : o.tiles;
  return plan;
}


// The run's size, known before any point is made (cells x points x thinning): refused past the
// limits the other commands keep, instead of filling a disk or running for hours.
void check_run_size(const Plan& plan, const std::vector<OutputFile*>& files, int width_pixels,
                    double height_pixels) {
  check_tiling_size(plan, "--region", "--tile-size");
  const double points = plan.window.area() * plan.mean_density;
  for (const OutputFile* file : files) {
    const OutputFormat kind = output_kind(file->path());
    if (kind == OutputFormat::pdf)
      check_memory(points * kPdfBytesPerDot, file->path() + ": a PDF of about " + count_text(points) + " dots");
    if (kind == OutputFormat::image)
      check_memory(static_cast<double>(width_pixels) * height_pixels * kCanvasBytesPerPixel,
                   file->path() + ": a render of " + std::to_string(width_pixels) + " x " + count_text(height_pixels) +
                       " pixels");
  }
}

// The height of a render `width_pixels` wide of the region, computed in double (it may not fit
// an int), as render_dots rounds it.
double render_height(const TileOptions& o, int width_pixels) {
  const double width = o.region[2] - o.region[0], height = o.region[3] - o.region[1];
  return std::max(1.0, std::round(height * (width_pixels / width)));
}

// A render's height, refused before any work when it is beyond what an image may be.
void check_render_height(const TileOptions& o, const std::vector<OutputFile*>& files) {
  bool render = false;
  for (const OutputFile* file : files) render = render || output_kind(file->path()) == OutputFormat::image;
  if (!render) return;  // the region was checked first (check_tiling_request)
  const double pixels = render_height(o, o.image_size);
  if (!(pixels <= kMaxCanvasSide))
    throw Error("--image-size " + std::to_string(o.image_size) + ": a render of the region " + exact_text(o.region[0]) +
                " " + exact_text(o.region[1]) + " " + exact_text(o.region[2]) + " " + exact_text(o.region[3]) + " would be " +
                count_text(pixels) + " pixels tall, more than the limit of " + std::to_string(kMaxCanvasSide) +
                ": use a smaller --image-size or a wider region");
}

std::vector<std::string> header_lines(const TileOptions& o, const Plan& plan, const TiledFormat& format) {
  const Window& w = plan.window;
  std::vector<std::string> lines;
  lines.push_back("bluetile tile: tiles " + plan.tiles_name + " (" +
                  std::string(tile_set_kind_name(plan.tiler->tile_set().kind)) + "), seed " + std::to_string(o.seed) +
                  ", tile size " + exact_text(plan.tiler->tile_size()) + ", region " + exact_text(w.x0) + " " + exact_text(w.y0) +
                  " " + exact_text(w.x1) + " " + exact_text(w.y1) + (o.normalize ? " (normalized onto the unit square)" : ""));
  if (!o.density_map.empty())
    lines.push_back("density map " + o.density_map + " (fit " + o.fit + ", " + transfer_text(o.transfer) +
                    "), max density " + exact_text(plan.max_density) + " points per unit area");
  else
    lines.push_back("density " + exact_text(plan.max_density) + " points per unit area");
  lines.push_back("columns " + tiled_column_names(format.columns));
  lines.push_back(tile_grid_comment(*plan.tiler, w, o.normalize));
  return lines;
}

void write_points(OutputFile& file, const Plan& plan, const TiledFormat& format, bool verbose) {
  Progress progress("tile", plan.tiler->cells(plan.window).rows());
  auto on_rows = [&](std::int64_t done, std::int64_t) { progress.update(done); };
  StreamTimes times;
  // Straight into the output: a staged file renamed into place at the end, or the device, FIFO
  // or standard output itself.
  file.write([&](OutputStream& out) {
    times = stream_tiled_points(*plan.tiler, plan.window, plan.thinning.get(), format, out, on_rows);
  });
  progress.finish();
  if (verbose)
    std::fprintf(stderr, "bluetile tile: %s: %zu points, %zu bytes; generate %.3f s, format %.3f s, write %.3f s\n",
                 file.path().c_str(), times.points, times.bytes, times.generate, times.format, times.write);
}

// The settings of one kind of output need an output of that kind: the columns and normalization a
// point file, the dots a drawing or render, --image-size a render.
void refuse_unused_output_options(const CLI::App& command, const std::vector<std::string>& paths) {
  bool point_file = false, drawing = false, render = false;
  for (const std::string& path : paths) {
    const OutputFormat kind = output_kind(path);
    point_file = point_file || kind == OutputFormat::points_text || kind == OutputFormat::points_csv ||
                 kind == OutputFormat::raw_columns;
    drawing = drawing || kind == OutputFormat::svg || kind == OutputFormat::pdf || kind == OutputFormat::image;
    render = render || kind == OutputFormat::image;
  }
  for (const char* name : {"--columns", "--normalize"})
    refuse_unless_used(command, name, point_file, "a point-file output (.txt .dat .pts .csv .bin, no extension, or -)");
  for (const char* name : {"--dot-radius", "--dots-follow-density"})
    refuse_unless_used(command, name, drawing, "a drawing or render output (.svg .pdf .png .tif .tiff .jpg .jpeg .exr .bmp)");
  refuse_unless_used(command, "--image-size", render, "a render output (.png .tif .tiff .jpg .jpeg .exr .bmp)");
}

void run_tile(const TileOptions& o, const CLI::App& command) {
  if (o.threads > 0) set_thread_count(static_cast<std::size_t>(o.threads));
  TiledFormat format;
  try {
    format.columns = parse_tiled_columns(o.columns);
  } catch (const Error& e) {
    // "columns: column 'x' given twice": here the option as given.
    throw Error("--columns '" + o.columns + "'" + std::string(e.what()).substr(std::string_view("columns").size()));
  }
  format.normalize = o.normalize;
  // Every output is declared, and so checked (folders, the same file twice), before any work;
  // all of them are published together at the end.
  // The image plugin is loaded before any output is staged.
  // Every name is checked against the formats tile writes first.
  bool images = !o.density_map.empty();
  for (const std::string& path : o.outputs) {
    const OutputFormat kind = output_kind(path);
    images = images || kind == OutputFormat::image;
    if (kind == OutputFormat::pdf && !pdf_unavailable_reason().empty())
      throw Error(path + ": " + pdf_unavailable_reason());
  }
  if (images) load_image_plugin();
  for (const std::string& path : o.outputs)
    if (output_kind(path) == OutputFormat::image) check_image_output(path);
  OutputSet outputs;
  add_declared_inputs(outputs, command);
  std::vector<OutputFile*> files;
  for (const std::string& path : o.outputs)
    files.push_back(&outputs.add(path, {.allow_stdout = output_kind(path) == OutputFormat::points_text,
                                        .binary_format = binary_output_format(output_kind(path))}));
  // Square to rounding (0.4 - 0.1 and 0.5 - 0.2 differ in the last bit), as fit_map_rectangle
  // takes a map of the region's aspect.
  const double width = o.region[2] - o.region[0], height = o.region[3] - o.region[1];
  if (o.normalize && std::abs(width - height) > 1e-12 * std::max(std::abs(width), std::abs(height)))
    throw Error("--normalize maps a square region onto the unit square; this region is " + shortest_text(width) +
                " x " + shortest_text(height));
  // A dot wider than the region draws nothing useful, and a huge one hung the PDF writer (1e20)
  // or came out as r="0" in SVG (1e100).
  if (o.dot_radius > std::max(width, height))
    throw Error("--dot-radius " + shortest_text(o.dot_radius) + ": expected at most the region's larger side, " +
                shortest_text(std::max(width, height)));
  check_render_height(o, files);
  Plan plan = make_plan(o);
  check_run_size(plan, files, o.image_size, render_height(o, o.image_size));
  format.header = header_lines(o, plan, format);

  DotStyle dots;
  dots.radius = o.dot_radius > 0.0 ? o.dot_radius : default_dot_radius(plan.max_density);
  dots.follow_density = o.dots_follow_density;
  for (OutputFile* file : files) {
    const auto started = std::chrono::steady_clock::now();
    bool drawn = true;  // a drawing or render, whose time -v reports here
    switch (output_kind(file->path())) {
      case OutputFormat::points_text:
      case OutputFormat::points_csv:
      case OutputFormat::raw_columns: {
        TiledFormat f = format;
        const OutputFormat kind = output_kind(file->path());
        f.encoding = kind == OutputFormat::raw_columns ? TiledFormat::Encoding::binary
                     : kind == OutputFormat::points_csv ? TiledFormat::Encoding::csv
                                                        : TiledFormat::Encoding::text;
        write_points(*file, plan, f, o.verbose);
        drawn = false;
        break;
      }
      case OutputFormat::svg:
        file->write([&](OutputStream& out) { write_dots_svg(out, *plan.tiler, plan.window, plan.thinning.get(), dots); });
        break;
      case OutputFormat::pdf:
        write_pdf(dots_drawing(*plan.tiler, plan.window, plan.thinning.get(), dots), *file);
        break;
      case OutputFormat::image:
        write_image(*file, render_dots(*plan.tiler, plan.window, plan.thinning.get(), dots, o.image_size));
        break;
      default:
        throw Error("internal: tile cannot write " + file->path());
    }
    if (o.verbose && drawn)
      std::fprintf(stderr, "bluetile tile: %s: drawn in %.3f s\n", file->path().c_str(),
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  }
  outputs.publish();
}

}  // namespace

void add_tile_command(CLI::App& app) {
  auto o = std::make_shared<TileOptions>();
  CLI::App* cmd = app.add_subcommand(
      "tile", "Points of any window of an aperiodic tiling of the plane, uniform or following a density map");
  add_input_option(cmd, "--tiles", o->tiles, InputKind::tiles,
                   "Tile-set file (bluetile wang --output); default: the set built into the tool");
  cmd->add_option("--region", o->region, "The window X0 Y0 X1 Y1 in plane units ([X0, X1) x [Y0, Y1), y up)")
      ->expected(4)
      ->required()
      ->allow_extra_args(false);
  const RealRange positive{0.0, kInfinity, true, false};
  add_real_option(cmd, "--tile-size", o->tile_size, positive, "Plane units per tile (default 1, or from the density)")
      ->default_str("");
  add_real_option(cmd, "--density", o->density, positive,
                  "Points per unit area of a uniform tiling (with --tile-size: thinned to it by rank)")
      ->default_str("");
  add_input_option(cmd, "--density-map", o->density_map, InputKind::image,
                   "Image whose values set the density (any format OpenImageIO reads; '-': standard input), placed on "
                   "the region by --fit");
  CLI::Option* fit = cmd->add_option("--fit", o->fit,
                  "How --density-map meets a region of another aspect: contain (the whole picture, centred, its "
                  "aspect kept; no points beside it), cover (the region filled, aspect kept, the overflow cut off "
                  "evenly) or stretch")
      ->check(CLI::IsMember({"contain", "cover", "stretch"}))
      ->capture_default_str();
  add_density_transfer_options(cmd, o->transfer);
  add_real_option(cmd, "--max-density", o->max_density, positive,
                  "With --density-map: points per unit area at the densest texel")
      ->default_str("");
  add_real_option(cmd, "--count", o->count, positive,
                  "With --density-map: about this many points in the region (default 30000 when neither this, "
                  "--max-density nor --tile-size is given)")
      ->default_str("");
  add_seed_option(cmd, o->seed, "Seed of the tiling");
  add_output_option(cmd, "-o,--output", o->outputs, {.formats = kTileFormats, .standard_output = true},
                    "Output, by extension: .txt .dat .pts (or none, or - for stdout) a point file, .csv the same "
                    "with a header line, .bin raw float64 columns, .svg or .pdf dots, .png .tif .tiff .jpg .jpeg .exr .bmp a render; repeat for several")
      ->required();
  cmd->add_option("--columns", o->columns, "Point-file columns, from x,y,i,j,tile,level,rank (i j: the cell)")
      ->capture_default_str();
  cmd->add_flag("--normalize", o->normalize,
                "Write coordinates relative to the (square) region, scaled onto [0,1)^2, for `bluetile analyze`");
  add_real_option(cmd, "--dot-radius", o->dot_radius, positive,
                  "Dot radius in plane units for .svg, .pdf and .png (default: dots cover 35 % where densest)")
      ->default_str("");
  cmd->add_flag("--dots-follow-density", o->dots_follow_density,
                "Dot area proportional to the local density (radius r sqrt(density / max density))");
  add_integer_option(cmd, "--image-size", o->image_size, 16, 16384, "Width of .png renders in pixels");
  add_threads_option(cmd, o->threads);
  cmd->add_flag("-v,--verbose", o->verbose, "On stderr: for each point file its counts and time split (generate, format, write), for each "
                "drawing or render its time");
  cmd->callback([o, fit, cmd] {
    if (fit->count() > 0 && o->density_map.empty()) throw Error("--fit " + o->fit + " places a --density-map: give one");
    check_tiling_request(tiling_request(*o), !o->density_map.empty(), kOptionNames);  // before any image is read
    refuse_transfer_without_map(*cmd, !o->density_map.empty());
    refuse_unused_output_options(*cmd, o->outputs);
    run_tile(*o, *cmd);
  });
}

}  // namespace bluetile::cli
