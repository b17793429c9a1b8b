// save_table and load_table: the sample-table formats of core/point_table.h.
#include <fstream>
#include <optional>

#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include "arguments.h"
#include "arrays.h"
#include "bindings.h"
#include "bluetile/core/error.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/point_table.h"

namespace pybluetile {

using namespace nb::literals;

namespace {

// The comment argument: read with comment_lines().
class CommentArg : public nb::object {
  NB_OBJECT_DEFAULT(CommentArg, nb::object, "str | collections.abc.Sequence[str]", detail::any_object)
};

// A str is one comment line, as one item of a sequence is: the table writer escapes a line break
// in it (\n), as the tool escapes one in a file name it writes as a comment, so that no comment
// adds a point or code. None: no comment. Anything else: TypeError naming the argument.
std::vector<std::string> comment_lines(const CommentArg& comment) {
  if (comment.is_none()) return {};
  PyObject* c = comment.ptr();
  const std::string type = nb::type_name(comment.type()).c_str();
  if (PyUnicode_Check(c)) return {text_or(nb::borrow<Text>(comment), {}, "comment")};
  if (!PySequence_Check(c) || PyBytes_Check(c) || PyByteArray_Check(c))
    throw nb::type_error(("comment: expected a str or a sequence of str, got " + type).c_str());
  std::vector<std::string> lines;
  const nb::object items = nb::steal(PySequence_Fast(c, "comment: expected a str or a sequence of str"));
  if (!items.is_valid()) throw nb::python_error();
  const Py_ssize_t n = PySequence_Fast_GET_SIZE(items.ptr());
  for (Py_ssize_t i = 0; i < n; ++i) {
    const nb::handle item = PySequence_Fast_GET_ITEM(items.ptr(), i);
    const std::string name = "comment[" + std::to_string(i) + "]";
    if (!PyUnicode_Check(item.ptr()))
      throw nb::type_error((name + ": expected a str, got " + nb::type_name(item.type()).c_str()).c_str());
    lines.push_back(text_or(nb::borrow<Text>(item), {}, name.c_str()));
  }
  return lines;
}

// The library's table_format_for, with messages that name the argument `format` where the
// library's name the tool's --format.
bluetile::TableFormat table_format(const std::string& path, const std::string& format) {
  std::string names;
  for (bluetile::TableFormat f : bluetile::kTableFormats) {
    const std::string_view name = bluetile::table_format_name(f);
    if (!format.empty() && format == name) return f;
    names += (names.empty() ? "'" : ", '") + std::string(name) + "'";
  }
  if (!format.empty()) throw bluetile::Error("format: expected one of " + names + ", got '" + format + "'");
  try {
    return bluetile::table_format_for(path);
  } catch (const bluetile::Error&) {
    // An extension that names no format: the same list as the library's message, from its table.
    std::string known;
    for (bluetile::TableFormat f : bluetile::kTableFormats) {
      std::string extensions;
      for (std::string_view e : bluetile::table_format_extensions(f))
        if (!e.empty()) extensions += (extensions.empty() ? "" : " ") + std::string(e);
      known += (known.empty() ? "" : ", ") + extensions + ": " + std::string(bluetile::table_format_name(f));
    }
    throw bluetile::Error(path + ": unknown extension '" + bluetile::file_extension(path) + "' (" + known +
                          "; or pass format=)");
  }
}

void save_table(const PathArg& path_arg, const ArrayArg& points, std::optional<ArrayArg> levels,
                const Text& format_arg, const Flag& float32_arg, const Text& name_arg, const CommentArg& comment_arg) {
  const std::string path = path_text(path_arg, "path");
  const std::string format = text_or(format_arg, "", "format"), name = text_or(name_arg, "", "name");
  const bool float32 = flag_or(float32_arg, false, "float32");
  const std::vector<std::string> comment = comment_lines(comment_arg);
  // Written as given, as `bluetile tile` writes plane coordinates: wrapping 1.5 to 0.5 wrote
  // another point.
  PointSets input = point_sets(array_arg(points, "points", ArrayKind::points), "points", OutsideTorus::keep);
  std::vector<bluetile::PointSet> sets;
  for (auto& s : input.sets) sets.push_back({std::move(s), {}});
  if (levels) {
    if (input.batched) throw nb::value_error("levels: only with points of shape (N, 2)");
    sets[0].levels = levels_array(array_arg(*levels, "levels", ArrayKind::levels), sets[0].points.size(), "levels",
                                  bluetile::kMaxTableLevel);
  }
  const bluetile::TableFormat f = table_format(path, format);
  // As the tool's --float32 and --name (and comment, which npy and binary tables cannot hold):
  // refused where they would change nothing.
  const std::string is = path + " is " + std::string(bluetile::table_format_name(f));
  if (float32 && f != bluetile::TableFormat::npy && f != bluetile::TableFormat::binary)
    throw bluetile::Error("float32: " + is + "; 4-byte floats are for npy and binary tables");
  if (!name.empty() && f != bluetile::TableFormat::header)
    throw bluetile::Error("name: " + is + "; the array name is for C headers (.h, .hpp)");
  const bool text = f == bluetile::TableFormat::text || f == bluetile::TableFormat::csv;
  if (!comment.empty() && !text && f != bluetile::TableFormat::header)
    throw bluetile::Error("comment: " + is + "; comment lines are for text and CSV tables and C headers");
  // A line the reader refuses ('domain: bounded') made a file load_table could not read back; a C
  // header is not read back, its '//' lines are free.
  if (text)
    for (std::size_t i = 0; i < comment.size(); ++i)
      bluetile::check_comment_line(comment[i], PyUnicode_Check(comment_arg.ptr()) ? "comment" : "comment[" + std::to_string(i) + "]");
  nb::gil_scoped_release release;
  bluetile::TableWriteOptions options;
  options.float32 = float32;
  options.name = name;
  options.comment = comment;
  // As the tool: npy and binary tables to a terminal (save_table('/dev/tty', ...)) are refused.
  bluetile::write_output(
      path,
      [&](bluetile::OutputStream& out) {
        bluetile::write_point_table(f, sets, options, path, [&](std::string_view bytes) { out.write(bytes); });
      },
      {.binary_format = bluetile::binary_table_format(f)});
}

nb::list load_table(const PathArg& path_arg, const Flag& levels_arg) {
  const std::string path = path_text(path_arg, "path");
  const bool levels = flag_or(levels_arg, false, "levels");
  std::vector<bluetile::PointSet> sets;
  {
    nb::gil_scoped_release release;
    sets = bluetile::read_point_table(path);
  }
  // As the tool refuses an empty file or one of comments only (`bluetile analyze -i`), not [].
  if (sets.empty()) throw bluetile::Error(path + ": no points");
  nb::list result;
  for (bluetile::PointSet& set : sets) {
    nb::object points = nb::cast(points_to_numpy({set.points}, false));
    if (!levels) {
      result.append(points);
      continue;
    }
    const std::size_t n = set.points.size();
    nb::object level = nb::none();
    if (set.has_levels()) level = nb::cast(to_numpy(std::vector<std::int32_t>(set.levels.begin(), set.levels.end()), {n}));
    result.append(nb::make_tuple(points, level));
  }
  return result;
}

}  // namespace

void bind_tables(nb::module_& m) {
  m.def("save_table", &save_table,
        nb::sig("def save_table(path: str | os.PathLike[str], points: numpy.typing.ArrayLike, *, "
                "levels: numpy.typing.ArrayLike | None = None, format: str = '', float32: bool = False, name: str = '', "
                "comment: str | collections.abc.Sequence[str] | None = None) -> None"),
        "path"_a.none(), "points"_a.none(), nb::kw_only(), "levels"_a = nb::none(), "format"_a.none() = "",
        "float32"_a.none() = false, "name"_a.none() = "", "comment"_a = nb::none(),
        R"(Writes point sets as the tool does with ``--output`` (and ``--format``).

``points``: shape (N, 2) or (K, N, 2); ``levels``: (N,) whole numbers for one set. The format is
``format`` ("text", "npy", "binary", "header", "csv") or the extension (.txt .dat .pts, .npy, .bpt,
.h .hpp, .csv; anything else is refused). A CSV has a header line ``x,y`` (``x,y,level``) and a
``# set k`` line before each set when there are several (``pandas.read_csv(path, comment='#')``).
``float32``: 4-byte values in npy and binary; ``name``: the C array of a header (default from the
file name); ``comment``: a str (one line) or a sequence of str (one line each) at the top (text,
CSV, header; refused for the others); a line break or other control character in one is written
escaped (\n, \xNN), as the tool writes one in a file name, so that a comment adds no point or code. In a text table, ``"domain periodic"`` or ``"domain
bounded"`` alone declares the domain, as the tool's header line does; a line that looks meant as
one but is not (``"domain: bounded"``, ``"Domain Bounded"``, ``"domain bounde"``), which
``load_table`` would refuse, raises pybluetile.Error naming it before anything is written.
Coordinates are written as given, outside [0, 1) too
(``tile``'s plane coordinates, as ``bluetile tile`` writes them); ``load_table`` places what it
reads on the unit torus, wrapping such coordinates, as ``bluetile relax -i`` does.
The file appears whole or not at all.)");

  m.def("load_table", &load_table,
        nb::sig("def load_table(path: str | os.PathLike[str], *, levels: bool = False) "
                "-> list[NDArray[numpy.float64]] | list[tuple[NDArray[numpy.float64], NDArray[numpy.int32] | None]]"),
        "path"_a.none(), nb::kw_only(), "levels"_a.none() = false,
        R"(Reads every set of a point file (text, with '#' lines between sets), an .npy file, a
binary point table (recognised by content) or a CSV (by its extension, .csv). Returns a list of
arrays of shape (N, 2), one per set; with ``levels=True`` a list of (points, levels) where levels is an (N,) int32 array or None.
A file with no points (empty, or comments only) raises pybluetile.Error '<path>: no points', as the
tool refuses it.)");
}

}  // namespace pybluetile
