#include "arguments.h"

#include <string_view>

namespace pybluetile {

using namespace nb::literals;

namespace {

// "float", "str", "pathlib.PosixPath", "numpy.float64"; "None" for None.
std::string type_text(nb::handle value) {
  if (value.is_none()) return "None";
  return nb::type_name(value.type()).c_str();
}

// str(value); a handle first, so that an attribute is converted rather than taken for a str.
std::string text_of(nb::handle value) { return nb::str(value).c_str(); }

// Python's bool or NumPy's (numpy.bool_, numpy.bool in NumPy 2, a static type: its tp_name has
// the module).
bool is_bool(nb::handle value) {
  if (PyBool_Check(value.ptr())) return true;
  const std::string_view type = Py_TYPE(value.ptr())->tp_name;
  return type == "numpy.bool_" || type == "numpy.bool";
}

// The int of an integer argument (NumPy's integers included, as range() takes them). A bool is
// refused: Python takes True as 1, and count=True is a slip, not a count.
nb::object python_int(const Whole& value, const char* name) {
  if (!PyIndex_Check(value.ptr()) || is_bool(value))
    throw nb::type_error((std::string(name) + ": expected an integer, got " + type_text(value)).c_str());
  PyObject* index = PyNumber_Index(value.ptr());
  if (!index) throw nb::python_error();
  return nb::steal(index);
}

[[noreturn]] void out_of_range(const char* name, const std::string& range, nb::handle value) {
  throw nb::value_error((std::string(name) + ": expected " + range + ", got " + text_of(value)).c_str());
}

const char* expectation(ArrayKind kind) {
  switch (kind) {
    case ArrayKind::points: return "an array of shape (N, 2) or (K, N, 2), or a sequence of [x, y] pairs";
    case ArrayKind::density: return "a 2-D array of densities (rows, columns), or a sequence of rows";
    case ArrayKind::levels: return "an array of whole numbers of shape (N,), or a sequence of them";
  }
  return "an array";
}

}  // namespace

long long whole_signed(const Whole& value, const char* name, long long low, long long high, const std::string& range) {
  const nb::object number = python_int(value, name);
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(number.ptr(), &overflow);
  if (v == -1 && PyErr_Occurred()) throw nb::python_error();
  if (overflow != 0 || v < low || v > high)
    out_of_range(name, range.empty() ? std::to_string(low) + " to " + std::to_string(high) : range, number);
  return v;
}

unsigned long long whole_unsigned(const Whole& value, const char* name, unsigned long long low,
                                  unsigned long long high, const std::string& range) {
  const nb::object number = python_int(value, name);
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(number.ptr(), &overflow);
  if (v == -1 && PyErr_Occurred()) throw nb::python_error();
  bool fits = overflow == 0 ? v >= 0 : overflow > 0;
  unsigned long long u = static_cast<unsigned long long>(v);
  if (fits && overflow > 0) {
    u = PyLong_AsUnsignedLongLong(number.ptr());
    if (PyErr_Occurred()) {  // past 2**64 - 1
      PyErr_Clear();
      fits = false;
    }
  }
  if (!fits || u < low || u > high)
    out_of_range(name, range.empty() ? std::to_string(low) + " to " + std::to_string(high) : range, number);
  return u;
}

double real_or(const Real& value, double fallback, const char* name) {
  if (value.is_none()) return fallback;
  PyObject* v = value.ptr();
  // What float() takes but text (which it would parse); a bool is a slip, as for integers.
  const PyNumberMethods* methods = Py_TYPE(v)->tp_as_number;
  const bool number = !is_bool(value) && (PyFloat_Check(v) || PyIndex_Check(v) || (methods && methods->nb_float));
  if (!number)
    throw nb::type_error((std::string(name) + ": expected a number (int or float), got " + type_text(value)).c_str());
  const double d = PyFloat_AsDouble(v);
  if (d == -1.0 && PyErr_Occurred()) {
    if (!PyErr_ExceptionMatches(PyExc_OverflowError)) throw nb::python_error();
    PyErr_Clear();
    throw nb::value_error((std::string(name) + ": expected a number, got an integer too large for a float").c_str());
  }
  return d;
}

bool flag_or(const Flag& value, bool fallback, const char* name) {
  if (value.is_none()) return fallback;
  if (!is_bool(value))
    throw nb::type_error((std::string(name) + ": expected a bool (True or False), got " + type_text(value)).c_str());
  const int truth = PyObject_IsTrue(value.ptr());
  if (truth < 0) throw nb::python_error();
  return truth != 0;
}

std::string text_or(const Text& value, const std::string& fallback, const char* name) {
  if (value.is_none()) return fallback;
  if (!PyUnicode_Check(value.ptr()))
    throw nb::type_error((std::string(name) + ": expected a str, got " + type_text(value)).c_str());
  Py_ssize_t size = 0;
  const char* utf8 = PyUnicode_AsUTF8AndSize(value.ptr(), &size);
  if (!utf8) {  // a lone surrogate
    PyErr_Clear();
    throw nb::value_error((std::string(name) + ": not valid text (" + text_of(nb::repr(value)) + ")").c_str());
  }
  return std::string(utf8, static_cast<std::size_t>(size));
}

std::string path_text(const PathArg& path, const char* name) {
  PyObject* p = path.ptr();
  if (!PyUnicode_Check(p) && !PyBytes_Check(p) && !PyObject_HasAttrString(p, "__fspath__"))
    throw nb::type_error((std::string(name) + ": expected a str or os.PathLike path, got " + type_text(path)).c_str());
  nb::object fs = nb::steal(PyOS_FSPath(p));
  if (!fs.is_valid()) throw nb::python_error();
  // Undecodable bytes of a name (held as surrogates in a str) go back to the file system as they came.
  nb::object bytes = PyBytes_Check(fs.ptr()) ? fs : nb::steal(PyUnicode_EncodeFSDefault(fs.ptr()));
  if (!bytes.is_valid()) throw nb::python_error();
  std::string text(PyBytes_AS_STRING(bytes.ptr()), static_cast<std::size_t>(PyBytes_GET_SIZE(bytes.ptr())));
  // As open(): a C path would end at the first NUL and name another file.
  if (text.find('\0') != std::string::npos) throw nb::value_error((std::string(name) + ": embedded null character").c_str());
  return text;
}

AnyArray array_arg(const ArrayArg& value, const char* name, ArrayKind kind) {
  AnyArray array;
  if (nb::try_cast(value, array)) return array;
  PyObject* v = value.ptr();
  const bool typed = PyObject_HasAttrString(v, "__array__") || PyObject_HasAttrString(v, "__array_interface__");
  const bool sequence = PySequence_Check(v) && !PyUnicode_Check(v) && !PyBytes_Check(v) && !PyByteArray_Check(v);
  if (!typed && !sequence)
    throw nb::type_error((std::string(name) + ": expected " + expectation(kind) + ", got " + type_text(value)).c_str());
  const nb::module_ numpy = nb::module_::import_("numpy");
  nb::object converted;
  try {
    // Python's numbers have no dtype: a sequence of them is read as float64 (so that [[0, 1]]
    // is a point); an object with a dtype of its own keeps it, checked as an array's.
    if (typed || kind == ArrayKind::levels)
      converted = numpy.attr("asarray")(value);
    else
      converted = numpy.attr("asarray")(value, "dtype"_a = "float64");
  } catch (nb::python_error& e) {
    if (!e.matches(PyExc_ValueError) && !e.matches(PyExc_TypeError)) throw;
    throw nb::value_error((std::string(name) + ": expected " + expectation(kind) + "; NumPy cannot read this " +
                           type_text(value) + " as numbers (" + text_of(e.value()) + ")")
                              .c_str());
  }
  // An array in the other byte order (a FITS catalogue, np.fromfile of another machine's data):
  // the array protocols carry only the machine's own, so it is read in that order first.
  if (!nb::try_cast(converted, array) && !nb::cast<bool>(converted.attr("dtype").attr("isnative")))
    converted = converted.attr("astype")(converted.attr("dtype").attr("newbyteorder")("="));
  if (!nb::try_cast(converted, array)) {  // a dtype no array protocol carries: object, str
    const std::string dtype = text_of(converted.attr("dtype"));
    // The words of levels_array, density_grid and point_sets for a dtype they refuse.
    if (kind == ArrayKind::levels)
      throw nb::type_error((std::string(name) + ": expected integer values, got " + dtype).c_str());
    if (kind == ArrayKind::density)
      throw nb::type_error((std::string(name) + ": expected float64 or float32, got " + dtype).c_str());
    throw nb::type_error((std::string(name) + ": expected float64 (or float32) values, got " + dtype +
                          "; convert with .astype(numpy.float64)").c_str());
  }
  return array;
}

}  // namespace pybluetile
