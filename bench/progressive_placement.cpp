// Which start relaxes a new level faster: uniform random (the paper) or best-candidate gaps?
// For base sets of N relaxed points plus N new ones, prints after K iterations the mean
// distance of the new points to their exact centroids (with the base fixed in the diagram) and
// the minimum nearest-neighbour distance over all points in hexagonal-spacing units, averaged
// over seeds. Usage: bluetile_progressive_bench [N] [seeds]; --help lists the modes.
//
// `bluetile_progressive_bench sets K N`: K hierarchies of 4 levels of N points each (as
// `bluetile progressive --count N --sets K --engine exact`), built one set after another with one
// exact engine and in parallel with an engine per worker, side by side in one run; checks that
// both give the same bits.
//
// `bluetile_progressive_bench prefixes N seeds [sigma]`: the prefix sweep (docs/RESULTS.md) of untiled
// progressive sets of N points (k at 1/16 ... 1 of N and every level boundary), rho and LF worst
// (and mean) over seeds 1..seeds, for the placement, voids and fill rank orders side by side, then
// the worst over every prefix from N/16 on in steps of 5 % ("dense"), built as
// `bluetile progressive --count N/16 --ratio 2 --levels 5 --engine exact`, as `--count N/16 --ratio 4
// --levels 3` and as `--count 1 --ratio 2 --levels log2(N)+1` (one point, then doubling). A fourth argument sets the
// void order's kernel width in hexagonal spacings (default kVoidSigmaFactor).
//
// `bluetile_progressive_bench anchors N seeds`: the same sweep for ranked tables from published
// samplers (ranked_samplers.h: Owen-scrambled Sobol', Mitchell's best candidate with 10 k
// candidates for point k) beside the fill order, seeds 1..seeds.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "bench_args.h"
#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/analysis/tiling_metrics.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/text.h"
#include "bluetile/relax/progressive.h"
#include "bluetile/relax/void_order.h"
#include "bluetile/relax/wang_relax.h"  // kMinVoidSigma, kMaxVoidSigma
#include "bluetile/voronoi/exact_engine.h"
#include "ranked_samplers.h"

using namespace bluetile;

