// Options shared by every subcommand that measures cells: which engine, and its settings.
#pragma once

#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "bluetile/core/output_file.h"
#include "bluetile/voronoi/engine.h"
#include "bluetile/raster/engine_choice.h"

namespace bluetile::cli {

// The library's engine choice (engine_choice.h: names, defaults, ranges), and the threads.
struct EngineOptions : EngineChoice {
  int threads = 0;  // CPU threads; 0 = all cores
};

void add_engine_options(CLI::App* command, EngineOptions& options);

// The raster engine's settings (--resolution, --coverage, --cone, --device, --pixel-work) change
// nothing on the exact engine: given for a run on it, they are refused before any work, with
// `why_exact` after the name of the engine (", the default with --bounded", or "" when --engine
// said so). `id_image`: the run draws an ID image, with a raster engine made from them.
void refuse_unused_raster_options(const CLI::App& command, const EngineOptions& options, const std::string& why_exact,
                                  bool id_image = false);

// The engine the options ask for; throws Error when it cannot be had.
std::unique_ptr<CentroidEngine> make_engine(const EngineOptions& options);

// The engine as a header names it: "exact", or "raster (area coverage, resolution from N, quad
// cones)" with the settings that shape its results.
std::string engine_text(const CentroidEngine& engine, const EngineOptions& options);

// The same settings as the options that give them, for a header that records its command line:
// "--engine exact", or "--engine raster --coverage area --cone quad" with "--resolution R" when one
// was given (from N otherwise).
std::string engine_arguments(const CentroidEngine& engine, const EngineOptions& options);

// Before a long raster job on a CPU device (lavapipe), one line on stderr with its estimated time
// and the exact engine's for the same cells (which is several times faster there): a user finds
// the fast path without reading the benchmarks. `site_iterations`: cells measured over the run.
void note_faster_engine(const CentroidEngine& engine, double site_iterations);
// After a raster run, one line on stderr when scenes went to the exact engine (sites on lines or
// in clusters: RasterOptions::max_cone_overlap), and one when cells did (point coverage whose
// samples missed them), so a user is not left thinking they were drawn.
void note_exact_hand_over(const CentroidEngine& engine);

// Writes the raster ID buffer of `scene` as an image (cells coloured, sites drawn). Uses
// `engine` when it is the raster engine, else a raster engine made from `options`.
void write_id_image(const EngineOptions& options, CentroidEngine& engine, const Scene& scene, OutputFile& out);

}  // namespace bluetile::cli
