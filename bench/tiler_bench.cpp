// bluetile_tiler_bench: the plane tiler's throughput and density control (figures in
// docs/BENCHMARKS.md and docs/RESULTS.md with the command that made them).
//   throughput  uniform points into memory (one big array, and cell by cell into a buffer that
//               stays in cache), density tests per second with a 1024^2 map, 10^6 stipples from
//               a 1024^2 image; one thread, interleaved repeats, the best and the median
//   ramp        density control on a linear ramp (density = x): count error over 16 vertical
//               strips, local rho (nearest-neighbour distance / d_hex at the target density)
#include <algorithm>
#include <chrono>
#include <cstring>
#include <ctime>
#include <memory>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "bench_args.h"
#include "bluetile/core/parallel.h"
#include "bluetile/tiling/default_tile_set.h"
#include "bluetile/tiling/tile_set_file.h"
#include "bluetile/tiling/density_thinning.h"
#include "bluetile/drawing/tiled_drawing.h"
#include "bluetile/tiling/tiler.h"

namespace bluetile {
namespace {

// CPU time of this thread: the machine is shared, and a wall clock would count the other
// processes' turns (wall figures are printed beside).
double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Timing {
  std::vector<double> runs;
  double best() const { return *std::min_element(runs.begin(), runs.end()); }
  double median() const {
    std::vector<double> r = runs;
    std::sort(r.begin(), r.end());
    return r[r.size() / 2];
  }
};

// A smooth 1024^2 test picture with the range of a photograph: soft blobs over a gradient,
// values in [0.02, 1].
std::vector<float> test_picture(int size) {
  std::vector<float> texels(static_cast<std::size_t>(size) * size);
  for (int r = 0; r < size; ++r)
    for (int c = 0; c < size; ++c) {
      double x = (c + 0.5) / size, y = (r + 0.5) / size;
      double v = 0.35 * x + 0.25 * (1.0 + std::sin(9.0 * x + 4.0 * y)) * (0.6 + 0.4 * std::cos(7.0 * y));
      v += 0.4 * std::exp(-((x - 0.3) * (x - 0.3) + (y - 0.6) * (y - 0.6)) / 0.01);
      texels[static_cast<std::size_t>(r) * size + c] = static_cast<float>(std::clamp(v, 0.02, 1.0));
    }
  return texels;
}

// Candidates the generator considers in a window: per cell, the ranks below the cell's upper
// bound; `lookups`: those of them between the lower and upper bound, which need the bilinear
// lookup (tiler.cpp, generate_cell).
double candidates(const Tiler& tiler, const Window& w, const Thinning& thinning, double* lookups) {
  *lookups = 0.0;
  CellRange range = tiler.cells(w);
  double total = 0.0;
  double s = tiler.tile_size();
  for (std::int64_t j = range.j0; j < range.j1; ++j)
    for (std::int64_t i = range.i0; i < range.i1; ++i) {
      double lo_x = static_cast<double>(i) * s, lo_y = static_cast<double>(j) * s;
      double hi_x = (static_cast<double>(i) + 1.0) * s, hi_y = (static_cast<double>(j) + 1.0) * s;
      if (hi_x < w.x0 || lo_x >= w.x1 || hi_y < w.y0 || lo_y >= w.y1) continue;
      double n = static_cast<double>(tiler.ranked_points(tiler.tile_at(i, j)).size());
      Thinning::Bounds b = thinning.fraction_bounds({lo_x, lo_y, hi_x, hi_y});
      double u = Thinning::dither(i, j, tiler.seed());
      double upper = std::clamp(std::ceil(b.max * n - u), 0.0, n);
      double lower = std::clamp(std::ceil(b.min * (1.0 - 1e-12) * n - u), 0.0, upper);
      total += upper;
      *lookups += upper - lower;
    }
  return total;
}

void throughput(const TileSet& set, int repeats) {
  set_thread_count(1);
  const double n = [&] {
    double total = 0.0;
    for (const Tile& t : set.tiles) total += static_cast<double>(t.points.size());
    return total / static_cast<double>(set.tiles.size());
  }();
  std::printf("tile set: %zu tiles, %.0f points per tile; one thread; %d interleaved repeats (best / median), times "
              "in thread CPU time\n\n",
              set.tiles.size(), n, repeats);

  // Uniform: about 2 x 10^7 points, the window 0.5 tile off the lattice so border cells are tested.
  Tiler tiler(set, 1, 1.0);
  const double side = std::sqrt(2e7 / n);
  Window uniform_window{0.5, 0.5, 0.5 + side, 0.5 + side};
  std::vector<Point> buffer(tiler.max_points_per_tile());

  // Density map: 1024^2 picture over a window; max density so that about 10^6 points are kept.
  const int size = 1024;
  std::vector<float> picture = test_picture(size);
  double mean = 0.0;
  for (float v : picture) mean += v;
  mean /= static_cast<double>(picture.size());
  Window stipple_window{0.0, 0.0, 1024.0, 1024.0};
  const double max_density = 1e6 / (stipple_window.area() * mean);
  Tiler stipple_tiler(set, 1, std::sqrt(n / max_density));
  Thinning stipple_map = Thinning::from_map(size, size, picture, stipple_window, 1.0);
  double stipple_lookups = 0.0, dense_lookups = 0.0;
  const double stipple_candidates = candidates(stipple_tiler, stipple_window, stipple_map, &stipple_lookups);

  // Density tests at a higher rate: the same picture at 10^7 kept points.
  Tiler dense_tiler(set, 1, std::sqrt(n / (10.0 * max_density)));
  const double dense_candidates = candidates(dense_tiler, stipple_window, stipple_map, &dense_lookups);

  // One array for every run, touched once before timing (new[] leaves Points uninitialised).
  const std::size_t bound = std::max({tiler.point_bound(uniform_window), stipple_tiler.point_bound(stipple_window),
                                      dense_tiler.point_bound(stipple_window)});
  std::unique_ptr<Point[]> big(new Point[bound]);
  std::memset(static_cast<void*>(big.get()), 0, bound * sizeof(Point));

  Timing into_array, cell_by_cell, stipples, dense, map_setup, memset_array;
  std::size_t array_points = 0, cell_points = 0, stipple_points = 0, dense_points = 0;
  for (int r = 0; r < repeats; ++r) {
    double t0 = thread_seconds();
    array_points = tiler.write_points(uniform_window, nullptr, big.get());
    into_array.runs.push_back(thread_seconds() - t0);

    // The memory's own speed on the same bytes: memset of the array the uniform run filled.
    t0 = thread_seconds();
    std::memset(static_cast<void*>(big.get()), r, array_points * sizeof(Point));
    memset_array.runs.push_back(thread_seconds() - t0);

    // Cell by cell: what an embedding renderer does with each cell's points.
    CellRange range = tiler.cells(uniform_window);
    double checksum = 0.0;
    cell_points = 0;
    t0 = thread_seconds();
    for (std::int64_t j = range.j0; j < range.j1; ++j)
      for (std::int64_t i = range.i0; i < range.i1; ++i) {
        CellPoints cell = tiler.cell_points(i, j, uniform_window, nullptr, buffer.data(), nullptr);
        cell_points += cell.positions.size();
        if (!cell.positions.empty()) checksum += cell.positions.back().x;
      }
    cell_by_cell.runs.push_back(thread_seconds() - t0);
    if (checksum == 0.125) std::printf(" ");  // keeps the loop from being optimised away

    t0 = thread_seconds();
    Thinning m = Thinning::from_map(size, size, picture, stipple_window, 1.0);
    map_setup.runs.push_back(thread_seconds() - t0);

    t0 = thread_seconds();
    stipple_points = stipple_tiler.write_points(stipple_window, &stipple_map, big.get());
    stipples.runs.push_back(thread_seconds() - t0);

    t0 = thread_seconds();
    dense_points = dense_tiler.write_points(stipple_window, &stipple_map, big.get());
    dense.runs.push_back(thread_seconds() - t0);
  }
  std::printf("| measurement | points | best | median | rate (best) | target |\n|---|---|---|---|---|---|\n");
  std::printf("| uniform, into one array | %zu | %.1f ms | %.1f ms | %.3g points/s | >= 3e8 |\n", array_points,
              1e3 * into_array.best(), 1e3 * into_array.median(), static_cast<double>(array_points) / into_array.best());
  std::printf("| memset of the same %.0f MB (the memory's speed) | - | %.1f ms | %.1f ms | %.3g bytes/s | - |\n",
              static_cast<double>(array_points * sizeof(Point)) / 1e6, 1e3 * memset_array.best(), 1e3 * memset_array.median(),
              static_cast<double>(array_points * sizeof(Point)) / memset_array.best());
  std::printf("| uniform, cell by cell into a cache-sized buffer | %zu | %.1f ms | %.1f ms | %.3g points/s | >= 3e8 |\n",
              cell_points, 1e3 * cell_by_cell.best(), 1e3 * cell_by_cell.median(), static_cast<double>(cell_points) / cell_by_cell.best());
  std::printf("| 1024^2 map, %.3g candidates (%.3g bilinear lookups) | %zu | %.1f ms | %.1f ms | %.3g candidates/s "
              "(%.3g lookups/s) | >= 1.5e8 |\n",
              dense_candidates, dense_lookups, dense_points, 1e3 * dense.best(), 1e3 * dense.median(),
              dense_candidates / dense.best(), dense_lookups / dense.best());
  std::printf("| 10^6 stipples from a 1024^2 map, %.3g candidates (%.3g lookups) | %zu | %.1f ms | %.1f ms | "
              "%.3g candidates/s | <= 20 ms |\n",
              stipple_candidates, stipple_lookups, stipple_points, 1e3 * stipples.best(), 1e3 * stipples.median(),
              stipple_candidates / stipples.best());
  std::printf("| map set-up (scale 1024^2 texels) | - | %.1f ms | %.1f ms | - | (in the 20 ms: %.1f ms) |\n",
              1e3 * map_setup.best(), 1e3 * map_setup.median(), 1e3 * (map_setup.best() + stipples.best()));
}

// Nearest-neighbour distance of every point (a bucket grid, exact).
std::vector<double> nearest_distances(const std::vector<Point>& points, const Window& w, double cell) {
  const auto columns = static_cast<std::int64_t>(std::ceil(w.width() / cell));
  const auto rows = static_cast<std::int64_t>(std::ceil(w.height() / cell));
  std::vector<std::vector<std::uint32_t>> grid(static_cast<std::size_t>(columns * rows));
  auto bucket = [&](Point p) {
    auto c = std::clamp<std::int64_t>(static_cast<std::int64_t>((p.x - w.x0) / cell), 0, columns - 1);
    auto r = std::clamp<std::int64_t>(static_cast<std::int64_t>((p.y - w.y0) / cell), 0, rows - 1);
    return std::pair<std::int64_t, std::int64_t>(c, r);
  };
  for (std::size_t k = 0; k < points.size(); ++k) {
    auto [c, r] = bucket(points[k]);
    grid[static_cast<std::size_t>(r * columns + c)].push_back(static_cast<std::uint32_t>(k));
  }
  std::vector<double> nearest(points.size(), std::numeric_limits<double>::infinity());
  for (std::size_t k = 0; k < points.size(); ++k) {
    auto [c, r] = bucket(points[k]);
    for (std::int64_t reach = 1;; ++reach) {
      double best = std::numeric_limits<double>::infinity();
      for (std::int64_t y = std::max<std::int64_t>(0, r - reach); y <= std::min(rows - 1, r + reach); ++y)
        for (std::int64_t x = std::max<std::int64_t>(0, c - reach); x <= std::min(columns - 1, c + reach); ++x)
          for (std::uint32_t q : grid[static_cast<std::size_t>(y * columns + x)])
            if (q != k) best = std::min(best, std::hypot(points[q].x - points[k].x, points[q].y - points[k].y));
      // Every point closer than reach * cell lies in the searched block.
      if (best <= static_cast<double>(reach) * cell || reach > columns + rows) {
        nearest[k] = best;
        break;
      }
    }
  }
  return nearest;
}

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const double last = static_cast<double>(v.size() - 1);
  return v[static_cast<std::size_t>(std::min(last, std::floor(p * last + 0.5)))];
}

void ramp(const TileSet& set, double count, std::uint64_t seed) {
  // Density = max x / W over [0, W) x [0, W): a W-texel ramp whose texel centres hold (c + 0.5) /
  // W is exactly x / W under bilinear lookup, except in the outer half texels (clamped).
  const int texels = 1024;
  const double W = 1.0;
  std::vector<float> ramp_texels(static_cast<std::size_t>(texels) * 2);
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < texels; ++c) ramp_texels[static_cast<std::size_t>(r * texels + c)] = static_cast<float>((c + 0.5) / texels);
  Window w{0.0, 0.0, W, W};
  const double max_density = 2.0 * count / w.area();  // the ramp's mean is 1/2
  double n = 0.0;
  for (const Tile& t : set.tiles) n += static_cast<double>(t.points.size());
  n /= static_cast<double>(set.tiles.size());
  Tiler tiler(set, seed, std::sqrt(n / max_density));
  Thinning map = Thinning::from_map(texels, 2, ramp_texels, w, 1.0);
  std::vector<Point> points;
  tiler.append_points(w, &map, points);