namespace {

int compare_parallel_sets(std::size_t sets, std::size_t n) {
  ExactEngine engine;
  HierarchyOptions options;
  options.count = n;
  options.seed = 1;
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  std::vector<PointSet> one_by_one;
  for (std::size_t k = 0; k < sets; ++k) {
    HierarchyOptions single = options;
    single.seed = options.seed + k;
    one_by_one.push_back(add_levels(engine, PointSet{}, single));
  }
  const auto middle = Clock::now();
  std::vector<PointSet> parallel =
      add_levels([] { return std::make_unique<ExactEngine>(); }, std::vector<PointSet>(sets), options);
  const auto stop = Clock::now();
  bool same = parallel.size() == one_by_one.size();
  for (std::size_t k = 0; same && k < sets; ++k) {
    same = parallel[k].levels == one_by_one[k].levels && parallel[k].points.size() == one_by_one[k].points.size();
    for (std::size_t i = 0; same && i < parallel[k].points.size(); ++i)
      same = parallel[k].points[i].x == one_by_one[k].points[i].x && parallel[k].points[i].y == one_by_one[k].points[i].y;
  }
  const double sequential_s = std::chrono::duration<double>(middle - start).count();
  const double parallel_s = std::chrono::duration<double>(stop - middle).count();
  std::printf("| %zu x %zu, 4 levels, 80 iterations | %zu | %.3f | %.3f | %.2fx | %s |\n", sets, n, thread_count(),
              sequential_s, parallel_s, sequential_s / parallel_s, same ? "same bits" : "DIFFER");
  return same ? 0 : 1;
}

// LF is NaN for prefixes of at most 4 points (tiling_metrics.h): worst_lf is the largest defined
// one (std::fmax leaves NaN out), NaN while there is none, and the tables print "-" for it.
struct SweepRow {
  double worst_rho = HUGE_VAL, mean_rho = 0.0, worst_lf = std::numeric_limits<double>::quiet_NaN(), mean_lf = 0.0;
};

// rho and LF of the first k points of every set, for every k of the sweep.
std::vector<SweepRow> measure_sweep(const std::vector<PointSet>& sets, const std::vector<std::size_t>& sweep) {
  std::vector<SweepRow> rows(sweep.size());
  for (const PointSet& set : sets) {
    for (std::size_t i = 0; i < sweep.size(); ++i) {
      const std::span<const Point> prefix(set.points.data(), sweep[i]);
      const TilingMetrics m = measure_tiling(prefix, 0, 0);
      rows[i].worst_rho = std::min(rows[i].worst_rho, m.rho);
      rows[i].worst_lf = std::fmax(rows[i].worst_lf, m.low_frequency);
      rows[i].mean_rho += m.rho / static_cast<double>(sets.size());
      rows[i].mean_lf += m.low_frequency / static_cast<double>(sets.size());
    }
  }
  return rows;
}

void print_sweep_table(const std::vector<std::string>& names, const std::vector<std::size_t>& sweep,
                       const std::vector<std::vector<SweepRow>>& results, const std::vector<std::size_t>& dense,
                       const std::vector<std::vector<SweepRow>>& dense_results) {
  std::printf("| k | k / N |");
  for (const std::string& name : names) std::printf(" %s rho | %s LF |", name.c_str(), name.c_str());
  std::printf("\n|---|---|");
  for (std::size_t i = 0; i < names.size(); ++i) std::printf("---|---|");
  std::printf("\n");
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    std::printf("| %zu | %.4f |", sweep[i], static_cast<double>(sweep[i]) / static_cast<double>(sweep.back()));
    for (const std::vector<SweepRow>& r : results)
      std::printf(" %.3f / %.3f | %s / %s |", r[i].worst_rho, r[i].mean_rho, measure_text(r[i].worst_lf, 4).c_str(),
                  measure_text(r[i].mean_lf, 4).c_str());
    std::printf("\n");
  }
  std::printf("| dense (%zu prefixes, worst) | |", dense.size());
  for (const std::vector<SweepRow>& r : dense_results) {
    SweepRow w;
    for (const SweepRow& row : r) w.worst_rho = std::min(w.worst_rho, row.worst_rho), w.worst_lf = std::fmax(w.worst_lf, row.worst_lf);
    std::printf(" %.3f | %s |", w.worst_rho, measure_text(w.worst_lf, 4).c_str());
  }
  std::printf("\n");
}

int compare_prefixes(std::size_t n, std::size_t seeds, double sigma) {
  struct Construction {
    const char* name;
    std::size_t count;
    double ratio;
    int levels;
  };
  int doublings = 0;
  while ((std::size_t{1} << doublings) < n) ++doublings;
  // Ratio 4 relaxes three new points for each fixed one, which leaves them freer to settle than
  // ratio 2's one for one: its boundaries are far closer to a set relaxed whole (docs/RESULTS.md).
  const Construction constructions[] = {{"N/16, ratio 2, 5 levels", n / 16, 2.0, 5},
                                        {"N/16, ratio 4, 3 levels", n / 16, 4.0, 3},
                                        {"1, ratio 2", 1, 2.0, doublings + 1}};
  using Clock = std::chrono::steady_clock;
  const ProgressiveOrder orders[] = {ProgressiveOrder::placement, ProgressiveOrder::voids, ProgressiveOrder::fill};
  for (const Construction& c : constructions) {
    std::vector<std::vector<SweepRow>> results, dense_results;
    std::vector<double> seconds;
    std::vector<std::size_t> sweep, dense;
    for (ProgressiveOrder order : orders) {
      HierarchyOptions options;
      options.count = c.count;
      options.ratio = c.ratio;
      options.levels = c.levels;
      options.seed = 1;
      options.rank_order = order;
      options.void_sigma = sigma;
      const auto start = Clock::now();
      const std::vector<PointSet> sets =
          add_levels([] { return std::make_unique<ExactEngine>(); }, std::vector<PointSet>(seeds), options);
      seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
      std::vector<std::size_t> boundaries;
      for (std::size_t i = 1; i < sets[0].levels.size(); ++i)
        if (sets[0].levels[i] != sets[0].levels[i - 1]) boundaries.push_back(i);
      sweep = prefix_sweep(sets[0].points.size(), boundaries);
      sweep.erase(std::remove_if(sweep.begin(), sweep.end(), [](std::size_t k) { return k < 2; }), sweep.end());
      results.push_back(measure_sweep(sets, sweep));
      dense.clear();
      for (double k = static_cast<double>(sweep.back()) / 16.0; k < static_cast<double>(sweep.back()); k *= 1.05)
        dense.push_back(static_cast<std::size_t>(std::lround(k)));
      dense_results.push_back(measure_sweep(sets, dense));
    }
    std::printf("\n%s (%zu points), worst / mean of seeds 1-%zu; built in %.2f s, %.2f s and %.2f s (%zu threads), sigma %.2f\n",
                c.name, sweep.back(), seeds, seconds[0], seconds[1], seconds[2], thread_count(), sigma);
    print_sweep_table({"placement", "voids", "fill"}, sweep, results, dense, dense_results);
  }
  return 0;
}

