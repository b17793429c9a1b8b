// The point-set output of a command (relax, dart, progressive, centroids, stipple): --output (a
// '{}' in it, every occurrence, is the set index: one file per set), --format, --float32, --name.
// The names and formats are checked when the output is made, before any work; the format comes
// from --format or each file's extension (the output-name rule, cli/output_names.h), never
// silently text. The files are outputs of the command's OutputSet (core/output_file.h): checked
// when declared, published with the command's other outputs. '-' is standard output (text, or
// --format).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bluetile/core/output_file.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/point_table.h"

namespace bluetile::cli {

struct PointOutputOptions {
  std::string output;
  std::string format;  // empty: by extension
  bool float32 = false;
  std::string name;  // C header: the array's name
  // A table that is no point table (centroids' cx cy area): TableView::named_fields; its formats
  // are kNamedTableFormats (no binary), and --format binary is refused when declared. Set it
  // before add_point_output_options.
  bool named_fields = false;
};

// Adds -o/--output (required unless `required` is false), --format, --float32 and --name; `what`
// says what is written. `several_sets`: the command can write more than one set, so the help
// says what "{}" in the name does.
void add_point_output_options(CLI::App* command, PointOutputOptions& options, const std::string& what,
                              bool required = true, bool several_sets = true);

// The point sets of --input `path` (every format read_point_table reads), refused unless every
// set holds at least one point: `command` is named in the message ("relax needs ..."). `options`:
// read_point_table's (points wrapped onto the torus unless options.wrap is false).
std::vector<PointSet> read_input_sets(const std::string& path, const std::string& command,
                                      const ReadOptions& options = {});

// The up-front memory check of computing the cells of all `sets` with `engine` (relax_memory_bytes):
// "<command> of the N points of PATH needs about ...".
void check_cells_memory(const std::vector<PointSet>& sets, const std::string& engine, const std::string& command,
                        const std::string& path);

// The domain a point file's "# domain bounded" or "# domain periodic" line declares (point_file.h),
// if any; sets of `path` that declare different ones are refused.
std::optional<Boundary> declared_domain(const std::vector<PointSet>& sets, const std::string& path);

// `pattern` with every "{}" replaced by the set's index, zero-padded to the width of the last.
std::string set_file_name(const std::string& pattern, std::size_t set, std::size_t sets);

class PointOutput {
 public:
  // The file, or one file per set when the name holds "{}", for `sets` sets, declared in
  // `outputs` (which the caller publishes).
  PointOutput(OutputSet& outputs, const PointOutputOptions& options, std::size_t sets);

  // Writes point sets; `header`: comment lines at the top (text and C header).
  void write(std::span<const PointSet> sets, const std::vector<std::string>& header);
  // Writes any other table (text: '# set k' lines between sets when one file holds several).
  void write(const TableView& table, const std::vector<std::string>& header);

 private:
  void write_one(OutputFile& file, const TableView& table, std::span<const PointSet> point_sets,
                 const std::vector<std::string>& header);

  PointOutputOptions options_;
  std::size_t sets_;
  std::vector<OutputFile*> files_;
};

}  // namespace bluetile::cli
