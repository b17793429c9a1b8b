// bluetile: blue-noise point sets by Lloyd relaxation (Hiller, Deussen, Keller 2001).
#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <memory>
#include <new>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "cli/app.h"
#include "bluetile/core/error.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/parallel.h"

namespace {

// The status of a pipeline's writer ended by SIGPIPE (128 + 13), which the tool ignores so that
// staged outputs are removed first; quiet, as `seq 1000000 | head` is.
constexpr int kReaderGoneStatus = 128 + SIGPIPE;

// What a command printed on standard output (reports, help) is still buffered: a full disk or a
// closed pipe there was ignored and the run exited 0 with its report lost. Flushed and checked
// here, so that `analyze ... > /dev/full` fails as `-o /dev/full` does.
int checked_standard_output(int code) {
  std::cout.flush();
  const bool failed = !std::cout.good() || std::fflush(stdout) != 0 || std::ferror(stdout) != 0;
  if (failed && code == 0) {
    if (errno == EPIPE) return kReaderGoneStatus;
    std::fprintf(stderr, "bluetile: standard output: cannot write: %s\n", std::strerror(errno));
    return 1;
  }
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  // OpenImageIO's dependencies load OpenBLAS, which the tool never calls; its initialiser would
  // start a worker per core beyond the first, with a 128 MiB buffer each on AVX-512 processors.
  // One thread (unless the user set it): the image commands then fit smaller memory limits
  // (plugin_address_space_needed, image_file.cpp). Set before any thread starts.
  setenv("OPENBLAS_NUM_THREADS", "1", 0);
  try {
    // Before any thread starts: every thread then leaves SIGINT, SIGTERM, SIGHUP to the watcher
    // that removes staged outputs (output_file.h).
    bluetile::install_interrupt_cleanup();
    // A closed pipe on "-o -" and a file-size limit (ulimit -f) are then write errors, with
    // staged outputs removed, instead of signals that end the process on the spot; the first
    // ends the run quietly (kReaderGoneStatus), the second is reported.
    std::signal(SIGPIPE, SIG_IGN);
    std::signal(SIGXFSZ, SIG_IGN);
    // A malformed BLUETILE_THREADS is refused before any work, unless it is not used: help and
    // --version do no work, and an explicit --threads wins over it.
    bool uses_environment = true;
    for (int k = 1; k < argc; ++k) {
      const std::string_view word = argv[k];
      if (word == "-h" || word == "--help" || word == "--version" || word == "--threads" ||
          word.rfind("--threads=", 0) == 0 || (k == 1 && word == "help"))
        uses_environment = false;
    }
    if (uses_environment) bluetile::thread_count();
  } catch (const bluetile::Error& e) {
    std::fprintf(stderr, "bluetile: %s\n", e.what());
    return 1;
  }

  std::unique_ptr<CLI::App> made = bluetile::cli::make_app();
  CLI::App& app = *made;
  const std::vector<CLI::App*> subcommands = app.get_subcommands([](const CLI::App*) { return true; });
  std::string commands;
  for (const CLI::App* command : subcommands) commands += (commands.empty() ? "" : ", ") + command->get_name();
  // "bluetile help" and "bluetile help COMMAND", as git and cargo take them: the tool's help or
  // the command's.
  std::vector<char*> words(argv, argv + argc);
  static char help_flag[] = "--help";
  if (argc > 1 && std::string_view(argv[1]) == "help") {
    if (argc > 3) {
      std::fprintf(stderr, "bluetile: help takes one command, got '%s' and '%s' (commands: %s)\n", argv[2], argv[3],
                   commands.c_str());
      return 2;
    }
    words = argc == 2 ? std::vector<char*>{argv[0], help_flag} : std::vector<char*>{argv[0], argv[2], help_flag};
  }
  // CLI11 asks for "A subcommand" when there is none, and takes an unknown first word for a stray
  // argument (or, with --help after it, prints the main help and exits 0): name the commands.
  if (words.size() == 1) {
    std::fprintf(stderr, "bluetile: a command is required (commands: %s; see --help)\n", commands.c_str());
    return 2;
  }
  if (words[1][0] != '-') {
    const bool known =
        std::any_of(subcommands.begin(), subcommands.end(), [&](CLI::App* command) { return command->check_name(words[1]); });
    if (!known) {
      std::fprintf(stderr, "bluetile: unknown command '%s' (commands: %s; see --help)\n", words[1], commands.c_str());
      return 2;
    }
  }
  try {
    app.parse(static_cast<int>(words.size()), words.data());
  } catch (const CLI::CallForHelp& e) {
    return checked_standard_output(app.exit(e));
  } catch (const CLI::CallForAllHelp& e) {
    return checked_standard_output(app.exit(e));
  } catch (const CLI::CallForVersion& e) {
    return checked_standard_output(app.exit(e));
  } catch (const bluetile::ReaderGone&) {
    return kReaderGoneStatus;
  } catch (const CLI::RequiredError& e) {
    // "analyze points.txt -o out" was "--input is required": the file given without its option.
    std::string stray;
    for (const CLI::App* command : app.get_subcommands())
      for (const std::string& word : command->remaining())
        if (stray.empty() && !word.empty() && word[0] != '-') stray = word;
    const std::string said = e.what();
    const std::size_t option_end = said.find(" is required");
    if (!stray.empty() && said.rfind("--", 0) == 0 && option_end != std::string::npos)
      std::fprintf(stderr, "bluetile: %s; '%s' was given without an option: %s %s? (see --help)\n", said.c_str(),
                   stray.c_str(), said.substr(0, option_end).c_str(), stray.c_str());
    else
      std::fprintf(stderr, "bluetile: %s (see --help)\n", said.c_str());
    return e.get_exit_code() != 0 ? e.get_exit_code() : 2;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "bluetile: %s (see --help)\n", e.what());
    return e.get_exit_code() != 0 ? e.get_exit_code() : 2;
  } catch (const bluetile::Error& e) {
    std::fprintf(stderr, "bluetile: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "bluetile: out of memory\n");
    return 1;
  } catch (const std::system_error& e) {
    // A thread, or memory for one, that the limits (ulimit -v, -u) did not leave.
    const std::error_code code = e.code();
    if (code == std::errc::resource_unavailable_try_again || code == std::errc::not_enough_memory) {
      std::fprintf(stderr, "bluetile: %s: out of memory or threads (ulimit -v, ulimit -u)\n", e.what());
    } else {
      std::fprintf(stderr, "bluetile: internal error: %s\n", e.what());
    }
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bluetile: internal error: %s\n", e.what());
    return 1;
  }
  return checked_standard_output(0);
}
