// Arguments as Python passed them, checked by name: an integer of any size (or not an integer), a
// number, a bool, a str, a path (str or os.PathLike) and an array (or a nested sequence).
// nanobind would refuse -1 for an unsigned seed, 2**64, a pathlib.Path, a list, None or a value of
// the wrong type with its list of signatures ("incompatible function arguments"); these take any
// object and the functions below say what was wrong with it, naming the argument. None passed for
// an argument that has a default means that default (the *_or readers), as in Python's own
// functions; for one without a default it is refused by name like any other wrong type.
#pragma once

#include <cstdint>
#include <string>
#include <type_traits>

#include <nanobind/nanobind.h>

#include "arrays.h"

namespace pybluetile {

namespace nb = nanobind;

namespace detail {
inline bool any_object(PyObject*) { return true; }
}  // namespace detail

// An integer argument: read with whole().
class Whole : public nb::object {
  NB_OBJECT_DEFAULT(Whole, nb::object, "int", detail::any_object)
};

// A path argument: read with path_text().
class PathArg : public nb::object {
  NB_OBJECT_DEFAULT(PathArg, nb::object, "str | os.PathLike[str]", detail::any_object)
};

// A float argument: read with real_or().
class Real : public nb::object {
  NB_OBJECT_DEFAULT(Real, nb::object, "float", detail::any_object)
};

// A bool argument: read with flag_or().
class Flag : public nb::object {
  NB_OBJECT_DEFAULT(Flag, nb::object, "bool", detail::any_object)
};

// A str argument: read with text_or().
class Text : public nb::object {
  NB_OBJECT_DEFAULT(Text, nb::object, "str", detail::any_object)
};

// An array argument: read with array_arg().
class ArrayArg : public nb::object {
  NB_OBJECT_DEFAULT(ArrayArg, nb::object, "numpy.typing.ArrayLike", detail::any_object)
};

// The Python int in `value` (or anything with __index__, as NumPy's integers) if it lies in
// [low, high]. Throws TypeError for a non-integer ("count: expected an integer, got float"; a bool
// too, which Python would take as 0 or 1; None where the argument has no default) and
// ValueError "<name>: expected <range>, got <value>" with the value as Python wrote it, where
// <range> is "<low> to <high>" unless `range` says more (as "1 to 100000000" for a count whose 0
// means "not given").
long long whole_signed(const Whole& value, const char* name, long long low, long long high, const std::string& range);
unsigned long long whole_unsigned(const Whole& value, const char* name, unsigned long long low,
                                  unsigned long long high, const std::string& range);

template <typename T>
T whole(const Whole& value, const char* name, T low, T high, const std::string& range = {}) {
  if constexpr (std::is_signed_v<T>)
    return static_cast<T>(whole_signed(value, name, low, high, range));
  else
    return static_cast<T>(whole_unsigned(value, name, low, high, range));
}

// whole(), or `fallback` (the argument's default) where Python passed None.
template <typename T>
T whole_or(const Whole& value, T fallback, const char* name, T low, T high, const std::string& range = {}) {
  return value.is_none() ? fallback : whole<T>(value, name, low, high, range);
}

// A seed (or a set of one): any unsigned 64-bit integer, as the tool's --seed; None: `fallback`.
inline std::uint64_t seed_or(const Whole& value, std::uint64_t fallback, const char* name = "seed") {
  return whole_or<std::uint64_t>(value, fallback, name, 0, UINT64_MAX);
}

// A number: a Python int or float, or anything float() takes as one without parsing text (NumPy's
// scalars); None: `fallback`. Its range is checked where it is used. Throws TypeError naming
// `name` for anything else (a bool or a str too) and ValueError for an int too large for a float.
double real_or(const Real& value, double fallback, const char* name);

// True or False (NumPy's bool too); None: `fallback`. Throws TypeError naming `name` for anything
// else: 0 and 1 are integers, and a string such as 'False' would be true.
bool flag_or(const Flag& value, bool fallback, const char* name);

// A str as UTF-8; None: `fallback`. Throws TypeError naming `name` for anything else.
std::string text_or(const Text& value, const std::string& fallback, const char* name);

// The file system's bytes of a str or os.PathLike (bytes paths too), as os.fsencode gives them.
// Throws TypeError naming `name` for anything else, ValueError for a NUL in it (as open()).
std::string path_text(const PathArg& path, const char* name);

// What an array argument holds, for its messages and for reading a sequence.
enum class ArrayKind {
  points,   // float64 (or float32) of shape (N, 2) or (K, N, 2); a sequence is read as float64
  density,  // float64 (or float32) of shape (rows, columns); a sequence is read as float64
  levels,   // whole numbers of shape (N,); a sequence is read as NumPy reads it
};

// The array in `value`: any CPU array nanobind reads (NumPy, DLPack, buffer protocol), else a
// nested sequence (a list of [x, y] pairs) or an object with __array__, read by numpy.asarray.
// Its dtype and shape are checked by point_sets, density_grid or levels_array. Throws TypeError
// for anything else and ValueError for a sequence NumPy cannot read as numbers, naming `name`.
AnyArray array_arg(const ArrayArg& value, const char* name, ArrayKind kind);

}  // namespace pybluetile
