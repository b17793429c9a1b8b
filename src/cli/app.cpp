#include "cli/app.h"

#include "cli/commands.h"
#include "cli/file_options.h"
#include "cli/numeric_options.h"

namespace bluetile::cli {
namespace {

// The tool's app takes its options' records with it (file_options.h, numeric_options.h): they are
// keyed by option, and a stale record matched another app's option at a reused address in the
// tests, which build several apps in one process (a test then failed or passed by the order).
class ToolApp final : public CLI::App {
 public:
  using CLI::App::App;
  ~ToolApp() override { forget_records(*this); }
  ToolApp(const ToolApp&) = delete;
  ToolApp& operator=(const ToolApp&) = delete;

 private:
  static void forget_records(const CLI::App& app) {
    for (const CLI::Option* option : app.get_options()) {
      forget_file_option(option);
      forget_numeric_option(option);
    }
    for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) forget_records(*command);
  }
};

}  // namespace

std::unique_ptr<CLI::App> make_app() {
  std::unique_ptr<CLI::App> app =
      std::make_unique<ToolApp>("bluetile: blue-noise sample points by Lloyd relaxation on the unit torus");
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
  // After the commands: a command's help would inherit it.
  app->footer("A command's options: bluetile help COMMAND, or bluetile COMMAND --help.");
  return app;
}

}  // namespace bluetile::cli
