// Area and moments of a polygon weighted by a density that is constant per texel (the weighted
// centroid of a Voronoi cell, Secord 2002 "Weighted Voronoi Stippling"), exact up to rounding.
#pragma once

#include <span>
#include <vector>

#include "bluetile/core/density_grid.h"
#include "bluetile/core/torus.h"

namespace bluetile {

struct Scene;

// Integrals over a region of rho, rho x, rho y and rho |x|^2, with x relative to the origin.
struct WeightedMoments {
  double mass = 0.0;
  Point first{0.0, 0.0};
  double second = 0.0;
};

// The moments of the simple polygon `polygon` (vertices counter-clockwise, relative to
// `origin`, a point of the domain) under `density` laid over the domain [0,W) x [0,H) of size
// `domain_size`. `periodic`: texel indices wrap, so the polygon may reach beyond the domain;
// otherwise the polygon must lie inside the closed domain (texels are clamped only against
// rounding).
WeightedMoments density_moments(std::span<const Point> polygon, Point origin, const DensityGrid& density,
                                Point domain_size, bool periodic);

// A polygon laid over the texel grid, shared by the integrations (density_moments and
// DensityPrefix) so that both see the same box and the same rounding.
struct TexelFrame {
  Point texel{0.0, 0.0};     // a texel's size, domain units
  long column = 0, row = 0;  // the grid texel (not yet wrapped) at the box's lower-left corner
  Point site{0.0, 0.0};      // the polygon's origin in the frame, domain units
  long columns = 0, rows = 0;  // texels the box spans
};

// The frame of `polygon` (at least one vertex, relative to `origin`): texel units, (0, 0) at the
// lower-left corner of its box; the vertices in those units go to `vertices`. Frame coordinates
// are >= 0 up to rounding, so converting one to an integer truncates as floor would; callers
// clamp against the rounding.
TexelFrame texel_frame(std::span<const Point> polygon, Point origin, const DensityGrid& density, Point domain_size,
                       std::vector<Point>& vertices);

// Throws Error when the density of `scene` cannot weight it: an empty grid, a texel that is not
// finite or negative, or zero everywhere. A scene without a density passes.
void check_density(const Scene& scene);

// True when every texel has the same value: the weighted centroid is then the unweighted one.
bool is_uniform(const DensityGrid& density);

}  // namespace bluetile
