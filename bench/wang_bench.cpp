// bluetile_wang_bench: build time and quality of Wang-tile sample sets (the paper,
// section 3), over seeds, for the figures table in docs/RESULTS.md.
//
//   quality: for every kind, points per tile, strategy and seed, builds a set and reports the
//            seam check (seamX, X/W) and the metrics of seeded torus tilings of each period
//            (rho, LF, C_LF, C_mid, diffuse anisotropy), each seed's row, then worst and mean;
//            with --untiled, the same plane metrics of untiled Lloyd sets of the same N.
//   time:    the time to build a set with each engine, interleaved repeats side by side.
//   levels:  a hierarchical set: the prefix sweep (fractions of the top count and every level
//            boundary) on the plane, per seed and worst over the seeds, rank orders side by side;
//            with --plot, the worst rho and LF against the prefix as a figure (SVG or PNG).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "bench_args.h"
#include "bluetile/analysis/tiling_metrics.h"
#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/point_table.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/text.h"
#include "bluetile/io/plot.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/relax/wang_relax.h"
#include "bluetile/tiling/seam_check.h"
#include "bluetile/voronoi/exact_engine.h"
#include "machine.h"

#ifdef BLUETILE_BENCH_RASTER
#include "bluetile/raster/raster_engine.h"
#endif

namespace bluetile::bench {
namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  std::string mode = "quality";
  std::vector<std::string> kinds{"wang8"};
  std::vector<std::size_t> points{52};
  std::vector<std::string> strategies{"exact"};
  std::vector<int> periods{16};
  int seeds = 4;
  std::uint64_t first_seed = 1;
  int iterations = WangLevelOptions{}.iterations;
  int warm = 10;
  double margin = 0.0;
  WangRefinement refine;  // the library's defaults
  int levels = 1;
  double ratio = 2.0;
  std::vector<std::string> rank_orders{"farthest"};  // levels mode: orders side by side
  int prefixes = 0;   // levels mode: also this many evenly spaced steps between level boundaries
  int repeats = 3;    // time mode
  std::vector<std::string> engines{"exact"};
  bool untiled = false;
  bool diagnose = false;
  int untiled_iterations = 80;
  int threads = 0;
  std::string plot;  // levels mode: the sweep figure, .svg or .png
};

WangStrategy strategy_of(const std::string& name) {
  if (name == "instances") return WangStrategy::instances;
  if (name == "rounds") return WangStrategy::rounds;
  return WangStrategy::exact;
}

std::unique_ptr<CentroidEngine> make_engine(const std::string& name) {
  if (name == "exact") return std::make_unique<ExactEngine>();
#ifdef BLUETILE_BENCH_RASTER
  if (name == "raster") return std::make_unique<RasterEngine>();
#endif
  throw Error("engine " + name + " not available in this build");
}

WangOptions wang_options(const Options& o, const std::string& kind, std::size_t n, const std::string& strategy,
                         std::uint64_t seed) {
  WangOptions w;
  w.kind = *parse_tile_set_kind(kind);
  w.points = n;
  w.levels = o.levels;
  w.ratio = o.ratio;
  w.seed = seed;
  w.level.iterations = o.iterations;
  w.level.warm_iterations = o.warm;
  w.level.strategy = strategy_of(strategy);
  w.level.edge_margin = o.margin;
  w.level.refine = o.refine;
  return w;
}

// Metrics of the period x period torus tiling `seed` of the first `prefix` ranks of every tile.
TilingMetrics plane_metrics(const TileSet& set, int period, std::uint64_t seed,
                            std::uint32_t prefix = std::numeric_limits<std::uint32_t>::max()) {
  TiledPlane plane = torus_tiling(set, period, seed, prefix);
  Periodogram p = compute_periodogram(plane.points, tiling_periodogram_size(plane.points.size(), period));
  return measure_tiling(plane.points, p, period, static_cast<int>(set.tiles.size()));
}

