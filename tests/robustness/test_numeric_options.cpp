// Every numeric option of every subcommand, found through the tool's own app (cli/app.h) and the
// record add_integer_option/add_real_option keep (cli/numeric_options.h): NaN, infinity, garbage
// and values just outside the range are refused with one line naming the option, the value and
// the accepted range, and nothing is written. A new command or option is covered as it is added.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <set>

#include <gtest/gtest.h>

#include "cli/app.h"
#include "cli/numeric_options.h"
#include "robustness_support.h"
#include "test_support.h"

namespace bluetile::robustness {
namespace {

using cli::NumericOption;
using cli::WholeNumber;
using test::TempDir;

struct BadValue {
  std::string text;
  std::string problem;
};

std::string text(WholeNumber v) { return (v.negative ? "-" : "") + std::to_string(v.magnitude); }

constexpr std::uint64_t kMaxMagnitude = std::numeric_limits<std::uint64_t>::max();

// v - 1 and v + 1 as decimal text (one past 2^64 - 1 written out: it is still out of range).
std::string one_below(WholeNumber v) {
  if (v.negative) return v.magnitude == kMaxMagnitude ? "-18446744073709551616" : "-" + std::to_string(v.magnitude + 1);
  return v.magnitude == 0 ? "-1" : std::to_string(v.magnitude - 1);
}
std::string one_above(WholeNumber v) {
  if (v.negative) return v.magnitude == 1 ? "0" : "-" + std::to_string(v.magnitude - 1);
  return v.magnitude == kMaxMagnitude ? "18446744073709551616" : std::to_string(v.magnitude + 1);
}

std::string real_text(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

std::vector<BadValue> bad_values(const NumericOption& o) {
  if (o.integer) {
    return {{"nan", "not a number"},
            {"inf", "not a number"},
            {"seven", "not a number"},
            {"1.5", "not an integer"},
            {one_below(o.min), "out of range"},
            {one_above(o.max), "out of range"}};
  }
  std::vector<BadValue> values = {{"nan", "not a finite number"},
                                  {"inf", "not a finite number"},
                                  {"-inf", "not a finite number"},
                                  {"seven", "not a number"},
                                  {"1e999", "out of range"}};
  const cli::RealRange& r = o.range;
  if (std::isfinite(r.min))
    values.push_back({real_text(r.min_open ? r.min : r.min - std::max(1.0, std::fabs(r.min))), "out of range"});
  if (std::isfinite(r.max))
    values.push_back({real_text(r.max_open ? r.max : r.max + std::max(1.0, std::fabs(r.max))), "out of range"});
  return values;
}

// Numbers the tool takes without the numeric idiom, each with the reason.
const std::set<std::string> kOtherNumbers = {
    "tile --region",    // four coordinates, checked together (finite, X0 < X1, Y0 < Y1) by the command
    "analyze --domain",  // the same, before any file is read
};

bool looks_numeric(const CLI::Option* option) {
  const std::string type = option->get_type_name();
  for (const char* name : {"INT", "UINT", "FLOAT", "NUMBER"})
    if (type.rfind(name, 0) == 0) return true;
  return false;
}

TEST(NumericOptions, EveryNumericOptionOfEveryCommandRefusesBadValues) {
  std::unique_ptr<CLI::App> app = cli::make_app();
  std::map<std::string, int> per_command;
  int runs = 0;
  for (const CLI::App* command : app->get_subcommands([](CLI::App*) { return true; })) {
    const std::string name = command->get_name();
    per_command[name] = 0;
    const bool has_output = command->get_option_no_throw("--output") != nullptr;
    for (const CLI::Option* option : command->get_options()) {
      const NumericOption* record = cli::find_numeric_option(option);
      if (!record) {
        EXPECT_TRUE(!looks_numeric(option) || kOtherNumbers.count(name + " " + option->get_name()))
            << name << " " << option->get_name() << " (" << option->get_type_name()
            << ") takes a number without add_integer_option or add_real_option";
        continue;
      }
      ++per_command[name];
      // The range in words, short whatever its bounds (not 309 digits of DBL_MAX).
      EXPECT_LT(record->range_text.size(), 60u) << name << " " << record->name << ": " << record->range_text;
      if (record->integer) {
        EXPECT_EQ(record->range_text, "an integer from " + text(record->min) + " to " + text(record->max));
      }
      TempDir dir;
      // All the values of one option at once: the tool as several children.
      std::vector<BadValue> values = bad_values(*record);
      std::vector<std::unique_ptr<Child>> children;
      for (const BadValue& v : values) {
        Invocation call;
        call.arguments = {name, record->name, v.text};
        if (has_output) call.arguments.insert(call.arguments.end(), {"--output", dir.file("out")});
        children.push_back(std::make_unique<Child>(call));
      }
      for (std::size_t k = 0; k < values.size(); ++k) {
        Outcome r = children[k]->wait();
        ++runs;
        EXPECT_EQ(r.exit_code, 105) << name << " " << record->name << " " << values[k].text << ": " << r.err;
        EXPECT_EQ(r.err, "bluetile: " + record->name + " " + values[k].text + ": " + values[k].problem + "; expected " +
                             record->range_text + " (see --help)\n")
            << name;
        EXPECT_EQ(r.out, "");
      }
      EXPECT_EQ(entries(dir.path()), std::vector<std::string>{}) << name << " " << record->name;
    }
  }
  // The commands that take numbers, each found with its options (the list grows with the tool).
  for (const char* command : {"relax", "centroids", "analyze", "dart", "progressive", "wang", "wang-check", "tile", "stipple"})
    EXPECT_GT(per_command[command], 0) << command << " has no numeric option on record";
  EXPECT_GE(per_command["wang"], 17);
  EXPECT_GT(runs, 400);
}

}  // namespace
}  // namespace bluetile::robustness
