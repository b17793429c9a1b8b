// The contract harness's view of the tool: every subcommand of the app (cli/app.h) with the file
// options it declares (cli/file_options.h) and the runs command_runs.h gives it; sound inputs of
// every kind; and cases (a run, what it must do) run a few at a time.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cli/file_options.h"
#include "command_runs.h"
#include "robustness_support.h"
#include "test_support.h"

namespace bluetile::robustness {

// A file option of a command, as the harness drives it.
struct FileArgument {
  std::string flag;                // on the command line ("--density-map"); "" for a positional
  std::vector<std::string> names;  // every name it answers to: "-i", "--input"; a positional's own
  cli::FileOption file;
  bool quick = false;     // given in the quick run
  std::string file_name;  // inputs: the sound copy's name; outputs: a name of a format it writes
  std::string label() const { return flag.empty() ? names.front() : flag; }
};

struct ContractCommand {
  const CommandRuns* runs = nullptr;
  std::vector<FileArgument> inputs, outputs;
  std::string name() const { return std::string(runs->command); }
};

// The app's subcommands that command_runs() has, with their file options, in the app's order.
const std::vector<ContractCommand>& contract_commands();

// The sound input of `kind` (made once per process).
const std::string& sound_input(cli::InputKind kind);

// A fresh folder (open to the unprivileged runs) holding a sound copy of every input of `c`.
std::unique_ptr<test::TempDir> folder_for(const ContractCommand& c);

// The path of `in`'s sound copy, or of `out`'s output, in `dir`.
std::string input_path(const FileArgument& in, const test::TempDir& dir);
std::string output_path(const FileArgument& out, const test::TempDir& dir);

// `c`'s quick run in `dir` (or its long run, `long_run`): the quick files' inputs and outputs
// there; `replace` names a file option by its flag or positional name, whose value `value`
// replaces (or adds).
std::vector<std::string> arguments(const ContractCommand& c, const test::TempDir& dir, const std::string& replace = "",
                                   const std::string& value = "", bool long_run = false);

// The quick (or long) run with every output `c` has, each in `dir`.
std::vector<std::string> writing_everything(const ContractCommand& c, const test::TempDir& dir, bool long_run = false);
std::vector<std::string> output_paths(const ContractCommand& c, const test::TempDir& dir);

bool no_staging_left(const std::vector<std::string>& entries);

// One run of the matrix: its arguments, what it must do, and checks of its own.
struct Case {
  std::string what;  // "relax --log: full device", for failure messages
  std::unique_ptr<test::TempDir> dir;
  Invocation call;
  bool refused = true;
  bool or_memory_refusal = false;             // not refused: or else refused for want of memory
  std::string named;                          // a refusal's message must contain this path
  std::vector<std::string> before;            // refused: the folder must be left as it was
  std::function<void(const Outcome&)> check;  // more checks (run after the common ones)
  std::string fifo;                           // an output FIFO to drain while the run goes
  std::chrono::seconds within{0};             // when set, the run must end within this (a hang detector)
};

// The case's call, run in the case's folder unless it names another.
Invocation in_its_folder(const Case& k);

// Runs `at_once` cases at a time (1 where each run's wall time is checked) and checks each.
void run_cases(std::vector<Case>& cases, std::size_t at_once = 4);

// Waits for the child; one still running after a minute is killed (and so fails its case).
Outcome wait_or_kill(Child& child);

// Sound runs of every command writing every output, in folders of their own, all at once: the
// folders, in contract_commands()' order (fails the test for a run that does not succeed).
std::vector<std::unique_ptr<test::TempDir>> sound_runs();

}  // namespace bluetile::robustness
