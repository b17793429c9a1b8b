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

constexpr bluetile::TableFormat kFormats[] = {bluetile::TableFormat::text, bluetile::TableFormat::npy,
                                               bluetile::TableFormat::binary, bluetile::TableFormat::header};

// The library's table_format_for, with messages that name the argument `format` where the
// library's name the tool's --format.
bluetile::TableFormat table_format(const std::string& path, const std::string& format) {
  std::string names;
  for (bluetile::TableFormat f : kFormats) {
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
    for (bluetile::TableFormat f : kFormats) {
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
                const std::string& format, bool float32, const std::string& name,
                const std::vector<std::string>& comment) {
  const std::string path = path_text(path_arg, "path");
  PointSets input = point_sets(array_arg(points, "points", ArrayKind::points), "points");
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
  if (!comment.empty() && f != bluetile::TableFormat::text && f != bluetile::TableFormat::header)
    throw bluetile::Error("comment: " + is + "; comment lines are for text tables and C headers");
  nb::gil_scoped_release release;
  bluetile::TableWriteOptions options;
  options.float32 = float32;
  options.name = name;
  options.comment = comment;
  bluetile::write_output(path, [&](bluetile::OutputStream& out) {
    bluetile::write_point_table(f, sets, options, path, [&](std::string_view bytes) { out.write(bytes); });
  });
}

nb::list load_table(const PathArg& path_arg, bool levels) {
  const std::string path = path_text(path_arg, "path");
  std::vector<bluetile::PointSet> sets;
  {
    nb::gil_scoped_release release;
    sets = bluetile::read_point_table(path);
  }
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
  m.def("save_table", &save_table, "path"_a, "points"_a, nb::kw_only(), "levels"_a = nb::none(), "format"_a = "",
        "float32"_a = false, "name"_a = "", "comment"_a = std::vector<std::string>{},
        R"(Writes point sets as the tool does with ``--output`` (and ``--format``).

``points``: shape (N, 2) or (K, N, 2); ``levels``: (N,) whole numbers for one set. The format is
``format`` ("text", "npy", "binary", "header") or the extension (.txt .dat .pts, .npy, .bpt, .h
.hpp; anything else is refused). ``float32``: 4-byte values in npy and binary; ``name``: the C
array of a header (default from the file name); ``comment``: lines at the top (text, header; refused for the others).
The file appears whole or not at all.)");

  m.def("load_table", &load_table,
        nb::sig("def load_table(path: str | os.PathLike[str], *, levels: bool = False) "
                "-> list[NDArray[numpy.float64]] | list[tuple[NDArray[numpy.float64], NDArray[numpy.int32] | None]]"),
        "path"_a, nb::kw_only(), "levels"_a = false,
        R"(Reads every set of a point file (text, with '#' lines between sets), an .npy file or a
binary point table, recognised by content. Returns a list of arrays of shape (N, 2), one per set;
with ``levels=True`` a list of (points, levels) where levels is an (N,) int32 array or None.)");
}

}  // namespace pybluetile
