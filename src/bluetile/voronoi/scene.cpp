#include "bluetile/voronoi/scene.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/text.h"
#include "bluetile/voronoi/density_moments.h"

namespace bluetile {
namespace {

bool inside(Point p, const Domain& domain) {
  return p.x >= 0.0 && p.x < domain.size.x && p.y >= 0.0 && p.y < domain.size.y;
}

// Whether every site lies in [0, size) on both axes. With SSE2 a site's x and y are compared in
// one register: the plain loop did not vectorize (four scalar compares a site, 17 us at 10^4
// sites on the calling thread alone, every engine call; docs/BENCHMARKS.md, "Two threads after
// the SIMD lanes"). The compares are ordered: false for NaN.
bool all_inside(std::span<const Point> sites, Point size) {
#if defined(__SSE2__)
  const __m128d zero = _mm_setzero_pd(), limit = _mm_set_pd(size.y, size.x);
  __m128d even = _mm_cmpeq_pd(zero, zero), odd = even;  // all bits set; two chains of ands
  std::size_t i = 0;
  for (; i + 2 <= sites.size(); i += 2) {
    const __m128d a = _mm_loadu_pd(&sites[i].x), b = _mm_loadu_pd(&sites[i + 1].x);
    even = _mm_and_pd(even, _mm_and_pd(_mm_cmpge_pd(a, zero), _mm_cmplt_pd(a, limit)));
    odd = _mm_and_pd(odd, _mm_and_pd(_mm_cmpge_pd(b, zero), _mm_cmplt_pd(b, limit)));
  }
  bool result = _mm_movemask_pd(_mm_and_pd(even, odd)) == 3;
  for (; i < sites.size(); ++i) result &= inside(sites[i], Domain{size});
  return result;
#else
  bool result = true;
  for (const Point& p : sites) result &= (p.x >= 0.0) & (p.x < size.x) & (p.y >= 0.0) & (p.y < size.y);
  return result;
#endif
}

// all_inside on all threads, in the parts in which Lloyd's move wrote the sites
// (move_to_centroids): each thread reads the sites in its own cache. Small scenes here: below
// kThreadedSites the check (about 0.4 ns a site) costs less than waking the pool.
bool all_inside_on_threads(std::span<const Point> sites, Point size) {
  constexpr std::size_t kPart = 256;
  constexpr std::size_t kThreadedSites = 8192;
  const std::size_t parts = (sites.size() + kPart - 1) / kPart;
  if (sites.size() < kThreadedSites || thread_count() < 2) return all_inside(sites, size);
  std::atomic<bool> every{true};
  parallel_for(parts, 1, [&](std::size_t begin, std::size_t end) {
    const std::size_t last = std::min(sites.size(), end * kPart);
    if (!all_inside(sites.subspan(begin * kPart, last - begin * kPart), size)) every.store(false, std::memory_order_relaxed);
  });
  return every.load();
}

}  // namespace

const Scene& validated_scene(const Scene& scene, Scene& storage) {
  check_domain(scene.domain, "scene");
  const Point size = scene.domain.size;
  if (scene.wanted_begin > scene.wanted_end || scene.wanted_end > scene.sites.size())
    throw Error("scene: wanted sites [" + std::to_string(scene.wanted_begin) + ", " + std::to_string(scene.wanted_end) +
                ") do not lie inside its " + std::to_string(scene.sites.size()) + " sites");
  if (scene.sites.size() > kMaxSceneSites)
    throw Error("scene: " + std::to_string(scene.sites.size()) + " sites, more than the " +
                std::to_string(kMaxSceneSites) + " an engine can index");
  check_density(scene);
  // One branch-free pass first (engines check every call): NaN and infinities fail the
  // comparisons too. The loop that names a bad site or wraps the ones outside runs only when one
  // is not inside.
  if (all_inside_on_threads(scene.sites, size)) return scene;
  std::size_t first_outside = scene.sites.size();
  for (std::size_t i = 0; i < scene.sites.size(); ++i) {
    const Point p = scene.sites[i];
    auto site = [&] { return "scene: site " + std::to_string(i) + " (" + exact_text(p.x) + ", " + exact_text(p.y) + ")"; };
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw Error(site() + " is not finite");
    if (first_outside == scene.sites.size() && !inside(p, scene.domain)) {
      if (!scene.periodic())
        throw Error(site() + " lies outside the bounded domain " + exact_text(size.x) + " x " + exact_text(size.y));
      first_outside = i;
    }
  }
  if (first_outside == scene.sites.size()) return scene;
  storage = scene;
  for (std::size_t i = first_outside; i < storage.sites.size(); ++i)
    storage.sites[i] = wrap_point(storage.sites[i], storage.domain);
  return storage;
}

void check_batch(std::string_view engine, std::size_t scenes, std::size_t results) {
  if (scenes != results)
    throw Error(std::string(engine) + " engine: " + counted(static_cast<long long>(scenes), "scene") +
                " but room for " + counted(static_cast<long long>(results), "result"));
}

}  // namespace bluetile