// Diagnostic: the largest coherent |sum_t F_t(m)|^2 / (T n) and incoherent sum_t |F_t(m)|^2 / (T n)
// over integer m with 0.5 sqrt(n) <= |m| < 1.5 sqrt(n): how much of C_mid is tile crystallinity
// and how much coherence between tiles.
std::pair<double, double> coherence_split(const TileSet& set, int& mx_out, int& my_out) {
  const double n = static_cast<double>(set.tiles[0].points.size());
  const double t = static_cast<double>(set.tiles.size());
  const int limit = static_cast<int>(std::ceil(1.5 * std::sqrt(n)));
  double best_coherent = 0.0, best_incoherent = 0.0;
  for (int my = -limit; my <= limit; ++my) {
    for (int mx = -limit; mx <= limit; ++mx) {
      const double m2 = static_cast<double>(mx * mx + my * my);
      if (m2 < 0.25 * n || m2 >= 2.25 * n) continue;
      double sr = 0.0, si = 0.0, incoherent = 0.0;
      for (const Tile& tile : set.tiles) {
        double tr = 0.0, ti = 0.0;
        for (Point p : tile.points) {
          const double a = -2.0 * 3.14159265358979323846 * (mx * p.x + my * p.y);
          tr += std::cos(a);
          ti += std::sin(a);
        }
        sr += tr, si += ti;
        incoherent += tr * tr + ti * ti;
      }
      const double coherent = (sr * sr + si * si) / (t * n);
      if (coherent > best_coherent) {
        best_coherent = coherent;
        mx_out = mx, my_out = my;
      }
      best_incoherent = std::max(best_incoherent, incoherent / (t * n));
    }
  }
  return {best_coherent, best_incoherent};
}

// Worst and mean over seeds of the defined values (NaN, a measure whose band holds no frequency of
// the plane: tiling_metrics.h, is left out; none defined gives NaN).
struct Stat {
  std::vector<double> values;
  void add(double v) {
    if (!std::isnan(v)) values.push_back(v);
  }
  double worst_low() const { return values.empty() ? kUndefined : *std::min_element(values.begin(), values.end()); }
  double worst_high() const { return values.empty() ? kUndefined : *std::max_element(values.begin(), values.end()); }
  double mean() const {
    if (values.empty()) return kUndefined;
    double s = 0.0;
    for (double v : values) s += v;
    return s / static_cast<double>(values.size());
  }
  static constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();
};

