// Numeric options, checked the same way everywhere: seeds, counts, ratios, tolerances.
//
// Integers are written in decimal, optionally in scientific notation when the value is a whole
// number ("1e6", "2.5e3"; "1.5" and "1e-3" are refused as not integers). Reals are finite decimal
// numbers. A value outside the option's range, NaN, infinity or garbage is refused with one line
// naming the option, the value and the accepted range, never clamped:
//   --seed 18446744073709551616: out of range; expected an integer from 0 to 18446744073709551615
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "bluetile/core/request_limits.h"
#include "bluetile/core/text.h"  // number_text, which the messages here use

namespace bluetile::cli {

// The library's limits of a request (core/request_limits.h), in the type the options take.
inline constexpr long long kMaxCount = static_cast<long long>(bluetile::kMaxSetPoints);  // points in a set
using bluetile::kMaxIterations;                                                           // Lloyd iterations
inline constexpr long long kMaxSets = static_cast<long long>(bluetile::kMaxSets);         // sets of one relax run
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// An integer as a sign and a magnitude, wide enough for every range we accept.
struct WholeNumber {
  bool negative = false;
  std::uint64_t magnitude = 0;
};

// Parses `text` as an integer (decimal or whole-number scientific notation). Returns "" and
// sets `value`, or the reason ("not a number", "not an integer", "out of range").
std::string parse_whole_number(std::string_view text, WholeNumber& value);

// The option's accepted range in words: "an integer from 1 to 100000000".
std::string integer_range(WholeNumber min, WholeNumber max);

template <typename T>
WholeNumber whole(T v) {
  if constexpr (std::numeric_limits<T>::is_signed) {
    if (v < 0) return {true, static_cast<std::uint64_t>(-(v + 1)) + 1};
  }
  return {false, static_cast<std::uint64_t>(v)};
}

// Checks text against [min, max]; returns "" and the value, or the message without the name.
std::string check_integer(std::string_view text, WholeNumber min, WholeNumber max, WholeNumber& value);

// A range of reals; an open end excludes its value. The default is [0, infinity).
struct RealRange {
  double min = 0.0;
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;
};

// Checks text against the range; returns "" and the value, or the message without the name.
std::string check_real(std::string_view text, RealRange range, double& value);

// The range in words: "a number from 0 to 0.25", "a finite number > 0".
std::string real_range(RealRange range);

// The record of a numeric option, kept so that tests can find every numeric option of every
// command (tests/robustness/test_options.cpp) and try bad values on it.
struct NumericOption {
  std::string name;  // as the messages write it: "--count"
  bool integer = false;
  WholeNumber min, max;  // integer options
  RealRange range;       // real options
  std::string range_text;  // "an integer from 1 to 100000000", "a finite number >= 0"
};

// The record of `option` when it was added by add_integer_option or add_real_option (or the
// seed and thread helpers), else null.
const NumericOption* find_numeric_option(const CLI::Option* option);
void register_numeric_option(const CLI::Option* option, NumericOption record);
// Drops the record of `option`, as forget_file_option does.
void forget_numeric_option(const CLI::Option* option);

// The name the messages use: the last of `names` ("-n,--count" -> "--count").
std::string message_name(const std::string& names);

// Adds an integer option with values in [min, max].
template <typename T>
CLI::Option* add_integer_option(CLI::App* command, const std::string& names, T& target, T min, T max,
                                const std::string& help) {
  const std::string name = message_name(names);
  CLI::Option* option = command->add_option_function<std::string>(
      names,
      [&target, min, max, name](const std::string& text) {
        WholeNumber value;
        std::string problem = check_integer(text, whole(min), whole(max), value);
        if (!problem.empty()) throw CLI::ValidationError(name + " " + text + ": " + problem);
        target = value.negative ? static_cast<T>(-static_cast<T>(value.magnitude - 1) - 1) : static_cast<T>(value.magnitude);
      },
      help);
  option->type_name("INT")->default_str(std::to_string(target));
  register_numeric_option(option, {name, true, whole(min), whole(max), {}, integer_range(whole(min), whole(max))});
  return option;
}

// Adds an option taking a finite real number in `range`.
CLI::Option* add_real_option(CLI::App* command, const std::string& names, double& target, RealRange range,
                             const std::string& help);

// Adds -s,--seed: any integer from 0 to 2^64 - 1.
CLI::Option* add_seed_option(CLI::App* command, std::uint64_t& seed, const std::string& help = "Seed");

// Adds --threads: 1 to 1024 CPU threads, 0 (the default) meaning all cores.
CLI::Option* add_threads_option(CLI::App* command, int& threads);

}  // namespace bluetile::cli
