#include "arrays.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>

#include "bluetile/core/text.h"

namespace pybluetile {
namespace {

std::string shape_text(const AnyArray& array) {
  std::string text = "(";
  for (std::size_t d = 0; d < array.ndim(); ++d) text += (d ? ", " : "") + std::to_string(array.shape(d));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

template <typename T>
double element(const AnyArray& array, std::size_t offset) {
  return static_cast<double>(static_cast<const T*>(array.data())[offset]);
}

// A value of the array as NumPy prints it: in the fewest digits that read back as the same value
// of its own type, so a float32 -0.1 is "-0.1", not the double's -0.10000000149011612.
std::string value_text(double v, bool is_float32) {
  if (!is_float32 || !std::isfinite(v)) return bluetile::shortest_text(v);
  const float f = static_cast<float>(v);
  const bluetile::ClassicNumbers classic;  // "-0.1", not "-0,1", under a comma locale the program set
  char buffer[32];
  for (int digits = 1; digits < 9; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
    if (std::strtof(buffer, nullptr) == f) return buffer;
  }
  std::snprintf(buffer, sizeof buffer, "%.9g", v);  // 9 digits read back as any float
  return buffer;
}

}  // namespace

std::string dtype_name(nb::dlpack::dtype dtype) {
  const char* kind = "unknown";
  switch (static_cast<nb::dlpack::dtype_code>(dtype.code)) {
    case nb::dlpack::dtype_code::Int: kind = "int"; break;
    case nb::dlpack::dtype_code::UInt: kind = "uint"; break;
    case nb::dlpack::dtype_code::Float: kind = "float"; break;
    case nb::dlpack::dtype_code::Bool: return "bool";
    case nb::dlpack::dtype_code::Complex: kind = "complex"; break;
    default: break;
  }
  return kind + std::to_string(dtype.bits);
}

PointSets point_sets(const AnyArray& array, const char* name, OutsideTorus outside) {
  const bool is_double = array.dtype() == nb::dtype<double>();
  if (!is_double && array.dtype() != nb::dtype<float>())
    throw nb::type_error((std::string(name) + ": expected float64 (or float32) values, got " +
                          dtype_name(array.dtype()) + "; convert with .astype(numpy.float64)").c_str());
  const std::size_t ndim = array.ndim();
  if ((ndim != 2 && ndim != 3) || array.shape(ndim - 1) != 2 || array.shape(ndim - 2) == 0 ||
      (ndim == 3 && array.shape(0) == 0)) {
    // x and y as two rows (numpy.array([xs, ys])): say how to turn them.
    const bool as_rows = (ndim == 2 || ndim == 3) && array.shape(ndim - 2) == 2 && array.shape(ndim - 1) > 2;
    throw nb::value_error((std::string(name) + ": expected shape (N, 2) or (K, N, 2) with N >= 1, got " +
                           shape_text(array) +
                           (as_rows ? std::string("; coordinates as rows? pass ") + name +
                                          (ndim == 2 ? ".T" : ".transpose(0, 2, 1)")
                                    : std::string()))
                              .c_str());
  }
  PointSets result;
  result.batched = ndim == 3;
  const std::size_t sets = result.batched ? array.shape(0) : 1, count = array.shape(ndim - 2);
  // Strides are in elements; any layout (a transposed or sliced view) is read as it is.
  const std::int64_t set_stride = result.batched ? array.stride(0) : 0;
  const std::int64_t row_stride = array.stride(ndim - 2), column_stride = array.stride(ndim - 1);
  result.sets.resize(sets);
  // "points[3]" or, batched, "points[1, 3]": the element a message names.
  auto element_name = [&](std::size_t k, std::size_t i) {
    return std::string(name) + "[" + (result.batched ? std::to_string(k) + ", " : "") + std::to_string(i) + "]";
  };
  for (std::size_t k = 0; k < sets; ++k) {
    std::vector<bluetile::Point>& points = result.sets[k];
    points.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      double xy[2];
      for (std::size_t c = 0; c < 2; ++c) {
        std::size_t offset = static_cast<std::size_t>(static_cast<std::int64_t>(k) * set_stride +
                                                      static_cast<std::int64_t>(i) * row_stride +
                                                      static_cast<std::int64_t>(c) * column_stride);
        xy[c] = is_double ? element<double>(array, offset) : element<float>(array, offset);
        if (!std::isfinite(xy[c]))
          throw nb::value_error(
              (element_name(k, i) + ": not a finite number '" + value_text(xy[c], !is_double) + "'").c_str());
      }
      for (std::size_t c = 0; c < 2 && (outside == OutsideTorus::refuse || outside == OutsideTorus::square); ++c)
        if (!(xy[c] >= 0.0 && xy[c] < 1.0)) {
          const std::string value = value_text(xy[c], !is_double);
          const std::string why = outside == OutsideTorus::square
                                      ? "bounded=True: the points lie in the unit square, and are not wrapped onto a torus"
                                      : name + std::string(" % 1.0 % 1.0 wraps them onto the torus; a single % 1.0 gives "
                                                           "1.0 for a tiny negative");
          throw nb::value_error((element_name(k, i) + ": " + (c == 0 ? "x" : "y") + " = " + value + " is outside [0, 1) (" +
                                 why + ")")
                                    .c_str());
        }
      points[i] = outside == OutsideTorus::keep ? bluetile::Point{xy[0], xy[1]}
                                                : bluetile::wrap_point({xy[0], xy[1]}, bluetile::Domain{});
    }
  }
  return result;
}

std::vector<int> levels_array(const AnyArray& array, std::size_t count, const char* name, int max) {
  const auto code = static_cast<nb::dlpack::dtype_code>(array.dtype().code);
  if (code != nb::dlpack::dtype_code::Int && code != nb::dlpack::dtype_code::UInt)
    throw nb::type_error((std::string(name) + ": expected integer values, got " + dtype_name(array.dtype())).c_str());
  if (array.ndim() != 1 || array.shape(0) != count)
    throw nb::value_error((std::string(name) + ": expected shape (" + std::to_string(count) + ",), got " +
                           shape_text(array)).c_str());
  std::vector<int> levels(count);
  const unsigned bits = array.dtype().bits;
  const bool is_signed = code == nb::dlpack::dtype_code::Int;
  for (std::size_t i = 0; i < count; ++i) {
    std::size_t offset = static_cast<std::size_t>(static_cast<std::int64_t>(i) * array.stride(0));
    const void* data = array.data();
    // Each width read as its own type: `signed ? int32 : uint32` would be uint32 (-1 read as
    // 4294967295), and a uint64 past 2**63 does not fit a long long.
    long long v = 0;
    std::uint64_t u = 0;
    if (is_signed) {
      switch (bits) {
        case 8: v = static_cast<const std::int8_t*>(data)[offset]; break;
        case 16: v = static_cast<const std::int16_t*>(data)[offset]; break;
        case 32: v = static_cast<const std::int32_t*>(data)[offset]; break;
        default: v = static_cast<const std::int64_t*>(data)[offset];
      }
    } else {
      switch (bits) {
        case 8: u = static_cast<const std::uint8_t*>(data)[offset]; break;
        case 16: u = static_cast<const std::uint16_t*>(data)[offset]; break;
        case 32: u = static_cast<const std::uint32_t*>(data)[offset]; break;
        default: u = static_cast<const std::uint64_t*>(data)[offset];
      }
      v = static_cast<long long>(std::min<std::uint64_t>(u, static_cast<std::uint64_t>(max) + 1));
    }
    if (v < 0 || v > max)
      throw nb::value_error((std::string(name) + "[" + std::to_string(i) + "]: level must be in [0, " +
                             std::to_string(max) + "], got " + (is_signed ? std::to_string(v) : std::to_string(u))).c_str());
    levels[i] = static_cast<int>(v);
  }
  return levels;
}

nb::ndarray<nb::numpy, double> points_to_numpy(const std::vector<std::vector<bluetile::Point>>& sets, bool batched) {
  const std::size_t count = sets.empty() ? 0 : sets[0].size();
  std::vector<double> values;
  values.reserve(sets.size() * count * 2);
  for (const auto& set : sets)
    for (const bluetile::Point& p : set) values.insert(values.end(), {p.x, p.y});
  if (batched) return to_numpy(std::move(values), {sets.size(), count, 2});
  return to_numpy(std::move(values), {count, 2});
}

bluetile::DensityGrid density_grid(const AnyArray& a, const char* name) {
  const std::string what(name);
  if (a.ndim() != 2 || a.shape(0) < 1 || a.shape(1) < 1)
    throw nb::value_error((what + ": expected a 2-D array of shape (rows, columns)").c_str());
  if (a.shape(0) > 65536 || a.shape(1) > 65536)
    throw nb::value_error((what + ": expected at most 65536 rows and columns").c_str());
  const bool f64 = a.dtype() == nb::dtype<double>(), f32 = a.dtype() == nb::dtype<float>();
  if (!f64 && !f32) throw nb::type_error((what + ": expected float64 or float32, got " + dtype_name(a.dtype())).c_str());
  const int height = static_cast<int>(a.shape(0)), width = static_cast<int>(a.shape(1));
  bluetile::DensityGrid grid(width, height);
  for (int r = 0; r < height; ++r)
    for (int c = 0; c < width; ++c) {
      const std::int64_t at = r * a.stride(0) + c * a.stride(1);
      const double v = f64 ? static_cast<const double*>(a.data())[at] : static_cast<const float*>(a.data())[at];
      if (!(v >= 0.0) || !std::isfinite(v))
        throw nb::value_error((what + ": values must be finite and >= 0, got " + value_text(v, f32) + " at row " +
                               std::to_string(r) + ", column " + std::to_string(c)).c_str());
      grid.at(c, height - 1 - r) = static_cast<float>(v);  // row 0 at the bottom, y up
    }
  return grid;
}

}  // namespace pybluetile
