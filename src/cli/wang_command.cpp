// bluetile wang: Wang-tile sample sets by Lloyd relaxation with multiple edge constraints (the
// paper, section 3); bluetile wang-check: the seam check and the analysis of a tiled plane.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/analysis/radial_power.h"
#include "bluetile/analysis/tiling_metrics.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/error.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/rng.h"
#include "bluetile/drawing/figures.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/relax/wang_relax.h"
#include "bluetile/tiling/seam_check.h"
#include "bluetile/tiling/tile_set_file.h"
#include "bluetile/voronoi/exact_engine.h"
#include "cli/commands.h"
#include "cli/engine_options.h"
#include "cli/memory_budget.h"
#include "cli/numeric_options.h"
#include "cli/output_names.h"
#include "cli/progress.h"

namespace bluetile::cli {
namespace {

struct WangCommandOptions {
  // wang8: the best seams and lattice coherence of the three at equal points per tile; the
  // 16-tile sets only win on diffuse anisotropy (docs/RESULTS.md, Wang tiles).
  std::string kind = "wang8";
  long long points = 52;
  int iterations = WangLevelOptions{}.iterations;
  int warm = 10;
  int levels = 1;
  double ratio = 2.0;
  // exact: the strategies' quality cannot be told apart over 4 seeds, and the noise-free mean
  // costs at most 0.15 s more than the cheapest at 13 and 52 points per tile (RESULTS.md).
  std::string strategy = "exact";
  int period = 16;
  double margin = 0.0;
  WangRefinement refine;  // the lattice and seam spacing steps, the library's defaults
  std::string rank_order = "farthest";
  double void_sigma = WangLevelOptions{}.void_sigma;
  std::uint64_t seed = 1;
  std::string output;
  bool check = false;
  bool verbose = false;
  EngineOptions engine;
};

// Points per tile past the library's limit (wang_relax.h), counted over the levels.
constexpr long long kMaxPointsPerTile = static_cast<long long>(kMaxWangPoints);

std::string fixed(double v, int decimals) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  return buffer;
}

std::string relation_name(TileRelation relation) {
  switch (relation) {
    case TileRelation::east: return "east of";
    case TileRelation::north: return "north of";
    case TileRelation::north_east: return "north-east of";
    case TileRelation::north_west: return "north-west of";
  }
  return "?";
}

// The seam check as a table, one row per level prefix.
std::string seam_report(const SeamCheck& check) {
  std::ostringstream out;
  out << "seam check: " << check.blocks << " admissible 2x2 blocks, " << check.tile_pairs << " tile pairs\n";
  char row[256];
  std::snprintf(row, sizeof row, "  %-6s %8s %10s %10s %8s %8s %6s  %s\n", "levels", "n/tile", "across", "within",
                "seamX", "within", "X/W", "closest pair across a seam");
  out << row;
  for (const SeamLevel& l : check.levels) {
    std::string pair = "tile " + std::to_string(l.closest.second_tile) + " point " +
                       std::to_string(l.closest.second_point) + " " + relation_name(l.closest.relation) + " tile " +
                       std::to_string(l.closest.first_tile) + " point " + std::to_string(l.closest.first_point);
    std::snprintf(row, sizeof row, "  0-%-4d %8zu %10.6f %10.6f %8.4f %8.4f %6.3f  %s\n", l.level, l.points_per_tile,
                  l.cross_min, l.within_min, l.cross_relative(), l.within_relative(), l.ratio(), pair.c_str());
    out << row;
  }
  out << "  (across: minimum distance between points of different tiles over every admissible block, tile units;\n"
         "   seamX and within: in hexagonal spacings of the tile's count; X/W = across / within)\n";
  return out.str();
}

std::string metrics_row(const std::string& label, const TilingMetrics& m, bool tiled) {
  char row[256];
  if (tiled)
    std::snprintf(row, sizeof row, "  %-28s %8zu %7.4f %8.5f %8.5f %8.2f %9.2f\n", label.c_str(), m.count, m.rho,
                  m.low_frequency, m.coherence_low, m.coherence_mid, m.diffuse_anisotropy_db);
  else
    std::snprintf(row, sizeof row, "  %-28s %8zu %7.4f %8.5f %8s %8s %9.2f\n", label.c_str(), m.count, m.rho,
                  m.low_frequency, "-", "-", m.diffuse_anisotropy_db);
  return row;
}

// The points of a tile once every level is added (each brings the count to round(R x count), as
// relax_wang_tiles does), refused up front past kMaxPointsPerTile: --levels 32 or --ratio 1e7
// otherwise ran on for hours towards an out-of-memory kill.
void check_points_per_tile(const WangCommandOptions& o, int tiles) {
  double total = static_cast<double>(o.points);
  for (int l = 1; l < o.levels; ++l) total = std::max(total, std::round(o.ratio * total));
  if (total <= static_cast<double>(kMaxPointsPerTile)) return;
  char text[300];
  std::snprintf(text, sizeof text,
                "--points %lld --levels %d --ratio %.17g makes about %.0f points per tile (%.0f in the %d tiles), more "
                "than the limit of %lld per tile: use fewer levels or a smaller ratio",
                o.points, o.levels, o.ratio, total, total * tiles, tiles, kMaxPointsPerTile);
  throw Error(text);
}

void run_wang(const WangCommandOptions& o) {
  static constexpr OutputFormat tile_set_formats[] = {OutputFormat::tile_set};
  output_format("--output", o.output, tile_set_formats);
  OutputSet outputs;  // checked before the work, written at the end
  OutputFile& output = outputs.add(o.output, {.allow_stdout = true});
  WangOptions w;
  w.kind = *parse_tile_set_kind(o.kind);
  w.points = static_cast<std::size_t>(o.points);
  w.levels = o.levels;
  w.ratio = o.ratio;
  w.seed = o.seed;
  w.level.iterations = o.iterations;
  w.level.warm_iterations = o.warm;
  w.level.strategy = parse_wang_strategy(o.strategy);
  w.level.period = o.period;
  w.level.edge_margin = o.margin;
  w.level.refine = o.refine;
  w.level.rank_order = parse_wang_rank_order(o.rank_order);
  w.level.void_sigma = o.void_sigma;
  if (o.levels > 1 && !(o.ratio > 1.0)) throw Error("--ratio must be above 1, got " + std::to_string(o.ratio));
  check_points_per_tile(o, TileRules(w.kind).tile_count());

  auto engine = make_engine(o.engine);
  Progress progress("wang", static_cast<long long>(o.levels) * (o.warm + o.iterations));
  w.level.on_iteration = [&](const WangIteration& it) {
    long long done = static_cast<long long>(it.level) * (o.warm + o.iterations) + (it.warm ? 0 : o.warm) + it.iteration;
    if (o.verbose) {
      progress.finish();
      std::fprintf(stderr, "level %d %s %d: max displacement %.3e, mean %.3e, energy %.9e, %zu scenes, %zu cells, %zu regrown\n",
                   it.level, it.warm ? "warm iteration" : "iteration", it.iteration, it.max_displacement,
                   it.mean_displacement, it.energy, it.scenes, it.cells, it.regrown);
    }
    progress.update(done, "level " + std::to_string(it.level) + (it.warm ? " warm start" : "") + ", max displacement " +
                              fixed(it.max_displacement, 6));
  };
  TileSet set = relax_wang_tiles(*engine, w);
  progress.finish();
  std::ostringstream command;
  command << "bluetile wang --set " << o.kind << " --points " << o.points << " --iterations " << o.iterations
          << " --warm " << o.warm << " --levels " << o.levels;
  if (o.levels > 1) command << " --ratio " << o.ratio;
  command << " --strategy " << o.strategy;
  if (o.strategy == "instances") command << " --period " << o.period;
  if (o.margin > 0.0) command << " --margin " << o.margin;
  const WangRefinement& r = o.refine;
  command << " --lattice-steps " << r.lattice_iterations << " --lattice-steps-per-iteration "
          << r.lattice_steps_per_iteration;
  if (r.lattice_iterations > 0 || r.lattice_steps_per_iteration > 0) command << " --lattice-step " << r.lattice_step;
  command << " --seam-steps " << r.seam_iterations;
  if (r.seam_iterations > 0) {
    command << " --seam-spacing " << r.seam_spacing;
    if (o.levels > 1) command << " --level-seam-spacing " << r.later_seam_spacing;
  }
  if (o.rank_order != "farthest") command << " --rank-order " << o.rank_order << " --void-sigma " << o.void_sigma;
  command << " --seed " << o.seed << " --engine " << engine->name();
  set.header = {"made by: " + command.str()};
  validate_tile_set(set);
  output.write(format_tile_set(set));
  outputs.publish();
  if (o.check) std::printf("%s", seam_report(check_seams(set)).c_str());
}

struct CheckOptions {
  std::string input;
  int period = 16;
  std::uint64_t seed = 1;
  std::string output;
  bool untiled = false;
  int untiled_iterations = 80;
  int image_size = 800;
};

// The picture of a tile set: every tile with its points and its edge (or corner) colours, then a
// small torus tiling with the Voronoi cells of its points and the colours on the seams, so a
// reader sees that colours match across every edge and points run on across them.
Canvas draw_tile_set(const TileSet& set, std::uint64_t seed) {
  constexpr int kTile = 130, kGap = 22, kColumns = 8, kPatch = 560, kPatchPeriod = 4;
  constexpr double kBar = 5.0;  // edge-colour bar width, pixels
  const TileRules rules(set.kind);
  const bool corners = rules.corner_coloured();
  auto colour_of = [](int c) { return series_colour(static_cast<std::size_t>(c) + 1); };  // vermilion, green
  const int tiles = static_cast<int>(set.tiles.size());
  const int rows = (tiles + kColumns - 1) / kColumns;
  const int caption = Canvas::text_height(2) + 8;
  const int width = kColumns * (kTile + kGap) + kGap;
  const int patch_top = kGap + rows * (kTile + caption + kGap) + caption;
  Canvas canvas(width, patch_top + kPatch + caption + kGap, colours::white);

  for (int t = 0; t < tiles; ++t) {
    const Tile& tile = set.tiles[static_cast<std::size_t>(t)];
    const double x0 = kGap + (t % kColumns) * (kTile + kGap);
    const double y0 = kGap + (t / kColumns) * (kTile + caption + kGap);
    const double x1 = x0 + kTile, y1 = y0 + kTile;
    canvas.line({x0, y0}, {x1, y0}, colours::light_grey), canvas.line({x1, y0}, {x1, y1}, colours::light_grey);
    canvas.line({x1, y1}, {x0, y1}, colours::light_grey), canvas.line({x0, y1}, {x0, y0}, colours::light_grey);
    const TileColours& c = tile.colours;
    if (corners) {  // NW NE SE SW
      canvas.disc({x0, y0}, 8.0, colour_of(c[0])), canvas.disc({x1, y0}, 8.0, colour_of(c[1]));
      canvas.disc({x1, y1}, 8.0, colour_of(c[2])), canvas.disc({x0, y1}, 8.0, colour_of(c[3]));
    } else {  // N E S W, bars just inside the edges, short of the corners
      const double in = kBar / 2.0, end = 10.0;
      canvas.line({x0 + end, y0 + in}, {x1 - end, y0 + in}, colour_of(c[0]), kBar);
      canvas.line({x1 - in, y0 + end}, {x1 - in, y1 - end}, colour_of(c[1]), kBar);
      canvas.line({x0 + end, y1 - in}, {x1 - end, y1 - in}, colour_of(c[2]), kBar);
      canvas.line({x0 + in, y0 + end}, {x0 + in, y1 - end}, colour_of(c[3]), kBar);
    }
    for (Point p : tile.points) canvas.disc({x0 + p.x * kTile, y0 + (1.0 - p.y) * kTile}, 2.0, colours::black);
    canvas.text(x0 + kTile / 2.0, y1 + 6, "tile " + std::to_string(t), colours::black, 2, Align::centre);
  }

  TiledPlane plane = torus_tiling(set, kPatchPeriod, seed);
  PointsFigure figure;
  figure.points = plane.points;
  figure.cells = true;
  const double px = (width - kPatch) / 2.0, py = patch_top;
  canvas.text(width / 2.0, py - caption + 4,
              std::to_string(kPatchPeriod) + "x" + std::to_string(kPatchPeriod) + " torus tiling (seed " +
                  std::to_string(seed) + ") with the Voronoi cells of its points",
              colours::black, 2, Align::centre);
  CanvasPainter painter(canvas);
  paint_points(figure, painter, px, py, kPatch);
  auto at = [&](double i, double j) { return points_figure_pixel({i / kPatchPeriod, j / kPatchPeriod}, px, py, kPatch); };
  for (int j = 0; j < kPatchPeriod; ++j) {
    for (int i = 0; i < kPatchPeriod; ++i) {
      const TileColours& c = rules.colours(plane.cell_tiles[static_cast<std::size_t>(j * kPatchPeriod + i)]);
      if (corners) {  // tile borders in grey, the colours on the lattice points
        canvas.line(at(i, j), at(i + 1, j), colours::grey, 1.5), canvas.line(at(i, j), at(i, j + 1), colours::grey, 1.5);
        canvas.disc(at(i, j + 1), 7.0, colour_of(c[0])), canvas.disc(at(i + 1, j + 1), 7.0, colour_of(c[1]));
        canvas.disc(at(i + 1, j), 7.0, colour_of(c[2])), canvas.disc(at(i, j), 7.0, colour_of(c[3]));
      } else {  // neighbours agree, so shared edges are drawn twice in one colour
        canvas.line(at(i, j + 1), at(i + 1, j + 1), colour_of(c[0]), 3.0);
        canvas.line(at(i + 1, j), at(i + 1, j + 1), colour_of(c[1]), 3.0);
        canvas.line(at(i, j), at(i + 1, j), colour_of(c[2]), 3.0);
        canvas.line(at(i, j), at(i, j + 1), colour_of(c[3]), 3.0);
      }
    }
  }
  return canvas;
}

void run_check(const CheckOptions& o) {
  // Every output is declared, and so checked, before any work; they appear together at the end.
  OutputSet outputs;
  outputs.add_input(o.input);
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
  if (!o.output.empty()) {
    // The spectrum image's periodogram is the largest allocation.
    std::size_t n = 0;
    for (const Tile& tile : set.tiles) n += tile.points.size();
    n = n / set.tiles.size() * static_cast<std::size_t>(o.period) * static_cast<std::size_t>(o.period);
    check_memory(static_cast<double>(periodogram_memory_bytes(n, default_periodogram_size(n))),
                 "the spectrum of the " + std::to_string(n) + "-point plane");
  }
  SeamCheck seams = check_seams(set);
  std::printf("%s: %s set, %zu tiles\n%s", o.input.c_str(), std::string(tile_set_kind_name(set.kind)).c_str(),
              set.tiles.size(), seam_report(seams).c_str());

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
  auto metrics_at = [&](std::size_t k) -> const TilingMetrics& {
    auto found = measured.find(k);
    if (found != measured.end()) return found->second;
    const auto prefix = static_cast<std::uint32_t>(k);
    TiledPlane p = torus_tiling(set, o.period, o.seed, prefix);
    // The plane's own periodogram (the non-uniform FFT above ~100 points): at 2048 points per
    // tile the per-tile sum (tiled_periodogram) takes minutes a prefix, this a second.
    Periodogram periodogram = compute_periodogram(p.points, tiling_periodogram_size(p.points.size(), o.period));
    return measured.emplace(k, measure_tiling(p.points, periodogram, o.period, tiles)).first->second;
  };
  nlohmann::json levels_json = nlohmann::json::array();
  std::size_t total = 0;
  for (const SeamLevel& level : seams.levels) {
    const TilingMetrics& m = metrics_at(level.points_per_tile);
    std::printf("%s", metrics_row("levels 0-" + std::to_string(level.level), m, true).c_str());
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
                             {"LF", m.low_frequency},
                             {"C_LF", m.coherence_low},
                             {"C_mid", m.coherence_mid},
                             {"lattice_peak", m.lattice_peak},
                             {"diffuse_anisotropy_db", m.diffuse_anisotropy_db}}}});
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
    std::printf("  %8zu %8zu %7.3f %8.4f %9.2f %8.3f %8.3f\n", k, m.count, m.rho, m.low_frequency, m.lattice_peak,
                m.coherence_low, m.coherence_mid);
    sweep_json.push_back({{"k", k}, {"N", m.count}, {"rho", m.rho}, {"LF", m.low_frequency},
                          {"lattice_peak", m.lattice_peak}, {"C_LF", m.coherence_low}, {"C_mid", m.coherence_mid}});
  }
  nlohmann::json stats = {{"input", o.input},
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
    std::printf("%s", metrics_row("untiled Lloyd, " + std::to_string(o.untiled_iterations) + " iterations", m, false).c_str());
    stats["untiled"] = {{"iterations", o.untiled_iterations},
                        {"N", m.count},
                        {"rho", m.rho},
                        {"LF", m.low_frequency},
                        {"diffuse_anisotropy_db", m.diffuse_anisotropy_db}};
  }
  std::printf("  (rho: min NN distance / hexagonal spacing; LF: mean periodogram for 0 < |k| < 0.5 sqrt(N);\n"
              "   C_LF, C_mid: tile-lattice coherence for M = %d; anisotropy: mean over annuli 0.5-1.6 sqrt(N),\n"
              "   lattice frequencies left out; lattice: mean periodogram at k = M m, 0 < |k| < sqrt(N))\n",
              o.period);

  if (o.output.empty()) return;
  file("stats.json").write(stats.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  file("plane.txt").write([&](OutputStream& out) {
    write_points(out, PointSet{plane.points, plane.levels},
                 {"bluetile wang-check: " + std::to_string(o.period) + "x" + std::to_string(o.period) +
                      " torus tiling of " + o.input + ", seed " + std::to_string(o.seed),
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
  write_image(file("radial.png"), draw_radial(curves, o.input));
  PointsFigure figure;
  figure.points = plane.points;
  write_image(file("points.png"), draw_points(figure, o.image_size));
  write_image(file("tiles.png"), draw_tile_set(set, o.seed));
  outputs.publish();
}

}  // namespace

void add_wang_command(CLI::App& app) {
  auto o = std::make_shared<WangCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "wang", "Wang-tile sample sets: tiles relaxed together by Lloyd's method under multiple edge constraints");
  cmd->add_option("--set", o->kind, "Tile set: wang8 (the paper's), wang16 (every edge combination) or corner16 (corner colours)")
      ->check(CLI::IsMember({"wang8", "wang16", "corner16"}))
      ->capture_default_str();
  add_integer_option(cmd, "-n,--points", o->points, 1LL, kMaxPointsPerTile, "Points per tile in level 0");
  add_integer_option(cmd, "-k,--iterations", o->iterations, 0, kMaxWangIterations, "Constrained Lloyd iterations per level");
  add_integer_option(cmd, "--warm", o->warm, 0, kMaxWangIterations,
                     "Warm start: periodic iterations of each tile alone before the constrained ones");
  add_integer_option(cmd, "-l,--levels", o->levels, 1, kMaxWangLevels, "Levels (hierarchical sets that tile)");
  // Above 10^8 a second level would pass the point limit at once (as progressive --ratio).
  add_real_option(cmd, "--ratio", o->ratio, {1.0, kMaxWangRatio, true, false},
                  "Each further level brings a tile's count to round(R x count)");
  cmd->add_option("--strategy", o->strategy,
                  "Neighbour configurations: exact (every admissible 3x3 block), instances (random torus tilings), "
                  "rounds (one block per fitting neighbour)")
      ->check(CLI::IsMember({"exact", "instances", "rounds"}))
      ->capture_default_str();
  add_integer_option(cmd, "--period", o->period, kMinWangPeriod, kMaxWangPeriod, "instances: the torus tiling is M x M tiles");
  add_real_option(cmd, "--margin", o->margin, {0.0, kMaxEdgeMargin}, "Keep points this far inside their tile (tile units)");
  add_integer_option(cmd, "--lattice-steps", o->refine.lattice_iterations, 0, kMaxLatticeSteps,
                     "Lattice decorrelation after each level's iterations: gradient steps that lower the tile-lattice "
                     "peaks C_LF (and, in level 0, C_mid) (0: none)");
  add_integer_option(cmd, "--lattice-steps-per-iteration", o->refine.lattice_steps_per_iteration, 0,
                     kMaxLatticeStepsPerIteration,
                     "Lattice steps after each constrained iteration of the second half, which Lloyd's next iteration "
                     "repairs (0: none)");
  add_real_option(cmd, "--lattice-step", o->refine.lattice_step, {kMinLatticeStep, kMaxLatticeStep},
                  "Largest move of one lattice step, in hexagonal spacings");
  add_integer_option(cmd, "--seam-steps", o->refine.seam_iterations, 0, kMaxSeamSteps,
                     "Seam spacing after each level's iterations: repulsion steps for points closer than the spacing "
                     "to a point they can meet in a tiling (0: none)");
  add_real_option(cmd, "--seam-spacing", o->refine.seam_spacing, {kMinSeamSpacing, kMaxSeamSpacing},
                  "Seam spacing of level 0, in hexagonal spacings of the tile's points");
  add_real_option(cmd, "--level-seam-spacing", o->refine.later_seam_spacing, {kMinSeamSpacing, kMaxSeamSpacing},
                  "Seam spacing of levels 1 and up, in hexagonal spacings of the tile's points");
  cmd->add_option("--rank-order", o->rank_order,
                  "Progressive order inside each level: farthest (greedy farthest point) or voids (tiled "
                  "void-and-cluster: lower low-frequency power and tile-lattice coherence between level boundaries, "
                  "closer nearest pairs)")
      ->check(CLI::IsMember({"farthest", "voids"}))
      ->capture_default_str();
  add_real_option(cmd, "--void-sigma", o->void_sigma, {kMinVoidSigma, kMaxVoidSigma}, "voids: kernel width in hexagonal spacings of the prefix");
  add_seed_option(cmd, o->seed);
  cmd->add_option("-o,--output", o->output, "Output tile-set file (.tiles or .txt; - for stdout)")->required();
  cmd->add_flag("--check", o->check, "Print the seam check of the result");
  cmd->add_flag("-v,--verbose", o->verbose, "Print displacement, energy and scene counts of every iteration on stderr");
  // The exact engine by default: a step is thousands of small cropped scenes, which it measures
  // in 0.3 s for 8 x 52 points x 25 iterations against 80 s for the raster engine on lavapipe
  // (docs/RESULTS.md, Wang tiles).
  o->engine.engine = "exact";
  add_engine_options(cmd, o->engine);
  cmd->callback([o] { run_wang(*o); });

  auto c = std::make_shared<CheckOptions>();
  CLI::App* check = app.add_subcommand(
      "wang-check", "Seam check of a tile set (every admissible 2x2 block) and the analysis of a tiled plane");
  check->add_option("tiles", c->input, "Tile-set file")->required()->check(CLI::ExistingFile);
  add_integer_option(check, "--period", c->period, 1, 1024, "The analysed plane is an M x M torus tiling");
  add_seed_option(check, c->seed, "Seed of the tiling");
  check->add_option("-o,--output", c->output,
                    "Folder for stats.json, plane.txt and the images (spectrum, radial power, points, the tile set)");
  check->add_flag("--untiled", c->untiled, "Compare with untiled Lloyd at the same N (exact engine)");
  add_integer_option(check, "--untiled-iterations", c->untiled_iterations, 0, 100000,
                     "Iterations of the untiled reference");
  add_integer_option(check, "--image-size", c->image_size, 64, 8192, "Side of points.png in pixels");
  check->callback([c] { run_check(*c); });
}

}  // namespace bluetile::cli
