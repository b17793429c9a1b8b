#include "cli/point_output.h"

#include <algorithm>

#include <sys/stat.h>

#include "bluetile/core/error.h"
#include "bluetile/core/memory_budget.h"
#include "bluetile/relax/lloyd.h"
#include "cli/file_options.h"
#include "cli/output_names.h"

namespace bluetile::cli {
namespace {

bool one_file_each(const std::string& output) { return output.find("{}") != std::string::npos; }

// --format, else the output-name rule (cli/output_names.h). The hint to say --format is for names
// no format owns (points.data); --format is refused for one another format owns (points.png).
TableFormat format_of(const std::string& path, const PointOutputOptions& options) {
  if (!options.format.empty()) return table_format_for(path, options.format);
  const bool owned = path != "-" && extension_names_a_format(file_extension(path));
  return table_format_of(output_format("--output", path, options.named_fields ? std::span<const OutputFormat>(kNamedTableFormats)
                                                                              : std::span<const OutputFormat>(kPointTableFormats),
                                       owned ? "" : "or say --format"));
}

// --format against the name: a file whose extension names another format would hold what its name
// denies (--format text -o f.npy wrote text into f.npy, which NumPy then refused). A name without
// an extension or with one no format has takes any format; so do "-" and special files (a FIFO,
// a device), which a name does not describe, and the generic .dat and .bin ("data", "binary"),
// which scripts give any table (every reader takes a table of any name by its content).
void check_format_agrees(const std::string& path, TableFormat format, const PointOutputOptions& options) {
  if (options.format.empty() || path == "-") return;
  struct stat status {};
  if (::stat(path.c_str(), &status) == 0 && !S_ISREG(status.st_mode)) return;
  const std::string extension = file_extension(path);
  if (extension.empty() || extension == ".dat" || extension == ".bin") return;
  for (OutputFormat named : {OutputFormat::points_text, OutputFormat::points_npy, OutputFormat::points_binary,
                             OutputFormat::points_header, OutputFormat::points_csv, OutputFormat::raw_columns,
                             OutputFormat::svg, OutputFormat::image, OutputFormat::pdf, OutputFormat::tile_set}) {
    const auto names = output_format_extensions(named);
    if (std::find(names.begin(), names.end(), extension) == names.end()) continue;
    if (named == output_format_of(format)) return;
    std::vector<std::string> fitting;  // ".txt, .dat, .pts or no extension"
    for (std::string_view name : table_format_extensions(format)) fitting.push_back(name.empty() ? "no extension" : std::string(name));
    std::string list;
    for (std::size_t i = 0; i < fitting.size(); ++i)
      list += (i == 0 ? "" : i + 1 == fitting.size() ? " or " : ", ") + fitting[i];
    throw Error("--format " + options.format + ": --output '" + path + "' is named as " +
                std::string(output_format_label(named)) + " ('" + extension + "'); give it " + list + " for " +
                options.format + ", or leave --format out");
  }
}

// --float32 and --name change only some formats; given for another, they would be ignored without
// a word, so they are refused before any work.
void check_format_options(const std::string& path, TableFormat format, const PointOutputOptions& options) {
  check_format_agrees(path, format, options);
  const std::string is = "--output '" + path + "' is " + std::string(table_format_name(format));
  if (options.float32 && format != TableFormat::npy && format != TableFormat::binary)
    throw Error("--float32: " + is + "; 4-byte floats are for npy and binary outputs");
  if (!options.name.empty() && format != TableFormat::header)
    throw Error("--name '" + options.name + "': " + is + "; the array name is for header outputs (.h, .hpp)");
  if (format == TableFormat::header) checked_table_name(path, options.name);
  if (format == TableFormat::binary && options.named_fields)
    throw Error("--format binary: a bluetile point table (.bpt) holds x y or x y level, which this table is not; "
                "write npy (a field per column), text or header");
}

// A file of one set, of several written one file each, says which it holds: the header
// describes the whole run ("3 sets of 16 points, seed 5 + set index").
std::vector<std::string> with_set_line(std::vector<std::string> header, std::size_t set, std::size_t sets) {
  header.insert(header.begin() + (header.empty() ? 0 : 1),
                "this file: set " + std::to_string(set) + " of " + std::to_string(sets));
  return header;
}

// One set of a table, as its own table.
TableView single_set(const TableView& table, std::size_t set) {
  TableView one = table;
  one.sets = 1;
  one.rows = [rows = table.rows, set](std::size_t) { return rows(set); };
  one.value = [value = table.value, set](std::size_t, std::size_t i, std::size_t c) { return value(set, i, c); };
  return one;
}

}  // namespace

void add_point_output_options(CLI::App* command, PointOutputOptions& options, const std::string& what, bool required,
                              bool several_sets) {
  const std::span<const OutputFormat> formats =
      options.named_fields ? std::span<const OutputFormat>(kNamedTableFormats) : std::span<const OutputFormat>(kPointTableFormats);
  CLI::Option* output = add_output_option(
      command, "-o,--output", options.output, {.formats = formats, .standard_output = true},
      several_sets ? what + " (every {} becomes the set index: one file per set)" : what);
  if (required) output->required();
  command->add_option("--format", options.format,
                      "text, npy (shape K x N x 2, or K x N x 3 with a level column), binary (.bpt, see README), header (C/C++) "
                      "or csv (a header line x,y or x,y,level); default: by the extension (.txt .dat .pts, .npy, .bpt, .h .hpp, .csv)")
      ->check(CLI::IsMember({"text", "npy", "binary", "header", "csv"}));
  command->add_flag("--float32", options.float32, "npy and binary: 4-byte floats instead of 8");
  command->add_option("--name", options.name, "header: the array's name (default: from the file name)");
}

std::string set_file_name(const std::string& pattern, std::size_t set, std::size_t sets) {
  std::string index = std::to_string(set);
  std::string width = std::to_string(sets - 1);
  index.insert(0, width.size() - index.size(), '0');
  std::string name = pattern;
  for (std::size_t at = name.find("{}"); at != std::string::npos; at = name.find("{}", at + index.size()))
    name.replace(at, 2, index);
  return name;
}

PointOutput::PointOutput(OutputSet& outputs, const PointOutputOptions& options, std::size_t sets)
    : options_(options), sets_(sets) {
  if (one_file_each(options.output)) {
    for (std::size_t k = 0; k < sets; ++k) {
      const std::string path = set_file_name(options.output, k, sets);
      // An unknown extension, or a header's array name that is no C name, is refused before any work.
      check_format_options(path, format_of(path, options), options);
      files_.push_back(&outputs.add(path));
    }
    return;
  }
  TableFormat format = format_of(options.output, options);
  check_format_options(options.output, format, options);
  if (format == TableFormat::text && sets > 1 && options.output.find('#') != std::string::npos)
    throw Error("--output '" + options.output + "': file names with '#' cannot hold several sets");
  // npy and .bpt are refused on a terminal (--format npy -o - in an interactive shell).
  files_.push_back(&outputs.add(options.output, {.allow_stdout = true, .binary_format = binary_table_format(format)}));
}

void PointOutput::write(std::span<const PointSet> sets, const std::vector<std::string>& header) {
  if (sets.size() != sets_) throw Error("internal: " + std::to_string(sets.size()) + " sets for " + std::to_string(sets_) + " outputs");
  const TableView table = point_sets_table(sets);
  if (files_.size() == 1) {
    write_one(*files_[0], table, sets, header);
    return;
  }
  for (std::size_t k = 0; k < sets.size(); ++k)
    write_one(*files_[k], single_set(table, k), sets.subspan(k, 1), with_set_line(header, k, sets.size()));
}

void PointOutput::write(const TableView& table, const std::vector<std::string>& header) {
  if (files_.size() == 1) {
    write_one(*files_[0], table, {}, header);
    return;
  }
  for (std::size_t k = 0; k < table.sets; ++k)
    write_one(*files_[k], single_set(table, k), {}, with_set_line(header, k, table.sets));
}

void PointOutput::write_one(OutputFile& file, const TableView& table, std::span<const PointSet> point_sets,
                            const std::vector<std::string>& header) {
  const TableFormat format = format_of(file.path(), options_);
  TableWriteOptions w;
  w.float32 = options_.float32;
  w.name = options_.name;
  w.comment = header;
  file.write([&](OutputStream& out) {
    const ByteSink sink = [&out](std::string_view bytes) { out.write(bytes); };
    if (!point_sets.empty()) {
      write_point_table(format, point_sets, w, file.path(), sink);
    } else if (format != TableFormat::text) {
      write_table(format, table, w, file.path(), sink);
    } else {
      sink(format_points(PointSet{}, header));
      write_text_table(table, file.path(), sink);
    }
  });
}

std::optional<Boundary> declared_domain(const std::vector<PointSet>& sets, const std::string& path) {
  std::optional<Boundary> declared;
  for (const PointSet& set : sets) {
    if (declared && set.declared_boundary && *set.declared_boundary != *declared)
      throw Error(input_name(path) + ": its sets declare both '# domain bounded' and '# domain periodic'");
    if (set.declared_boundary) declared = set.declared_boundary;
  }
  return declared;
}

void check_cells_memory(const std::vector<PointSet>& sets, const std::string& engine, const std::string& command,
                        const std::string& path) {
  std::size_t n = 0;
  for (const PointSet& set : sets) n += set.points.size();
  check_memory(relax_memory_bytes(static_cast<double>(n), engine),
               command + " of the " + std::to_string(n) + " points of " + input_name(path));
}

std::vector<PointSet> read_input_sets(const std::string& path, const std::string& command, const ReadOptions& options) {
  std::vector<PointSet> sets = read_point_table(path, options);
  if (sets.empty()) throw Error(input_name(path) + ": no points");
  for (std::size_t k = 0; k < sets.size(); ++k) {
    if (!sets[k].points.empty()) continue;
    const std::string which = sets.size() == 1 ? "" : " (set " + std::to_string(k) + " of " + std::to_string(sets.size()) + ")";
    throw Error(input_name(path) + which + ": 0 points; " + command + " needs at least 1 point per set");
  }
  return sets;
}

}  // namespace bluetile::cli
