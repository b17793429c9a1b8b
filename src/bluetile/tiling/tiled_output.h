// Writing a tiled window as points: text point files or CSV streamed chunk by chunk (bounded
// memory whatever the window's size; formatting split across threads, chunks written in order)
// and a raw binary form. Drawings of the points are in tiled_drawing.h.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bluetile/core/output_file.h"
#include "bluetile/core/point_file.h"
#include "bluetile/tiling/density_thinning.h"
#include "bluetile/tiling/tiler.h"

namespace bluetile {

// What each output line holds, in order. x and y are the point's coordinates (plane units, or the
// window mapped onto [0,1)^2 with `normalize`), i and j its cell, tile the tile id.
enum class TiledColumn : std::uint8_t { x, y, i, j, tile, level, rank };

// Parses "x,y,level" (names as in TiledColumn, comma-separated, each at most once). Throws Error
// naming the unknown or repeated column.
std::vector<TiledColumn> parse_tiled_columns(std::string_view list);
std::string tiled_column_names(const std::vector<TiledColumn>& columns);

struct TiledFormat {
  std::vector<TiledColumn> columns{TiledColumn::x, TiledColumn::y};
  // Coordinates relative to the window, divided by its width (a square window becomes [0,1)^2,
  // the unit torus `analyze` reads).
  bool normalize = false;
  // text: point-file conventions (17 significant digits, blanks between values, `#` header
  // lines); csv: the same with ',' between values and a line of the column names after the
  // header; binary: raw little-endian float64 values, the columns of each point in order, no header.
  enum class Encoding { text, csv, binary } encoding = Encoding::text;
  std::vector<std::string> header;  // text and csv: written as "# " lines first
};

// Where a streamed write spent its time (seconds of wall time on the calling thread).
struct StreamTimes {
  double generate = 0.0;  // the tiler producing points
  double format = 0.0;    // text formatting (threads in parallel)
  double write = 0.0;     // handing bytes to the operating system
  std::size_t points = 0;
  std::size_t bytes = 0;
};

// Streams every kept point of `window` to `out` in the tiler's fixed order: straight into the
// output (a staged file, a device, a FIFO, standard output), never through a copy. Holds at most
// about `chunk_points` points and their text at a time. `progress(done_rows, total_rows)` is
// called after each row of cells when given. A failed write throws the stream's Error ("<path>:
// cannot write: ..."); the caller closes the stream.
StreamTimes stream_tiled_points(const Tiler& tiler, const Window& window, const Thinning* thinning,
                                const TiledFormat& format, OutputStream& out,
                                const std::function<void(std::int64_t, std::int64_t)>& progress = {},
                                std::size_t chunk_points = 1u << 18);

// The cell edges of a tiled window in a point file's coordinates: x = origin.x + k spacing.x,
// y = origin.y + k spacing.y for integers k.
struct TileGrid {
  Point origin{0.0, 0.0};
  Point spacing{1.0, 1.0};
};

// The header line (without "# ") that declares the grid: "tile grid OX OY SX SY".
std::string tile_grid_comment(const Tiler& tiler, const Window& window, bool normalize);
// The grid a set's header declares (the leading comment lines of a file `bluetile tile` wrote,
// PointSet::header), if it does; nullopt for any other set, or a grid line that is not one.
std::optional<TileGrid> declared_tile_grid(const PointSet& set);

}  // namespace bluetile
