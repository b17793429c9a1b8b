// The raster engine's coverage check: a bounded cone can miss samples of its own cell, which
// then show a wrong site (or none). Every pass is checked and redone with larger radii when it
// fails, never accepted. Pure host code.
#pragma once

#include <cstdint>
#include <span>

#include "bluetile/gpu/raster_layout.h"
#include "bluetile/raster/raster_scene.h"

namespace bluetile {

// Whether the ID image of the last pass is the nearest-site diagram at every sample: no sample
// uncovered, and for every site s whose farthest owned sample lies at F_s, every site t within
// 2 F_s of s has a cone radius of at least F_s. Then every site nearer to a sample than the
// site it shows drew that sample, so it would show. Fills scene.need; on failure grows the
// radii that caused it (doubles them all when samples were uncovered).
bool check_coverage(RasterScene& scene, std::span<const gpu::SiteSums> sums, std::uint32_t uncovered);

// The distance from a site to its farthest owned sample (domain units).
double farthest_sample(const gpu::SiteSums& sums);

}  // namespace bluetile
