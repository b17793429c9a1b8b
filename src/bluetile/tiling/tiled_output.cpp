#include "bluetile/tiling/tiled_output.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <locale>
#include <sstream>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace {

constexpr std::string_view kColumnNames[] = {"x", "y", "i", "j", "tile", "level", "rank"};
constexpr const char* kTileGridPrefix = "tile grid";

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// One chunk of a window's points: positions and ranks, and the cell each run of them came from.
struct Chunk {
  struct Cell {
    std::int64_t i, j;
    int tile;
    std::size_t begin;
  };
  std::vector<Point> positions;
  std::vector<std::uint32_t> ranks;
  std::vector<Cell> cells;

  void clear() {
    positions.clear();
    ranks.clear();
    cells.clear();
  }
  // The cell of point k (cells are in order of `begin`).
  const Cell& cell_of(std::size_t k) const {
    auto it = std::upper_bound(cells.begin(), cells.end(), k, [](std::size_t v, const Cell& c) { return v < c.begin; });
    return *(it - 1);
  }
};

// The value of column `c` for point k of the chunk, as a double (exact for the integers: cells are
// within 2^31 of the origin, ranks and levels far below 2^53).
struct ColumnValues {
  const Tiler& tiler;
  const Window& window;
  const TiledFormat& format;

  bool integer(TiledColumn c) const { return c != TiledColumn::x && c != TiledColumn::y; }
  // normalize: each axis over its own side (a square region, to rounding: tile --normalize).
  double coordinate(double v, double origin, double side) const { return format.normalize ? (v - origin) / side : v; }
  long long integer_value(TiledColumn c, const Chunk::Cell& cell, std::uint32_t rank) const {
    switch (c) {
      case TiledColumn::i: return cell.i;
      case TiledColumn::j: return cell.j;
      case TiledColumn::tile: return cell.tile;
      case TiledColumn::level: return tiler.ranked_levels(cell.tile)[rank];
      case TiledColumn::rank: return rank;
      default: return 0;
    }
  }
};

void format_text(const Chunk& chunk, std::size_t begin, std::size_t end, const ColumnValues& values, std::string& text) {
  text.clear();
  char line[40 * 7 + 8];
  const auto& columns = values.format.columns;
  const char separator = values.format.encoding == TiledFormat::Encoding::csv ? ',' : ' ';
  for (std::size_t k = begin; k < end; ++k) {
    const Chunk::Cell& cell = chunk.cell_of(k);
    char* at = line;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (c > 0) *at++ = separator;
      TiledColumn column = columns[c];
      if (column == TiledColumn::x || column == TiledColumn::y) {
        double v = column == TiledColumn::x ? values.coordinate(chunk.positions[k].x, values.window.x0, values.window.width())
                                            : values.coordinate(chunk.positions[k].y, values.window.y0, values.window.height());
        // %.17g, as point files are written (std::to_chars with a precision is printf's %g).
        at = std::to_chars(at, line + sizeof line, v, std::chars_format::general, 17).ptr;
      } else {
        at = std::to_chars(at, line + sizeof line, values.integer_value(column, cell, chunk.ranks[k])).ptr;
      }
    }
    *at++ = '\n';
    text.append(line, static_cast<std::size_t>(at - line));
  }
}

void format_binary(const Chunk& chunk, std::size_t begin, std::size_t end, const ColumnValues& values,
                   std::string& bytes) {
  static_assert(std::endian::native == std::endian::little, "binary point files are little-endian float64");
  const auto& columns = values.format.columns;
  bytes.resize((end - begin) * columns.size() * sizeof(double));
  char* at = bytes.data();
  for (std::size_t k = begin; k < end; ++k) {
    const Chunk::Cell& cell = chunk.cell_of(k);
    for (TiledColumn column : columns) {
      double v = column == TiledColumn::x   ? values.coordinate(chunk.positions[k].x, values.window.x0, values.window.width())
                 : column == TiledColumn::y ? values.coordinate(chunk.positions[k].y, values.window.y0, values.window.height())
                                            : static_cast<double>(values.integer_value(column, cell, chunk.ranks[k]));
      std::memcpy(at, &v, sizeof v);
      at += sizeof v;
    }
  }
}

}  // namespace

std::vector<TiledColumn> parse_tiled_columns(std::string_view list) {
  std::vector<TiledColumn> columns;
  std::size_t start = 0;
  while (start <= list.size()) {
    std::size_t comma = std::min(list.find(',', start), list.size());
    std::string_view name = list.substr(start, comma - start);
    auto found = std::find(std::begin(kColumnNames), std::end(kColumnNames), name);
    if (found == std::end(kColumnNames))
      throw Error("columns: unknown column '" + std::string(name) + "' (known: x, y, i, j, tile, level, rank)");
    auto column = static_cast<TiledColumn>(found - std::begin(kColumnNames));
    if (std::find(columns.begin(), columns.end(), column) != columns.end())
      throw Error("columns: column '" + std::string(name) + "' given twice");
    columns.push_back(column);
    start = comma + 1;
  }
  return columns;
}

