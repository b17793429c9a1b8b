// Radial distribution function by a pair-distance histogram with translation edge correction
// (Ohser and Stoyan 1981; Illian et al. 2008, section 4.3), and the Hankel transform to the
// radial power spectrum (Heck, Schlömer and Deussen 2013, section 3).
#include "bluetile/analysis/pair_correlation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/text.h"
#include "bluetile/voronoi/site_grid.h"

namespace bluetile {
namespace {

constexpr std::size_t kPointsPerBin = 8;         // psa's rbinsize 0.125: N / 8 bins
constexpr std::size_t kMinBins = 32, kMaxBins = 1000;
// Points per block of the pair loop: each block keeps its own histogram, summed in block order
// afterwards, so the floating-point sums do not depend on the thread count.
constexpr std::size_t kBlockPoints = 1024;
constexpr std::size_t kMaxBlocks = 64;

}  // namespace

RadialDistribution radial_distribution(std::span<const Point> points, const RdfOptions& options, const Domain& domain) {
  const std::size_t n = points.size();
  if (n < 2) throw Error("the radial distribution function needs at least 2 points, got " + std::to_string(n));
  if (!(options.range >= 0.0) || !std::isfinite(options.range))
    throw Error("RDF range must be a positive number of hexagonal spacings");
  check_domain(domain, "radial distribution");
  // A NaN point fell out of every bin without a word.
  check_finite_points(points, "radial distribution");
  const bool periodic = options.boundary == Boundary::periodic;
  const double width = domain.size.x, height = domain.size.y;
  if (!periodic) {
    for (const Point& p : points)
      if (!(p.x >= 0.0 && p.x < width && p.y >= 0.0 && p.y < height))
        throw Error("a bounded set's points must lie inside the domain");
  }

  RadialDistribution rdf;
  rdf.count = n;
  rdf.area = domain.area();
  rdf.hexagonal_spacing = hexagonal_spacing(static_cast<double>(n), rdf.area);
  const double wanted = (options.range > 0.0 ? options.range : kDefaultRdfRange) * rdf.hexagonal_spacing;
  const double half = 0.5 * std::min(width, height);
  if (options.range > 0.0 && wanted > half * (1.0 + 1e-12))
    throw Error("RDF range " + number_text(options.range) + " hexagonal spacings is more than half the domain's " +
                "shorter side, " + fixed_text(half / rdf.hexagonal_spacing, 2) + " spacings for " + std::to_string(n) +
                " points (where a torus annulus starts to overlap itself)");
  const double range = std::min(wanted, half);
  const std::size_t bins = options.bins > 0 ? options.bins : std::clamp(n / kPointsPerBin, kMinBins, kMaxBins);
  if (bins > 1000000) throw Error("too many RDF bins (at most 1000000)");
  rdf.bin_width = range / static_cast<double>(bins);

  // Buckets about a third of `range` wide: the pairs within the range of a point lie in the 7 x 7
  // buckets around it, 1.7 times the disc's area (3 x 3 buckets of `range` would be 2.9 times).
  std::vector<Point> inside(points.begin(), points.end());
  for (Point& p : inside) p = wrap_point(p, domain);  // bounded ones were checked above
  const double per_bucket = std::max(1.0, static_cast<double>(n) * range * range / (9.0 * rdf.area));
  const SiteGrid grid(inside, domain, per_bucket, false);

  const std::size_t block_points = std::max(kBlockPoints, (n + kMaxBlocks - 1) / kMaxBlocks);
  const std::size_t blocks = (n + block_points - 1) / block_points;
  std::vector<std::vector<double>> partial(blocks, std::vector<double>(bins, 0.0));
  const double range_squared = range * range;
  parallel_for(blocks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t block = begin; block < end; ++block) {
      std::vector<double>& histogram = partial[block];
      const std::size_t first = block * block_points, last = std::min(n, first + block_points);
      if (periodic) {
        // On the torus the grid visits every copy once. Points are taken in the grid's storage
        // order (neighbouring points after one another, so their buckets stay in cache) and each
        // pair is measured once, from its lower index, and counted twice: the weight is 1 both
        // ways and integer sums are exact, so the histogram is the same as over ordered pairs.
        const auto indices = grid.site_indices();
        for (std::size_t s = first; s < last; ++s) {
          const std::uint32_t i = indices[s];
          const Point p = grid.stored_point(s);
          grid.for_each_site_near(p, range, [&](std::uint32_t j, Point q) {
            if (j <= i) return;
            const Point d = torus_offset(p, q, domain);
            const double r2 = d.x * d.x + d.y * d.y;
            if (r2 >= range_squared) return;
            const auto bin = static_cast<std::size_t>(std::sqrt(r2) / rdf.bin_width);
            if (bin < bins) histogram[bin] += 2.0;  // else r just below the range, rounded up
          });
        }
        continue;
      }
      for (std::size_t i = first; i < last; ++i) {
        const Point p = inside[i];
        // A bounded set ignores the wrap-around buckets the grid also visits, by measuring
        // plain distances.
        grid.for_each_near(p, range, [&](std::uint32_t j) {
          if (j == i) return;
          const Point d = inside[j] - p;
          const double r2 = d.x * d.x + d.y * d.y;
          if (r2 >= range_squared) return;
          const auto bin = static_cast<std::size_t>(std::sqrt(r2) / rdf.bin_width);
          if (bin >= bins) return;  // r just below the range, rounded up
          histogram[bin] += (width * height) / ((width - std::abs(d.x)) * (height - std::abs(d.y)));
        });
      }
    }
  });

  rdf.g.assign(bins, 0.0);
  for (const auto& histogram : partial)
    for (std::size_t b = 0; b < bins; ++b) rdf.g[b] += histogram[b];
  const double pairs = static_cast<double>(n) * static_cast<double>(n - 1);
  for (std::size_t b = 0; b < bins; ++b) {
    const double r0 = static_cast<double>(b) * rdf.bin_width, r1 = r0 + rdf.bin_width;
    const double annulus = std::numbers::pi * (r1 * r1 - r0 * r0);
    rdf.g[b] *= rdf.area / (pairs * annulus);
  }
  return rdf;
}

