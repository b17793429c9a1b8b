// Arguments as Python passed them, checked by name: an integer of any size (or not an integer),
// a path (str or os.PathLike) and an array (or a nested sequence). nanobind would refuse -1 for
// an unsigned seed, 2**64, a pathlib.Path or a list with its list of signatures ("incompatible
// function arguments"); these take any object and the functions below say what was wrong with it,
// naming the argument.
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

// An array argument: read with array_arg().
class ArrayArg : public nb::object {
  NB_OBJECT_DEFAULT(ArrayArg, nb::object, "numpy.typing.ArrayLike", detail::any_object)
};

// The Python int in `value` (or anything with __index__, as NumPy's integers) if it lies in
// [low, high]. Throws TypeError for a non-integer ("count: expected an integer, got float") and
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

// A seed (or a set of one): any unsigned 64-bit integer, as the tool's --seed.
inline std::uint64_t seed_value(const Whole& value, const char* name = "seed") {
  return whole<std::uint64_t>(value, name, 0, UINT64_MAX);
}

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
