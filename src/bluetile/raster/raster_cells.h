// From a raster pass's per-site sums to cells: whole pixels (integer offsets), device pieces
// (fixed point) and host pieces (double) in domain units, relative to each site. Pure host code.
#pragma once

#include <span>
#include <vector>

#include "bluetile/gpu/raster_layout.h"
#include "bluetile/voronoi/engine.h"
#include "bluetile/raster/raster_reference.h"
#include "bluetile/raster/raster_scene.h"

namespace bluetile {

// The wanted cells of `scene` into `out`. `host_pieces` holds one entry per site (pieces of
// pixels split on the host; may be empty). A cell with no area (in point coverage: no sample)
// is measured by the exact engine (exact_fallback). A scene whose density varies takes its
// masses, centroids and second moments from `weighted` (one per site) and the host pieces'
// weighted moments; a cell of mass 0 keeps its site (zero_density), as in the exact engine.
void assemble_cells(const RasterScene& scene, std::span<const gpu::SiteSums> sums, std::span<const PieceSums> host_pieces,
                    SceneCells& out, std::span<const WeightedSums> weighted = {});

}  // namespace bluetile
