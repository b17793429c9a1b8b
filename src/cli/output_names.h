// The one rule every command's outputs follow (README, "Output names"): a file's extension (any
// case) picks its format among the formats that output can be written in; any other extension is
// refused before any work, with the option, the file and the accepted extensions. "-" (standard
// output) and a name without an extension (a device, /dev/stdout) take the output's first format.
// Point-table extensions are the library's (core/point_table.h).
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "bluetile/core/point_table.h"

namespace bluetile::cli {

enum class OutputFormat {
  points_text,    // point files (core/point_file.h)
  points_npy,     // sample tables (core/point_table.h)
  points_binary,  // .bpt
  points_header,  // C/C++ header
  points_csv,     // comma-separated values with a header line
  raw_columns,    // tile's raw float64 columns
  svg,            // an SVG drawing
  image,          // a raster image through OpenImageIO
  pdf,            // a PDF drawing through cairo
  tile_set,       // a tile-set file (tiling/tile_set.h)
};

// What a format is called in messages: "text points", "NumPy", ...
std::string_view output_format_label(OutputFormat format);

// OutputOptions::binary_format for an output in `format`: the words for binary bytes ("NumPy
// (.npy)", "image", "PDF"), which are refused on a terminal; "" for text (points, SVG, a header).
std::string_view binary_output_format(OutputFormat format);

// The extensions that name `format`, lower case with their dot, as file_extension gives them
// ("" stands for a name without one).
std::span<const std::string_view> output_format_extensions(OutputFormat format);

// The point-table formats, in the order a point output lists them (text first: "-" is text).
inline constexpr OutputFormat kPointTableFormats[] = {OutputFormat::points_text, OutputFormat::points_npy,
                                                      OutputFormat::points_binary, OutputFormat::points_header,
                                                      OutputFormat::points_csv};

// A table that is no point table (centroids' cx cy area): the point-table formats but binary,
// whose columns are x y or x y level (TableView::named_fields).
inline constexpr OutputFormat kNamedTableFormats[] = {OutputFormat::points_text, OutputFormat::points_npy,
                                                      OutputFormat::points_header, OutputFormat::points_csv};

// The format `path`, given to the output option `option`, is written in: the first of `accepted`
// whose extensions hold the path's; "-" and a name without an extension the first of `accepted`.
// Throws Error("<option> '<path>': ...") listing every accepted extension otherwise;
// `alternative` (e.g. "or say --format") ends that message when not empty.
OutputFormat output_format(std::string_view option, const std::string& path, std::span<const OutputFormat> accepted,
                           std::string_view alternative = {});

// Whether `extension` (as file_extension gives it; not "") names one of the formats above.
bool extension_names_a_format(const std::string& extension);

// For an output of one text format (a CSV log, psa's point text) that takes any other name:
// refuses an extension that names one of the formats above other than text points and CSV (.npy,
// .svg, .png, ...), which the file would not be, with "<option> '<path>': this output writes <what>, not
// '<extension>'".
void check_text_output_name(std::string_view option, const std::string& path, std::string_view what);

// The table format of a point-table output format (only those), and back.
TableFormat table_format_of(OutputFormat format);
OutputFormat output_format_of(TableFormat format);

}  // namespace bluetile::cli
