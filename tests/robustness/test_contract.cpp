// The contract harness: every subcommand of the tool's own app (cli/app.h), with the inputs and
// outputs it declares (cli/command_files.h), through one matrix. Every output goes to a full
// device, a FIFO, a read-only folder, a symbolic link, an input's own path (and a hard or
// symbolic link to it) and under ulimit -f; every input is given truncated, empty, as binary
// garbage, missing and as a folder. A refusal is exit status 1 (105 where the option parser
// refuses), one `bluetile:` line naming the path, and the folder exactly as before (no staging
// file left); a FIFO output receives the bytes and a link is followed. Devices need mknod (root)
// and the read-only folder an unprivileged user: skipped with a message otherwise. Beyond those:
// - every output into a tmpfs one page smaller than it (in a user and mount namespace of its own,
//   so no root needed), so that it fills mid-write: refused with "No space left on device",
//   nothing left in the tmpfs;
// - every command, writing every output, under ulimit -v 15 to 600 MiB: success, or a refusal that
//   says memory is short, never a signal, the folder as before;
// - every command's requests past its size limits (declared beside its files): refused within
//   seconds with the estimate, nothing written; a command must declare one, or no_size_limit.
// A new command declared in command_files.cpp gets every cell without a new test.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include "bluetile/core/point_file.h"
#include "bluetile/core/rng.h"
#include "bluetile/io/image_file.h"
#include "cli/app.h"
#include "cli/command_files.h"
#include "robustness_support.h"
#include "test_support.h"

