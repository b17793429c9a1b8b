// The host reference of the raster engine's device passes (see raster_reference.h): the same
// method as shaders/classify.comp and shaders/split_body.glsl, written out again in C++.
#include "bluetile/raster/raster_reference.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>

#include "bluetile/core/parallel.h"

namespace bluetile {
namespace {

// As classify.comp's wrapped_offset: d = i - p wrapped so that d + c - f lies in [-size/2, size/2)
// (on a torus; in a bounded domain nothing wraps).
int wrapped_offset(int i, int p, float c, float f, int size, bool periodic) {
  int d = i - p;
  if (!periodic) return d;
  const float t = static_cast<float>(d) + c - f;
  if (t < -0.5f * static_cast<float>(size)) {
    d += size;
  } else if (t >= 0.5f * static_cast<float>(size)) {
    d -= size;
  }
  return d;
}

std::int64_t run_sum(std::int64_t d0, std::int64_t n) { return n * d0 + n * (n - 1) / 2; }
std::int64_t run_sum_squares(std::int64_t d0, std::int64_t n) {
  return n * d0 * d0 + d0 * n * (n - 1) + (n - 1) * n * (2 * n - 1) / 6;
}

std::int64_t fixed(double v, double scale) { return static_cast<std::int64_t>(std::floor(v * scale + 0.5)); }

void add_weighted(WeightedSums& sums, const WeightedMoments& m, const RasterScene& scene) {
  const double area = scene.density_scale * scene.scale_area, first = scene.density_scale * scene.scale_first,
               second = scene.density_scale * scene.scale_second;
  sums.mass += fixed(m.mass, area);
  sums.x += fixed(m.first.x, first);
  sums.y += fixed(m.first.y, first);
  sums.second += fixed(m.second, second);
}

void add_run(gpu::SiteSums& s, int dx0, int dy, int n) {
  s.count += static_cast<std::uint32_t>(n);
  s.sum_x += run_sum(dx0, n);
  s.sum_xx += run_sum_squares(dx0, n);
  s.sum_y += static_cast<std::int64_t>(n) * dy;
  s.sum_yy += static_cast<std::int64_t>(n) * dy * dy;
}

// What the shaders read of a site (SiteInfo).
struct SiteFrame {
  int px = 0, py = 0;
  float fx = 0.0f, fy = 0.0f;
};

}  // namespace

std::vector<std::uint32_t> raster_site_masks(const RasterScene& scene) {
  const std::size_t words_per_row = static_cast<std::size_t>(scene.rx + 15) / 16;
  std::vector<std::uint32_t> masks(words_per_row * static_cast<std::size_t>(scene.ry), 0u);
  for (std::size_t s = 0; s < scene.size(); ++s) {
    if (scene.coincident[s]) continue;
    int px, py;
    double fx, fy;
    scene.site_pixel(s, px, py, fx, fy);
    std::uint32_t& word = masks[static_cast<std::size_t>(py) * words_per_row + static_cast<std::size_t>(px / 16)];
    const std::uint32_t shift = 2u * static_cast<std::uint32_t>(px % 16);
    // A second site in the pixel sets the "several" bit.
    if (word & (1u << shift)) word |= 2u << shift;
    word |= 1u << shift;
  }
  return masks;
}

void add_sums(gpu::SiteSums& a, const gpu::SiteSums& b) {
  a.sum_x += b.sum_x;
  a.sum_y += b.sum_y;
  a.sum_xx += b.sum_xx;
  a.sum_yy += b.sum_yy;
  a.piece_area += b.piece_area;
  a.piece_x += b.piece_x;
  a.piece_y += b.piece_y;
  a.piece_second += b.piece_second;
  a.count += b.count;
  a.owned += b.owned;
  a.farthest = std::max(a.farthest, b.farthest);
}

namespace {

std::uint32_t classify_rows(const RasterScene& scene, std::span<const std::uint32_t> ids, const std::vector<std::uint32_t>& masks,
                            int row_begin, int row_end, std::span<gpu::SiteSums> sums, std::vector<std::uint32_t>& boundary,
                            std::span<WeightedSums> weighted);

}  // namespace

std::uint32_t reference_classify(const RasterScene& scene, std::span<const std::uint32_t> ids, std::span<gpu::SiteSums> sums,
                                 std::vector<std::uint32_t>& boundary, std::span<WeightedSums> weighted) {
  const std::vector<std::uint32_t> masks = scene.area ? raster_site_masks(scene) : std::vector<std::uint32_t>{};
  return classify_rows(scene, ids, masks, 0, scene.ry, sums, boundary, weighted);
}

std::uint32_t reference_pass(const RasterScene& scene, std::span<const std::uint32_t> ids, std::span<gpu::SiteSums> sums,
                             bool split, bool parallel, std::vector<std::uint32_t>& host_pixels, std::uint64_t& boundary_count,
                             std::span<WeightedSums> weighted, ReferenceTiming* timing) {
  using Clock = std::chrono::steady_clock;
  auto stage_start = Clock::now();
  auto end_stage = [&](double ReferenceTiming::*stage) {
    const auto now = Clock::now();
    if (timing) timing->*stage += std::chrono::duration<double>(now - stage_start).count();
    stage_start = now;
  };
  const std::vector<std::uint32_t> masks = scene.area ? raster_site_masks(scene) : std::vector<std::uint32_t>{};
  const std::size_t n = scene.size();
  // One slice of rows per thread, each with its own sums (exact integers: merged in any order).
  const std::size_t slices = parallel ? std::max<std::size_t>(1, std::min<std::size_t>(thread_count(), static_cast<std::size_t>(scene.ry))) : 1;
  std::vector<std::vector<gpu::SiteSums>> slice_sums(slices);
  std::vector<std::vector<WeightedSums>> slice_weighted(slices);
  std::vector<std::vector<std::uint32_t>> slice_boundary(slices), slice_host(slices);
  std::vector<std::uint32_t> slice_uncovered(slices, 0);
  auto rows = [&](std::size_t k, int& begin, int& end) {
    begin = static_cast<int>(k * static_cast<std::size_t>(scene.ry) / slices);
    end = static_cast<int>((k + 1) * static_cast<std::size_t>(scene.ry) / slices);
  };
  parallel_for(slices, 1, [&](std::size_t first, std::size_t last) {
    for (std::size_t k = first; k < last; ++k) {
      int begin, end;
      rows(k, begin, end);
      std::span<gpu::SiteSums> target = sums;
      std::span<WeightedSums> weighted_target = weighted;
      if (k > 0) {
        slice_sums[k].assign(n, gpu::SiteSums{});
        target = slice_sums[k];
        if (!weighted.empty()) {
          slice_weighted[k].assign(n, WeightedSums{});
          weighted_target = slice_weighted[k];
        }
      }
      slice_uncovered[k] = classify_rows(scene, ids, masks, begin, end, target, slice_boundary[k], weighted_target);
    }
  });
  std::uint32_t uncovered = 0;
  boundary_count = 0;
  for (std::size_t k = 0; k < slices; ++k) {
    uncovered += slice_uncovered[k];
    boundary_count += slice_boundary[k].size();
  }
  end_stage(&ReferenceTiming::classify);
  if (split && uncovered == 0) {
    parallel_for(slices, 1, [&](std::size_t first, std::size_t last) {
      for (std::size_t k = first; k < last; ++k) {
        std::span<gpu::SiteSums> target = k > 0 ? std::span<gpu::SiteSums>(slice_sums[k]) : sums;
        std::span<WeightedSums> weighted_target = k > 0 && !weighted.empty() ? std::span<WeightedSums>(slice_weighted[k]) : weighted;
        for (std::uint32_t pixel : slice_boundary[k])
          if (!reference_split(scene, ids, pixel, target, weighted_target)) slice_host[k].push_back(pixel);
      }
    });
  }
  end_stage(&ReferenceTiming::split);
  for (std::size_t k = 1; k < slices; ++k)
    for (std::size_t i = 0; i < n; ++i) add_sums(sums[i], slice_sums[k][i]);
  for (std::size_t k = 1; k < slices && !weighted.empty(); ++k)
    for (std::size_t i = 0; i < n; ++i) {
      weighted[i].mass += slice_weighted[k][i].mass;
      weighted[i].x += slice_weighted[k][i].x;
      weighted[i].y += slice_weighted[k][i].y;
      weighted[i].second += slice_weighted[k][i].second;
    }
  for (std::size_t k = 0; k < slices; ++k) host_pixels.insert(host_pixels.end(), slice_host[k].begin(), slice_host[k].end());
  end_stage(&ReferenceTiming::reduce);
  return uncovered;
}

namespace {

std::uint32_t classify_rows(const RasterScene& scene, std::span<const std::uint32_t> ids, const std::vector<std::uint32_t>& masks,
                            int row_begin, int row_end, std::span<gpu::SiteSums> sums, std::vector<std::uint32_t>& boundary,
                            std::span<WeightedSums> weighted) {
  const int rx = scene.rx, ry = scene.ry;
  const bool periodic = scene.periodic;
  const bool area = scene.area;
  const float hx = static_cast<float>(scene.hx), hy = static_cast<float>(scene.hy);
  std::vector<SiteFrame> frames(scene.size());
  for (std::size_t s = 0; s < scene.size(); ++s) {
    double fx, fy;
    scene.site_pixel(s, frames[s].px, frames[s].py, fx, fy);
    frames[s].fx = static_cast<float>(fx);
    frames[s].fy = static_cast<float>(fy);
  }
  const std::size_t words_per_row = static_cast<std::size_t>(rx + 15) / 16;
  auto id_at = [&](int i, int j) -> std::uint32_t {
    // A bounded raster has no samples beyond its last column and row: no pixel there is whole.
    if (!periodic && (i >= rx || j >= ry)) return 0u;
    i = i >= rx ? i - rx : i;
    j = j >= ry ? j - ry : j;
    return ids[static_cast<std::size_t>(j) * rx + i];
  };
  // Whole pixels weighted by their moments under the density (varying densities only).
  auto add_weighted_run = [&](std::uint32_t id, int dx0, int dy, int length, int i_begin, int j) {
    const std::size_t s = id - 1;
    const Point site = scene.sites[s];
    const double cy = (frames[s].py + 0.5) * scene.hy - site.y + dy * scene.hy;
    const double ax = (frames[s].px + 0.5) * scene.hx - site.x;
    const WeightedMoments* pixel = scene.pixel_density->data() + static_cast<std::size_t>(j) * rx + i_begin;
    WeightedMoments run;
    for (int k = 0; k < length; ++k) {
      const WeightedMoments& m = pixel[k];
      const double cx = ax + (dx0 + k) * scene.hx;
      run.mass += m.mass;
      run.first.x += m.mass * cx + m.first.x;
      run.first.y += m.mass * cy + m.first.y;
      run.second += m.second + 2.0 * (cx * m.first.x + cy * m.first.y) + m.mass * (cx * cx + cy * cy);
    }
    add_weighted(weighted[s], run, scene);
  };
  const bool weigh = !weighted.empty() && scene.density;
  auto add_pixel_run = [&](std::uint32_t id, int dx0, int dy, int length, int i_end, int j) {
    add_run(sums[id - 1], dx0, dy, length);
    if (weigh) add_weighted_run(id, dx0, dy, length, i_end - length, j);
  };
  auto distance_squared = [&](const SiteFrame& f, int dx, int dy) {
    const float ox = (static_cast<float>(dx) - f.fx) * hx, oy = (static_cast<float>(dy) - f.fy) * hy;
    return ox * ox + oy * oy;
  };
  auto flush_samples = [&](std::uint32_t id, int dx, int dy, int length, float far) {
    gpu::SiteSums& s = sums[id - 1];
    s.owned += static_cast<std::uint32_t>(length);
    s.farthest = std::max(s.farthest, std::bit_cast<std::uint32_t>(far));
    if (!area) add_run(s, dx, dy, length);
  };
  std::uint32_t uncovered = 0;
  for (int j = row_begin; j < row_end; ++j) {
    for (int i0 = 0; i0 < rx; i0 += BLUETILE_CLASSIFY_SEGMENT) {
      const int i1 = std::min(i0 + BLUETILE_CLASSIFY_SEGMENT, rx);
      std::uint32_t site_id = 0;
      SiteFrame site;
      bool split = false;
      int dy_sample = 0, dy_pixel = 0;
      std::uint32_t sample_site = 0;
      int sample_dx = 0, sample_dy = 0, sample_length = 0;
      float sample_far = 0.0f;
      std::uint32_t pixel_site = 0;
      int pixel_dx = 0, pixel_dy = 0, pixel_length = 0;
      std::uint32_t a = id_at(i0, j), c = area ? id_at(i0, j + 1) : 0u;
      for (int i = i0; i < i1; ++i) {
        const std::uint32_t b = id_at(i + 1, j), e = area ? id_at(i + 1, j + 1) : 0u;
        if (a == 0) {
          ++uncovered;
        } else if (a != site_id) {
          site_id = a;
          site = frames[a - 1];
          split = scene.split[a - 1] != 0;
          dy_sample = wrapped_offset(j, site.py, 0.0f, site.fy, ry, periodic);
          dy_pixel = wrapped_offset(j, site.py, 0.5f, site.fy, ry, periodic);
        }
        if (a != 0) {
          const int dx = wrapped_offset(i, site.px, 0.0f, site.fx, rx, periodic);
          if (a == sample_site && dx == sample_dx + sample_length) {
            ++sample_length;
          } else {
            if (sample_length > 0) flush_samples(sample_site, sample_dx, sample_dy, sample_length, sample_far);
            sample_site = a;
            sample_dx = dx;
            sample_dy = dy_sample;
            sample_length = 1;
            sample_far = distance_squared(site, dx, dy_sample);
          }
          sample_far = std::max(sample_far, distance_squared(site, dx, dy_sample));
        }
        if (area) {
          bool whole = a != 0 && a == b && a == c && a == e && !split;
          int dx = 0;
          if (whole) {
            const std::uint32_t word = masks[static_cast<std::size_t>(j) * words_per_row + static_cast<std::size_t>(i >> 4)] >>
                                       (2u * static_cast<std::uint32_t>(i & 15));
            const bool holds_site = word & 1u, holds_several = word & 2u;
            whole = !holds_site || (!holds_several && site.px == i && site.py == j);
            dx = wrapped_offset(i, site.px, 0.5f, site.fx, rx, periodic);
            const float tx = static_cast<float>(dx) + 0.5f - site.fx, ty = static_cast<float>(dy_pixel) + 0.5f - site.fy;
            whole = whole && (!periodic || (std::abs(tx) < 0.5f * static_cast<float>(rx) - 1.0f &&
                                            std::abs(ty) < 0.5f * static_cast<float>(ry) - 1.0f));
          }
          if (whole && a == pixel_site && dx == pixel_dx + pixel_length) {
            ++pixel_length;
          } else {
            if (pixel_length > 0) add_pixel_run(pixel_site, pixel_dx, pixel_dy, pixel_length, i, j);
            pixel_length = 0;
            if (whole) {
              pixel_site = a;
              pixel_dx = dx;
              pixel_dy = dy_pixel;
              pixel_length = 1;
            } else {
              boundary.push_back(static_cast<std::uint32_t>(j * rx + i));
            }
          }
        }
        a = b;
        c = e;
      }
      if (sample_length > 0) flush_samples(sample_site, sample_dx, sample_dy, sample_length, sample_far);
      if (pixel_length > 0) add_pixel_run(pixel_site, pixel_dx, pixel_dy, pixel_length, i1, j);
    }
  }
  return uncovered;
}

}  // namespace

double corner_owner_distance(const RasterScene& scene, std::span<const std::uint32_t> ids, std::uint32_t pixel) {
  const int rx = scene.rx, ry = scene.ry;
  const int i = static_cast<int>(pixel % static_cast<std::uint32_t>(rx)), j = static_cast<int>(pixel / static_cast<std::uint32_t>(rx));
  const Point lattice{static_cast<double>(i) * scene.hx, static_cast<double>(j) * scene.hy};
  const Point half_pixel{0.5 * scene.hx, 0.5 * scene.hy};
  const Point domain = scene.scene->domain.size;
  double nearest = 1e30;
  for (int corner = 0; corner < 4; ++corner) {
    int ci = i + (corner & 1), cj = j + (corner >> 1);
    if (!scene.periodic && (ci >= rx || cj >= ry)) continue;  // beyond a bounded raster
    ci = ci >= rx ? ci - rx : ci;
    cj = cj >= ry ? cj - ry : cj;
    const std::uint32_t id = ids[static_cast<std::size_t>(cj) * rx + ci];
    if (id == 0) continue;
    const Point from{scene.sites[id - 1].x - lattice.x, scene.sites[id - 1].y - lattice.y};
    Point o = from - half_pixel;
    if (scene.periodic) o = {raster_detail::wrap_axis(o.x, domain.x), raster_detail::wrap_axis(o.y, domain.y)};
    nearest = std::min(nearest, std::sqrt(o.x * o.x + o.y * o.y));
  }
  return nearest;
}

WeightedMoments piece_density(const RasterScene& scene, std::uint32_t site, const PolygonMoments& moments,
                              const ConvexPolygon& piece) {
  thread_local std::vector<Point> vertices;
  vertices.clear();
  Point lo{HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL};
  for (const PolygonVertex& v : piece.vertices()) {
    vertices.push_back(v.p);
    lo = {std::min(lo.x, v.p.x), std::min(lo.y, v.p.y)};
    hi = {std::max(hi.x, v.p.x), std::max(hi.y, v.p.y)};
  }
  // A piece inside one texel (texels no smaller than pixels, mostly) is its density times its
  // moments, without the texel walk.
  const DensityGrid& density = *scene.density;
  const Point size = scene.scene->domain.size, origin = scene.sites[site];
  const Point texel{size.x / density.width, size.y / density.height};
  auto texel_of = [](double x, double side) { return static_cast<long>(std::floor(x / side)); };
  const long column = texel_of(origin.x + lo.x, texel.x), row = texel_of(origin.y + lo.y, texel.y);
  if (column == texel_of(origin.x + hi.x, texel.x) && row == texel_of(origin.y + hi.y, texel.y)) {
    auto index = [&](long i, int count) {
      if (!scene.periodic) return static_cast<int>(std::clamp<long>(i, 0, count - 1));
      const long m = i % count;
      return static_cast<int>(m < 0 ? m + count : m);
    };
    const double rho = density.at(index(column, density.width), index(row, density.height));
    return {rho * moments.area(), rho * moments.first_moment(), rho * moments.second_moment()};
  }
  // On a torus the piece may lie around a copy of the site beyond the domain: the density's
  // texels wrap, so the site itself serves as the origin.
  return density_moments(vertices, scene.sites[site], *scene.density, scene.scene->domain.size, scene.periodic);
}

bool reference_split(const RasterScene& scene, std::span<const std::uint32_t> ids, std::uint32_t pixel,
                     std::span<gpu::SiteSums> sums, std::span<WeightedSums> weighted) {
  const bool weigh = !weighted.empty() && scene.density;
  // (split_boundary_pixel reports pieces only once it knows it keeps the pixel.)
  return split_boundary_pixel(scene, corner_owner_distance(scene, ids, pixel), pixel, true,
                              [&](std::uint32_t site, const PolygonMoments& m, const ConvexPolygon& polygon) {
                                if (weigh) add_weighted(weighted[site], piece_density(scene, site, m, polygon), scene);
                                gpu::SiteSums& s = sums[site];
                                s.piece_area += fixed(m.area(), scene.scale_area);
                                s.piece_x += fixed(m.first_moment().x, scene.scale_first);
                                s.piece_y += fixed(m.first_moment().y, scene.scale_first);
                                s.piece_second += fixed(m.second_moment(), scene.scale_second);
                              });
}

void host_split(const RasterScene& scene, double nearest, std::uint32_t pixel, std::span<PieceSums> pieces) {
  split_boundary_pixel(scene, nearest, pixel, false, [&](std::uint32_t site, const PolygonMoments& m, const ConvexPolygon& polygon) {
    PieceSums& p = pieces[site];
    if (scene.density) {
      const WeightedMoments w = piece_density(scene, site, m, polygon);
      p.weighted.mass += w.mass;
      p.weighted.first = p.weighted.first + w.first;
      p.weighted.second += w.second;
    }
    p.area += m.area();
    p.x += m.first_moment().x;
    p.y += m.first_moment().y;
    p.second += m.second_moment();
  });
}

RasterSearch::RasterSearch(const RasterScene& scene) : tree(scene.sites, scene.scene->domain, scene.periodic) {
  const SiteGrid& grid = scene.grid();
  const auto starts = grid.bucket_starts();
  const auto indices = grid.site_indices();
  bucket.assign(scene.size(), 0);
  slot.assign(scene.size(), 0);
  for (std::size_t b = 0; b + 1 < starts.size(); ++b)
    for (std::uint32_t k = starts[b]; k < starts[b + 1]; ++k) {
      bucket[indices[k]] = static_cast<std::uint32_t>(b);
      slot[indices[k]] = k;
    }
}

const RasterSearch& raster_search(const RasterScene& scene) {
  RasterSearchCache& cache = *scene.search_cache_;
  std::call_once(cache.once, [&] { cache.search = std::make_unique<RasterSearch>(scene); });
  return *cache.search;
}

namespace raster_detail {

void tree_candidates(const RasterScene& scene, int i, int j, double reach, long lo_x, long hi_x, long lo_y, long hi_y,
                     std::vector<Candidate>& out) {
  const RasterSearch& search = raster_search(scene);
  const SiteGrid& grid = scene.grid();
  const long columns = grid.columns(), rows = grid.rows();
  const Point h{scene.hx, scene.hy};
  const Point domain = scene.scene->domain.size;
  const Point lattice{static_cast<double>(i) * h.x, static_cast<double>(j) * h.y};
  const Point half_pixel = 0.5 * h;
  const double diagonal = std::sqrt(h.x * h.x + h.y * h.y) * (1.0 + 1.0 / 65536.0);
  const Point centre{(static_cast<double>(i) + 0.5) * h.x, (static_cast<double>(j) + 0.5) * h.y};
  // Roundings of the tree's distances against the split's, and of box tests: far below this.
  const double margin = 1e-9 * std::max(domain.x, domain.y);
  struct Keyed {
    Candidate c;
    long by, bx;
    std::uint32_t slot;
  };
  auto before = [](const Keyed& a, const Keyed& b) {
    if (a.by != b.by) return a.by < b.by;
    if (a.bx != b.bx) return a.bx < b.bx;
    return a.slot < b.slot;
  };
  thread_local std::vector<SiteTree::Copy> copies;
  thread_local std::vector<Keyed> found;
  // The copies in `disks` that the grid window would give as first-stage candidates, with the
  // window's arithmetic and in its order.
  auto gather = [&](std::span<const SiteTree::Disk> disks) {
    copies.clear();
    found.clear();
    search.tree.copies_in_disks(disks, copies);
    scene.search_cache_->sites_examined.fetch_add(copies.size(), std::memory_order_relaxed);
    for (const SiteTree::Copy& k : copies) {
      if (scene.coincident[k.index]) continue;
      const long by = static_cast<long>(search.bucket[k.index]) / columns + k.ky * rows;
      const long bx = static_cast<long>(search.bucket[k.index]) % columns + k.kx * columns;
      if (by < lo_y || by > hi_y || bx < lo_x || bx > hi_x) continue;
      const Point site = scene.sites[k.index];
      const Point from = Point{site.x - lattice.x, site.y - lattice.y} - half_pixel;
      const Point o{from.x + static_cast<double>(k.kx) * domain.x, from.y + static_cast<double>(k.ky) * domain.y};
      const double d2 = o.x * o.x + o.y * o.y;
      if (d2 > reach * reach) continue;
      found.push_back({{k.index, k.kx, k.ky, o, d2}, by, bx, search.slot[k.index]});
    }
    std::sort(found.begin(), found.end(), before);
  };
  // The nearest copy (the first of equals in window order): within a hair of the tree's nearest.
  const SiteTree::Disk near{centre, std::sqrt(search.tree.nearest_squared(centre)) * (1.0 + 1e-9) + margin};
  gather(std::span<const SiteTree::Disk>(&near, 1));
  if (found.empty()) {
    const SiteTree::Disk all{centre, reach + margin};
    gather(std::span<const SiteTree::Disk>(&all, 1));
  }
  if (found.empty()) return;
  std::size_t nearest_index = 0;
  for (std::size_t c = 1; c < found.size(); ++c)
    if (found[c].c.distance_squared < found[nearest_index].c.distance_squared) nearest_index = c;
  const Keyed s0 = found[nearest_index];
  const double reach2 = std::sqrt(s0.c.distance_squared) + diagonal;
  const Point site0 = scene.sites[s0.c.site];
  const Point from0{site0.x - lattice.x, site0.y - lattice.y};
  const Point corner0{-(from0.x + static_cast<double>(s0.c.image_x) * domain.x), -(from0.y + static_cast<double>(s0.c.image_y) * domain.y)};
  // A site cuts the pixel only if it is nearer than s0 at some corner: it lies in the disk about
  // that corner through s0 (split_boundary_pixel's test, which decides below).
  const Point s0_copy{site0.x + static_cast<double>(s0.c.image_x) * domain.x, site0.y + static_cast<double>(s0.c.image_y) * domain.y};
  SiteTree::Disk disks[4];
  for (int corner = 0; corner < 4; ++corner) {
    const Point p{corner0.x + static_cast<double>(corner & 1) * h.x, corner0.y + static_cast<double>(corner >> 1) * h.y};
    disks[corner] = {s0_copy + p, std::sqrt(p.x * p.x + p.y * p.y) * (1.0 + 1e-9) + margin};
  }
  gather(disks);
  out.clear();
  for (const Keyed& k : found) {
    const Candidate& t = k.c;
    if (t.distance_squared > reach2 * reach2) continue;
    const bool is_s0 = t.site == s0.c.site && t.image_x == s0.c.image_x && t.image_y == s0.c.image_y;
    if (!is_s0 && !nearer_at_some_corner(scene, t, s0.c, corner0, h)) continue;
    out.push_back(t);
  }
}

}  // namespace raster_detail

}  // namespace bluetile
