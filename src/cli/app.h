// The tool's command line: the app with every subcommand and its options, as main() parses it.
// The robustness tests build the same app to enumerate the subcommands and their options.
#pragma once

#include <memory>

#include <CLI/CLI.hpp>

namespace bluetile::cli {

std::unique_ptr<CLI::App> make_app();

}  // namespace bluetile::cli
