// Options shared by every subcommand that reads a density map (relax --density-map, stipple,
// tile --density-map): how image values become density, spelled alike everywhere. The image
// option itself belongs to each command.
#pragma once

#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "bluetile/io/density_map.h"

namespace bluetile::cli {

struct DensityMapOptions {
  std::string transfer = "auto";  // auto | srgb | linear
  bool invert = false;  // density 1 - luminance; a command whose maps are dark-dense sets it first
  double gamma = 1.0;
};

// Registers --transfer, --invert/--no-invert and --gamma on `command`. --invert means the same
// everywhere, density = 1 - luminance (dark means dense), and --no-invert density = luminance;
// `options.invert` as given is the command's default, which the help states.
void add_density_transfer_options(CLI::App* command, DensityMapOptions& options);

// Registers --weight-exponent for the commands that relax toward a map (relax, stipple): Lloyd's
// cells are weighted by map^E, and 2 makes the dots' density follow the map (relax/lloyd.h).
void add_weight_exponent_option(CLI::App* command, double& exponent);

// The transfer the options name.
DensityTransfer density_transfer(const DensityMapOptions& options);

// For commands whose map is optional (relax, tile): --transfer, --invert, --no-invert, --gamma
// and --weight-exponent given without a --density-map are refused ("--gamma shapes a
// --density-map: give one"), not ignored.
void refuse_transfer_without_map(const CLI::App& command, bool has_map);

// The options as output headers record them, so that a file says how its map was read:
// "transfer auto, invert, gamma 1".
std::string transfer_text(const DensityMapOptions& options);

}  // namespace bluetile::cli