  // The density the map asks for, integrated over each strip exactly (the bilinear ramp is
  // linear between the first and last texel centres and constant outside them).
  auto density = [&](double x) {
    double t = std::clamp(x / W * texels - 0.5, 0.0, texels - 1.0);
    return max_density * (t + 0.5) / texels;
  };
  auto integral = [&](double a, double b) {  // of density over [a, b] x [0, W], by Simpson on a fine grid
    const int steps = 2000;
    double h = (b - a) / steps, sum = density(a) + density(b);
    for (int k = 1; k < steps; ++k) sum += density(a + k * h) * (k % 2 == 1 ? 4.0 : 2.0);
    return sum * h / 3.0 * W;
  };
  const int strips = 16;
  std::vector<double> counted(strips, 0.0);
  for (Point p : points) counted[std::min(strips - 1, static_cast<int>(p.x / W * strips))] += 1.0;
  double mean_error = 0.0, max_error = 0.0, lowest = 0.0;
  for (int s = 0; s < strips; ++s) {
    double expected = integral(W * s / strips, W * (s + 1) / strips);
    double error = std::fabs(counted[s] - expected) / expected;
    mean_error += error / strips;
    max_error = std::max(max_error, error);
    if (s == 0) lowest = error;
  }
  // Local rho: NN distance / d_hex(D(p)) with D(p) the map's density at the point; points closer
  // to the window's border than 2 d_hex(D(p)) are left out (their neighbours are cut off).
  std::vector<double> nearest = nearest_distances(points, w, 2.0 * hexagonal_spacing(max_density));
  std::vector<double> rho;
  for (std::size_t k = 0; k < points.size(); ++k) {
    Point p = points[k];
    double d_hex = hexagonal_spacing(density(p.x));
    double margin = std::min({p.x - w.x0, w.x1 - p.x, p.y - w.y0, w.y1 - p.y});
    if (margin < 2.0 * d_hex) continue;
    rho.push_back(nearest[k] / d_hex);
  }
  if (rho.empty()) {  // too few points for any to lie 2 d_hex inside the window
    std::printf("| %.0f | %llu | %zu | %.2f %% | %.2f %% | %.2f %% | - | - | - | 0 |\n", count,
                static_cast<unsigned long long>(seed), points.size(), 100.0 * mean_error, 100.0 * max_error, 100.0 * lowest);
    return;
  }
  std::printf("| %.0f | %llu | %zu | %.2f %% | %.2f %% | %.2f %% | %.3f | %.3f | %.3f | %.3f |\n", count,
              static_cast<unsigned long long>(seed), points.size(), 100.0 * mean_error, 100.0 * max_error,
              100.0 * lowest, *std::min_element(rho.begin(), rho.end()), percentile(rho, 0.01), percentile(rho, 0.5),
              static_cast<double>(rho.size()) / static_cast<double>(points.size()));
}

