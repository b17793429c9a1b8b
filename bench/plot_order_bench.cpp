// Pen-plotter order of N uniform dots (sampling/plot_order.h): time, and the pen-up travel of the
// greedy path and after 2-opt, both over the random-tour constant 0.7124 sqrt(N) (Beardwood,
// Halton, Hammersley 1959; Applegate et al. 2006). Usage: bluetile_plot_order_bench [N...]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bluetile/core/rng.h"
#include "bench_args.h"
#include "bluetile/sampling/plot_order.h"

using namespace bluetile;

int main(int argc, char** argv) try {
  CLI::App app{"Pen-plotter order of N uniform dots: time, and the pen-up travel of the greedy path and after 2-opt, "
               "both over the random-tour constant 0.7124 sqrt(N)",
               "bluetile_plot_order_bench"};
  std::vector<std::size_t> sizes = {1000, 10000, 100000};
  bench::add_integers(app, "N", sizes, 1LL, bench::kMaxCount, "Numbers of dots, one table row each");
  if (!bench::parse(app, argc, argv)) return 0;
  std::printf("| dots | time (s) | greedy / 0.7124 sqrt(N) | after 2-opt / 0.7124 sqrt(N) |\n|---|---|---|---|\n");
  for (std::size_t n : sizes) {
    Rng rng(1);
    std::vector<Point> dots(n);
    for (Point& p : dots) p = {rng.uniform(), rng.uniform()};
    const auto start = std::chrono::steady_clock::now();
    const PlotOrder plot = plot_order(dots);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double tour = 0.7124 * std::sqrt(static_cast<double>(n));
    std::printf("| %zu | %.3f | %.3f | %.3f |\n", n, seconds, plot.greedy_travel / tour, plot.travel / tour);
  }
  return 0;
} catch (...) {
  return bench::exit_status("bluetile_plot_order_bench");
}
