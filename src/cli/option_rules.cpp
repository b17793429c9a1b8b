#include "cli/option_rules.h"

#include "bluetile/core/error.h"

namespace bluetile::cli {

void refuse_unless_used(const CLI::App& command, const std::string& name, bool used, const std::string& needs,
                        const std::string& this_run) {
  if (used || command.count(name) == 0) return;
  const CLI::Option* option = command.get_option(name);
  const std::string given = option->get_expected_min() == 0 ? name : name + " " + option->as<std::string>();
  throw Error(given + ": only with " + needs + (this_run.empty() ? "" : " (this run: " + this_run + ")"));
}

}  // namespace bluetile::cli
