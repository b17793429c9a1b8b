#include "cli/file_options.h"

#include <map>

#include "bluetile/core/error.h"

namespace bluetile::cli {
namespace {

std::map<const CLI::Option*, FileOption>& file_registry() {
  static std::map<const CLI::Option*, FileOption> registry;
  return registry;
}

// The name messages use: the last of `names`, or a positional's own.
std::string name_of(const std::string& names) { return CLI::detail::split(names, ',').back(); }

CLI::Option* record(CLI::Option* option, FileOption file) {
  file_registry().insert_or_assign(option, std::move(file));
  return option;
}

std::function<std::vector<std::string>()> one_value(const std::string& target) {
  return [&target] { return target.empty() ? std::vector<std::string>{} : std::vector<std::string>{target}; };
}

std::function<std::vector<std::string>()> all_values(const std::vector<std::string>& targets) {
  return [&targets] { return targets; };
}

}  // namespace

const FileOption* find_file_option(const CLI::Option* option) {
  auto it = file_registry().find(option);
  return it == file_registry().end() ? nullptr : &it->second;
}

void forget_file_option(const CLI::Option* option) { file_registry().erase(option); }

CLI::Option* add_input_option(CLI::App* command, const std::string& names, std::string& target, InputKind kind,
                              const std::string& help) {
  return record(command->add_option(names, target, help),
                {name_of(names), FileOption::Role::input, kind, {}, one_value(target)});
}

CLI::Option* add_input_option(CLI::App* command, const std::string& names, std::vector<std::string>& targets,
                              InputKind kind, const std::string& help) {
  return record(command->add_option(names, targets, help),
                {name_of(names), FileOption::Role::input, kind, {}, all_values(targets)});
}

CLI::Option* add_output_option(CLI::App* command, const std::string& names, std::string& target,
                               OutputDeclaration output, const std::string& help) {
  return record(command->add_option(names, target, help),
                {name_of(names), FileOption::Role::output, {}, output, one_value(target)});
}

CLI::Option* add_output_option(CLI::App* command, const std::string& names, std::vector<std::string>& targets,
                               OutputDeclaration output, const std::string& help) {
  return record(command->add_option(names, targets, help),
                {name_of(names), FileOption::Role::output, {}, output, all_values(targets)});
}

CLI::Option* add_output_folder_option(CLI::App* command, const std::string& names, std::string& target,
                                      const std::string& help) {
  return record(command->add_option(names, target, help),
                {name_of(names), FileOption::Role::folder, {}, {}, one_value(target)});
}

void add_declared_inputs(OutputSet& outputs, const CLI::App& command) {
  std::string reads_standard_input;  // the option that took "-" first
  for (const CLI::Option* option : command.get_options()) {
    const FileOption* file = find_file_option(option);
    if (file == nullptr || file->role != FileOption::Role::input) continue;
    for (const std::string& path : file->values()) {
      // The second reader would find standard input already read to its end.
      if (path == "-" && !reads_standard_input.empty())
        throw Error("-: " + reads_standard_input + " and " + file->name +
                    " both read standard input, which can be read once: give one of them a file");
      if (path == "-") reads_standard_input = file->name;
      outputs.add_input(path);
    }
  }
}

}  // namespace bluetile::cli