namespace bluetile::robustness {
namespace {

namespace fs = std::filesystem;
using cli::CommandFiles;
using cli::InputKind;
using test::read_text;
using test::TempDir;
using Names = std::vector<std::string>;

constexpr int kParallelRuns = 4;                    // children at once: the runs mostly wait on the loader
constexpr long kFileSizeLimit = 512;               // bytes: under every quick run's output, over any message
constexpr auto kRunLimit = std::chrono::seconds(60);  // a run still going then is a hang: killed, and failed

// Sound inputs of each kind, made once in-process.
struct Fixtures {
  TempDir dir;
  std::string points, tiles, image;
  Fixtures() {
    PointSet set;
    Rng rng(7);
    for (int i = 0; i < 30; ++i) set.points.push_back(rng.point(Domain{}));
    points = dir.write("points.txt", format_points(set));
    // A small set (4 points a tile) from the tool itself: wang-check on the built-in set takes 20 s.
    tiles = dir.file("tiles.txt");
    const Outcome made = run({"wang", "-n", "4", "-k", "1", "--warm", "0", "--lattice-steps", "0",
                              "--lattice-steps-per-iteration", "0", "--strategy", "rounds", "-o", tiles});
    EXPECT_EQ(made.exit_code, 0) << made.err;
    std::vector<float> values(8 * 8);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = 0.1f + static_cast<float>(i % 7) / 8.0f;
    image = dir.file("map.png");
    write_image_file(image, 8, 8, 1, values, SampleFormat::uint8);
  }
  const std::string& of(InputKind kind) const {
    return kind == InputKind::points ? points : kind == InputKind::tiles ? tiles : image;
  }
};

const Fixtures& fixtures() {
  static const Fixtures made;
  return made;
}

std::string extension_of(InputKind kind) { return kind == InputKind::image ? ".png" : ".txt"; }

// The copy of the sound input that folder_for() made for `in`.
std::string input_file(const cli::InputOption& in, const TempDir& dir) {
  return dir.file("input-" + std::string(in.option == "" ? "positional" : in.option.substr(in.option.find_first_not_of('-'))) +
                  extension_of(in.kind));
}

// One run of the matrix: its arguments, what it must do, and checks of its own.
struct Case {
  std::string what;  // "relax --log: full device", for failure messages
  std::unique_ptr<TempDir> dir;
  Invocation call;
  bool refused = true;
  bool or_memory_refusal = false;        // not refused: or else refused for want of memory
  std::string named;                     // a refusal's message must contain this path
  Names before;                          // refused: the folder must be left as it was
  std::function<void(const Outcome&)> check;  // more checks (run after the common ones)
  std::string fifo;                      // an output FIFO to drain while the run goes
  std::chrono::seconds within{0};        // when set, the run must end within this (a hang detector)
};

// The command's quick run in `dir`: inputs copied there, outputs there; `input_value` and
// `output_value` replace (or add) the value of one input or output option.
std::vector<std::string> arguments(const CommandFiles& c, const TempDir& dir, const std::string& input_option,
                                   const std::string& input_value, const std::string& output_option,
                                   const std::string& output_value) {
  std::vector<std::string> args = {std::string(c.command)};
  for (std::string_view a : c.quick_run) args.emplace_back(a);
  for (const auto& in : c.inputs) {
    std::string value;
    if (std::string(in.option) == input_option && !input_value.empty()) value = input_value;
    else if (in.always) value = input_file(in, dir);
    if (value.empty()) continue;
    if (!in.option.empty()) args.emplace_back(in.option);
    args.push_back(value);
  }
  for (const auto& out : c.outputs) {
    std::string value;
    if (std::string(out.option) == output_option && !output_value.empty()) value = output_value;
    else if (out.always) value = dir.file(std::string(out.name));
    if (value.empty()) continue;
    args.emplace_back(out.option);
    args.push_back(value);
  }
  return args;
}

// A fresh folder holding a copy of each input the command's quick run reads (by option).
std::unique_ptr<TempDir> folder_for(const CommandFiles& c) {
  auto dir = std::make_unique<TempDir>();
  chmod(dir->path().c_str(), 0755);  // readable by the unprivileged runs
  for (const auto& in : c.inputs) fs::copy_file(fixtures().of(in.kind), input_file(in, *dir));
  return dir;
}

// The quick run with every output the command has, each in `dir`.
std::vector<std::string> writing_everything(const CommandFiles& c, const TempDir& dir) {
  std::vector<std::string> args = arguments(c, dir, "", "", "", "");
  for (const auto& out : c.outputs)
    if (!out.always) args.insert(args.end(), {std::string(out.option), dir.file(std::string(out.name))});
  return args;
}

std::vector<std::string> output_paths(const CommandFiles& c, const TempDir& dir) {
  std::vector<std::string> paths;
  for (const auto& out : c.outputs) paths.push_back(dir.file(std::string(out.name)));
  return paths;
}

bool no_staging_left(const Names& names) {
  return std::none_of(names.begin(), names.end(), [](const std::string& n) { return n.find(".bluetile") != std::string::npos; });
}

std::vector<Case> output_cases(const CommandFiles& c, bool& devices_skipped) {
  std::vector<Case> cases;
  for (const auto& out : c.outputs) {
    const std::string option(out.option), label = std::string(c.command) + " " + option + ": ";
    auto add = [&](Case k) { cases.push_back(std::move(k)); };

    {  // A full device: nothing fits (files), or no folder (folders).
      Case k;
      k.what = label + "full device";
      k.dir = folder_for(c);
      const std::string device = k.dir->file("full-" + std::string(out.name));
      if (mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 7)) != 0) {
        devices_skipped = true;
      } else {
        k.call.arguments = arguments(c, *k.dir, "", "", option, device);
        k.named = device;
        k.before = entries(k.dir->path());
        add(std::move(k));
      }
    }
    {  // A FIFO: streamed into it (files); not a folder (folders).
      Case k;
      k.what = label + "FIFO";
      k.dir = folder_for(c);
      const std::string fifo = k.dir->file("pipe-" + std::string(out.name));
      EXPECT_EQ(mkfifo(fifo.c_str(), 0666), 0);
      k.call.arguments = arguments(c, *k.dir, "", "", option, fifo);
      k.named = fifo;
      k.before = entries(k.dir->path());
      if (!out.folder) {
        k.refused = false;
        k.fifo = fifo;
      }
      add(std::move(k));
    }
    {  // A read-only folder, as a user without rights over it.
      Case k;
      k.what = label + "read-only folder";
      k.dir = folder_for(c);
      chmod(k.dir->path().c_str(), 0777);  // the other outputs of the run may be written
      const std::string locked = k.dir->file("locked");
      fs::create_directory(locked);
      chmod(locked.c_str(), 0555);
      k.call.arguments = arguments(c, *k.dir, "", "", option, locked + "/" + std::string(out.name));
      k.call.unprivileged = true;
      k.named = locked;
      k.before = entries(k.dir->path());
      add(std::move(k));
    }
    {  // A symbolic link: followed, and still a link afterwards.
      Case k;
      k.what = label + "symbolic link";
      k.dir = folder_for(c);
      const std::string real = k.dir->file("real"), link = k.dir->file("link-" + std::string(out.name));
      fs::create_directory(real);
      const std::string target = real + "/" + std::string(out.name);
      if (out.folder) fs::create_directory(target);
      else k.dir->write("real/" + std::string(out.name), "old\n");
      fs::create_symlink(target, link);
      k.call.arguments = arguments(c, *k.dir, "", "", option, link);
      k.refused = false;
      const bool folder = out.folder;
      k.check = [link, target, folder, what = k.what](const Outcome&) {
        EXPECT_TRUE(fs::is_symlink(link)) << what;
        if (folder) {
          EXPECT_FALSE(fs::is_empty(target)) << what;
        } else {
          EXPECT_NE(read_text(target), "old\n") << what;
        }
      };
      add(std::move(k));
    }
    for (const auto& in : c.inputs) {
      // Every input's own path, a hard link to it and a symbolic link to it: refused, the input
      // untouched. An input the quick run does not read is added for the case.
      for (const char* how : {"path", "hard link", "symbolic link"}) {
        Case k;
        k.what = label + "same file as " + (in.option.empty() ? "the input" : std::string(in.option)) + " (" + how + ")";
        k.dir = folder_for(c);
        const std::string input = input_file(in, *k.dir);
        std::string path = input;
        if (std::string(how) == "hard link") {
          path = k.dir->file("hard-link" + extension_of(in.kind));
          fs::create_hard_link(input, path);
        } else if (std::string(how) == "symbolic link") {
          path = k.dir->file("link" + extension_of(in.kind));
          fs::create_symlink(input, path);
        }
        k.call.arguments = arguments(c, *k.dir, std::string(in.option), input, option, path);
        k.named = path;
        k.before = entries(k.dir->path());
        const std::string bytes = read_text(input);
        k.check = [input, bytes, what = k.what](const Outcome&) { EXPECT_EQ(read_text(input), bytes) << what; };
        add(std::move(k));
      }
    }
    {  // ulimit -f: no output fits (the limit holds for the captured stderr too: a message fits).
      Case k;
      k.what = label + "ulimit -f";
      k.dir = folder_for(c);
      k.call.arguments = arguments(c, *k.dir, "", "", option, k.dir->file(std::string(out.name)));
      k.call.file_size_bytes = kFileSizeLimit;
      k.before = entries(k.dir->path());
      add(std::move(k));
    }
  }
  return cases;
}