void quality(const Options& o) {
  ExactEngine engine;
  std::printf("| set | n | strategy | M | seed | seamX | X/W | W | rho | LF | C_LF | C_mid | aniso dB | build s |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& kind : o.kinds) {
    for (std::size_t n : o.points) {
      for (const std::string& strategy : o.strategies) {
        std::map<int, std::map<std::string, Stat>> stats;
        for (int s = 0; s < o.seeds; ++s) {
          const std::uint64_t seed = o.first_seed + static_cast<std::uint64_t>(s);
          auto start = Clock::now();
          TileSet set = relax_wang_tiles(engine, wang_options(o, kind, n, strategy, seed));
          double build = std::chrono::duration<double>(Clock::now() - start).count();
          SeamCheck seams = check_seams(set);
          const SeamLevel& top = seams.levels.back();
          if (o.diagnose) {
            int mx = 0, my = 0;
            auto [coherent, incoherent] = coherence_split(set, mx, my);
            std::printf("  diagnose seed %llu: coherent max %.1f at m = (%d, %d), incoherent max %.1f\n",
                        static_cast<unsigned long long>(seed), coherent, mx, my, incoherent);
          }
          for (int period : o.periods) {
            TilingMetrics m = plane_metrics(set, period, derive_seed(seed, 1000));
            auto& st = stats[period];
            st["seamX"].add(top.cross_relative());
            st["X/W"].add(top.ratio());
            st["W"].add(top.within_relative());
            st["rho"].add(m.rho);
            st["LF"].add(m.low_frequency);
            st["C_LF"].add(m.coherence_low);
            st["C_mid"].add(m.coherence_mid);
            st["aniso"].add(m.diffuse_anisotropy_db);
            st["build"].add(build);
            std::printf("| %s | %zu | %s | %d | %llu | %.3f | %.3f | %.3f | %.3f | %s | %s | %s | %s | %.2f |\n",
                        kind.c_str(), n, strategy.c_str(), period, static_cast<unsigned long long>(seed),
                        top.cross_relative(), top.ratio(), top.within_relative(), m.rho,
                        measure_text(m.low_frequency, 4).c_str(), measure_text(m.coherence_low, 4).c_str(),
                        measure_text(m.coherence_mid, 1).c_str(), measure_text(m.diffuse_anisotropy_db, 2).c_str(), build);
            std::fflush(stdout);
          }
        }
        for (auto& [period, st] : stats) {
          std::printf("| **%s** | **%zu** | **%s** | **%d** | worst | %.3f | %.3f | %.3f | %.3f | %s | %s | %s | %s | %.2f |\n",
                      kind.c_str(), n, strategy.c_str(), period, st["seamX"].worst_low(), st["X/W"].worst_low(),
                      st["W"].worst_low(), st["rho"].worst_low(), measure_text(st["LF"].worst_high(), 4).c_str(),
                      measure_text(st["C_LF"].worst_high(), 4).c_str(), measure_text(st["C_mid"].worst_high(), 1).c_str(),
                      measure_text(st["aniso"].worst_high(), 2).c_str(), st["build"].worst_high());
          std::printf("| **%s** | **%zu** | **%s** | **%d** | mean | %.3f | %.3f | %.3f | %.3f | %s | %s | %s | %s | %.2f |\n",
                      kind.c_str(), n, strategy.c_str(), period, st["seamX"].mean(), st["X/W"].mean(), st["W"].mean(),
                      st["rho"].mean(), measure_text(st["LF"].mean(), 4).c_str(), measure_text(st["C_LF"].mean(), 4).c_str(),
                      measure_text(st["C_mid"].mean(), 1).c_str(), measure_text(st["aniso"].mean(), 2).c_str(),
                      st["build"].mean());
        }
        std::fflush(stdout);
      }
    }
  }
  if (!o.untiled) return;
  // Untiled Lloyd at the N of each tiled plane (N = n M^2 whatever the set).
  std::printf("\n| untiled Lloyd | N | iterations | seed | rho | LF | aniso dB |\n|---|---|---|---|---|---|---|\n");
  for (std::size_t n : o.points) {
    for (int period : o.periods) {
      const std::size_t count = n * static_cast<std::size_t>(period * period);
      Stat rho, lf, an;
      for (int s = 0; s < o.seeds; ++s) {
        Rng rng(derive_seed(o.first_seed + static_cast<std::uint64_t>(s), 77));
        std::vector<Point> sites(count);
        for (Point& p : sites) p = rng.point(Domain{});
        Scene scene = make_scene(sites);
        LloydOptions lloyd;
        lloyd.iterations = o.untiled_iterations;
        relax_lloyd(engine, scene, lloyd);
        TilingMetrics m = measure_tiling(scene.sites, 0, 1);
        rho.add(m.rho);
        lf.add(m.low_frequency);
        an.add(m.diffuse_anisotropy_db);
        std::printf("| | %zu | %d | %d | %.3f | %s | %s |\n", count, o.untiled_iterations, s, m.rho,
                    measure_text(m.low_frequency, 4).c_str(), measure_text(m.diffuse_anisotropy_db, 2).c_str());
      }
      std::printf("| worst | %zu | %d | | %.3f | %s | %s |\n", count, o.untiled_iterations, rho.worst_low(),
                  measure_text(lf.worst_high(), 4).c_str(), measure_text(an.worst_high(), 2).c_str());
      std::printf("| mean | %zu | %d | | %.3f | %s | %s |\n", count, o.untiled_iterations, rho.mean(),
                  measure_text(lf.mean(), 4).c_str(), measure_text(an.mean(), 2).c_str());
      std::fflush(stdout);
    }
  }
}

void timing(const Options& o) {
  std::vector<std::unique_ptr<CentroidEngine>> engines;
  for (const std::string& e : o.engines) engines.push_back(make_engine(e));
  std::printf("| engine | set | n | strategy | levels | warm | iterations | repeat | seconds |\n|---|---|---|---|---|---|---|---|---|\n");
  std::map<std::string, Stat> totals;
  for (int r = 0; r < o.repeats; ++r) {
    for (std::size_t e = 0; e < engines.size(); ++e) {  // interleaved: engines side by side
      for (const std::string& kind : o.kinds) {
        for (std::size_t n : o.points) {
          for (const std::string& strategy : o.strategies) {
            auto start = Clock::now();
            WangOptions w = wang_options(o, kind, n, strategy, o.first_seed);
            relax_wang_tiles(*engines[e], w);
            double seconds = std::chrono::duration<double>(Clock::now() - start).count();
            std::string key = o.engines[e] + " " + kind + " " + std::to_string(n) + " " + strategy;
            totals[key].add(seconds);
            std::printf("| %s | %s | %zu | %s | %d | %d | %d | %d | %.3f |\n", o.engines[e].c_str(), kind.c_str(), n,
                        strategy.c_str(), o.levels, o.warm, o.iterations, r, seconds);
            std::fflush(stdout);
          }
        }
      }
    }
  }
  std::printf("\n| configuration | min s | median s | max s |\n|---|---|---|---|\n");
  for (auto& [key, st] : totals) {
    std::vector<double> v = st.values;
    std::sort(v.begin(), v.end());
    std::printf("| %s | %.3f | %.3f | %.3f |\n", key.c_str(), v.front(), v[v.size() / 2], v.back());
  }
}

