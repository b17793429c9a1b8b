// bluetile devices: the Vulkan devices the loader sees, with type and driver, and which one
// the raster engine picks by default.
#include <cstdio>

#include "cli/commands.h"
#include "bluetile/gpu/context.h"

namespace bluetile::cli {
namespace {

void run_devices() {
  auto devices = gpu::list_devices();
  if (devices.empty()) {
    std::printf("no Vulkan devices (install a driver, for example Mesa's lavapipe: mesa-vulkan-drivers)\n");
    return;
  }
  std::size_t chosen = devices.size();
  for (const auto& d : devices)
    if (chosen == devices.size() && d.suitable && d.type == "cpu") chosen = d.index;
  for (const auto& d : devices)
    if (chosen == devices.size() && d.suitable) chosen = d.index;
  for (const auto& d : devices) {
    std::printf("%zu%s %s  type %s  driver %s  Vulkan %s%s\n", d.index, d.index == chosen ? "*" : " ", d.name.c_str(),
                d.type.c_str(), d.driver.c_str(), d.api_version.c_str(),
                d.suitable ? "" : ("  (unusable: lacks " + d.missing + ")").c_str());
  }
  std::printf("* = default; pick another with --device NAME|INDEX\n");
}

}  // namespace

void add_devices_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("devices", "List the Vulkan devices (type and driver) the raster engine can use");
  cmd->callback([] { run_devices(); });
}

}  // namespace bluetile::cli
