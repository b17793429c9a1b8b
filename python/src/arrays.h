// NumPy arrays in and out of the library: point sets of shape (N, 2) or (K, N, 2), checked
// once here (dtype, shape, finite values) with messages that name the argument.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <string>
#include <vector>

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include "bluetile/core/density_grid.h"
#include "bluetile/core/torus.h"

namespace pybluetile {

namespace nb = nanobind;

// Any array on the CPU: dtype and shape are checked by the functions below, so that a wrong
// one gets a message naming it instead of nanobind's list of signatures.
using AnyArray = nb::ndarray<nb::ro, nb::device::cpu>;

struct PointSets {
  std::vector<std::vector<bluetile::Point>> sets;
  bool batched = false;  // the array had shape (K, N, 2); else (N, 2), one set
};

// What point_sets does with a coordinate outside [0, 1).
enum class OutsideTorus {
  wrap,    // wrapped onto the torus, as `relax` wraps point files
  refuse,  // refused, as `analyze` refuses them (wrapping (1, 1) onto (0, 0) would measure a pair that is not there)
  keep,    // kept as given: a table to be saved holds plane coordinates too, as `bluetile tile` writes them
  square,  // refused, as `relax --bounded` refuses them: a bounded set lies in the square, no torus to wrap onto
};

// float64 or float32 values, shape (N, 2) or (K, N, 2) with N >= 1, every value finite, placed
// as `outside` says. Throws TypeError (dtype) or ValueError (shape, values) naming `name`.
PointSets point_sets(const AnyArray& array, const char* name, OutsideTorus outside = OutsideTorus::wrap);

// Whole numbers (any integer dtype) of shape (N,), each in [0, max].
std::vector<int> levels_array(const AnyArray& array, std::size_t count, const char* name, int max);

// A density map: a 2-D float64 or float32 array of shape (rows, columns), row 0 at the top (as
// images and matplotlib's imshow have it), every value finite and >= 0; the grid's row 0 is the
// bottom (density_grid.h). Throws TypeError (dtype) or ValueError naming `name` and, for a bad
// value, its row and column.
bluetile::DensityGrid density_grid(const AnyArray& array, const char* name);

// A NumPy array owning `values` (moved, not copied), of the given shape.
template <typename T>
nb::ndarray<nb::numpy, T> to_numpy(std::vector<T>&& values, std::initializer_list<std::size_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  nb::capsule owner(owned, [](void* p) noexcept { delete static_cast<std::vector<T>*>(p); });
  return nb::ndarray<nb::numpy, T>(owned->data(), shape, owner);
}

// Sets of equal size as an array of shape (K, N, 2), or (N, 2) when not batched.
nb::ndarray<nb::numpy, double> points_to_numpy(const std::vector<std::vector<bluetile::Point>>& sets, bool batched);

// A name of the dtype as NumPy spells it ("int64", "float32", ...).
std::string dtype_name(nb::dlpack::dtype dtype);

}  // namespace pybluetile