int compare_anchors(std::size_t n, std::size_t seeds) {
  // N is a multiple of 16, seeds at least 1 (checked in main).
  using Clock = std::chrono::steady_clock;
  const std::size_t boundaries[] = {n / 16, n / 8, n / 4, n / 2};
  const std::vector<std::size_t> sweep = prefix_sweep(n, boundaries);
  std::vector<std::size_t> dense;
  for (double k = static_cast<double>(n) / 16.0; k < static_cast<double>(n); k *= 1.05)
    dense.push_back(static_cast<std::size_t>(std::lround(k)));
  const std::vector<std::string> names = {"Owen-Sobol", "best candidate", "fill"};
  std::vector<std::vector<PointSet>> sets(names.size());
  std::vector<double> seconds;
  for (std::size_t which = 0; which < names.size(); ++which) {
    const auto start = Clock::now();
    if (which == 2) {
      HierarchyOptions options;
      options.count = n / 16;
      options.ratio = 2.0;
      options.levels = 5;
      options.seed = 1;
      options.rank_order = ProgressiveOrder::fill;
      sets[which] = add_levels([] { return std::make_unique<ExactEngine>(); }, std::vector<PointSet>(seeds), options);
    } else {
      for (std::size_t s = 1; s <= seeds; ++s) {
        PointSet set;
        set.points = which == 0 ? bench::owen_sobol_points(n, s) : bench::best_candidate_points(n, s, 10);
        sets[which].push_back(std::move(set));
      }
    }
    seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }
  std::vector<std::vector<SweepRow>> results, dense_results;
  for (const std::vector<PointSet>& s : sets) {
    results.push_back(measure_sweep(s, sweep));
    dense_results.push_back(measure_sweep(s, dense));
  }
  std::printf("%zu points, worst / mean of seeds 1-%zu; made in %.2f s, %.2f s and %.2f s\n", n, seeds, seconds[0],
              seconds[1], seconds[2]);
  print_sweep_table(names, sweep, results, dense, dense_results);
  return 0;
}

}  // namespace

