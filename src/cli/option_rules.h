// Options that only some runs use. Where a run would not use one, it is refused, not ignored:
// an option given and silently dropped reads as if it had worked (wang --void-sigma with the fill
// order, stipple --png-width without --png). The same rule as --seed without --count, the raster
// settings with the exact engine and --transfer without a --density-map.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace bluetile::cli {

// Throws Error when `name` was given on `command` and the run does not use it (`used` false):
//   --void-sigma 0.6: only with --rank-order voids (this run: --rank-order fill)
// `needs` says what makes the run use the option, `this_run` the run's settings it depends on
// (empty: no parenthesis). A flag is named alone, an option with the value given.
void refuse_unless_used(const CLI::App& command, const std::string& name, bool used, const std::string& needs,
                        const std::string& this_run = "");

}  // namespace bluetile::cli