// Worst over the seeds of one prefix of the sweep.
struct SweepWorst {
  // lf, lattice, c_lf: the largest defined value (std::fmax leaves NaN out), NaN while there is none.
  static constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();
  double rho = HUGE_VAL, lf = kUndefined, lattice = kUndefined, c_lf = kUndefined;
};
using SweepKey = std::tuple<std::string, std::string, std::size_t, std::string, std::size_t>;  // set, strategy, n0, order, prefix

// The sweep's worst rho and LF against the prefix (log axis), one line per set and order, with
// Kopf et al. 2006's recursive Wang tiles as the band between two grey lines and the issue's
// targets dashed (docs/RESULTS.md, "Every prefix"). rho runs to 1.4 to leave the legend room above the data.
void plot_sweep(const Options& o, const std::map<SweepKey, SweepWorst>& worst) {
  Plot plot;
  plot.title = "Prefix sweep, worst of " + std::to_string(o.seeds) + " seeds, M = " + std::to_string(o.periods[0]);
  plot.x_label = "points per tile k (the first k ranks of every tile)";
  plot.log_x = true;
  PlotPanel rho{.y_label = "rho", .y_min = 0.0, .y_max = 1.4}, lf{.y_label = "LF", .y_min = 0.0};
  std::map<std::tuple<std::string, std::string, std::size_t, std::string>, std::size_t> line;  // key -> series index
  for (const auto& [key, w] : worst) {
    const auto& [kind, strategy, n, order, prefix] = key;
    auto [at, fresh] = line.try_emplace({kind, strategy, n, order}, rho.series.size());
    if (fresh) {
      const Colour c = series_colour(at->second);
      const std::string label = kind + " " + std::to_string(n) + " " + strategy + " " + order;
      rho.series.push_back({label, {}, {}, c, 2.0});
      lf.series.push_back({label, {}, {}, c, 2.0});
    }
    rho.series[at->second].x.push_back(static_cast<double>(prefix));
    rho.series[at->second].y.push_back(w.rho);
    lf.series[at->second].x.push_back(static_cast<double>(prefix));
    lf.series[at->second].y.push_back(w.lf);
  }
  double lo = HUGE_VAL, hi = 0.0;
  for (const PlotSeries& s : rho.series)
    for (double x : s.x) lo = std::min(lo, x), hi = std::max(hi, x);
  auto level = [&](PlotPanel& panel, const std::string& label, double y, Colour c, bool dashed) {
    PlotSeries s{label, {lo, hi}, {y, y}, c, 1.5};
    s.dashed = dashed;
    panel.series.push_back(s);
  };
  const Colour kopf = colours::grey, target = colours::black;
  level(rho, "Kopf 2006 (0.22-0.50)", 0.22, kopf, false);
  level(rho, "", 0.50, kopf, false);
  level(rho, "target: every prefix 0.60, boundaries 0.70", 0.60, target, true);
  level(rho, "", 0.70, target, true);
  level(lf, "", 0.11, kopf, false);
  level(lf, "", 0.20, kopf, false);
  level(lf, "", 0.03, target, true);
  level(lf, "", 0.015, target, true);
  plot.panels = {rho, lf};
  const int width = 900, height = 760;
  if (file_extension(o.plot) == ".png") write_image(o.plot, render_plot(plot, width, height));
  else render_plot_svg(plot, width, height).write(o.plot);
}

