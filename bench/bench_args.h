// The options of the benchmark programs, checked the way the tool checks its own (numbers by
// src/cli/numeric_options.h, so "1e6" is a count and "nan" is not a number anywhere).
//
// `--help` prints the usage and exits 0. A bad argument (an unknown option or mode, a missing
// value, a value that is not a number, out of range, not one of the accepted names, or an option
// that needs another) is one line on standard error and exit status 2:
//   bluetile_tiler_bench: --repeats '0': out of range; expected an integer from 1 to 1000000
// An error while running (an input file that cannot be read) is one line and status 1. Every
// program has the same shape:
//
//   int main(int argc, char** argv) try {
//     CLI::App app{"what it measures", "bluetile_x_bench"};
//     bench::add_integer(app, "--repeats", repeats, 1, bench::kMaxRepeats, "Interleaved repeats");
//     if (!bench::parse(app, argc, argv)) return 0;  // --help
//     ...
//   } catch (...) {
//     return bench::exit_status("bluetile_x_bench");
//   }
#pragma once

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>

#include "bluetile/core/parallel.h"
#include "cli/numeric_options.h"

namespace bluetile::bench {

using cli::RealRange;

// Upper limits shared by the programs; beyond them a value is a typo.
inline constexpr long long kMaxCount = cli::kMaxCount;  // points, sites, dots
inline constexpr int kMaxRepeats = 1'000'000;
using bluetile::kMaxIterations;
inline constexpr int kMaxThreads = static_cast<int>(bluetile::kMaxThreads);
inline constexpr std::uint64_t kMaxSeed = UINT64_MAX;

// A bad argument, with its whole message ("--repeats '0': out of range; ..."): exit status 2.
class BadArgument : public CLI::ParseError {
 public:
  explicit BadArgument(std::string message) : CLI::ParseError(std::move(message), 2) {}
};

// "<option> '<value>': <expected>", the message of a BadArgument.
BadArgument bad_argument(const std::string& option, const std::string& value, const std::string& expected);

// The value of `text` as an integer in [min, max], or a BadArgument naming `option`.
std::int64_t signed_integer(const std::string& option, const std::string& text, std::int64_t min, std::int64_t max);
std::uint64_t unsigned_integer(const std::string& option, const std::string& text, std::uint64_t min, std::uint64_t max);

template <typename T>
T integer_argument(const std::string& option, const std::string& text, T min, T max) {
  if constexpr (std::is_unsigned_v<T>) {
    return static_cast<T>(unsigned_integer(option, text, min, max));
  } else {
    return static_cast<T>(signed_integer(option, text, min, max));
  }
}

// The value of `text` as a finite number in `range`, or a BadArgument naming `option`.
double real_argument(const std::string& option, const std::string& text, RealRange range);

// `text` if it is one of `accepted`, or a BadArgument listing them.
const std::string& name_argument(const std::string& option, const std::string& text, const std::vector<std::string>& accepted);

// The name messages give an option: the last of its names ("-n,--count" -> "--count").
std::string option_name(const std::string& names);
// `values` joined by `separator`, for the defaults in the help.
std::string joined(const std::vector<std::string>& values, const std::string& separator = ",");
template <typename T>
std::string joined_numbers(const std::vector<T>& values) {
  std::vector<std::string> text;
  for (const T& v : values) {
    if constexpr (std::is_floating_point_v<T>) {
      text.push_back(number_text(v));
    } else {
      text.push_back(std::to_string(v));
    }
  }
  return joined(text);
}

// Options and positionals ("N") that take an integer in [min, max]; the list form takes several
// values (comma-separated when the caller adds ->delimiter(',')) and replaces the default list.
template <typename T, typename Limit>
CLI::Option* add_integer(CLI::App& app, const std::string& names, T& target, Limit min, Limit max, const std::string& help) {
  const std::string name = option_name(names);
  return app
      .add_option_function<std::string>(
          names,
          [&target, name, min, max](const std::string& text) {
            target = static_cast<T>(integer_argument<Limit>(name, text, min, max));
          },
          help)
      ->type_name("INT")
      ->default_str(std::to_string(target));
}

template <typename T, typename Limit>
CLI::Option* add_integers(CLI::App& app, const std::string& names, std::vector<T>& target, Limit min, Limit max,
                          const std::string& help) {
  const std::string name = option_name(names);
  return app
      .add_option_function<std::vector<std::string>>(
          names,
          [&target, name, min, max](const std::vector<std::string>& texts) {
            target.clear();
            for (const std::string& text : texts) target.push_back(static_cast<T>(integer_argument<Limit>(name, text, min, max)));
          },
          help)
      ->type_name("INT")
      ->default_str(joined_numbers(target));
}

// Options and positionals that take a finite number in `range`.
CLI::Option* add_real(CLI::App& app, const std::string& names, double& target, RealRange range, const std::string& help);
CLI::Option* add_reals(CLI::App& app, const std::string& names, std::vector<double>& target, RealRange range,
                       const std::string& help);

// Options that take one of `accepted` (engines, jobs, kinds, modes): one, or a list.
CLI::Option* add_name(CLI::App& app, const std::string& names, std::string& target, std::vector<std::string> accepted,
                      const std::string& help);
CLI::Option* add_names(CLI::App& app, const std::string& names, std::vector<std::string>& target,
                       std::vector<std::string> accepted, const std::string& help);

// What was given for `option`, as the messages quote it ("1,2" for a list).
std::string given(const CLI::Option* option);

// Refuses `option` when it was given and `allowed` is false: "<option> '<value>': <expected>"
// ("needs --range", "only in levels mode").
void check_given(const CLI::Option* option, bool allowed, const std::string& expected);

// Parses the command line. Returns false after printing the help (--help: exit 0); throws
// CLI::ParseError for a bad argument, which exit_status reports.
bool parse(CLI::App& app, int argc, char** argv);

// For `catch (...)` around main: reports the exception in flight as one line
// "<program>: <what>" on standard error and returns the exit status (2 for a bad argument, 1
// for any other error).
int exit_status(const char* program);

}  // namespace bluetile::bench
