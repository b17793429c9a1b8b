// How the contract harness (test_contract.cpp) runs each subcommand. What a command reads and
// writes is not here: each command declares its file options where it adds them
// (cli/file_options.h), and the harness takes them from the app (make_app, cli/app.h). This table
// holds only what the harness cannot know: a quick run and a long run of each command, its
// options that take text but name no file, and requests past each of its size limits. The harness
// fails for a command of the app missing here, and for an option that takes text and is neither a
// declared file option nor listed in not_files.
#pragma once

#include <span>
#include <string_view>
#include <vector>

namespace bluetile::robustness {

// A request past one of the command's up-front size limits: refused at once, before any output is
// staged, with the estimate (and the option to change where there is one).
struct Oversized {
  // After the command; "{<option>}" (any of a file option's names: "{-i}", "{--tiles}", "{tiles}"
  // for a positional) stands for a sound input of that option, or for an output path of it, in the
  // run's folder; "{<name>}" naming no option for a file of that name there. The quick run's
  // outputs are added.
  std::vector<std::string_view> arguments;
  std::string_view message;  // a part of the refusal: the estimate's words
};

struct CommandRuns {
  std::string_view command;
  // Arguments of a run that succeeds in well under a second (exact engine, a few points), beside
  // the file options in quick_files.
  std::vector<std::string_view> quick_run;
  // File options the quick run needs (by any of their names; a positional by its name): each input
  // gets a sound file of its kind, each output a path in the run's folder.
  std::vector<std::string_view> quick_files;
  // Arguments, in place of quick_run, of a run that goes on computing for many seconds after its
  // outputs are declared (with the same files); empty where the harness's small inputs allow none.
  std::vector<std::string_view> long_run;
  // Options that take text but name no file (a name, a label, a device).
  std::vector<std::string_view> not_files;
  // One request past each size limit; the harness fails a command without one unless it says that
  // nothing it is asked for has a size (devices).
  std::vector<Oversized> oversized;
  bool no_size_limit = false;
};

// Every subcommand of make_app(), in its order.
std::span<const CommandRuns> command_runs();

}  // namespace bluetile::robustness