// The prefix sweep of hierarchical sets (prefix_sweep: fixed fractions of the top count and every
// level boundary), per seed, and the worst over the seeds of each prefix, one rank order beside
// the other. Every order ranks the same positions of level 0; later levels are relaxed around
// points stored in rank order, so they differ in rounding.
void levels(const Options& o) {
  ExactEngine engine;
  std::map<SweepKey, SweepWorst> worst;
  std::printf("| set | n0 | order | seed | prefix per tile | level boundary | rho | LF | lattice peak | seamX | C_LF | C_mid |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& kind : o.kinds) {
    for (std::size_t n : o.points) {
      for (const std::string& strategy : o.strategies) {
        for (const std::string& order : o.rank_orders) {
          for (int s = 0; s < o.seeds; ++s) {
            const std::uint64_t seed = o.first_seed + static_cast<std::uint64_t>(s);
            WangOptions w = wang_options(o, kind, n, strategy, seed);
            w.level.rank_order = parse_wang_rank_order(order);
            TileSet set = relax_wang_tiles(engine, w);
            SeamCheck seams = check_seams(set);
            std::vector<std::size_t> boundaries;
            for (const SeamLevel& level : seams.levels) boundaries.push_back(level.points_per_tile);
            std::vector<std::size_t> counts = boundaries;
            for (std::size_t l = 1; l < boundaries.size(); ++l)
              for (int i = 1; i < o.prefixes; ++i)
                counts.push_back(boundaries[l - 1] + (boundaries[l] - boundaries[l - 1]) * static_cast<std::size_t>(i) /
                                                         static_cast<std::size_t>(o.prefixes));
            for (const std::size_t prefix : prefix_sweep(boundaries.back(), counts)) {
              const auto at = std::find(boundaries.begin(), boundaries.end(), prefix);
              const int level = at == boundaries.end() ? -1 : static_cast<int>(at - boundaries.begin());
              TilingMetrics m = plane_metrics(set, o.periods[0], derive_seed(seed, 1000), static_cast<std::uint32_t>(prefix));
              double seam = level >= 0 ? seams.levels[static_cast<std::size_t>(level)].cross_relative() : 0.0;
              std::printf("| %s | %zu | %s | %llu | %zu | %s | %.3f | %s | %s | %s | %s | %s |\n", kind.c_str(), n,
                          order.c_str(), static_cast<unsigned long long>(seed), prefix,
                          level >= 0 ? std::to_string(level).c_str() : "", m.rho,
                          measure_text(m.low_frequency, 4).c_str(), measure_text(m.lattice_peak, 1).c_str(),
                          level >= 0 ? std::to_string(seam).substr(0, 5).c_str() : "",
                          measure_text(m.coherence_low, 4).c_str(), measure_text(m.coherence_mid, 1).c_str());
              std::fflush(stdout);
              SweepWorst& row = worst[{kind, strategy, n, order, prefix}];
              row.rho = std::min(row.rho, m.rho);
              row.lf = std::fmax(row.lf, m.low_frequency);
              row.lattice = std::fmax(row.lattice, m.lattice_peak);
              row.c_lf = std::fmax(row.c_lf, m.coherence_low);
            }
          }
        }
      }
    }
  }
  std::printf("\nworst over %d seeds:\n\n| set | strategy | n0 | order | prefix per tile | rho | LF | lattice peak | C_LF |\n"
              "|---|---|---|---|---|---|---|---|---|\n", o.seeds);
  for (const auto& [key, w] : worst) {
    const auto& [kind, strategy, n, order, prefix] = key;
    std::printf("| %s | %s | %zu | %s | %zu | %.3f | %s | %s | %s |\n", kind.c_str(), strategy.c_str(), n,
                order.c_str(), prefix, w.rho, measure_text(w.lf, 4).c_str(), measure_text(w.lattice, 1).c_str(),
                measure_text(w.c_lf, 3).c_str());
  }
  if (!o.plot.empty()) plot_sweep(o, worst);
}

}  // namespace
}  // namespace bluetile::bench

