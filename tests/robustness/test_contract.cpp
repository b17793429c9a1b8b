// The contract harness: every subcommand of the tool's own app (cli/app.h), with the inputs and
// outputs it declares where it adds them (cli/file_options.h), through one matrix. Every output
// goes to a full device, a FIFO, standard output, a read-only folder, a symbolic link, an input's
// own path (and a hard or symbolic link to it) and under ulimit -f; every input is given
// truncated, empty, as binary garbage, missing and as a folder. A refusal is exit status 1 (105
// where the option parser refuses), one `bluetile:` line naming the path, and the folder exactly
// as before (no staging file left); a FIFO output receives the bytes, standard output exactly the
// bytes a file gets, and a link is followed. Devices need mknod (root) and the read-only folder an
// unprivileged user: skipped with a message otherwise. Beyond those:
// - every output into a tmpfs one page smaller than it (in a user and mount namespace of its own,
//   so no root needed), so that it fills mid-write: refused with "No space left on device",
//   nothing left in the tmpfs;
// - every command, writing every output, under ulimit -v 15 to 600 MiB: success, or a refusal that
//   says memory is short, never a signal, the folder as before;
// - every command's requests past its size limits (command_runs.cpp): refused within seconds with
//   the estimate, nothing written; a command must declare one, or no_size_limit.
// Interrupts are test_contract_interrupts.cpp's. A new command, or a new file option of a command,
// gets every cell without a new test.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <set>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include "bluetile/core/rng.h"
#include "bluetile/io/pdf.h"
#include "cli/app.h"
#include "cli/file_options.h"
#include "contract_support.h"

