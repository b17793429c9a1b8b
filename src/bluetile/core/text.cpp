#include "bluetile/core/text.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "bluetile/core/error.h"

namespace bluetile {

std::string exact_text(double v) {
  const ClassicNumbers classic;
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

std::string shortest_text(double v) {
  const ClassicNumbers classic;
  char buffer[32];
  for (int digits = 1; digits < 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
    if (std::strtod(buffer, nullptr) == v) return buffer;
  }
  return exact_text(v);  // NaN, and doubles that need all 17 digits
}

std::string number_text(double v) {
  const ClassicNumbers classic;
  if (std::isinf(v)) return v > 0 ? "infinity" : "-infinity";
  if (v == std::floor(v) && std::fabs(v) < 1e15) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.0f", v);
    return buffer;
  }
  return shortest_text(v);
}

std::string count_text(double v) {
  const ClassicNumbers classic;
  char text[40];
  std::snprintf(text, sizeof text, v < 1e18 ? "%.0f" : "%.3g", v);
  return text;
}

std::string counted(long long n, std::string_view noun) {
  return std::to_string(n) + " " + std::string(noun) + (n == 1 ? "" : "s");
}

std::string fixed_text(double v, int decimals) {
  const ClassicNumbers classic;
  char buffer[352];  // %f of the largest double is 309 digits, plus the decimals asked for
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  return buffer;
}

std::string measure_text(double v, int decimals) { return std::isfinite(v) ? fixed_text(v, decimals) : "-"; }

std::string csv_number(double v, int digits) {
  const ClassicNumbers classic;
  if (!std::isfinite(v)) return "";
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;
}

std::string csv_defined_number(double v, int digits, const std::string& what) {
  if (!std::isfinite(v))
    throw Error(what + " is " + number_text(v) + ", where it must be a finite number: not written");
  return csv_number(v, digits);
}

namespace {

// The C locale, made once and never freed (threads may hold it until they end).
locale_t classic_locale() {
  static const locale_t classic = newlocale(LC_ALL_MASK, "C", static_cast<locale_t>(0));
  return classic;
}

}  // namespace

// Where newlocale failed (no memory at the first call), uselocale(0) only asks, and changes nothing.
ClassicNumbers::ClassicNumbers() : previous_(uselocale(classic_locale())) {}
ClassicNumbers::~ClassicNumbers() { uselocale(previous_); }

std::string_view next_line(std::string_view& rest) {
  const std::size_t end = rest.find_first_of("\r\n");
  const std::string_view line = rest.substr(0, end);
  if (end == std::string_view::npos) rest = {};
  else rest.remove_prefix(end + (rest.substr(end, 2) == "\r\n" ? 2 : 1));
  return line;
}

std::string lower_case(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string comment_line(std::string_view text, bool c_comment) {
  std::string line;
  line.reserve(text.size());
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n') line += "\\n";
    else if (c == '\r') line += "\\r";
    else if ((byte < 0x20 && c != '\t') || byte == 0x7F || (c_comment && c == '\\')) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      line += escaped;
    } else {
      line += c;
    }
  }
  return line;
}

}  // namespace bluetile
