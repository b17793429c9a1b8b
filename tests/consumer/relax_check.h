// Shared by the consumer projects: relaxes 256 random points with the exact engine and checks
// that Lloyd did its work (numbers a broken link or a wrong header would not give).
#pragma once

#include <cstdio>
#include <cstdlib>
#include <vector>

#include <bluetile/analysis/nearest_neighbour.h>
#include <bluetile/core/rng.h>
#include <bluetile/relax/lloyd.h>
#include <bluetile/voronoi/exact_engine.h>

inline void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "consumer: check failed: %s\n", what);
    std::exit(1);
  }
}

// The relaxed scene; its minimum nearest-neighbour distance, in hexagonal spacings, has to rise
// from a random start's (~0.05) to a relaxed set's (> 0.6, the paper's table).
inline bluetile::Scene relaxed_scene() {
  bluetile::Rng rng(7);
  std::vector<bluetile::Point> points(256);
  for (bluetile::Point& p : points) p = rng.point(bluetile::Domain{});
  bluetile::Scene scene = bluetile::make_scene(points);
  bluetile::ExactEngine engine;
  bluetile::LloydOptions options;
  options.iterations = 40;
  options.keep_history = true;
  bluetile::LloydResult result = bluetile::relax_lloyd(engine, scene, options);
  check(result.history.size() == 40, "40 iterations ran");
  check(result.history.back().energy < result.history.front().energy, "Lloyd energy fell");
  bluetile::NearestNeighbourStats nn = bluetile::nearest_neighbour_stats(scene.sites);
  std::printf("consumer: min nearest-neighbour distance %.3f hexagonal spacings\n", nn.min / nn.hexagonal_spacing);
  check(nn.min / nn.hexagonal_spacing > 0.6, "relaxed points are well spread");
  return scene;
}
