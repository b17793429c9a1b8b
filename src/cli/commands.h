// One function per subcommand: each registers its options on the app and the code to run.
#pragma once

#include <CLI/CLI.hpp>

namespace bluetile::cli {

void add_relax_command(CLI::App& app);
void add_centroids_command(CLI::App& app);
void add_analyze_command(CLI::App& app);
void add_dart_command(CLI::App& app);
void add_progressive_command(CLI::App& app);
void add_devices_command(CLI::App& app);
void add_wang_command(CLI::App& app);
void add_wang_check_command(CLI::App& app);
void add_tile_command(CLI::App& app);
void add_stipple_command(CLI::App& app);

}  // namespace bluetile::cli
