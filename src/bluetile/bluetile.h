// Every public header of the library, for a program that would rather include one. The parts of
// the images and raster components come in where the program links them (bluetile::images,
// bluetile::raster or bluetile::bluetile define BLUETILE_WITH_IMAGES and BLUETILE_WITH_RASTER),
// so a program that links bluetile::core alone needs neither OpenImageIO's plugin nor Vulkan.
// Internal headers (src/bluetile/CMakeLists.txt) are not installed and not included here.
#pragma once

// core: points, files, the engine interface and the exact engine, the loops, analysis, tiling.
#include "bluetile/core/density_grid.h"
#include "bluetile/core/error.h"
#include "bluetile/core/input_file.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/point_table.h"
#include "bluetile/core/request_limits.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/torus.h"
#include "bluetile/voronoi/density_moments.h"
#include "bluetile/voronoi/engine.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/voronoi/site_grid.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/relax/progressive.h"
#include "bluetile/relax/stipple.h"
#include "bluetile/relax/wang_relax.h"
#include "bluetile/analysis/bond_order.h"
#include "bluetile/analysis/discrepancy.h"
#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/analysis/pair_correlation.h"
#include "bluetile/analysis/periodogram.h"
#include "bluetile/analysis/radial_power.h"
#include "bluetile/analysis/spectral_measures.h"
#include "bluetile/analysis/summary.h"
#include "bluetile/analysis/summary_record.h"
#include "bluetile/analysis/tiling_metrics.h"
#include "bluetile/sampling/dart_throwing.h"
#include "bluetile/sampling/density_sampling.h"
#include "bluetile/sampling/plot_order.h"
#include "bluetile/tiling/default_tile_set.h"
#include "bluetile/tiling/density_thinning.h"
#include "bluetile/tiling/seam_check.h"
#include "bluetile/tiling/tile_set.h"
#include "bluetile/tiling/tile_set_file.h"
#include "bluetile/tiling/tiled_output.h"
#include "bluetile/tiling/tiler.h"
#include "bluetile/tiling/tiling_plan.h"

#if BLUETILE_WITH_IMAGES
// images: density maps, image files, figures, SVG, PDF, plots, drawings of tiled windows.
#include "bluetile/io/density_map.h"
#include "bluetile/io/image.h"
#include "bluetile/io/image_file.h"
#include "bluetile/io/pdf.h"
#include "bluetile/io/plot.h"
#include "bluetile/io/svg.h"
#include "bluetile/drawing/figures.h"
#include "bluetile/drawing/tiled_drawing.h"
#endif

#if BLUETILE_WITH_RASTER
// raster: the Vulkan centroid engine and the device list.
#include "bluetile/gpu/context.h"
#include "bluetile/gpu/raster_layout.h"
#include "bluetile/raster/engine_choice.h"
#include "bluetile/raster/raster_engine.h"
#include "bluetile/raster/raster_scene.h"
#endif