// Damaged copies of a sound input: cut inside its last line (text) or halfway (binary), empty,
// and bytes that are no file of any kind; and no file at all, or a folder, where it should be.
std::vector<std::pair<std::string, std::string>> damaged(InputKind kind) {
  const std::string sound = read_text(fixtures().of(kind));
  std::string truncated = kind == InputKind::image ? sound.substr(0, sound.size() / 2) : sound.substr(0, sound.rfind(' '));
  std::string garbage;
  Rng rng(11);
  for (int i = 0; i < 300; ++i) garbage.push_back(static_cast<char>(rng.below(256)));
  return {{"truncated", truncated}, {"empty", ""}, {"garbage", garbage}, {"missing", ""}, {"a folder", ""}};
}

std::vector<Case> input_cases(const CommandFiles& c) {
  std::vector<Case> cases;
  for (const auto& in : c.inputs) {
    for (const auto& [how, bytes] : damaged(in.kind)) {
      Case k;
      k.what = std::string(c.command) + " " + (in.option.empty() ? "(positional)" : std::string(in.option)) + ": " + how;
      k.dir = folder_for(c);
      const std::string path = k.dir->file(how + extension_of(in.kind));
      if (how == "missing") {
      } else if (how == "a folder") {
        fs::create_directory(path);
      } else {
        k.dir->write(how + extension_of(in.kind), bytes);
      }
      k.call.arguments = arguments(c, *k.dir, std::string(in.option), path, "", "");
      k.named = path;
      k.before = entries(k.dir->path());
      cases.push_back(std::move(k));
    }
  }
  return cases;
}

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

