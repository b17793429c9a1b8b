#include "contract_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <csignal>
#include <filesystem>
#include <mutex>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bluetile/core/point_file.h"
#include "bluetile/core/rng.h"
#include "bluetile/io/image_file.h"
#include "bluetile/io/pdf.h"
#include "cli/app.h"

namespace bluetile::robustness {

namespace fs = std::filesystem;
using cli::FileOption;
using cli::InputKind;
using test::TempDir;

namespace {

constexpr auto kRunLimit = std::chrono::seconds(60);  // a run still going then is a hang: killed, and failed

// Sound inputs of each kind, made once in-process.
struct Fixtures {
  TempDir dir;
  std::string points, tiles, image;
  Fixtures() {
    PointSet set;
    Rng rng(7);
    // Enough that most outputs of the quick runs fill more than a pipe's page.
    for (int i = 0; i < 200; ++i) set.points.push_back(rng.point(Domain{}));
    points = dir.write("points.txt", format_points(set));
    // A small set (4 points a tile) from the tool itself: wang-check on the built-in set takes 20 s.
    tiles = dir.file("tiles.txt");
    const Outcome made = run({"wang", "-n", "4", "-k", "1", "--warm", "0", "--lattice-steps", "0",
                              "--lattice-steps-per-iteration", "0", "--strategy", "rounds", "-o", tiles});
    EXPECT_EQ(made.exit_code, 0) << made.err;
    // Taller than wide, so that a render's height can pass its limit while its width cannot.
    std::vector<float> values(8 * 16);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = 0.1f + static_cast<float>(i % 7) / 8.0f;
    image = dir.file("map.png");
    write_image_file(image, 8, 16, 1, values, SampleFormat::uint8);
  }
};

const Fixtures& fixtures() {
  static const Fixtures made;
  return made;
}

std::string without_dashes(const std::string& name) { return name.substr(name.find_first_not_of('-')); }

// A name of the first format `out` writes that this build can write (no PDF without cairo).
std::string output_file_name(const FileArgument& out) {
  const std::string stem = without_dashes(out.label());
  if (out.file.role == FileOption::Role::folder) return stem;
  if (out.file.output.formats.empty()) return stem + std::string(out.file.output.extension);
  for (cli::OutputFormat format : out.file.output.formats) {
    if (format == cli::OutputFormat::pdf && !pdf_unavailable_reason().empty()) continue;
    for (std::string_view extension : cli::output_format_extensions(format))
      if (!extension.empty()) return stem + std::string(extension);
  }
  ADD_FAILURE() << out.label() << ": no format this build writes";
  return stem;
}

const CommandRuns* runs_of(const std::string& command) {
  for (const CommandRuns& r : command_runs())
    if (r.command == command) return &r;
  return nullptr;
}

std::vector<ContractCommand> make_commands() {
  // The records point into the app's options: it lives as long as the process.
  static const std::unique_ptr<CLI::App> app = cli::make_app();
  std::vector<ContractCommand> commands;
  for (const CLI::App* command : app->get_subcommands([](CLI::App*) { return true; })) {
    ContractCommand c;
    c.runs = runs_of(command->get_name());
    if (c.runs == nullptr) continue;  // Contract.EveryOptionOfEveryCommandIsDeclared fails for it
    for (const CLI::Option* option : command->get_options()) {
      const FileOption* file = cli::find_file_option(option);
      if (file == nullptr) continue;
      FileArgument a;
      a.file = *file;
      if (option->nonpositional()) {
        for (const std::string& s : option->get_snames()) a.names.push_back("-" + s);
        for (const std::string& l : option->get_lnames()) a.names.push_back("--" + l);
        a.flag = option->get_lnames().empty() ? a.names.front() : "--" + option->get_lnames().front();
      } else {
        a.names.push_back(option->get_name(true));
      }
      for (std::string_view q : c.runs->quick_files)
        a.quick = a.quick || std::find(a.names.begin(), a.names.end(), q) != a.names.end();
      if (file->role == FileOption::Role::input) {
        a.file_name = "input-" + without_dashes(a.label()) + (file->kind == InputKind::image ? ".png" : ".txt");
        c.inputs.push_back(std::move(a));
      } else {
        a.file_name = output_file_name(a);
        c.outputs.push_back(std::move(a));
      }
    }
    commands.push_back(std::move(c));
  }
  return commands;
}

}  // namespace

const std::vector<ContractCommand>& contract_commands() {
  static const std::vector<ContractCommand> commands = make_commands();
  return commands;
}

const std::string& sound_input(InputKind kind) {
  const Fixtures& f = fixtures();
  return kind == InputKind::points ? f.points : kind == InputKind::tiles ? f.tiles : f.image;
}

std::string input_path(const FileArgument& in, const TempDir& dir) { return dir.file(in.file_name); }
std::string output_path(const FileArgument& out, const TempDir& dir) { return dir.file(out.file_name); }

std::unique_ptr<TempDir> folder_for(const ContractCommand& c) {
  auto dir = std::make_unique<TempDir>();
  chmod(dir->path().c_str(), 0755);  // readable by the unprivileged runs
  for (const FileArgument& in : c.inputs) fs::copy_file(sound_input(in.file.kind), input_path(in, *dir));
  return dir;
}

std::vector<std::string> arguments(const ContractCommand& c, const TempDir& dir, const std::string& replace,
                                   const std::string& value, bool long_run) {
  std::vector<std::string> args = {c.name()};
  for (std::string_view a : long_run ? c.runs->long_run : c.runs->quick_run) args.emplace_back(a);
  auto add = [&](const FileArgument& f, const std::string& sound) {
    const bool replaced = !replace.empty() && replace == f.label();
    if (!replaced && !f.quick) return;
    if (!f.flag.empty()) args.push_back(f.flag);
    args.push_back(replaced ? value : sound);
  };
  for (const FileArgument& in : c.inputs) add(in, input_path(in, dir));
  for (const FileArgument& out : c.outputs) add(out, output_path(out, dir));
  return args;
}

std::vector<std::string> writing_everything(const ContractCommand& c, const TempDir& dir, bool long_run) {
  std::vector<std::string> args = arguments(c, dir, "", "", long_run);
  for (const FileArgument& out : c.outputs)
    if (!out.quick) args.insert(args.end(), {out.flag, output_path(out, dir)});
  return args;
}

std::vector<std::string> output_paths(const ContractCommand& c, const TempDir& dir) {
  std::vector<std::string> paths;
  for (const FileArgument& out : c.outputs) paths.push_back(output_path(out, dir));
  return paths;
}

bool no_staging_left(const std::vector<std::string>& names) {
  return std::none_of(names.begin(), names.end(), [](const std::string& n) { return n.find(".bluetile") != std::string::npos; });
}

namespace {

// Reads a FIFO until `stop` is set and nothing is left, without waiting for a writer.
class FifoDrain {
 public:
  explicit FifoDrain(const std::string& path) {
    fd_ = open(path.c_str(), O_RDONLY | O_NONBLOCK);
    thread_ = std::thread([this] {
      char buffer[65536];
      for (;;) {
        const ssize_t n = read(fd_, buffer, sizeof buffer);
        if (n > 0) {
          bytes_ += static_cast<std::size_t>(n);
          continue;
        }
        if (stop_) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
    });
  }
  // The bytes read in all, once the writer is gone.
  std::size_t finish() {
    stop_ = true;
    thread_.join();
    close(fd_);
    return bytes_;
  }

 private:
  int fd_ = -1;
  std::atomic<bool> stop_{false};
  std::size_t bytes_ = 0;
  std::thread thread_;
};

}  // namespace

Invocation in_its_folder(const Case& k) {
  Invocation call = k.call;
  if (call.working_directory.empty()) call.working_directory = k.dir->path();
  return call;
}

Outcome wait_or_kill(Child& child) {
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  std::thread watchdog([&] {
    std::unique_lock<std::mutex> lock(mutex);
    if (!finished.wait_for(lock, kRunLimit, [&] { return done; })) kill(child.pid(), SIGKILL);
  });
  Outcome outcome = child.wait();
  {
    std::lock_guard<std::mutex> lock(mutex);
    done = true;
  }
  finished.notify_one();
  watchdog.join();
  return outcome;
}

void run_cases(std::vector<Case>& cases, std::size_t at_once) {
  for (std::size_t start = 0; start < cases.size(); start += at_once) {
    const std::size_t end = std::min(cases.size(), start + at_once);
    std::vector<std::unique_ptr<FifoDrain>> drains;
    std::vector<std::unique_ptr<Child>> children;
    const auto started = std::chrono::steady_clock::now();
    for (std::size_t i = start; i < end; ++i) {
      drains.push_back(cases[i].fifo.empty() ? nullptr : std::make_unique<FifoDrain>(cases[i].fifo));
      children.push_back(std::make_unique<Child>(in_its_folder(cases[i])));
    }
    for (std::size_t i = start; i < end; ++i) {
      Case& k = cases[i];
      const Outcome r = wait_or_kill(*children[i - start]);
      const auto took = std::chrono::steady_clock::now() - started;
      if (k.within.count() > 0) {
        EXPECT_LT(took, k.within) << k.what << ": still running after " << k.within.count() << " s";
      }
      const std::size_t drained = drains[i - start] ? drains[i - start]->finish() : 0;
      const bool memory_refusal = k.or_memory_refusal && r.exit_code != 0;
      if (memory_refusal) {
        EXPECT_TRUE(r.err.find("memory") != std::string::npos || r.err.find("address space") != std::string::npos)
            << k.what << ": the refusal does not say memory is short: " << r.err;
      }
      if (k.refused || memory_refusal) {
        // 1: found by the command; 105: by the option parser (an ExistingFile check, say).
        EXPECT_TRUE(r.exit_code == 1 || r.exit_code == 105) << k.what << ": status " << r.exit_code << ": " << r.err;
        EXPECT_EQ(r.err.rfind("bluetile: ", 0), 0u) << k.what << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << k.what << ": " << r.err;
        EXPECT_NE(r.err.find(k.named), std::string::npos) << k.what << ": the message names " << k.named << ": " << r.err;
        EXPECT_EQ(entries(k.dir->path()), k.before) << k.what << ": " << r.err;
      } else {
        EXPECT_EQ(r.exit_code, 0) << k.what << ": " << r.err;
        EXPECT_TRUE(no_staging_left(entries(k.dir->path()))) << k.what;
        if (!k.fifo.empty()) {
          EXPECT_GT(drained, 0u) << k.what << ": nothing came through the FIFO";
        }
      }
      if (k.check) k.check(r);
    }
  }
}

std::vector<std::unique_ptr<TempDir>> sound_runs() {
  const std::vector<ContractCommand>& commands = contract_commands();
  std::vector<std::unique_ptr<TempDir>> folders;
  std::vector<std::unique_ptr<Child>> children;
  for (const ContractCommand& c : commands) {
    folders.push_back(folder_for(c));
    Invocation call{writing_everything(c, *folders.back())};
    call.working_directory = folders.back()->path();
    children.push_back(std::make_unique<Child>(call));
  }
  for (std::size_t i = 0; i < commands.size(); ++i) {
    const Outcome made = wait_or_kill(*children[i]);
    EXPECT_EQ(made.exit_code, 0) << commands[i].name() << ": " << made.err;
  }
  return folders;
}

}  // namespace bluetile::robustness
