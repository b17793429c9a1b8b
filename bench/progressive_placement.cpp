// Which start relaxes a new level faster: uniform random (the paper) or best-candidate gaps?
// For base sets of N relaxed points plus N new ones, prints after K iterations the mean
// distance of the new points to their exact centroids (with the base fixed in the diagram) and
// the minimum nearest-neighbour distance over all points in hexagonal-spacing units, averaged
// over seeds. Usage: bluetile_progressive_bench [N] [seeds]
//
// `bluetile_progressive_bench sets K N`: K hierarchies of 4 levels of N points each (as
// `bluetile progressive --count N --sets K --engine exact`), built one set after another with one
// exact engine and in parallel with an engine per worker, side by side in one run; checks that
// both give the same bits.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/relax/progressive.h"
#include "bluetile/voronoi/exact_engine.h"

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

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "sets") == 0) {
    const std::size_t sets = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 256;
    const std::size_t n = argc > 3 ? std::strtoul(argv[3], nullptr, 10) : 64;
    return compare_parallel_sets(sets, n);
  }
  const std::size_t n = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 1000;
  const int seeds = argc > 2 ? std::atoi(argv[2]) : 5;
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
}
