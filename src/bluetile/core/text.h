// Numbers and words in messages and tables, formatted one way everywhere.
#pragma once

#include <string>
#include <string_view>

#include <locale.h>

namespace bluetile {

// `v` with 17 significant digits ("%.17g"): reads back as the same double.
std::string exact_text(double v);

// `v` in the fewest significant digits that read back as the same double (0.1, not
// 0.10000000000000001), for messages that quote a range or a value.
std::string shortest_text(double v);

// A number as messages and help write it: whole numbers below 10^15 in full ("100", not
// "1e+02"), "infinity" and "-infinity", else shortest_text.
std::string number_text(double v);

// A count, whole up to 10^18 and in scientific notation beyond, where its digits are noise
// ("100000000000000", "1.23e+20").
std::string count_text(double v);

// `n` and the noun, plural unless n is 1 ("1 iteration", "80 iterations"); regular nouns only.
std::string counted(long long n, std::string_view noun);

// `v` with `decimals` digits after the point ("%.*f"), for tables meant for reading.
std::string fixed_text(double v, int decimals);

// A measure in a table meant for reading: fixed_text, or "-" where the measure is undefined (NaN
// or infinite: LF of a set too small to hold its band, say), never a bare "nan".
std::string measure_text(double v, int decimals);

// A number as a CSV field, "%.*g" with `digits` significant digits, or the empty field (CSV's
// missing value, stats.json's null) where `v` is undefined (NaN or infinite).
std::string csv_number(double v, int digits);

// The same for a field that must hold a value: throws Error("<what> is nan: ...") where `v` is
// not finite, rather than writing the empty field that reads as "undefined".
std::string csv_defined_number(double v, int digits, const std::string& what);

// While it lives, the printf and strtod families in the calling thread read and write numbers
// with a '.', whatever locale the program set: under Python's locale.setlocale(LC_ALL, '') in a
// German locale the library wrote point files as "0,5 0,25", which no reader takes, and CSV
// fields that split in two. Every number the library formats goes through one (the functions
// above hold their own). Nests; costs two thread-local stores.
class ClassicNumbers {
 public:
  ClassicNumbers();
  ~ClassicNumbers();
  ClassicNumbers(const ClassicNumbers&) = delete;
  ClassicNumbers& operator=(const ClassicNumbers&) = delete;

 private:
  locale_t previous_;
};

// The next line of `rest`, which loses it and its end: a line ends at "\n", "\r\n" or a lone
// "\r" (classic Mac OS), as every text reader here takes it (point files read in chunks do the
// same in PointTextParser).
std::string_view next_line(std::string_view& rest);

// `s` in ASCII lower case (file extensions, device names).
std::string lower_case(std::string s);

// `text` made safe as the rest of one comment line of an output file: line breaks and other
// control characters (tabs excepted) become \n, \r or \xNN, so that a file name or comment
// holding them cannot add a line (a point, or code in a C header). `c_comment`: backslashes become
// \x5c too, since a // comment that ends in one continues on the next line.
std::string comment_line(std::string_view text, bool c_comment = false);

}  // namespace bluetile
