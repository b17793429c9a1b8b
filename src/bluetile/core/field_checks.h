// Range and name checks of option fields, one message form for every front end:
// "<field>: expected <low> to <high>[ unit], got <value>" and
// "<field>: expected one of 'a', 'b', got '<value>'".
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace bluetile {

// Throws Error unless low <= value <= high.
void check_whole_field(std::string_view field, long long value, long long low, long long high);
// Throws Error unless low <= value <= high (NaN is outside); `unit` follows the range (" tile units").
void check_real_field(std::string_view field, double value, double low, double high, std::string_view unit = {});
// Throws Error unless `value` is one of `names`.
void check_name_field(std::string_view field, const std::string& value, const std::vector<std::string>& names);

}  // namespace bluetile
