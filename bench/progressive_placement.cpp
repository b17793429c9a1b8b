// Which start relaxes a new level faster: uniform random (the paper) or best-candidate gaps?
// For base sets of N relaxed points plus N new ones, prints after K iterations the mean
// distance of the new points to their exact centroids (with the base fixed in the diagram) and
// the minimum nearest-neighbour distance over all points in hexagonal-spacing units, averaged
// over seeds. Usage: bluetile_progressive_bench [N] [seeds]
#include <cstdio>
#include <cstdlib>

#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/core/rng.h"
#include "bluetile/relax/progressive.h"
#include "bluetile/voronoi/exact_engine.h"

using namespace bluetile;

int main(int argc, char** argv) {
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
