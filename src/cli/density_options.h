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
  bool invert = false;
  double gamma = 1.0;
};

// Registers --transfer, --invert and --gamma on `command`. `invert_help` says what --invert
// means for this command (a command whose maps are dark-dense by nature says so).
void add_density_transfer_options(CLI::App* command, DensityMapOptions& options,
                                  std::string_view invert_help = "Dark means dense: density 1 - luminance");

// Registers --weight-exponent for the commands that relax toward a map (relax, stipple): Lloyd's
// cells are weighted by map^E, and 2 makes the dots' density follow the map (relax/lloyd.h).
void add_weight_exponent_option(CLI::App* command, double& exponent);

// The transfer the options name; `invert_by_default` flips the meaning of --invert for a command
// whose default is dark-dense (stipple).
DensityTransfer density_transfer(const DensityMapOptions& options, bool invert_by_default = false);

}  // namespace bluetile::cli