int main(int argc, char** argv) try {
  CLI::App app{"Which start relaxes a new level faster, uniform random (the paper) or best-candidate gaps: for base sets "
               "of N relaxed points plus N new ones, the mean distance of the new points to their exact centroids and "
               "the minimum nearest-neighbour distance after K iterations, averaged over seeds. Or one of the modes "
               "below",
               "bluetile_progressive_bench"};
  std::size_t n = 1000;
  int seeds = 5;
  // The first word is N or a mode: a word that is neither is an unknown mode.
  app.add_option_function<std::string>(
         "N",
         [&n](const std::string& text) {
           const bool number = !text.empty() && std::string_view("0123456789+-.").find(text[0]) != std::string_view::npos;
           if (!number)
             throw bench::bad_argument("mode", text, "unknown mode; expected sets, prefixes, anchors, or N (a point count)");
           n = bench::integer_argument<std::size_t>("N", text, 1, bench::kMaxCount);
         },
         "Base points, and as many new ones")
      ->type_name("INT")
      ->default_str(std::to_string(n));
  bench::add_integer(app, "seeds", seeds, 1, bench::kMaxRepeats, "Seeds 0 .. seeds-1 to average over");

  CLI::App* sets_mode = app.add_subcommand(
      "sets", "K hierarchies of 4 levels of N points each (as bluetile progressive --count N --sets K --engine exact), "
              "one set after another and in parallel, side by side; checks that both give the same bits");
  std::size_t sets = 256, set_points = 64;
  bench::add_integer(*sets_mode, "K", sets, 1LL, 10'000'000LL, "Hierarchies");
  bench::add_integer(*sets_mode, "N", set_points, 1LL, bench::kMaxCount, "Points of each level");

  CLI::App* prefixes_mode = app.add_subcommand(
      "prefixes", "The prefix sweep (docs/RESULTS.md) of untiled progressive sets of N points built three ways (N/16 "
                  "at ratio 2 and at ratio 4, and one point doubling), rho and LF worst and mean over seeds 1..seeds, "
                  "for the placement, voids and fill rank orders side by side");
  std::size_t prefix_points = 4096, prefix_seeds = 4;
  double sigma = kVoidSigmaFactor;
  // 32 points at least: two of the constructions start from N/16, and the sweep measures prefixes
  // from N/16 on, which need 2 points.
  bench::add_integer(*prefixes_mode, "N", prefix_points, 32LL, bench::kMaxCount, "Points of each set");
  bench::add_integer(*prefixes_mode, "seeds", prefix_seeds, 1LL, static_cast<long long>(bench::kMaxRepeats), "Seeds");
  bench::add_real(*prefixes_mode, "sigma", sigma, {kMinVoidSigma, kMaxVoidSigma},
                  "The void order's kernel width in hexagonal spacings");

  CLI::App* anchors_mode = app.add_subcommand(
      "anchors", "The same sweep for ranked tables of published samplers (Owen-scrambled Sobol', Mitchell's best "
                 "candidate) beside the fill order, seeds 1..seeds");
  std::size_t anchor_points = 4096, anchor_seeds = 4;
  // The fill's five levels from N/16 at ratio 2 make N points only for a multiple of 16; 32 at least
  // for prefixes of 2 points from N/16 on.
  auto* anchor_n = bench::add_integer(*anchors_mode, "N", anchor_points, 32LL, bench::kMaxCount,
                                      "Points of each set, a multiple of 16");
  bench::add_integer(*anchors_mode, "seeds", anchor_seeds, 1LL, static_cast<long long>(bench::kMaxRepeats), "Seeds");
  app.require_subcommand(0, 1);
  if (!bench::parse(app, argc, argv)) return 0;

  if (anchors_mode->parsed()) {
    bench::check_given(anchor_n, anchor_points % 16 == 0, "expected a multiple of 16");
    return compare_anchors(anchor_points, anchor_seeds);
  }
  if (prefixes_mode->parsed()) return compare_prefixes(prefix_points, prefix_seeds, sigma);
  if (sets_mode->parsed()) return compare_parallel_sets(sets, set_points);
  const int checkpoints[] = {0, 5, 10, 20, 40, 80};
  ExactEngine engine;
  std::printf("N=%zu base + %zu new, %d seeds, exact engine\n", n, n, seeds);
  std::printf("| placement | iterations | mean distance to centroid (x hex spacing) | min NN (x hex spacing) |\n");
  std::printf("|---|---|---|---|\n");
  for (Placement placement : {Placement::random, Placement::gaps}) {
    for (int k : checkpoints) {
      double centroid_distance = 0.0, min_nn = 0.0;
      for (int s = 0; s < seeds; ++s) {
        LevelOptions base_options;
        base_options.add = n;
        base_options.seed = derive_seed(static_cast<std::uint64_t>(s), 0);
        base_options.placement = Placement::random;
        PointSet base = add_level(engine, PointSet{}, base_options);
        LevelOptions level;
        level.add = n;
        level.iterations = k;
        level.seed = derive_seed(static_cast<std::uint64_t>(s), 1);
        level.placement = placement;
        PointSet all = add_level(engine, base, level);
        Scene scene = make_scene(all.points);
        scene.wanted_begin = n;
        SceneCells cells = engine.compute(scene);
        double sum = 0.0;
        for (std::size_t i = 0; i < n; ++i) sum += torus_distance(all.points[n + i], cells.cells[i].centroid, scene.domain);
        NearestNeighbourStats nn = nearest_neighbour_stats(all.points);
        centroid_distance += sum / static_cast<double>(n) / nn.hexagonal_spacing;
        min_nn += nn.min / nn.hexagonal_spacing;
      }
      std::printf("| %s | %d | %.4f | %.3f |\n", placement == Placement::random ? "random" : "gaps", k,
                  centroid_distance / seeds, min_nn / seeds);
    }
  }
  return 0;
} catch (...) {
  return bench::exit_status("bluetile_progressive_bench");
}
