// The options that name files, declared once, where each command adds them: add_input_option,
// add_output_option and add_output_folder_option bind the option to its value, as add_option
// does, and keep a record of what it names (an input and what it holds, an output and its formats,
// a folder of outputs). Commands take their inputs from that record (add_declared_inputs), so that
// every file a command reads is an input of its same-file check; the robustness harness
// (tests/robustness/test_contract.cpp) takes every command's inputs and outputs from it, so that a
// new file option is put through the harness's matrix as it is added.
#pragma once

#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "bluetile/core/output_file.h"
#include "cli/output_names.h"

namespace bluetile::cli {

// What an input holds (the harness makes a sound file of that kind, then damages it).
enum class InputKind { points, tiles, image };

// What an output option writes.
struct OutputDeclaration {
  // The formats its extension picks from (cli/output_names.h), first the one "-" and names
  // without an extension take; empty for an output of one format that takes any name (a log).
  std::span<const OutputFormat> formats;
  // An output of one format: its usual extension (".csv").
  std::string_view extension;
  // "-" writes to standard output (else it is refused as one).
  bool standard_output = false;
};

// Outputs several commands declare alike.
inline constexpr OutputFormat kImageFormats[] = {OutputFormat::image};
inline constexpr OutputDeclaration kCsvLog{.extension = ".csv", .standard_output = true};

// The record of a file option.
struct FileOption {
  enum class Role { input, output, folder };
  std::string name;  // as messages write it: "--density-map"; a positional's name
  Role role = Role::input;
  InputKind kind = InputKind::points;  // inputs
  OutputDeclaration output;            // outputs
  std::function<std::vector<std::string>()> values;  // the paths given on the command line, once parsed
};

// The record of `option` when one of the helpers below added it, else null.
const FileOption* find_file_option(const CLI::Option* option);

// Drops the record of `option`: the registry is keyed by option, and a later app's options may
// reuse the address (make_app's app calls it for each of its options as it goes).
void forget_file_option(const CLI::Option* option);

// An option (or a positional, named without dashes) that names a file the command reads; "-" is
// standard input where the command's reader takes it.
CLI::Option* add_input_option(CLI::App* command, const std::string& names, std::string& target, InputKind kind,
                              const std::string& help);
CLI::Option* add_input_option(CLI::App* command, const std::string& names, std::vector<std::string>& targets,
                              InputKind kind, const std::string& help);

// An option that names a file the command writes (repeatable when `targets` is a vector).
CLI::Option* add_output_option(CLI::App* command, const std::string& names, std::string& target,
                               OutputDeclaration output, const std::string& help);
CLI::Option* add_output_option(CLI::App* command, const std::string& names, std::vector<std::string>& targets,
                               OutputDeclaration output, const std::string& help);

// An option that names a folder the command writes its files into.
CLI::Option* add_output_folder_option(CLI::App* command, const std::string& names, std::string& target,
                                      const std::string& help);

// Declares every input `command` was given (by the options above) in `outputs`, so that no output
// may be the same file as one of them, and refuses '-' given to two of them (standard input can
// be read once). Call it before declaring the outputs.
void add_declared_inputs(OutputSet& outputs, const CLI::App& command);

}  // namespace bluetile::cli
