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

#include <CLI/CLI.hpp>

namespace bluetile::cli {

// Limits shared by the subcommands. Beyond them a value is almost surely a typo, and would need
// tens of GiB or years.
inline constexpr long long kMaxCount = 100'000'000;     // points in a set
inline constexpr int kMaxIterations = 100'000'000;      // Lloyd iterations
inline constexpr long long kMaxSets = 10'000'000;       // sets of one relax run

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

// Adds an integer option with values in [min, max].
template <typename T>
CLI::Option* add_integer_option(CLI::App* command, const std::string& names, T& target, T min, T max,
                                const std::string& help) {
  CLI::Option* option = command->add_option_function<std::string>(
      names,
      [&target, min, max, names](const std::string& text) {
        WholeNumber value;
        std::string problem = check_integer(text, whole(min), whole(max), value);
        if (!problem.empty()) throw CLI::ValidationError(CLI::detail::split(names, ',').back() + " " + text + ": " + problem);
        target = value.negative ? static_cast<T>(-static_cast<T>(value.magnitude - 1) - 1) : static_cast<T>(value.magnitude);
      },
      help);
  option->type_name("INT")->default_str(std::to_string(target));
  return option;
}

// A range of reals; an open end excludes its value. The default is [0, infinity).
struct RealRange {
  double min = 0.0;
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;
};

// Checks text against the range; returns "" and the value, or the message without the name.
std::string check_real(std::string_view text, RealRange range, double& value);

// Adds an option taking a finite real number in `range`.
CLI::Option* add_real_option(CLI::App* command, const std::string& names, double& target, RealRange range,
                             const std::string& help);

}  // namespace bluetile::cli
