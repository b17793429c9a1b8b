#include "cli/numeric_options.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "bluetile/core/parallel.h"

namespace bluetile::cli {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// a < b for sign-and-magnitude integers.
bool less(WholeNumber a, WholeNumber b) {
  if (a.negative != b.negative) return a.negative;
  return a.negative ? a.magnitude > b.magnitude : a.magnitude < b.magnitude;
}

std::string to_string(WholeNumber v) { return (v.negative ? "-" : "") + std::to_string(v.magnitude); }

}  // namespace

std::string real_range(RealRange r) {
  const bool has_min = std::isfinite(r.min), has_max = std::isfinite(r.max);
  if (has_min && has_max) {
    if (!r.min_open && !r.max_open) return "a number from " + number_text(r.min) + " to " + number_text(r.max);
    return "a number " + std::string(r.min_open ? "above " : "at least ") + number_text(r.min) +
           (r.max_open ? " and below " : " and at most ") + number_text(r.max);
  }
  if (has_min) return "a finite number " + std::string(r.min_open ? "> " : ">= ") + number_text(r.min);
  if (has_max) return "a finite number " + std::string(r.max_open ? "< " : "<= ") + number_text(r.max);
  return "a finite number";
}


std::string parse_whole_number(std::string_view text, WholeNumber& value) {
  // sign? digits [. digits] [e sign? digits], read exactly as a decimal, never through a double.
  std::size_t i = 0;
  bool negative = false;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) negative = text[i++] == '-';
  std::string digits;  // significant digits, integer and fraction part together
  long long exponent = 0;
  bool any_digit = false;
  while (i < text.size() && is_digit(text[i])) {
    digits += text[i++];
    any_digit = true;
  }
  if (i < text.size() && text[i] == '.') {
    ++i;
    while (i < text.size() && is_digit(text[i])) {
      digits += text[i++];
      --exponent;
      any_digit = true;
    }
  }
  if (!any_digit) return "not a number";
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    bool exponent_negative = false;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) exponent_negative = text[i++] == '-';
    if (i == text.size()) return "not a number";
    long long e = 0;
    while (i < text.size() && is_digit(text[i])) {
      if (e < 100000) e = e * 10 + (text[i] - '0');
      ++i;
    }
    exponent += exponent_negative ? -e : e;
  }
  if (i != text.size()) return "not a number";
  // Leading zeros carry nothing; trailing zeros can absorb a negative exponent.
  std::size_t first = digits.find_first_not_of('0');
  if (first == std::string::npos) {
    value = {false, 0};
    return "";
  }
  digits.erase(0, first);
  while (exponent < 0 && digits.back() == '0') {
    digits.pop_back();
    ++exponent;
  }
  if (exponent < 0) return "not an integer";
  if (static_cast<long long>(digits.size()) + exponent > 20) return "out of range";
  std::uint64_t magnitude = 0;
  for (char c : digits) {
    if (__builtin_mul_overflow(magnitude, 10u, &magnitude) ||
        __builtin_add_overflow(magnitude, static_cast<unsigned>(c - '0'), &magnitude))
      return "out of range";
  }
  for (long long e = 0; e < exponent; ++e)
    if (__builtin_mul_overflow(magnitude, 10u, &magnitude)) return "out of range";
  value = {negative && magnitude != 0, magnitude};
  return "";
}

std::string integer_range(WholeNumber min, WholeNumber max) {
  return "an integer from " + to_string(min) + " to " + to_string(max);
}

std::string check_integer(std::string_view text, WholeNumber min, WholeNumber max, WholeNumber& value) {
  std::string problem = parse_whole_number(text, value);
  if (problem.empty() && (less(value, min) || less(max, value))) problem = "out of range";
  if (problem.empty()) return "";
  return problem + "; expected " + integer_range(min, max);
}

std::string check_real(std::string_view text, RealRange range, double& value) {
  std::string problem;
  // A leading '+' is read as CLI11 reads it (from_chars takes none); a sign after it is not.
  if (text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+') text.remove_prefix(1);
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range) {
    problem = "out of range";
  } else if (ec != std::errc() || end != text.data() + text.size()) {
    problem = "not a number";
  } else if (!std::isfinite(value)) {
    problem = "not a finite number";
  } else if (value < range.min || (range.min_open && value == range.min) || value > range.max ||
             (range.max_open && value == range.max)) {
    problem = "out of range";
  }
  if (problem.empty()) return "";
  return problem + "; expected " + real_range(range);
}

namespace {

std::map<const CLI::Option*, NumericOption>& numeric_registry() {
  static std::map<const CLI::Option*, NumericOption> registry;
  return registry;
}

}  // namespace

const NumericOption* find_numeric_option(const CLI::Option* option) {
  auto it = numeric_registry().find(option);
  return it == numeric_registry().end() ? nullptr : &it->second;
}

void register_numeric_option(const CLI::Option* option, NumericOption record) {
  numeric_registry().insert_or_assign(option, std::move(record));
}

void forget_numeric_option(const CLI::Option* option) { numeric_registry().erase(option); }

std::string message_name(const std::string& names) { return CLI::detail::split(names, ',').back(); }

CLI::Option* add_real_option(CLI::App* command, const std::string& names, double& target, RealRange range,
                             const std::string& help) {
  const std::string name = message_name(names);
  CLI::Option* option = command->add_option_function<std::string>(
      names,
      [&target, range, name](const std::string& text) {
        double value = 0.0;
        std::string problem = check_real(text, range, value);
        if (!problem.empty()) throw CLI::ValidationError(name + " " + text + ": " + problem);
        target = value;
      },
      help);
  option->type_name("NUMBER")->default_str(number_text(target));
  register_numeric_option(option, {name, false, {}, {}, range, real_range(range)});
  return option;
}

CLI::Option* add_seed_option(CLI::App* command, std::uint64_t& seed, const std::string& help) {
  return add_integer_option(command, "-s,--seed", seed, std::uint64_t{0}, std::numeric_limits<std::uint64_t>::max(), help);
}

CLI::Option* add_threads_option(CLI::App* command, int& threads) {
  return add_integer_option(command, "--threads", threads, 1, static_cast<int>(kMaxThreads),
                            "CPU threads (default: all cores this process may use, as nproc counts them); output does not depend on it")
      ->default_str("all cores");
}

}  // namespace bluetile::cli