// Dynamic range: density from 1 down to 1/range across the window's width, log-linear; count
// error over 16 strips (each a factor range^(1/16) apart) and, with `image`, a render.
void dynamic_range(const TileSet& set, double range, const std::string& image) {
  const int texels = 2048;
  std::vector<float> ramp_texels(static_cast<std::size_t>(texels) * 2);
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < texels; ++c)
      ramp_texels[static_cast<std::size_t>(r * texels + c)] = static_cast<float>(std::pow(range, -(c + 0.5) / texels));
  double n = 0.0;
  for (const Tile& t : set.tiles) n += static_cast<double>(t.points.size());
  n /= static_cast<double>(set.tiles.size());
  const Window w{0.0, 0.0, 64.0, 8.0};
  Tiler tiler(set, 1, 4.0);
  Thinning map = Thinning::from_map(texels, 2, ramp_texels, w, 1.0);
  std::vector<Point> points;
  tiler.append_points(w, &map, points);
  const double max_density = tiler.full_density();
  // The map's density at x (bilinear between texel centres: log-linear is approximated by linear
  // pieces one texel wide), integrated per strip by Simpson's rule on texel-wide steps.
  auto density = [&](double x) { return max_density * map.fraction_at({x, 4.0}); };
  const int strips = 16;
  std::vector<double> counted(strips, 0.0);
  for (Point p : points) counted[std::min(strips - 1, static_cast<int>(p.x / w.width() * strips))] += 1.0;
  std::printf("\nDynamic range %.0f:1 (density max %.4g to %.4g per unit area over [0, 64) x [0, 8), tile size 4, "
              "%.0f points per tile): %zu points\n\n| strip | density (start) | expected | counted | error |\n"
              "|---|---|---|---|---|\n",
              range, max_density, max_density / range, n, points.size());
  for (int s = 0; s < strips; ++s) {
    double a = w.width() * s / strips, b = w.width() * (s + 1) / strips;
    const int steps = 4096;
    double h = (b - a) / steps, sum = density(a) + density(b);
    for (int k = 1; k < steps; ++k) sum += density(a + k * h) * (k % 2 == 1 ? 4.0 : 2.0);
    double expected = sum * h / 3.0 * w.height();
    std::printf("| %d | %.4g | %.1f | %.0f | %+.2f %% |\n", s, density(a), expected, counted[s],
                100.0 * (counted[s] - expected) / expected);
  }
  if (!image.empty()) {
    DotStyle style{1.5 * default_dot_radius(max_density), false};
    write_image(image, render_dots(tiler, w, &map, style, 2048));
  }
}

}  // namespace
}  // namespace bluetile

