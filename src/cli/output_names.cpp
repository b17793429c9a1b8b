#include "cli/output_names.h"

#include <algorithm>
#include <cassert>

#include "bluetile/core/error.h"

namespace bluetile::cli {

std::string_view output_format_label(OutputFormat format) {
  switch (format) {
    case OutputFormat::points_text: return "text points";
    case OutputFormat::points_npy: return "NumPy";
    case OutputFormat::points_binary: return "point table";
    case OutputFormat::points_header: return "C header";
    case OutputFormat::points_csv: return "CSV";
    case OutputFormat::raw_columns: return "raw float64 columns";
    case OutputFormat::svg: return "SVG";
    case OutputFormat::image: return "image";
    case OutputFormat::pdf: return "PDF";
    case OutputFormat::tile_set: return "tile set";
  }
  return "";
}

std::string_view binary_output_format(OutputFormat format) {
  switch (format) {
    case OutputFormat::points_npy: return binary_table_format(TableFormat::npy);
    case OutputFormat::points_binary: return binary_table_format(TableFormat::binary);
    case OutputFormat::raw_columns:
    case OutputFormat::image:
    case OutputFormat::pdf: return output_format_label(format);
    default: return "";
  }
}

std::span<const std::string_view> output_format_extensions(OutputFormat format) {
  static constexpr std::string_view raw_columns[] = {".bin"};
  static constexpr std::string_view svg[] = {".svg"};
  // The raster formats OpenImageIO writes that a drawing is wanted in; each is still checked
  // against the plugin (io/image_file.h) when the output is declared.
  static constexpr std::string_view image[] = {".png", ".tif", ".tiff", ".jpg", ".jpeg", ".exr", ".bmp"};
  static constexpr std::string_view pdf[] = {".pdf"};
  // README and docs name tile sets both ways.
  static constexpr std::string_view tile_set[] = {".tiles", ".txt"};
  switch (format) {
    case OutputFormat::points_text:
    case OutputFormat::points_npy:
    case OutputFormat::points_binary:
    case OutputFormat::points_header:
    case OutputFormat::points_csv: return table_format_extensions(table_format_of(format));
    case OutputFormat::raw_columns: return raw_columns;
    case OutputFormat::svg: return svg;
    case OutputFormat::image: return image;
    case OutputFormat::pdf: return pdf;
    case OutputFormat::tile_set: return tile_set;
  }
  return {};
}

OutputFormat output_format(std::string_view option, const std::string& path, std::span<const OutputFormat> accepted,
                           std::string_view alternative) {
  if (accepted.empty()) throw Error("internal: " + std::string(option) + " accepts no format");
  const std::string extension = path == "-" ? "" : file_extension(path);
  if (extension.empty()) return accepted.front();
  for (OutputFormat format : accepted) {
    const auto names = output_format_extensions(format);
    if (std::find(names.begin(), names.end(), extension) != names.end()) return format;
  }
  std::string list;
  for (OutputFormat format : accepted) {
    if (!list.empty()) list += ", ";
    bool first = true;
    for (std::string_view name : output_format_extensions(format)) {
      if (name.empty()) continue;
      list += first ? "" : " ";
      list += name;
      first = false;
    }
    list += " (" + std::string(output_format_label(format)) + ")";
  }
  std::string message = std::string(option) + " '" + path + "': this output writes " + list + ", not '" + extension + "'";
  if (!alternative.empty()) message += "; " + std::string(alternative);
  throw Error(message);
}

bool extension_names_a_format(const std::string& extension) {
  if (extension.empty()) return false;
  for (OutputFormat format : {OutputFormat::points_text, OutputFormat::points_npy, OutputFormat::points_binary,
                              OutputFormat::points_header, OutputFormat::points_csv, OutputFormat::raw_columns,
                              OutputFormat::svg, OutputFormat::image, OutputFormat::pdf, OutputFormat::tile_set}) {
    const auto names = output_format_extensions(format);
    if (std::find(names.begin(), names.end(), extension) != names.end()) return true;
  }
  return false;
}

void check_text_output_name(std::string_view option, const std::string& path, std::string_view what) {
  const std::string extension = path == "-" ? "" : file_extension(path);
  const auto text = output_format_extensions(OutputFormat::points_text);
  if (extension.empty() || std::find(text.begin(), text.end(), extension) != text.end()) return;
  for (OutputFormat format : {OutputFormat::points_npy, OutputFormat::points_binary, OutputFormat::points_header,
                              OutputFormat::raw_columns, OutputFormat::svg, OutputFormat::image, OutputFormat::pdf,
                              OutputFormat::tile_set}) {
    const auto names = output_format_extensions(format);
    if (std::find(names.begin(), names.end(), extension) != names.end())
      throw Error(std::string(option) + " '" + path + "': this output writes " + std::string(what) + ", not '" +
                  extension + "' (" + std::string(output_format_label(format)) + ")");
  }
}

TableFormat table_format_of(OutputFormat format) {
  switch (format) {
    case OutputFormat::points_npy: return TableFormat::npy;
    case OutputFormat::points_binary: return TableFormat::binary;
    case OutputFormat::points_header: return TableFormat::header;
    case OutputFormat::points_text: return TableFormat::text;
    case OutputFormat::points_csv: return TableFormat::csv;
    default: assert(false && "not a point-table format"); return TableFormat::text;
  }
}

OutputFormat output_format_of(TableFormat format) {
  switch (format) {
    case TableFormat::text: return OutputFormat::points_text;
    case TableFormat::npy: return OutputFormat::points_npy;
    case TableFormat::binary: return OutputFormat::points_binary;
    case TableFormat::header: return OutputFormat::points_header;
    case TableFormat::csv: return OutputFormat::points_csv;
  }
  return OutputFormat::points_text;
}

}  // namespace bluetile::cli
