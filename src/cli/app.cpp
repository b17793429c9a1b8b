#include "cli/app.h"

#include "cli/commands.h"

namespace bluetile::cli {

std::unique_ptr<CLI::App> make_app() {
  auto app = std::make_unique<CLI::App>("bluetile: blue-noise sample points by Lloyd relaxation on the unit torus");
  app->require_subcommand(1);
  app->set_version_flag("--version", "bluetile 0.1.0");
  add_relax_command(*app);
  add_centroids_command(*app);
  add_analyze_command(*app);
  add_dart_command(*app);
  add_progressive_command(*app);
  add_devices_command(*app);
  add_wang_command(*app);
  add_wang_check_command(*app);
  add_tile_command(*app);
  add_stipple_command(*app);
  return app;
}

}  // namespace bluetile::cli