int main(int argc, char** argv) try {
  namespace bench = bluetile::bench;
  CLI::App app{"The plane tiler's throughput (uniform points, density tests, 10^6 stipples; one thread) and density "
               "control (a linear ramp, and with --range a dynamic range). Without --throughput, --ramp or --range: "
               "throughput and ramp",
               "bluetile_tiler_bench"};
  std::string tiles;
  int repeats = 7;
  std::vector<double> counts = {1e4, 1e5, 1e6};
  std::vector<std::uint64_t> seeds = {1, 2, 3, 4};
  bool run_throughput = false, run_ramp = false;
  double range = 0.0;
  std::string range_image;
  auto* range_option = bench::add_real(app, "--range", range, {1.0, 1e12},
                                       "Dynamic range check: density from 1 down to 1/R across a window")
                           ->default_str("off");
  auto* range_image_option = app.add_option("--range-image", range_image, "With --range: a PNG render of it");
  app.add_option("--tiles", tiles, "Tile-set file (default: the built-in set)");
  bench::add_integer(app, "--repeats", repeats, 1, bench::kMaxRepeats, "Throughput: interleaved timed repeats");
  bench::add_integers(app, "--counts", counts, 1LL, bench::kMaxCount, "Ramp: expected point counts");
  bench::add_integers(app, "--seeds", seeds, std::uint64_t{0}, bench::kMaxSeed, "Ramp: seeds");
  app.add_flag("--throughput", run_throughput, "Points per second and density tests per second");
  app.add_flag("--ramp", run_ramp, "Density control on a linear ramp");
  if (!bench::parse(app, argc, argv)) return 0;
  bench::check_given(range_image_option, range_option->count() > 0, "needs --range");
  if (!run_throughput && !run_ramp && range == 0.0) run_throughput = run_ramp = true;
  bluetile::TileSet set = tiles.empty() ? bluetile::default_tile_set() : bluetile::read_tile_set(tiles);
  if (run_throughput) bluetile::throughput(set, repeats);
  if (range > 0.0) bluetile::dynamic_range(set, range, range_image);
  if (run_ramp) {
    std::printf("\nLinear ramp, density = x over the unit square, 1024-texel map; 16 strips; local rho with borders "
                "(2 d_hex) excluded\n\n");
    std::printf("| points | seed | kept | strip error mean | max | lowest strip | rho min | rho p1 | rho median | "
                "share measured |\n|---|---|---|---|---|---|---|---|---|---|\n");
    for (double count : counts)
      for (std::uint64_t seed : seeds) bluetile::ramp(set, count, seed);
  }
  return 0;
} catch (...) {
  return bluetile::bench::exit_status("bluetile_tiler_bench");
}
