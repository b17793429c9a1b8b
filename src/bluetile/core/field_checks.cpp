#include "bluetile/core/field_checks.h"

#include <algorithm>

#include "bluetile/core/error.h"
#include "bluetile/core/text.h"

namespace bluetile {

void check_whole_field(std::string_view field, long long value, long long low, long long high) {
  if (value < low || value > high)
    throw Error(std::string(field) + ": expected " + std::to_string(low) + " to " + std::to_string(high) + ", got " +
                std::to_string(value));
}

void check_real_field(std::string_view field, double value, double low, double high, std::string_view unit) {
  if (!(value >= low && value <= high))
    throw Error(std::string(field) + ": expected " + shortest_text(low) + " to " + shortest_text(high) +
                std::string(unit) + ", got " + shortest_text(value));
}

void check_name_field(std::string_view field, const std::string& value, const std::vector<std::string>& names) {
  if (std::find(names.begin(), names.end(), value) != names.end()) return;
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "'" : ", '") + name + "'";
  throw Error(std::string(field) + ": expected one of " + list + ", got '" + value + "'");
}

}  // namespace bluetile