// Waits for the child; one still running after kRunLimit is killed (and so fails its case).
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

// Runs `at_once` cases at a time (1 where each run's wall time is checked).
void run_cases(std::vector<Case>& cases, std::size_t at_once = kParallelRuns) {
  for (std::size_t start = 0; start < cases.size(); start += at_once) {
    const std::size_t end = std::min(cases.size(), start + at_once);
    std::vector<std::unique_ptr<FifoDrain>> drains;
    std::vector<std::unique_ptr<Child>> children;
    const auto started = std::chrono::steady_clock::now();
    for (std::size_t i = start; i < end; ++i) {
      drains.push_back(cases[i].fifo.empty() ? nullptr : std::make_unique<FifoDrain>(cases[i].fifo));
      children.push_back(std::make_unique<Child>(cases[i].call));
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

const CommandFiles* declared(std::string_view command) {
  for (const CommandFiles& c : cli::command_files())
    if (c.command == command) return &c;
  return nullptr;
}

// Every option of every subcommand that takes free text (no fixed choices) is a declared input,
// output or non-file option: a new command or option cannot slip past the harness.
TEST(Contract, EveryFileOptionOfEveryCommandIsDeclared) {
  std::unique_ptr<CLI::App> app = cli::make_app();
  std::set<std::string_view> commands;
  for (const CLI::App* command : app->get_subcommands([](CLI::App*) { return true; })) {
    const std::string name = command->get_name();
    const CommandFiles* files = declared(name);
    ASSERT_NE(files, nullptr) << name << " is missing from cli/command_files.cpp";
    commands.insert(files->command);
    for (const CLI::Option* option : command->get_options()) {
      const std::string type = option->get_type_name();
      if (type.rfind("TEXT", 0) != 0 || type.find('{') != std::string::npos) continue;
      const std::string flag = option->get_lnames().empty() ? "" : "--" + option->get_lnames().front();
      const std::string shortest = option->get_snames().empty() ? flag : "-" + option->get_snames().front();
      bool known = false;
      for (const auto& in : files->inputs) known |= in.option == shortest || in.option == flag || (in.option.empty() && flag.empty());
      for (const auto& out : files->outputs) known |= out.option == shortest || out.option == flag;
      for (std::string_view other : files->not_files) known |= other == flag;
      EXPECT_TRUE(known) << name << " " << option->get_name() << " takes text but cli/command_files.cpp does not say "
                         << "whether it is an input, an output or no file";
    }
  }
  EXPECT_EQ(commands.size(), cli::command_files().size()) << "a declared command the app does not have";
}

TEST(Contract, EveryOutputOfEveryCommandUnderTheMatrix) {
  bool devices_skipped = false;
  std::vector<Case> cases;
  for (const CommandFiles& c : cli::command_files())
    for (Case& k : output_cases(c, devices_skipped)) cases.push_back(std::move(k));
  if (geteuid() != 0) {
    // Without root the read-only folder does not hold root out, and the run as nobody is not
    // possible: those cases are for root only.
    std::erase_if(cases, [](const Case& k) { return k.call.unprivileged; });
    std::printf("contract: not root: read-only folder cases skipped\n");
  }
  if (devices_skipped) std::printf("contract: mknod refused (needs root): device outputs skipped\n");
  EXPECT_GT(cases.size(), 60u);
  run_cases(cases);
}

TEST(Contract, EveryInputOfEveryCommandDamaged) {
  std::vector<Case> cases;
  for (const CommandFiles& c : cli::command_files())
    for (Case& k : input_cases(c)) cases.push_back(std::move(k));
  EXPECT_GT(cases.size(), 25u);
  run_cases(cases);
}

// Ctrl-C at some moment of a run that writes every output the command has: either the run was
// done (status 0) or it ends by SIGINT with the folder exactly as before, or, when the signal came
// after the outputs were published, with every one of them there (all or none) and no staging
// file. The moments fall in the
// image plugin's loading, the reading and the writing, depending on the command and the load.
TEST(Contract, EveryCommandInterruptedLeavesNothing) {
  int interrupted = 0, finished = 0;
  for (const int delay_ms : {30, 150, 400}) {
    std::vector<Case> cases;
    std::vector<std::unique_ptr<Child>> children;
    for (const CommandFiles& c : cli::command_files()) {
      if (c.outputs.empty()) continue;
      Case k;
      k.what = std::string(c.command) + ": SIGINT after " + std::to_string(delay_ms) + " ms";
      k.dir = folder_for(c);
      k.call.arguments = writing_everything(c, *k.dir);
      k.before = entries(k.dir->path());
      const std::vector<std::string> outputs = output_paths(c, *k.dir);
      k.check = [outputs, what = k.what](const Outcome& r) {
        if (r.signal != SIGINT) return;
        std::size_t present = 0;
        for (const std::string& path : outputs) present += fs::exists(path);
        EXPECT_TRUE(present == 0 || present == outputs.size()) << what << ": " << present << " of " << outputs.size()
                                                             << " outputs published";
      };
      cases.push_back(std::move(k));
    }
    for (const Case& k : cases) children.push_back(std::make_unique<Child>(k.call));
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    for (const auto& child : children) kill(child->pid(), SIGINT);
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const Outcome r = wait_or_kill(*children[i]);
      if (r.signal == SIGINT) {
        ++interrupted;
        EXPECT_TRUE(no_staging_left(entries(cases[i].dir->path()))) << cases[i].what;
        cases[i].check(r);
      } else {
        ++finished;
        EXPECT_EQ(r.exit_code, 0) << cases[i].what << ": " << r.err;
        EXPECT_TRUE(no_staging_left(entries(cases[i].dir->path()))) << cases[i].what;
      }
    }
  }
  std::printf("contract: %d runs interrupted, %d finished first\n", interrupted, finished);
}

// A filesystem that fills during the write, as a real one behaves (the temporary file is made,
// part of it written, then it must be removed and never renamed over the output): a tmpfs, in a
// user and mount namespace of the run's own (no root needed), one page smaller than the output
// needs: a page taken by a filler, the rest one page short of the output's size on a sound run.
// The script mounts it at $1 with size $2, runs the tool, then lists what is left in it after a
// marker on stdout.
constexpr const char* kFullTmpfsScript =
    "m=$1; size=$2; shift 2; mount -t tmpfs -o size=$size tmpfs \"$m\" || exit 120; "
    "head -c $(getconf PAGESIZE) /dev/zero > \"$m/filler\" || exit 121; \"$@\"; rc=$?; "
    "echo '--- left in the tmpfs'; (cd \"$m\" && find . -mindepth 1 | sort); exit $rc";
constexpr const char* kTmpfsMarker = "--- left in the tmpfs\n";

// What the script listed in the tmpfs after the run, or "(no listing)".
std::string tmpfs_listing(const Outcome& r) {
  const std::size_t at = r.out.rfind(kTmpfsMarker);
  return at == std::string::npos ? "(no listing)" : r.out.substr(at + std::string(kTmpfsMarker).size());
}

Invocation in_tmpfs(const std::string& unshare, const std::string& mount_point, std::uintmax_t bytes,
                    std::vector<std::string> arguments) {
  Invocation call{std::move(arguments)};
  call.wrapper = {unshare, "--user", "--map-root-user", "--mount", "sh", "-c", kFullTmpfsScript, "sh", mount_point,
                  std::to_string(bytes)};
  return call;
}

// The pages a tmpfs gives a file's (or a folder's files') data.
std::uintmax_t pages_of(const fs::path& path) {
  const auto page = static_cast<std::uintmax_t>(sysconf(_SC_PAGESIZE));
  if (!fs::is_directory(path)) return (fs::file_size(path) + page - 1) / page;
  std::uintmax_t pages = 0;
  for (const auto& entry : fs::recursive_directory_iterator(path))
    if (entry.is_regular_file()) pages += (entry.file_size() + page - 1) / page;
  return pages;
}

TEST(Contract, EveryOutputOfEveryCommandIntoAFullTmpfs) {
  const std::string unshare = find_program("unshare");
  if (unshare.empty()) GTEST_SKIP() << "no unshare on PATH: the full tmpfs needs a user and mount namespace";
  const auto page = static_cast<std::uintmax_t>(sysconf(_SC_PAGESIZE));
  {
    TempDir probe;
    fs::create_directory(probe.file("full"));
    const Outcome r = run(in_tmpfs(unshare, probe.file("full"), page, {"--help"}));
    if (r.exit_code != 0 || tmpfs_listing(r) != "./filler\n")
      GTEST_SKIP() << "no tmpfs in a user namespace here (unshare --user --map-root-user --mount; mount -t tmpfs): status "
                   << r.exit_code << ": " << r.err;
  }
  // Sound runs, all at once, for the sizes of the outputs (the same bytes whatever else a run writes).
  const std::span<const CommandFiles> commands = cli::command_files();
  std::vector<std::unique_ptr<TempDir>> sound;
  std::vector<std::unique_ptr<Child>> children;
  for (const CommandFiles& c : commands) {
    sound.push_back(folder_for(c));
    children.push_back(std::make_unique<Child>(Invocation{writing_everything(c, *sound.back())}));
  }
  for (std::size_t i = 0; i < commands.size(); ++i) {
    const Outcome made = wait_or_kill(*children[i]);
    ASSERT_EQ(made.exit_code, 0) << commands[i].command << ": " << made.err;
  }
  std::vector<Case> cases;
  for (std::size_t i = 0; i < commands.size(); ++i) {
    const CommandFiles& c = commands[i];
    for (const auto& out : c.outputs) {
      Case k;
      k.what = std::string(c.command) + " " + std::string(out.option) + ": full tmpfs";
      k.dir = folder_for(c);
      const std::string mount_point = k.dir->file("full"), path = mount_point + "/" + std::string(out.name);
      fs::create_directory(mount_point);
      const std::uintmax_t pages = pages_of(sound[i]->file(std::string(out.name)));
      k.call = in_tmpfs(unshare, mount_point, std::max<std::uintmax_t>(pages, 1) * page,
                        arguments(c, *k.dir, "", "", std::string(out.option), path));
      k.named = path;
      k.before = entries(k.dir->path());
      k.check = [what = k.what + " (" + std::to_string(pages) + " pages)"](const Outcome& r) {
        EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << what << ": " << r.err;
        EXPECT_EQ(tmpfs_listing(r), "./filler\n") << what << ": left in the tmpfs";
      };
      cases.push_back(std::move(k));
    }
  }
  EXPECT_GT(cases.size(), 15u);
  run_cases(cases);
}

// Every command, writing every output, under address-space limits (ulimit -v) where the image
// plugin, the Vulkan driver and the threads load or fail to: it succeeds, or refuses with one line
// that says memory is short, the folder as before; never a signal, never a bare internal error.
TEST(Contract, EveryCommandUnderAddressSpaceLimits) {
  if (sanitized()) GTEST_SKIP() << "the address sanitizer reserves terabytes of address space: ulimit -v cannot apply";
  int succeeded = 0, refused = 0;
  std::vector<Case> cases;
  for (const long mib : {15L, 25L, 150L, 300L, 450L, 600L}) {
    for (const CommandFiles& c : cli::command_files()) {
      Case k;
      k.what = std::string(c.command) + ": ulimit -v " + std::to_string(mib << 10);
      k.dir = folder_for(c);
      k.call.arguments = writing_everything(c, *k.dir);
      k.call.address_space_bytes = mib << 20;
      k.refused = false;
      k.or_memory_refusal = true;
      k.before = entries(k.dir->path());
      k.check = [&succeeded, &refused, outputs = output_paths(c, *k.dir), what = k.what](const Outcome& r) {
        if (r.exit_code != 0) {
          ++refused;
          return;
        }
        ++succeeded;
        for (const std::string& path : outputs) EXPECT_TRUE(fs::exists(path)) << what << ": " << path;
      };
      cases.push_back(std::move(k));
    }
  }
  run_cases(cases);
  std::printf("contract: under ulimit -v, %d runs succeeded, %d refused for memory\n", succeeded, refused);
  EXPECT_GT(refused, 10);  // the limits are low enough to matter
}

// Every command's requests past its size limits (command_files.h): refused at once (the loose
// bound only catches a run that goes on), with the estimate, nothing written. ulimit -v 2 GiB
// stands in for a small machine; ulimit -f keeps a run that does start from filling the disk.
TEST(Contract, EveryCommandRefusesRequestsPastItsSizeLimits) {
  if (sanitized()) GTEST_SKIP() << "ulimit -v stands in for a small machine, and the sanitizer needs terabytes of it";
  std::vector<Case> cases;
  for (const CommandFiles& c : cli::command_files()) {
    EXPECT_TRUE(c.no_size_limit || !c.oversized.empty())
        << c.command << " declares no request past its size limits in cli/command_files.cpp (nor no_size_limit)";
    EXPECT_FALSE(c.no_size_limit && !c.oversized.empty()) << c.command;
    for (const cli::Oversized& o : c.oversized) {
      Case k;
      k.dir = folder_for(c);
      std::vector<std::string> args = {std::string(c.command)};
      for (std::string_view a : o.arguments) {
        args.emplace_back(a);
        if (a.size() < 2 || a.front() != '{' || a.back() != '}') continue;
        const std::string_view name = a.substr(1, a.size() - 2);
        std::string value;
        for (const auto& in : c.inputs) {
          const char* kind = in.kind == InputKind::points ? "points" : in.kind == InputKind::tiles ? "tiles" : "image";
          if (name == kind && value.empty()) value = input_file(in, *k.dir);  // the first input of the kind
        }
        for (const auto& out : c.outputs)
          if (name == out.name) value = k.dir->file(std::string(out.name));
        EXPECT_FALSE(value.empty()) << c.command << ": " << a << " is no input or output it declares";
        args.back() = value;
      }
      for (const std::string& a : args) k.what.append(a).append(" ");
      k.what += "(past a size limit)";
      for (const auto& out : c.outputs)
        if (out.always) args.insert(args.end(), {std::string(out.option), k.dir->file(std::string(out.name))});
      k.call.arguments = std::move(args);
      k.call.address_space_bytes = 2L << 30;
      k.call.file_size_bytes = 1L << 20;
      k.within = std::chrono::seconds(10);
      k.before = entries(k.dir->path());
      k.check = [message = std::string(o.message), what = k.what](const Outcome& r) {
        EXPECT_NE(r.err.find(message), std::string::npos) << what << ": the refusal lacks \"" << message << "\": " << r.err;
        EXPECT_EQ(r.out, "") << what;
      };
      cases.push_back(std::move(k));
    }
  }
  run_cases(cases, 1);
}

}  // namespace
}  // namespace bluetile::robustness