int main(int argc, char** argv) try {
  using namespace bluetile;
  using namespace bluetile::bench;
  Options o;
  CLI::App app{"Build time and quality of Wang-tile sample sets over seeds. quality: the seam check and the plane "
               "metrics of seeded torus tilings, per seed, worst and mean; time: the build time with each engine, "
               "interleaved repeats; levels: the prefix sweep of a hierarchical set, rank orders side by side",
               "bluetile_wang_bench"};
  add_name(app, "mode", o.mode, {"quality", "time", "levels"}, "quality | time | levels");
  add_names(app, "--set", o.kinds, {"wang8", "wang16", "corner16", "corner81"}, "Tile set kinds");
  add_integers(app, "--points", o.points, std::size_t{1}, kMaxWangPoints, "Points per tile (level 0)");
  add_names(app, "--strategy", o.strategies, {"exact", "instances", "rounds"}, "Strategies");
  add_integers(app, "--period", o.periods, kMinWangPeriod, kMaxWangPeriod, "Torus tiling sizes M for the plane metrics");
  add_integer(app, "--seeds", o.seeds, 1, kMaxRepeats, "Seeds per configuration");
  add_integer(app, "--first-seed", o.first_seed, std::uint64_t{0}, kMaxSeed, "First seed");
  add_integer(app, "--iterations", o.iterations, 0, kMaxWangIterations, "Constrained iterations per level");
  add_integer(app, "--warm", o.warm, 0, kMaxWangIterations, "Warm-start iterations per level");
  add_real(app, "--margin", o.margin, {0.0, kMaxEdgeMargin}, "Edge margin (tile units)");
  add_integer(app, "--lattice-steps", o.refine.lattice_iterations, 0, kMaxLatticeSteps,
              "Lattice decorrelation steps after each level (0: none)");
  add_integer(app, "--lattice-steps-per-iteration", o.refine.lattice_steps_per_iteration, 0, kMaxLatticeStepsPerIteration,
              "Lattice steps after each constrained iteration of the second half (0: none)");
  add_real(app, "--lattice-step", o.refine.lattice_step, {kMinLatticeStep, kMaxLatticeStep},
           "Largest move of a lattice step, in hexagonal spacings");
  add_integer(app, "--seam-steps", o.refine.seam_iterations, 0, kMaxSeamSteps, "Seam spacing steps after each level (0: none)");
  add_real(app, "--seam-spacing", o.refine.seam_spacing, {kMinSeamSpacing, kMaxSeamSpacing},
           "Seam spacing of level 0, in hexagonal spacings");
  add_real(app, "--level-seam-spacing", o.refine.later_seam_spacing, {kMinSeamSpacing, kMaxSeamSpacing},
           "Seam spacing of levels 1 and up, in hexagonal spacings");
  add_integer(app, "--filled-lattice-steps", o.refine.filled_lattice_steps, 0, kMaxLatticeSteps,
              "fill: lattice steps on each filled level (0: none)");
  add_real(app, "--filled-lattice-spacing", o.refine.filled_lattice_spacing, {kMinSeamSpacing, kMaxSeamSpacing},
           "fill: the spacing those steps keep, in hexagonal spacings");
  add_integer(app, "--filled-lattice-up-to", o.refine.filled_lattice_up_to, std::size_t{1}, kMaxWangPoints,
              "fill: lattice steps only on filled levels of at most this many points per tile");
  add_integer(app, "--levels", o.levels, 1, kMaxWangLevels, "Levels");
  add_real(app, "--ratio", o.ratio, {1.0, kMaxWangRatio, true, false}, "Level ratio");
  auto* prefixes = add_integer(app, "--prefixes", o.prefixes, 0, kMaxRepeats,
                               "levels mode: also this many evenly spaced steps between level boundaries");
  auto* rank_orders = add_names(app, "--rank-order", o.rank_orders, {"farthest", "voids", "fill"},
                                "levels mode: rank orders side by side");
  auto* repeats = add_integer(app, "--repeats", o.repeats, 1, kMaxRepeats, "time mode: interleaved repeats");
  auto* engines = add_names(app, "--engine", o.engines, {"exact", "raster"}, "time mode: engines side by side");
  auto* diagnose = app.add_flag("--diagnose", o.diagnose, "quality mode: split C_mid into tile crystallinity and coherence");
  auto* untiled = app.add_flag("--untiled", o.untiled, "quality mode: also untiled Lloyd at the same N");
  auto* untiled_iterations = add_integer(app, "--untiled-iterations", o.untiled_iterations, 0, kMaxIterations,
                                         "quality mode, with --untiled: iterations of the untiled reference");
  auto* plot = app.add_option("--plot", o.plot, "levels mode: the sweep's worst rho and LF against k, as SVG (or .png)");
  add_integer(app, "--threads", o.threads, 1, bench::kMaxThreads, "Threads")->default_str("all cores");
  if (!parse(app, argc, argv)) return 0;
  for (CLI::Option* option : {prefixes, rank_orders, plot}) check_given(option, o.mode == "levels", "only in levels mode");
  for (CLI::Option* option : {repeats, engines}) check_given(option, o.mode == "time", "only in time mode");
  for (CLI::Option* option : {diagnose, untiled}) check_given(option, o.mode == "quality", "only in quality mode");
  check_given(untiled_iterations, o.mode == "quality" && o.untiled, "only in quality mode with --untiled");
  if (o.threads > 0) set_thread_count(static_cast<std::size_t>(o.threads));
  for (const auto& [name, value] : machine_facts()) std::printf("%s: %s\n", name.c_str(), value.c_str());
  std::printf("\n");
  if (o.mode == "quality") quality(o);
  if (o.mode == "time") timing(o);
  if (o.mode == "levels") levels(o);
  return 0;
} catch (...) {
  return bluetile::bench::exit_status("bluetile_wang_bench");
}
