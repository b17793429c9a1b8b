// The periodogram's two methods side by side (docs/BENCHMARKS.md, "Analysis at scale"):
// seconds for the direct sum and the non-uniform FFT at psa's default F for each N, and the
// largest difference between them relative to P(0) = N. The direct sum is skipped above
// --direct-max points (it grows as N^2). Then, for --rdf-count, the seconds of psa's
// RDF-derived radial power (spectral_measures.h), whose pair histogram out to 0.25 is O(N^2).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bluetile/analysis/periodogram.h"
#include "bluetile/analysis/spectral_measures.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) try {
  namespace bench = bluetile::bench;
  CLI::App app{"Direct sum against the non-uniform FFT: seconds of each for N uniform points at psa's default F, and "
               "their largest difference relative to P(0) = N; then seconds of psa's RDF-derived radial power",
               "bluetile_periodogram_bench"};
  std::vector<std::size_t> counts = {1000, 4096, 16384, 65536, 262144, 1000000};
  std::size_t direct_max = 65536;
  int threads = 0;
  bench::add_integers(app, "-n,--count", counts, 1LL, bench::kMaxCount, "Point counts");
  bench::add_integer(app, "--direct-max", direct_max, 0LL, bench::kMaxCount,
                     "Largest N for the direct sum (O(N^2); 0: never)");
  std::vector<std::size_t> rdf_counts;
  bench::add_integers(app, "--rdf-count", rdf_counts, 2LL, bench::kMaxCount,
                      "Point counts for psa's RDF spectrum (O(N^2); none by default)")
      ->default_str("none");
  bench::add_integer(app, "--threads", threads, 1, bench::kMaxThreads, "Threads")->default_str("all cores");
  if (!bench::parse(app, argc, argv)) return 0;
  if (threads > 0) bluetile::set_thread_count(static_cast<std::size_t>(threads));
  std::printf("| N | F | M | direct s | NUFFT s | max diff / N | chosen |\n|---|---|---|---|---|---|---|\n");
  for (std::size_t n : counts) {
    bluetile::Rng rng(n);
    std::vector<bluetile::Point> points(n);
    for (auto& p : points) p = {rng.uniform(), rng.uniform()};
    const int f = bluetile::default_periodogram_size(n);
    auto start = std::chrono::steady_clock::now();
    const bluetile::Periodogram fast = bluetile::compute_periodogram_nufft(points, f);
    const double fast_s = seconds_since(start);
    std::string direct_s = "-", diff = "-";
    if (n <= direct_max) {
      start = std::chrono::steady_clock::now();
      const bluetile::Periodogram direct = bluetile::compute_periodogram_direct(points, f);
      char text[32];
      std::snprintf(text, sizeof text, "%.3f", seconds_since(start));
      direct_s = text;
      double worst = 0.0;
      for (std::size_t i = 0; i < direct.power.size(); ++i) worst = std::max(worst, std::abs(fast.power[i] - direct.power[i]));
      std::snprintf(text, sizeof text, "%.1e", worst / static_cast<double>(n));
      diff = text;
    }
    std::printf("| %zu | %d | %zu | %s | %.3f | %s | %s |\n", n, f, bluetile::periodogram_nufft_grid(f), direct_s.c_str(),
                fast_s, diff.c_str(), bluetile::periodogram_uses_nufft(n, f) ? "NUFFT" : "direct");
    std::fflush(stdout);
  }
  if (!rdf_counts.empty()) std::printf("\n| N | RDF spectrum s | pairs < 0.25 |\n|---|---|---|\n");
  for (std::size_t n : rdf_counts) {
    bluetile::Rng rng(n);
    std::vector<bluetile::Point> points(n);
    for (auto& p : points) p = {rng.uniform(), rng.uniform()};
    const auto start = std::chrono::steady_clock::now();
    const bluetile::RdfPowerSpectrum spectrum = bluetile::rdf_power_spectrum(points);
    std::printf("| %zu | %.3f | %.3g |\n", n, seconds_since(start), bluetile::rdf_power_spectrum_pairs(n));
    std::fflush(stdout);
  }
  return 0;
} catch (...) {
  return bluetile::bench::exit_status("bluetile_periodogram_bench");
}
