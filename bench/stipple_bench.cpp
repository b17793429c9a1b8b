// What weighting costs: a stipple (weighted Lloyd in a bounded domain, density from an image)
// against unweighted relaxation of the same N on the same engine, K iterations each, repeats
// interleaved so that the machine's drift hits both alike. Prints a markdown table.
// Usage: bluetile_stipple_bench [--image PNG] [--texels 1024] [--counts 10000,100000]
//        [--iterations 50] [--repeats 3] [--engines exact,raster]
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bluetile/core/rng.h"
#include "bluetile/io/density_map.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/sampling/density_sampling.h"
#include "bluetile/voronoi/exact_engine.h"
#if BLUETILE_BENCH_RASTER
#include "bluetile/raster/raster_engine.h"
#endif

using namespace bluetile;

namespace {

// The picture resampled to texels x texels by bilinear lookup, so every run sees the same grid
// size whatever the source; without a picture, a procedural one (a dark disc and a ramp).
DensityGrid bench_density(const std::string& image, int texels) {
  DensityGrid source;
  if (!image.empty()) {
    DensityTransfer dark_is_dense;
    dark_is_dense.invert = true;
    source = load_density_map(image, dark_is_dense);
  }
  DensityGrid grid(texels, texels);
  for (int j = 0; j < texels; ++j) {
    for (int i = 0; i < texels; ++i) {
      const Point uv{(i + 0.5) / texels, (j + 0.5) / texels};
      if (!source.empty()) {
        grid.at(i, j) = static_cast<float>(sample_bilinear(source, uv));
      } else {
        const double r = std::hypot(uv.x - 0.4, uv.y - 0.55);
        grid.at(i, j) = static_cast<float>(r < 0.25 ? 0.9 : 0.05 + 0.5 * uv.x);
      }
    }
  }
  return grid;
}

std::unique_ptr<CentroidEngine> make(const std::string& name) {
  if (name == "raster") {
#if BLUETILE_BENCH_RASTER
    return std::make_unique<RasterEngine>(RasterOptions{});
#else
    throw std::runtime_error("this build has no raster engine");
#endif
  }
  return std::make_unique<ExactEngine>();
}

// Wall-clock and CPU seconds (all threads) of one run. On a shared machine the CPU time is the
// steadier figure; both are reported.
struct Timing {
  double wall = 0.0, cpu = 0.0;
};

// Whether the runs ask for the Lloyd energy (--no-energy: not, as bluetile stipple and relax run
// without --log or -v).
bool g_energy = true;

Timing time_run(CentroidEngine& engine, Scene scene, int iterations, Scene* relaxed = nullptr) {
  LloydOptions options;
  options.iterations = iterations;
  options.energy = g_energy;
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  relax_lloyd(engine, scene, options);
  const Timing t{std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                 static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC};
  if (relaxed) *relaxed = std::move(scene);
  return t;
}

// `iterations` centroid computations of one fixed scene: what an iteration costs once the
// sites are where the stipple leaves them, with and without the density (site motion excluded).
Timing time_measure(CentroidEngine& engine, Scene scene, int iterations) {
  scene.second_moments = g_energy;
  std::vector<SceneCells> cells(1);
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  for (int k = 0; k < iterations; ++k) engine.compute(std::span<const Scene>(&scene, 1), cells);
  return {std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
          static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC};
}

Timing median(std::vector<Timing> v) {
  auto middle = [&](auto field) {
    std::vector<double> x;
    for (const Timing& t : v) x.push_back(t.*field);
    std::sort(x.begin(), x.end());
    return x[x.size() / 2];
  };
  return {middle(&Timing::wall), middle(&Timing::cpu)};
}

}  // namespace