RadialDistribution average_distributions(std::span<const RadialDistribution> distributions) {
  if (distributions.empty()) throw Error("no radial distributions to average");
  RadialDistribution mean = distributions[0];
  for (std::size_t k = 1; k < distributions.size(); ++k) {
    const RadialDistribution& d = distributions[k];
    if (d.count != mean.count || d.g.size() != mean.g.size() || d.bin_width != mean.bin_width)
      throw Error("cannot average radial distributions of different sizes or ranges");
    for (std::size_t b = 0; b < d.g.size(); ++b) mean.g[b] += d.g[b];
  }
  for (double& v : mean.g) v /= static_cast<double>(distributions.size());
  mean.sets = distributions.size();
  return mean;
}

double power_from_rdf(const RadialDistribution& rdf, double frequency) {
  if (!(frequency >= 0.0) || !std::isfinite(frequency)) throw Error("frequency must be finite and >= 0");
  const double a = 2.0 * std::numbers::pi * frequency;
  // Integral of J0(a r) 2 pi r dr from 0 to r: 2 pi r J1(a r) / a (pi r^2 at a = 0).
  auto disc = [&](double r) {
    if (a * r < 1e-8) return std::numbers::pi * r * r;
    return 2.0 * std::numbers::pi * r * std::cyl_bessel_j(1.0, a * r) / a;
  };
  double sum = 0.0, previous = 0.0;
  for (std::size_t b = 0; b < rdf.g.size(); ++b) {
    const double next = disc(static_cast<double>(b + 1) * rdf.bin_width);
    sum += (rdf.g[b] - 1.0) * (next - previous);
    previous = next;
  }
  return 1.0 + static_cast<double>(rdf.count - 1) / rdf.area * sum;
}

}  // namespace bluetile
