// What every subcommand reads and writes, declared once: which of its options name input files
// (and of which kind), which name outputs (files or a folder), and the free-text options that
// name no file. The robustness harness (tests/robustness/test_contract.cpp) drives every output
// and input declared here through its matrix of special and damaged paths, and fails for any
// option of the app (make_app, app.h) that this table does not classify: a new command or file
// option is covered once it is declared here. Each command also declares requests past its size
// limits, which the harness requires refused up front.
#pragma once

#include <span>
#include <string_view>
#include <vector>

namespace bluetile::cli {

// What an input option reads: the harness makes a sound file of that kind, then damages it.
enum class InputKind { points, tiles, image };

struct InputOption {
  std::string_view option;  // as given on the command line: "-i", "--density-map", or "" for a positional
  InputKind kind;
  bool always = false;  // part of the command's quick run (else added only when it is tested)
};

struct OutputOption {
  std::string_view option;
  std::string_view name;  // a file name of the right extension (a folder's name for folders)
  bool folder = false;    // the option names a folder of outputs
  bool always = false;    // part of the quick run
};

// A request past one of the command's up-front size limits: refused at once, before any output is
// staged, with the estimate (and the option to change where there is one).
struct Oversized {
  // After the command; "{points}", "{tiles}" and "{image}" stand for a sound input of that kind,
  // "{<name>}" for the path of the output of that name. The outputs marked `always` are added.
  std::vector<std::string_view> arguments;
  std::string_view message;  // a part of the refusal: the estimate's words
};

struct CommandFiles {
  std::string_view command;
  // Arguments of a run that succeeds in well under a second (exact engine, a few points), beside
  // the inputs and outputs marked `always`.
  std::vector<std::string_view> quick_run;
  std::vector<InputOption> inputs;
  std::vector<OutputOption> outputs;
  // Free-text options that name no file (a name, a label, a device).
  std::vector<std::string_view> not_files;
  // One request past each size limit; the harness fails a command without one unless it declares
  // that nothing it is asked for has a size (devices).
  std::vector<Oversized> oversized;
  bool no_size_limit = false;
};

// Every subcommand of make_app(), in its order.
std::span<const CommandFiles> command_files();

}  // namespace bluetile::cli
