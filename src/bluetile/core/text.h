// Numbers and words in messages and tables, formatted one way everywhere.
#pragma once

#include <string>

namespace bluetile {

// `v` with 17 significant digits ("%.17g"): reads back as the same double.
std::string exact_text(double v);

// `v` in the fewest significant digits that read back as the same double (0.1, not
// 0.10000000000000001), for messages that quote a range or a value.
std::string shortest_text(double v);

// `v` with `decimals` digits after the point ("%.*f"), for tables meant for reading.
std::string fixed_text(double v, int decimals);

// `s` in ASCII lower case (file extensions, device names).
std::string lower_case(std::string s);

}  // namespace bluetile
