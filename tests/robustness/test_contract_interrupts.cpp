// The contract harness's interrupts: every command of the app (contract_support.h), stopped by
// Ctrl-C (SIGINT) while it computes, while it writes, and at moments chosen by the clock. A run
// interrupted ends by SIGINT, leaves no staging file, and publishes all of its outputs or none.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <functional>
#include <thread>

#include <fcntl.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "contract_support.h"

namespace bluetile::robustness {
namespace {

namespace fs = std::filesystem;
using cli::FileOption;
using test::TempDir;
using Names = std::vector<std::string>;

// Waits until `ready` holds, for at most 20 s.
template <typename Ready>
bool wait_until(Ready ready) {
  for (int i = 0; i < 2000; ++i) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

// Ctrl-C at some moment of a run that writes every output the command has: either the run was
// done (status 0) or it ends by SIGINT with the folder exactly as before, or, when the signal came
// after the outputs were published, with every one of them there (all or none) and no staging
// file. The moments fall in the image plugin's loading, the reading and the writing, depending on
// the command and the load.
TEST(ContractInterrupts, EveryCommandInterruptedByTheClockLeavesNothing) {
  int interrupted = 0, finished = 0;
  for (const int delay_ms : {30, 150, 400}) {
    std::vector<Case> cases;
    std::vector<std::unique_ptr<Child>> children;
    for (const ContractCommand& c : contract_commands()) {
      if (c.outputs.empty()) continue;
      Case k;
      k.what = c.name() + ": SIGINT after " + std::to_string(delay_ms) + " ms";
      k.dir = folder_for(c);
      k.call.arguments = writing_everything(c, *k.dir);
      const std::vector<std::string> outputs = output_paths(c, *k.dir);
      k.check = [outputs, what = k.what](const Outcome&) {
        std::size_t present = 0;
        for (const std::string& path : outputs) present += fs::exists(path);
        EXPECT_TRUE(present == 0 || present == outputs.size()) << what << ": " << present << " of " << outputs.size()
                                                             << " outputs published";
      };
      cases.push_back(std::move(k));
    }
    for (const Case& k : cases) children.push_back(std::make_unique<Child>(in_its_folder(k)));
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

// Starts every case at once, sends SIGINT to each when `ready(case)` holds, and requires each to
// end by that signal with its folder as before.
void interrupt_when(std::vector<Case>& cases, const std::function<bool(const Case&)>& ready) {
  std::vector<std::unique_ptr<Child>> children;
  for (const Case& k : cases) children.push_back(std::make_unique<Child>(in_its_folder(k)));
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const bool reached = wait_until([&] { return ready(cases[i]); });
    EXPECT_TRUE(reached) << cases[i].what << ": the run never got there";
    kill(children[i]->pid(), SIGINT);
  }
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Outcome r = wait_or_kill(*children[i]);
    EXPECT_EQ(r.signal, SIGINT) << cases[i].what << ": the run was not interrupted (status " << r.exit_code << "): " << r.err;
    EXPECT_EQ(entries(cases[i].dir->path()), cases[i].before) << cases[i].what;
    if (cases[i].check) cases[i].check(r);
  }
}

// Ctrl-C while the command computes: its long run (command_runs.h) with every output, interrupted
// once its outputs are declared (their staging folder is there) and long before it could end.
TEST(ContractInterrupts, EveryCommandInterruptedWhileItComputesLeavesNothing) {
  std::vector<Case> cases;
  for (const ContractCommand& c : contract_commands()) {
    if (c.runs->long_run.empty() || c.outputs.empty()) continue;
    Case k;
    k.what = c.name() + ": SIGINT in its long run";
    k.dir = folder_for(c);
    k.call.arguments = writing_everything(c, *k.dir, /*long_run=*/true);
    k.call.file_size_bytes = 1L << 30;  // a streamed output cannot fill the disk meanwhile
    k.before = entries(k.dir->path());
    cases.push_back(std::move(k));
  }
  EXPECT_GE(cases.size(), 8u);
  interrupt_when(cases, [](const Case& k) { return !no_staging_left(entries(k.dir->path())); });
}

// Ctrl-C while the command writes: one output at a time is a FIFO whose buffer is one page and
// whose reader reads nothing, so that the write blocks part-way (for a folder, its largest file is
// the FIFO); the other outputs are files, staged meanwhile. Outputs of the quick run no larger than
// a page cannot block and are left out (listed).
TEST(ContractInterrupts, EveryOutputInterruptedWhileItIsWrittenLeavesNothing) {
  const auto page = static_cast<std::uintmax_t>(sysconf(_SC_PAGESIZE));
  const std::vector<ContractCommand>& commands = contract_commands();
  const std::vector<std::unique_ptr<TempDir>> sound = sound_runs();
  std::vector<Case> cases;
  std::vector<int> readers;
  std::string small;
  for (std::size_t i = 0; i < commands.size(); ++i) {
    const ContractCommand& c = commands[i];
    for (const FileArgument& out : c.outputs) {
      // The output's bytes, or its folder's largest file.
      std::string file = output_path(out, *sound[i]);
      if (out.file.role == FileOption::Role::folder) {
        std::uintmax_t largest = 0;
        for (const auto& entry : fs::directory_iterator(output_path(out, *sound[i])))
          if (entry.is_regular_file() && entry.file_size() > largest) largest = entry.file_size(), file = entry.path();
      }
      if (fs::file_size(file) <= page) {
        small += " " + c.name() + " " + out.label() + " (" + std::to_string(fs::file_size(file)) + " bytes)";
        continue;
      }
      Case k;
      k.what = c.name() + " " + out.label() + ": SIGINT while it is written";
      k.dir = folder_for(c);
      std::string fifo = output_path(out, *k.dir);
      if (out.file.role == FileOption::Role::folder) {
        fs::create_directory(fifo);
        fifo += "/" + fs::path(file).filename().string();
      }
      EXPECT_EQ(mkfifo(fifo.c_str(), 0600), 0) << fifo;
      // Lets the tool open its end at once; never read, one page of buffer.
      const int reader = open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
      EXPECT_GE(reader, 0) << fifo;
      fcntl(reader, F_SETPIPE_SZ, static_cast<int>(page));
      readers.push_back(reader);
      k.call.arguments = writing_everything(c, *k.dir);
      k.before = entries(k.dir->path());
      cases.push_back(std::move(k));
    }
  }
  std::printf("contract: %zu outputs interrupted while written; too small to block a pipe:%s\n", cases.size(),
              small.c_str());
  EXPECT_GE(cases.size(), 12u);
  // Ready when the pipe is full: the writer is blocked in it.
  interrupt_when(cases, [&](const Case& k) {
    int queued = 0;
    const int reader = readers[static_cast<std::size_t>(&k - cases.data())];
    return ioctl(reader, FIONREAD, &queued) == 0 && static_cast<std::uintmax_t>(queued) >= page;
  });
  for (int fd : readers) close(fd);
}

}  // namespace
}  // namespace bluetile::robustness