std::string tiled_column_names(const std::vector<TiledColumn>& columns) {
  std::string names;
  for (TiledColumn c : columns) {
    if (!names.empty()) names += ' ';
    names += kColumnNames[static_cast<std::size_t>(c)];
  }
  return names;
}

StreamTimes stream_tiled_points(const Tiler& tiler, const Window& window, const Thinning* thinning,
                                const TiledFormat& format, OutputStream& out,
                                const std::function<void(std::int64_t, std::int64_t)>& progress,
                                std::size_t chunk_points) {
  using Clock = std::chrono::steady_clock;
  StreamTimes times;
  const CellRange range = tiler.cells(window);
  const ColumnValues values{tiler, window, format};
  const bool binary = format.encoding == TiledFormat::Encoding::binary;
  if (!binary) {
    std::string header;
    for (const std::string& line : format.header) header += "# " + comment_line(line) + "\n";
    if (format.encoding == TiledFormat::Encoding::csv) {
      std::string names = tiled_column_names(format.columns);
      std::replace(names.begin(), names.end(), ' ', ',');
      header += names + "\n";
    }
    out.write(header);
    times.bytes += header.size();
  }
  // One piece of text per thread and chunk: formatting is pure, so the bytes do not depend on
  // how many threads there are.
  const std::size_t parts = std::max<std::size_t>(1, thread_count());
  std::vector<std::string> texts(parts);
  Chunk chunk;
  chunk.positions.reserve(chunk_points + tiler.max_points_per_tile());
  chunk.ranks.reserve(chunk_points + tiler.max_points_per_tile());
  std::vector<Point> positions(tiler.max_points_per_tile());
  std::vector<std::uint32_t> ranks(tiler.max_points_per_tile());

  auto flush = [&] {
    if (chunk.positions.empty()) return;
    auto start = Clock::now();
    const std::size_t n = chunk.positions.size();
    parallel_for(parts, 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t p = begin; p < end; ++p) {
        std::size_t a = n * p / parts, b = n * (p + 1) / parts;
        if (binary)
          format_binary(chunk, a, b, values, texts[p]);
        else
          format_text(chunk, a, b, values, texts[p]);
      }
    });
    times.format += seconds_since(start);
    start = Clock::now();
    for (const std::string& text : texts) {
      out.write(text);
      times.bytes += text.size();
    }
    times.write += seconds_since(start);
    times.points += n;
    chunk.clear();
  };

  for (std::int64_t j = range.j0; j < range.j1; ++j) {
    auto start = Clock::now();
    for (std::int64_t i = range.i0; i < range.i1; ++i) {
      // Gathered per row of cells as they come; a chunk is flushed once it is full.
      CellPoints cell = tiler.cell_points(i, j, window, thinning, positions.data(), ranks.data());
      if (cell.positions.empty()) continue;
      chunk.cells.push_back({cell.i, cell.j, cell.tile, chunk.positions.size()});
      chunk.positions.insert(chunk.positions.end(), cell.positions.begin(), cell.positions.end());
      chunk.ranks.insert(chunk.ranks.end(), cell.ranks.begin(), cell.ranks.end());
      if (chunk.positions.size() >= chunk_points) {
        times.generate += seconds_since(start);
        flush();
        start = Clock::now();
      }
    }
    times.generate += seconds_since(start);
    if (progress) progress(j - range.j0 + 1, range.rows());
  }
  flush();
  return times;
}

std::string tile_grid_comment(const Tiler& tiler, const Window& window, bool normalize) {
  const double s = tiler.tile_size();
  double ox = 0.0, oy = 0.0, sx = s, sy = s;
  if (normalize) {
    // Cell edges at k S; in the file's coordinates (k S - x0) / width, (k S - y0) / height. The
    // origin is taken as the first edge at or left of the window, so its value stays small.
    const double w = window.width(), h = window.height();
    ox = (std::floor(window.x0 / s) * s - window.x0) / w;
    oy = (std::floor(window.y0 / s) * s - window.y0) / h;
    sx = s / w, sy = s / h;
  }
  const ClassicNumbers classic;
  char text[160];
  std::snprintf(text, sizeof text, "%s %.17g %.17g %.17g %.17g", kTileGridPrefix, ox, oy, sx, sy);
  return text;
}

std::optional<TileGrid> declared_tile_grid(const PointSet& set) {
  const std::string prefix = std::string(kTileGridPrefix) + " ";
  for (const std::string& comment : set.header) {
    const std::size_t start = comment.find_first_not_of(' ');
    if (start == std::string::npos || comment.compare(start, prefix.size(), prefix) != 0) continue;
    std::istringstream fields(comment.substr(start + prefix.size()));
    fields.imbue(std::locale::classic());
    TileGrid grid;
    if (fields >> grid.origin.x >> grid.origin.y >> grid.spacing.x >> grid.spacing.y && std::isfinite(grid.origin.x) &&
        std::isfinite(grid.origin.y) && grid.spacing.x > 0.0 && grid.spacing.y > 0.0 && std::isfinite(grid.spacing.x) &&
        std::isfinite(grid.spacing.y))
      return grid;
    return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace bluetile