int main(int argc, char** argv) try {
  CLI::App app{"What weighting costs: a stipple (weighted Lloyd in a bounded domain, density from a picture) against "
               "unweighted relaxation of the same N on the same engine, K iterations each, repeats interleaved",
               "bluetile_stipple_bench"};
  std::string image;
  int texels = 1024, iterations = 50, repeats = 3;
  std::vector<long long> counts = {10000, 100000};
  std::vector<std::string> engines = {"exact", "raster"};
  app.add_option("--image", image, "Picture whose darkness is the density (default: a procedural one)");
  bench::add_integer(app, "--texels", texels, 1, 16384, "Density grid side after resampling");
  bench::add_integers(app, "--counts", counts, 1LL, bench::kMaxCount, "Point counts")->delimiter(',');
  bench::add_integer(app, "--iterations", iterations, 1, bench::kMaxIterations, "Lloyd iterations per run");
  bench::add_integer(app, "--repeats", repeats, 1, bench::kMaxRepeats, "Interleaved repeats (the median is reported)");
  bench::add_names(app, "--engines", engines, {"exact", "raster"}, "Engines")->delimiter(',');
  bool no_energy = false;
  app.add_flag("--no-energy", no_energy,
               "Ask for no Lloyd energy (no second moments), as bluetile stipple and relax without --log or -v");
  if (!bench::parse(app, argc, argv)) return 0;
  g_energy = !no_energy;

  auto density = std::make_shared<DensityGrid>(bench_density(image, texels));
  std::printf("density %d x %d texels from %s, %d iterations, median of %d interleaved repeats, energy %s\n\n", texels,
              texels, image.empty() ? "a procedural picture" : image.c_str(), iterations, repeats,
              g_energy ? "asked" : "not asked");
  std::printf("Seconds for the whole run, wall clock (CPU time of all threads in brackets).\n\n");
  std::printf("| engine | N | stipple (weighted, bounded) | unweighted bounded | unweighted periodic | "
              "stipple / unweighted bounded | stipple / unweighted periodic | stipple's sites: weighted / unweighted |\n"
              "|---|---|---|---|---|---|---|---|\n");
  for (const std::string& name : engines) {
    for (long long n : counts) {
      const auto count = static_cast<std::size_t>(n);
      // Each run's natural start: density-proportional for the stipple, uniform for the others.
      Rng stipple_rng(derive_seed(1, 0));
      Scene stipple = make_scene(sample_density(*density, Domain{}, count, stipple_rng));
      stipple.boundary = Boundary::bounded;
      stipple.density = density;
      Rng plain_rng(derive_seed(1, 0));
      std::vector<Point> uniform(count);
      for (Point& p : uniform) p = plain_rng.point(Domain{});
      Scene bounded = make_scene(uniform);
      bounded.boundary = Boundary::bounded;
      Scene periodic = make_scene(uniform);
      std::vector<Timing> t_stipple, t_bounded, t_periodic, t_weighted_sites, t_unweighted_sites;
      try {
        auto engine = make(name);
        for (int r = 0; r < repeats; ++r) {
          Scene relaxed;
          t_stipple.push_back(time_run(*engine, stipple, iterations, &relaxed));
          t_bounded.push_back(time_run(*engine, bounded, iterations));
          t_periodic.push_back(time_run(*engine, periodic, iterations));
          // The same relaxed stipple sites measured with and without the density: the weighting's
          // own cost, apart from what the sites' uneven spread costs the cell search.
          t_weighted_sites.push_back(time_measure(*engine, relaxed, iterations));
          relaxed.density.reset();
          t_unweighted_sites.push_back(time_measure(*engine, relaxed, iterations));
        }
      } catch (const std::exception& e) {
        std::printf("| %s | %lld | %s | | | | | |\n", name.c_str(), n, e.what());
        continue;
      }
      const Timing s = median(t_stipple), b = median(t_bounded), p = median(t_periodic);
      const Timing ws = median(t_weighted_sites), us = median(t_unweighted_sites);
      std::printf("| %s | %lld | %.3f (%.3f) | %.3f (%.3f) | %.3f (%.3f) | %.2f (%.2f) | %.2f (%.2f) | %.2f (%.2f) |\n",
                  name.c_str(), n, s.wall, s.cpu, b.wall, b.cpu, p.wall, p.cpu, s.wall / b.wall, s.cpu / b.cpu,
                  s.wall / p.wall, s.cpu / p.cpu, ws.wall / us.wall, ws.cpu / us.cpu);
      std::fflush(stdout);
    }
  }
  return 0;
} catch (...) {
  return bench::exit_status("bluetile_stipple_bench");
}