namespace bluetile::robustness {
namespace {

namespace fs = std::filesystem;
using cli::FileOption;
using cli::InputKind;
using test::read_text;
using test::TempDir;
using Names = std::vector<std::string>;

constexpr long kFileSizeLimit = 512;  // bytes: under every quick run's output, over any message

std::vector<Case> output_cases(const ContractCommand& c, bool& devices_skipped) {
  std::vector<Case> cases;
  for (const FileArgument& out : c.outputs) {
    const std::string option = out.label(), label = c.name() + " " + option + ": ";
    const bool folder = out.file.role == FileOption::Role::folder;
    auto add = [&](Case k) { cases.push_back(std::move(k)); };

    {  // A full device: nothing fits (files), or no folder (folders).
      Case k;
      k.what = label + "full device";
      k.dir = folder_for(c);
      const std::string device = k.dir->file("full-" + out.file_name);
      if (mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 7)) != 0) {
        devices_skipped = true;
      } else {
        k.call.arguments = arguments(c, *k.dir, option, device);
        k.named = device;
        k.before = entries(k.dir->path());
        add(std::move(k));
      }
    }
    {  // A FIFO: streamed into it (files); not a folder (folders).
      Case k;
      k.what = label + "FIFO";
      k.dir = folder_for(c);
      const std::string fifo = k.dir->file("pipe-" + out.file_name);
      EXPECT_EQ(mkfifo(fifo.c_str(), 0666), 0);
      k.call.arguments = arguments(c, *k.dir, option, fifo);
      k.named = fifo;
      k.before = entries(k.dir->path());
      if (!folder) {
        k.refused = false;
        k.fifo = fifo;
      }
      add(std::move(k));
    }
    {  // Standard output: the bytes a file gets, and nothing else (standard_output outputs), or
       // refused. The file to compare with is written by a run before the batch (reference_runs).
      Case k;
      k.what = label + "standard output";
      k.dir = folder_for(c);
      k.call.arguments = arguments(c, *k.dir, option, "-");
      k.named = "-";
      k.before = entries(k.dir->path());
      if (out.file.output.standard_output && !folder) {
        k.refused = false;
        k.check = [reference = k.dir->file("reference-" + out.file_name), what = k.what](const Outcome& r) {
          EXPECT_FALSE(r.out.empty()) << what;
          EXPECT_TRUE(r.out == read_text(reference))
              << what << ": standard output is not the bytes a file gets (" << r.out.size() << " bytes, the file "
              << read_text(reference).size() << "): " << r.out.substr(0, 200);
        };
      } else {
        k.check = [what = k.what](const Outcome& r) {
          EXPECT_EQ(r.err, "bluetile: -: this output cannot be standard output\n") << what;
          EXPECT_EQ(r.out, "") << what;
        };
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
      k.call.arguments = arguments(c, *k.dir, option, locked + "/" + out.file_name);
      k.call.unprivileged = true;
      k.named = locked;
      k.before = entries(k.dir->path());
      add(std::move(k));
    }
    {  // A symbolic link: followed, and still a link afterwards.
      Case k;
      k.what = label + "symbolic link";
      k.dir = folder_for(c);
      const std::string real = k.dir->file("real"), link = k.dir->file("link-" + out.file_name);
      fs::create_directory(real);
      const std::string target = real + "/" + out.file_name;
      if (folder) fs::create_directory(target);
      else k.dir->write("real/" + out.file_name, "old\n");
      fs::create_symlink(target, link);
      k.call.arguments = arguments(c, *k.dir, option, link);
      k.refused = false;
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
    for (const FileArgument& in : c.inputs) {
      // Every input's own path, a hard link to it and a symbolic link to it: refused, the input
      // untouched. An input the quick run does not read is added for the case.
      for (const char* how : {"path", "hard link", "symbolic link"}) {
        Case k;
        k.what = label + "same file as " + in.label() + " (" + how + ")";
        k.dir = folder_for(c);
        const std::string input = input_path(in, *k.dir);
        const std::string extension = fs::path(input).extension().string();
        std::string path = input;
        if (std::string(how) == "hard link") {
          path = k.dir->file("hard-link" + extension);
          fs::create_hard_link(input, path);
        } else if (std::string(how) == "symbolic link") {
          path = k.dir->file("link" + extension);
          fs::create_symlink(input, path);
        }
        k.call.arguments = arguments(c, *k.dir, in.label(), input);
        // The output option, replaced or added after the arguments made with the input.
        std::vector<std::string>& args = k.call.arguments;
        auto at = std::find(args.begin(), args.end(), output_path(out, *k.dir));
        if (out.quick && at != args.end()) {
          *at = path;
        } else {
          if (!out.flag.empty()) args.push_back(out.flag);
          args.push_back(path);
        }
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
      k.call.arguments = arguments(c, *k.dir, option, output_path(out, *k.dir));
      k.call.file_size_bytes = kFileSizeLimit;
      k.before = entries(k.dir->path());
      add(std::move(k));
    }
  }
  return cases;
}

// The references the standard-output cases compare with: each case's run with the output to a
// file "reference-NAME" in the case's folder, all before the batch, a few at a time.
void reference_runs(std::vector<Case>& cases) {
  std::vector<Case> references;
  for (const Case& k : cases) {
    if (k.refused || k.call.arguments.empty()) continue;
    auto dash = std::find(k.call.arguments.begin(), k.call.arguments.end(), "-");
    if (dash == k.call.arguments.end() || k.what.find(": standard output") == std::string::npos) continue;
    Case reference;
    reference.what = k.what + " (the reference run to a file)";
    reference.dir = std::make_unique<TempDir>();  // unused: the run writes into the case's folder
    reference.call = k.call;
    const std::string name = k.what.substr(0, k.what.find(':'));
    for (const ContractCommand& c : contract_commands())
      for (const FileArgument& out : c.outputs)
        if (c.name() + " " + out.label() == name)
          reference.call.arguments[static_cast<std::size_t>(dash - k.call.arguments.begin())] =
              k.dir->file("reference-" + out.file_name);
    reference.refused = false;
    references.push_back(std::move(reference));
  }
  run_cases(references);
}

// Damaged copies of a sound input: cut inside its last line (text) or halfway (binary), empty,
// and bytes that are no file of any kind; and no file at all, or a folder, where it should be.
std::vector<std::pair<std::string, std::string>> damaged(InputKind kind) {
  const std::string sound = read_text(sound_input(kind));
  std::string truncated = kind == InputKind::image ? sound.substr(0, sound.size() / 2) : sound.substr(0, sound.rfind(' '));
  std::string garbage;
  Rng rng(11);
  for (int i = 0; i < 300; ++i) garbage.push_back(static_cast<char>(rng.below(256)));
  return {{"truncated", truncated}, {"empty", ""}, {"garbage", garbage}, {"missing", ""}, {"a folder", ""}};
}

std::vector<Case> input_cases(const ContractCommand& c) {
  std::vector<Case> cases;
  for (const FileArgument& in : c.inputs) {
    for (const auto& [how, bytes] : damaged(in.file.kind)) {
      Case k;
      k.what = c.name() + " " + in.label() + ": " + how;
      k.dir = folder_for(c);
      const std::string name = how + fs::path(in.file_name).extension().string();
      const std::string path = k.dir->file(name);
      if (how == "missing") {
      } else if (how == "a folder") {
        fs::create_directory(path);
      } else {
        k.dir->write(name, bytes);
      }
      k.call.arguments = arguments(c, *k.dir, in.label(), path);
      k.named = path;
      k.before = entries(k.dir->path());
      cases.push_back(std::move(k));
    }
  }
  return cases;
}

const CommandRuns* runs_of(std::string_view command) {
  for (const CommandRuns& r : command_runs())
    if (r.command == command) return &r;
  return nullptr;
}

// Every option of every subcommand that takes free text (no fixed choices) is a file option the
// command declared (cli/file_options.h) or one command_runs.cpp says names no file; every command
// has its runs there, and the quick runs name only file options the command has.
TEST(Contract, EveryOptionOfEveryCommandIsDeclared) {
  std::unique_ptr<CLI::App> app = cli::make_app();
  std::set<std::string_view> commands;
  for (const CLI::App* command : app->get_subcommands([](CLI::App*) { return true; })) {
    const std::string name = command->get_name();
    const CommandRuns* runs = runs_of(name);
    ASSERT_NE(runs, nullptr) << name << " is missing from tests/robustness/command_runs.cpp";
    commands.insert(runs->command);
    std::set<std::string> file_names;
    for (const CLI::Option* option : command->get_options()) {
      const bool file = cli::find_file_option(option) != nullptr;
      std::vector<std::string> names = {option->get_name(true)};
      for (const std::string& s : option->get_snames()) names.push_back("-" + s);
      for (const std::string& l : option->get_lnames()) names.push_back("--" + l);
      if (file) file_names.insert(names.begin(), names.end());
      const std::string type = option->get_type_name();
      if (file || type.rfind("TEXT", 0) != 0 || type.find('{') != std::string::npos) continue;
      const bool no_file = std::any_of(runs->not_files.begin(), runs->not_files.end(), [&](std::string_view n) {
        return std::find(names.begin(), names.end(), n) != names.end();
      });
      EXPECT_TRUE(no_file) << name << " " << option->get_name() << " takes text but is neither declared a file option "
                           << "(add_input_option, add_output_option: cli/file_options.h) nor listed in not_files "
                           << "(tests/robustness/command_runs.cpp)";
    }
    for (std::string_view q : runs->quick_files)
      EXPECT_TRUE(file_names.count(std::string(q))) << name << ": the quick run's " << q << " is no file option of it";
  }
  EXPECT_EQ(commands.size(), command_runs().size()) << "command_runs.cpp has a command the app does not have";
  // The harness sees what the commands declare: inputs of every kind, outputs and folders.
  std::size_t inputs = 0, outputs = 0;
  for (const ContractCommand& c : contract_commands()) inputs += c.inputs.size(), outputs += c.outputs.size();
  EXPECT_GE(inputs, 10u);
  EXPECT_GE(outputs, 16u);
}

TEST(Contract, EveryOutputOfEveryCommandUnderTheMatrix) {
  bool devices_skipped = false;
  std::vector<Case> cases;
  for (const ContractCommand& c : contract_commands())
    for (Case& k : output_cases(c, devices_skipped)) cases.push_back(std::move(k));
  if (geteuid() != 0) {
    // Without root the read-only folder does not hold root out, and the run as nobody is not
    // possible: those cases are for root only.
    std::erase_if(cases, [](const Case& k) { return k.call.unprivileged; });
    std::printf("contract: not root: read-only folder cases skipped\n");
  }
  if (devices_skipped) std::printf("contract: mknod refused (needs root): device outputs skipped\n");
  EXPECT_GT(cases.size(), 100u);
  reference_runs(cases);
  run_cases(cases);
}

TEST(Contract, EveryInputOfEveryCommandDamaged) {
  std::vector<Case> cases;
  for (const ContractCommand& c : contract_commands())
    for (Case& k : input_cases(c)) cases.push_back(std::move(k));
  EXPECT_GE(cases.size(), 50u);
  run_cases(cases);
}

// Writes `bytes` into the FIFO `path` once a reader opens it, while `child` runs; gives up when the
// child has ended without opening it. A reader that stops early ends the write (EPIPE; SIGPIPE is
// ignored while the test feeds).
void feed_fifo(const std::string& path, const std::string& bytes, const std::atomic<bool>& child_done) {
  int fd = -1;
  while (fd < 0 && !child_done.load()) {
    fd = open(path.c_str(), O_WRONLY | O_NONBLOCK);  // ENXIO while no reader has it open
    if (fd < 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (fd < 0) return;
  fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = write(fd, bytes.data() + done, bytes.size() - done);
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  close(fd);
}

// Every input of every command given as a named FIFO (mkfifo), fed the sound input once: the run
// succeeds. analyze opened its input a second time, for the tile grid of a tiled output, and
// waited for a second writer forever.
TEST(Contract, EveryInputOfEveryCommandReadFromAFifo) {
  struct sigaction ignore {}, previous {};
  ignore.sa_handler = SIG_IGN;
  sigaction(SIGPIPE, &ignore, &previous);
  std::size_t inputs = 0;
  for (const ContractCommand& c : contract_commands()) {
    for (const FileArgument& in : c.inputs) {
      if (!in.quick) continue;  // the quick run gives it: the run would not read it otherwise
      ++inputs;
      const std::string what = c.name() + " " + in.label() + " from a FIFO";
      std::unique_ptr<TempDir> dir = folder_for(c);
      const std::string fifo = dir->file("fifo-" + in.file_name);
      ASSERT_EQ(mkfifo(fifo.c_str(), 0666), 0) << what;
      Invocation call{arguments(c, *dir, in.label(), fifo)};
      call.working_directory = dir->path();
      std::atomic<bool> child_done{false};
      Child child(call);
      std::thread writer(feed_fifo, fifo, read_text(input_path(in, *dir)), std::cref(child_done));
      const Outcome r = wait_or_kill(child);
      child_done = true;
      writer.join();
      EXPECT_EQ(r.exit_code, 0) << what << ": " << (r.signal == SIGKILL ? "still running after a minute (hung)" : r.err);
    }
  }
  sigaction(SIGPIPE, &previous, nullptr);
  EXPECT_GE(inputs, 7u);
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
  // Sound runs, for the sizes of the outputs (the same bytes whatever else a run writes).
  const std::vector<ContractCommand>& commands = contract_commands();
  const std::vector<std::unique_ptr<TempDir>> sound = sound_runs();
  std::vector<Case> cases;
  for (std::size_t i = 0; i < commands.size(); ++i) {
    const ContractCommand& c = commands[i];
    for (const FileArgument& out : c.outputs) {
      Case k;
      k.what = c.name() + " " + out.label() + ": full tmpfs";
      k.dir = folder_for(c);
      const std::string mount_point = k.dir->file("full"), path = mount_point + "/" + out.file_name;
      fs::create_directory(mount_point);
      const std::uintmax_t pages = pages_of(output_path(out, *sound[i]));
      k.call = in_tmpfs(unshare, mount_point, std::max<std::uintmax_t>(pages, 1) * page,
                        arguments(c, *k.dir, out.label(), path));
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
// The smallest limit is 20 MiB: the binary itself, with the built-in tile set (7.7 MB of text,
// 81 tiles of 2048 points), maps about 11 MB, and below about 18 MiB with its libraries the
// loader cannot start it at all (status 127 before main; it was 15 MiB with the 0.8 MB wang8 set).
TEST(Contract, EveryCommandUnderAddressSpaceLimits) {
  if (sanitized()) GTEST_SKIP() << "the address sanitizer reserves terabytes of address space: ulimit -v cannot apply";
  int succeeded = 0, refused = 0;
  std::vector<Case> cases;
  for (const long mib : {20L, 25L, 150L, 300L, 450L, 600L}) {
    for (const ContractCommand& c : contract_commands()) {
      Case k;
      k.what = c.name() + ": ulimit -v " + std::to_string(mib << 10);
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

// Every command's requests past its size limits (command_runs.h): refused at once (the loose
// bound only catches a run that goes on), with the estimate, nothing written. ulimit -v 2 GiB
// stands in for a small machine; ulimit -f keeps a run that does start from filling the disk.
TEST(Contract, EveryCommandRefusesRequestsPastItsSizeLimits) {
  if (sanitized()) GTEST_SKIP() << "ulimit -v stands in for a small machine, and the sanitizer needs terabytes of it";
  std::vector<Case> cases;
  for (const ContractCommand& c : contract_commands()) {
    const CommandRuns& runs = *c.runs;
    EXPECT_TRUE(runs.no_size_limit || !runs.oversized.empty())
        << c.name() << " declares no request past its size limits in command_runs.cpp (nor no_size_limit)";
    EXPECT_FALSE(runs.no_size_limit && !runs.oversized.empty()) << c.name();
    for (const Oversized& o : runs.oversized) {
      Case k;
      k.dir = folder_for(c);
      std::vector<std::string> args = {c.name()};
      bool pdf = false;
      for (std::string_view a : o.arguments) {
        args.emplace_back(a);
        if (a.size() < 2 || a.front() != '{' || a.back() != '}') continue;
        const std::string name(a.substr(1, a.size() - 2));
        args.back() = k.dir->file(name);  // a file of that name, unless it names a file option
        for (const FileArgument& in : c.inputs)
          if (std::find(in.names.begin(), in.names.end(), name) != in.names.end()) args.back() = input_path(in, *k.dir);
        for (const FileArgument& out : c.outputs)
          if (std::find(out.names.begin(), out.names.end(), name) != out.names.end()) args.back() = output_path(out, *k.dir);
        pdf = pdf || fs::path(args.back()).extension() == ".pdf";
      }
      if (pdf && !pdf_unavailable_reason().empty()) continue;  // refused for want of cairo instead
      for (const std::string& a : args) k.what.append(a).append(" ");
      k.what += "(past a size limit)";
      for (const FileArgument& out : c.outputs)
        if (out.quick) args.insert(args.end(), {out.flag, output_path(out, *k.dir)});
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
  EXPECT_GE(cases.size(), 20u);
  run_cases(cases, 1);
}

}  // namespace
}  // namespace bluetile::robustness
