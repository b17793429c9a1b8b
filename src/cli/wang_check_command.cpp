// bluetile wang-check: the seam check of a tile set and the analysis of a plane it tiles.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/analysis/radial_power.h"
#include "bluetile/analysis/tiling_metrics.h"
#include "bluetile/core/error.h"
#include "bluetile/core/memory_budget.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/text.h"
#include "bluetile/drawing/figures.h"
#include "bluetile/drawing/tile_set_drawing.h"
#include "bluetile/io/image_file.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/tiling/seam_check.h"
#include "bluetile/tiling/tile_set_file.h"
#include "bluetile/voronoi/exact_engine.h"
#include "cli/commands.h"
#include "cli/file_options.h"
#include "cli/numeric_options.h"
#include "cli/progress.h"
#include "cli/seam_report.h"

namespace bluetile::cli {
namespace {

// A measure whose band holds no frequency is undefined (NaN, tiling_metrics.h): "-" in the
// tables, null in stats.json. LF of planes of at most 4 points, the lattice peak of one point a
// tile, the anisotropy of a 1 x 1 tiling; C_LF and C_mid of the untiled plane.
std::string metrics_row(const std::string& label, const TilingMetrics& m) {
  char row[256];
  std::snprintf(row, sizeof row, "  %-28s %8zu %7.4f %8s %8s %8s %9s\n", label.c_str(), m.count, m.rho,
                measure_text(m.low_frequency, 5).c_str(), measure_text(m.coherence_low, 5).c_str(),
                measure_text(m.coherence_mid, 2).c_str(), measure_text(m.diffuse_anisotropy_db, 2).c_str());
  return row;
}

bool any_undefined(const TilingMetrics& m) {
  return std::isnan(m.low_frequency) || std::isnan(m.coherence_low) || std::isnan(m.coherence_mid) ||
         std::isnan(m.lattice_peak) || std::isnan(m.diffuse_anisotropy_db);
}

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

struct CheckOptions {
  std::string input;
  int period = 16;
  std::uint64_t seed = 1;
  std::string output;
  bool untiled = false;
  int untiled_iterations = 80;
  int image_size = 800;
  int threads = 0;
};

void run_check(const CheckOptions& o, const CLI::App& command) {
  if (o.threads > 0) set_thread_count(static_cast<std::size_t>(o.threads));
  // The output folder's PNGs are drawn at the end: the image plugin is loaded first, as analyze
  // loads it, so that too little memory for it is said before the measurement.
  if (!o.output.empty()) load_image_plugin();
  // Every output is declared, and so checked, before any work; they appear together at the end.
  OutputSet outputs;
  add_declared_inputs(outputs, command);
  std::vector<OutputFile*> files;
  if (!o.output.empty()) {
    outputs.add_folder(o.output);
    for (const char* name : {"stats.json", "plane.txt", "spectrum.png", "spectrum-untiled.png", "radial.png",
                             "points.png", "tiles.png"}) {
      if (std::string(name) == "spectrum-untiled.png" && !o.untiled) continue;
      files.push_back(&outputs.add((std::filesystem::path(o.output) / name).string()));
    }
  }
  auto file = [&](const std::string& name) -> OutputFile& {
    for (OutputFile* f : files)
      if (std::filesystem::path(f->path()).filename() == name) return *f;
    throw Error("internal: no output " + name);
  };
  TileSet set = read_tile_set(o.input);
  {
    // The plane and its largest periodogram, outputs or not: the measurement's, and the spectrum
    // image's larger one when there is an output folder.
    std::size_t n = 0;
    for (const Tile& tile : set.tiles) n += tile.points.size();
    n = n / set.tiles.size() * static_cast<std::size_t>(o.period) * static_cast<std::size_t>(o.period);
    const int measured = tiling_periodogram_size(n, o.period);
    const int size = o.output.empty() ? measured : std::max(measured, default_periodogram_size(n));
    check_memory(static_cast<double>(sizeof(Point) * n + periodogram_memory_bytes(n, size)),
                 "the spectrum of the " + std::to_string(n) + "-point plane");
  }
  SeamCheck seams = check_seams(set);
  std::printf("%s: %s set, %zu tiles\n%s", input_name(o.input).c_str(), std::string(tile_set_kind_name(set.kind)).c_str(),
              set.tiles.size(), seam_report(seams).c_str());
  // A set whose tiles hold different counts (the reader takes up to 4x): every row below measures
  // the smallest tile's count, and the rest would go unmentioned.
  for (const SeamLevel& level : seams.levels) {
    std::size_t fewest = SIZE_MAX, most = 0;
    for (const Tile& tile : set.tiles) {
      std::size_t n = 0;
      for (std::size_t k = 0; k < tile.points.size(); ++k) n += (k < tile.levels.size() ? tile.levels[k] : 0) <= level.level ? 1 : 0;
      fewest = std::min(fewest, n);
      most = std::max(most, n);
    }
    if (fewest != most)
      std::printf("note: levels 0-%d: the tiles hold %zu to %zu points; each row measures the first %zu by rank of "
                  "every tile\n",
                  level.level, fewest, most, fewest);
  }

  const int tiles = static_cast<int>(set.tiles.size());
  TiledPlane plane = torus_tiling(set, o.period, o.seed);
  std::printf("\ntiled plane: %dx%d torus tiling, seed %llu\n", o.period, o.period, static_cast<unsigned long long>(o.seed));
  char head[256];
  std::snprintf(head, sizeof head, "  %-28s %8s %7s %8s %8s %8s %9s\n", "prefix", "N", "rho", "LF", "C_LF", "C_mid",
                "aniso dB");
  std::printf("%s", head);
  // The plane of the first k ranks of every tile, each measured once (level boundaries are in
  // the sweep too).
  std::map<std::size_t, TilingMetrics> measured;
  bool undefined = false;  // some tiled row holds a "-"
  auto metrics_at = [&](std::size_t k) -> const TilingMetrics& {
    auto found = measured.find(k);
    if (found != measured.end()) return found->second;
    const auto prefix = static_cast<std::uint32_t>(k);
    TiledPlane p = torus_tiling(set, o.period, o.seed, prefix);
    // The plane's own periodogram (the non-uniform FFT above ~100 points): at 2048 points per
    // tile the per-tile sum (tiled_periodogram) takes minutes a prefix, this a second.
    Periodogram periodogram = compute_periodogram(p.points, tiling_periodogram_size(p.points.size(), o.period));
    const TilingMetrics& m = measured.emplace(k, measure_tiling(p.points, periodogram, o.period, tiles)).first->second;
    undefined = undefined || any_undefined(m);
    return m;
  };
  nlohmann::json levels_json = nlohmann::json::array();
  std::size_t total = 0;
  for (const SeamLevel& level : seams.levels) {
    const TilingMetrics& m = metrics_at(level.points_per_tile);
    std::printf("%s", metrics_row("levels 0-" + std::to_string(level.level), m).c_str());
    levels_json.push_back({{"level", level.level},
                           {"points_per_tile", level.points_per_tile},
                           {"seam_min", level.cross_min},
                           {"within_min", level.within_min},
                           {"seamX", level.cross_relative()},
                           {"within_relative", level.within_relative()},
                           {"X_over_W", level.ratio()},
                           {"plane",
                            {{"N", m.count},
                             {"rho", m.rho},
                             {"LF", number(m.low_frequency)},
                             {"C_LF", number(m.coherence_low)},
                             {"C_mid", number(m.coherence_mid)},
                             {"lattice_peak", number(m.lattice_peak)},
                             {"diffuse_anisotropy_db", number(m.diffuse_anisotropy_db)}}}});
    total = level.points_per_tile;
  }
  // The prefix sweep: the first k points by rank of every tile, k at fixed fractions of the top
  // count and at every level boundary.
  std::vector<std::size_t> boundaries;
  for (const SeamLevel& level : seams.levels) boundaries.push_back(level.points_per_tile);
  const std::vector<std::size_t> sweep = prefix_sweep(total, boundaries);
  std::printf("\nprefix sweep (%dx%d torus tiling):\n  %8s %8s %7s %8s %9s %8s %8s\n", o.period, o.period, "k/tile", "N",
              "rho", "LF", "lattice", "C_LF", "C_mid");
  nlohmann::json sweep_json = nlohmann::json::array();
  for (const std::size_t k : sweep) {
    if (k * static_cast<std::size_t>(o.period) * static_cast<std::size_t>(o.period) < 2) continue;
    const TilingMetrics& m = metrics_at(k);
    std::printf("  %8zu %8zu %7.3f %8s %9s %8s %8s\n", k, m.count, m.rho, measure_text(m.low_frequency, 4).c_str(),
                measure_text(m.lattice_peak, 2).c_str(), measure_text(m.coherence_low, 3).c_str(),
                measure_text(m.coherence_mid, 3).c_str());
    sweep_json.push_back({{"k", k}, {"N", m.count}, {"rho", m.rho}, {"LF", number(m.low_frequency)},
                          {"lattice_peak", number(m.lattice_peak)}, {"C_LF", number(m.coherence_low)},
                          {"C_mid", number(m.coherence_mid)}});
  }
  nlohmann::json stats = {{"input", input_name(o.input)},
                          {"set", tile_set_kind_name(set.kind)},
                          {"tiles", tiles},
                          {"blocks", seams.blocks},
                          {"period", o.period},
                          {"seed", o.seed},
                          {"levels", levels_json},
                          {"prefix_sweep", sweep_json}};

  std::vector<Point> untiled;
  if (o.untiled) {
    Rng rng(derive_seed(o.seed, 1));
    untiled.resize(plane.points.size());
    for (Point& p : untiled) p = rng.point(Domain{});
    Scene scene = make_scene(untiled);
    ExactEngine engine;
    LloydOptions lloyd;
    lloyd.iterations = o.untiled_iterations;
    Progress progress("untiled Lloyd", o.untiled_iterations);
    lloyd.on_iteration = [&](const LloydIteration& it) { progress.update(it.iteration); };
    relax_lloyd(engine, scene, lloyd);
    progress.finish();
    untiled = scene.sites;
    TilingMetrics m = measure_tiling(untiled, 0, 1);
    std::printf("%s", metrics_row("untiled Lloyd, " + std::to_string(o.untiled_iterations) + " iterations", m).c_str());
    stats["untiled"] = {{"iterations", o.untiled_iterations},
                        {"N", m.count},
                        {"rho", m.rho},
                        {"LF", number(m.low_frequency)},
                        {"diffuse_anisotropy_db", number(m.diffuse_anisotropy_db)}};
  }
  std::printf("  (rho: min NN distance / hexagonal spacing; LF: mean periodogram for 0 < |k| < 0.5 sqrt(N);\n"
              "   C_LF, C_mid: tile-lattice coherence for M = %d; anisotropy: mean over annuli 0.5-1.6 sqrt(N),\n"
              "   lattice frequencies left out; lattice: mean periodogram at k = M m, 0 < |k| < sqrt(N))\n",
              o.period);
  if (undefined)
    std::printf("  (\"-\": no frequency in the measure's band, null in stats.json: LF of at most 4 points, lattice of\n"
                "   1 point a tile, aniso dB where every frequency of its annuli is a lattice one, as at --period 1)\n");

  if (o.output.empty()) return;
  file("stats.json").write(stats.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  file("plane.txt").write([&](OutputStream& out) {
    write_points(out, PointSet{plane.points, plane.levels},
                 {"bluetile wang-check: " + std::to_string(o.period) + "x" + std::to_string(o.period) +
                      " torus tiling of " + input_name(o.input) + ", seed " + std::to_string(o.seed),
                  "columns: x y level"});
  });
  Periodogram full = compute_periodogram(plane.points, default_periodogram_size(plane.points.size()));
  write_image(file("spectrum.png"), draw_spectrum(full));
  std::vector<RadialCurve> curves{{"tiled, " + std::to_string(o.period) + "x" + std::to_string(o.period),
                                   radial_power(full), plane.points.size()}};
  if (!untiled.empty()) {
    Periodogram reference = compute_periodogram(untiled, full.size);
    write_image(file("spectrum-untiled.png"), draw_spectrum(reference));
    curves.push_back({"untiled Lloyd", radial_power(reference), untiled.size()});
  }
  write_image(file("radial.png"), draw_radial(curves, input_name(o.input)));
  PointsFigure figure;
  figure.points = plane.points;
  write_image(file("points.png"), draw_points(figure, o.image_size));
  write_image(file("tiles.png"), draw_tile_set(set, o.seed));
  outputs.publish();
}

}  // namespace

void add_wang_check_command(CLI::App& app) {
  auto c = std::make_shared<CheckOptions>();
  CLI::App* check = app.add_subcommand(
      "wang-check", "Seam check of a tile set (every admissible 2x2 block) and the analysis of a tiled plane");
  // -i as every other command takes its input; the tile set alone as the argument as before.
  add_input_option(check, "-i,--input,tiles", c->input, InputKind::tiles,
                   "Tile-set file ('-': standard input), alone or as -i,--input FILE")
      ->required();
  add_integer_option(check, "--period", c->period, 1, 1024, "The analysed plane is an M x M torus tiling");
  add_seed_option(check, c->seed, "Seed of the tiling");
  add_output_folder_option(check, "-o,--output", c->output,
                           "Folder for stats.json, plane.txt and the images (spectrum, radial power, points, the tile set)");
  check->add_flag("--untiled", c->untiled, "Compare with untiled Lloyd at the same N (exact engine)");
  CLI::Option* untiled = check->get_option("--untiled");
  add_integer_option(check, "--untiled-iterations", c->untiled_iterations, 0, 100000,
                     "Iterations of the untiled reference (with --untiled)")
      ->needs(untiled);
  add_integer_option(check, "--image-size", c->image_size, 64, 8192, "Side of points.png in pixels (with --output)")
      ->needs(check->get_option("--output"));
  add_threads_option(check, c->threads);
  check->callback([c, check] { run_check(*c, *check); });
}

}  // namespace bluetile::cli
