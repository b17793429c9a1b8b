// wang_tiles, tile_set and tile: Wang-tile sample sets (Hiller, Deussen, Keller 2001, section 3)
// and windows of the aperiodic plane they tile. A tile set travels as the text of its file
// (the format `bluetile wang` writes and `bluetile tile --tiles` reads), so that a set made here
// and one made by the tool are the same thing; tile_set() opens it into arrays.
#include <cmath>
#include <optional>

#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>

#include "arguments.h"
#include "arrays.h"
#include "bindings.h"
#include "engines.h"
#include "bluetile/core/error.h"
#include "bluetile/core/memory_budget.h"
#include "bluetile/core/text.h"
#include "bluetile/relax/wang_relax.h"
#include "bluetile/tiling/default_tile_set.h"
#include "bluetile/tiling/density_thinning.h"
#include "bluetile/tiling/tile_set.h"
#include "bluetile/tiling/tile_set_file.h"
#include "bluetile/tiling/tiler.h"
#include "bluetile/tiling/tiling_plan.h"

namespace pybluetile {

using namespace nb::literals;

namespace {

// The text of a file starts with its version line.
constexpr std::string_view kTileSetMagic = "# bluetile tiles";

struct TileSource {
  std::optional<std::string> text, path;  // neither: the set built into the library
};

// A tile set's text, not a path: it has a line break (a set of one line holds no tile, and no
// path has one) or starts with the version line after spaces and a UTF-8 byte-order mark (which
// the parser skips, or refuses by line number: a message quoting kilobytes of text as a file name
// that is too long helps no one).
bool is_tile_set_text(std::string_view s) {
  if (s.find_first_of("\n\r") != std::string_view::npos) return true;
  if (s.starts_with("\xEF\xBB\xBF")) s.remove_prefix(3);
  const std::size_t start = s.find_first_not_of(" \t\f\v");
  return start != std::string_view::npos && s.substr(start).starts_with(kTileSetMagic);
}

// A str or bytes argument is the text of a file by is_tile_set_text, else a path, as an
// os.PathLike is.
TileSource tile_source(const std::optional<PathArg>& tiles) {
  if (!tiles) return {};
  PyObject* p = tiles->ptr();
  if (PyBytes_Check(p)) {
    const std::string_view bytes(PyBytes_AS_STRING(p), static_cast<std::size_t>(PyBytes_GET_SIZE(p)));
    if (is_tile_set_text(bytes)) return {std::string(bytes), {}};
  } else if (PyUnicode_Check(p)) {
    Py_ssize_t size = 0;
    const char* utf8 = PyUnicode_AsUTF8AndSize(p, &size);
    if (!utf8) {
      PyErr_Clear();  // not a file's text (a lone surrogate of an undecodable name): a path
    } else {
      const std::string_view text(utf8, static_cast<std::size_t>(size));
      if (is_tile_set_text(text)) return {std::string(text), {}};
    }
  }
  return {{}, path_text(*tiles, "tiles")};
}

bluetile::TileSet load_tile_set(const TileSource& tiles) {
  if (tiles.text) return bluetile::parse_tile_set(*tiles.text, "tiles");
  if (tiles.path) return bluetile::read_tile_set(*tiles.path);
  return bluetile::default_tile_set();
}

std::string wang_tiles(const Text& set_arg, const Whole& points_arg, const Whole& iterations_arg, const Whole& warm_arg,
                       const Whole& levels_arg, const Real& ratio_arg, const Text& strategy_arg, const Whole& period_arg,
                       const Real& margin_arg, const Whole& lattice_steps_arg,
                       const Whole& lattice_steps_per_iteration_arg, const Real& lattice_step_arg,
                       const Whole& seam_steps_arg, const Real& seam_spacing_arg, const Real& level_seam_spacing_arg,
                       const Text& rank_order_arg, const Real& void_sigma_arg, const Whole& filled_lattice_steps_arg,
                       const Real& filled_lattice_spacing_arg, const Whole& filled_lattice_up_to_arg,
                       const Whole& seed_arg, const Text& engine_arg) {
  // None: the default, the library's (WangOptions).
  const bluetile::WangOptions d;
  const std::string set = text_or(set_arg, std::string(bluetile::tile_set_kind_name(d.kind)), "set");
  const auto kind = bluetile::parse_tile_set_kind(set);
  if (!kind) throw nb::value_error(("set: expected one of " + bluetile::tile_set_kind_list() + ", got '" + set + "'").c_str());
  // The library's ranges (bluetile::validate(WangOptions) checks them again), here so that a
  // value past the library's types gets the same message.
  const auto points = whole_or<std::size_t>(points_arg, d.points, "points", 1, bluetile::kMaxWangPoints);
  const int iterations = whole_or<int>(iterations_arg, d.level.iterations, "iterations", 0, bluetile::kMaxWangIterations);
  const int warm = whole_or<int>(warm_arg, d.level.warm_iterations, "warm", 0, bluetile::kMaxWangIterations);
  const int levels = whole_or<int>(levels_arg, d.levels, "levels", 1, bluetile::kMaxWangLevels);
  const int period = whole_or<int>(period_arg, d.level.period, "period", bluetile::kMinWangPeriod, bluetile::kMaxWangPeriod);
  const int lattice_steps =
      whole_or<int>(lattice_steps_arg, d.level.refine.lattice_iterations, "lattice_steps", 0, bluetile::kMaxLatticeSteps);
  const int lattice_steps_per_iteration =
      whole_or<int>(lattice_steps_per_iteration_arg, d.level.refine.lattice_steps_per_iteration,
                    "lattice_steps_per_iteration", 0, bluetile::kMaxLatticeStepsPerIteration);
  const int seam_steps =
      whole_or<int>(seam_steps_arg, d.level.refine.seam_iterations, "seam_steps", 0, bluetile::kMaxSeamSteps);
  const int filled_lattice_steps = whole_or<int>(filled_lattice_steps_arg, d.level.refine.filled_lattice_steps,
                                                 "filled_lattice_steps", 0, bluetile::kMaxLatticeSteps);
  const auto filled_lattice_up_to = whole_or<std::size_t>(filled_lattice_up_to_arg, d.level.refine.filled_lattice_up_to,
                                                          "filled_lattice_up_to", 1, bluetile::kMaxWangPoints);
  const std::uint64_t seed = seed_or(seed_arg, d.seed);
  const double ratio = real_or(ratio_arg, d.ratio, "ratio"), margin = real_or(margin_arg, d.level.edge_margin, "margin");
  const double lattice_step = real_or(lattice_step_arg, d.level.refine.lattice_step, "lattice_step");
  const double seam_spacing = real_or(seam_spacing_arg, d.level.refine.seam_spacing, "seam_spacing");
  const double level_seam_spacing =
      real_or(level_seam_spacing_arg, d.level.refine.later_seam_spacing, "level_seam_spacing");
  const double filled_lattice_spacing =
      real_or(filled_lattice_spacing_arg, d.level.refine.filled_lattice_spacing, "filled_lattice_spacing");
  const double void_sigma = real_or(void_sigma_arg, d.level.void_sigma, "void_sigma");
  const std::string strategy = text_or(strategy_arg, "auto", "strategy");
  const std::string rank_order =
      text_or(rank_order_arg, bluetile::wang_rank_order_name(d.level.rank_order), "rank_order");
  const std::string engine = text_or(engine_arg, "exact", "engine");
  EngineChoice choice;
  choice.engine = engine;
  check_engine_choice(choice);

  bluetile::WangOptions w;
  w.kind = *kind;
  w.points = points;
  w.levels = levels;
  w.ratio = ratio;
  w.seed = seed;
  w.level.iterations = iterations;
  w.level.warm_iterations = warm;
  w.level.strategy = bluetile::parse_wang_strategy(strategy, *kind);
  w.level.period = period;
  w.level.edge_margin = margin;
  w.level.refine = {.lattice_steps_per_iteration = lattice_steps_per_iteration,
                    .lattice_iterations = lattice_steps,
                    .lattice_step = lattice_step,
                    .seam_iterations = seam_steps,
                    .seam_spacing = seam_spacing,
                    .later_seam_spacing = level_seam_spacing,
                    .filled_lattice_steps = filled_lattice_steps,
                    .filled_lattice_spacing = filled_lattice_spacing,
                    .filled_lattice_up_to = filled_lattice_up_to};
  w.level.rank_order = bluetile::parse_wang_rank_order(rank_order);
  w.level.void_sigma = void_sigma;
  // validate() writes the limit as "1e+08"; here as it is typed.
  if (!(ratio > 1.0 && ratio <= bluetile::kMaxWangRatio))
    throw bluetile::Error("ratio: expected above 1 to " + bluetile::number_text(bluetile::kMaxWangRatio) + ", got " +
                          bluetile::number_text(ratio));
  bluetile::validate(w);
  // As the tool's wang: a setting this call would not use (bluetile::wang_setting_used) is refused
  // where it differs from its default (the tool refuses it given at all; a default cannot be told
  // from one given here): what makes a call use it, and this call's arguments it depends on.
  const auto real = [](double v) { return bluetile::shortest_text(v); };
  const std::string levels_text = "levels=" + std::to_string(levels), order_text = "rank_order='" + rank_order + "'";
  const std::string seams_text = "seam_steps=" + std::to_string(seam_steps);
  std::string strategy_text = "strategy='" + strategy + "'";
  if (strategy == "auto") strategy_text += ", " + std::string(bluetile::wang_strategy_name(w.level.strategy)) + " for " + set;
  const std::string filled_steps = "rank_order='fill', levels=2 or more and filled_lattice_steps above 0";
  const std::string filled_call = order_text + ", " + levels_text + ", filled_lattice_steps=" + std::to_string(filled_lattice_steps);
  const bluetile::WangRefinement& r = d.level.refine;
  struct Rule {
    const char* setting;
    bool differs;
    std::string value, needs, this_call;
  };
  const Rule rules[] = {
      {"ratio", ratio != d.ratio, real(ratio), "levels=2 or more", levels_text},
      {"period", period != d.level.period, std::to_string(period), "strategy='instances'", strategy_text},
      {"void_sigma", void_sigma != d.level.void_sigma, real(void_sigma), "rank_order='voids'", order_text},
      {"lattice_step", lattice_step != r.lattice_step, real(lattice_step),
       "lattice_steps or lattice_steps_per_iteration above 0",
       "lattice_steps=" + std::to_string(lattice_steps) +
           ", lattice_steps_per_iteration=" + std::to_string(lattice_steps_per_iteration)},
      {"seam_spacing", seam_spacing != r.seam_spacing, real(seam_spacing), "seam_steps above 0", seams_text},
      {"level_seam_spacing", level_seam_spacing != r.later_seam_spacing, real(level_seam_spacing),
       "seam_steps above 0, levels=2 or more and rank_order='farthest' or 'voids', whose later levels are relaxed, "
       "not filled",
       seams_text + ", " + levels_text + ", " + order_text},
      {"filled_lattice_steps", filled_lattice_steps != r.filled_lattice_steps, std::to_string(filled_lattice_steps),
       "rank_order='fill' and levels=2 or more", order_text + ", " + levels_text},
      {"filled_lattice_spacing", filled_lattice_spacing != r.filled_lattice_spacing, real(filled_lattice_spacing),
       filled_steps, filled_call},
      {"filled_lattice_up_to", filled_lattice_up_to != r.filled_lattice_up_to, std::to_string(filled_lattice_up_to),
       filled_steps, filled_call},
  };
  for (const Rule& rule : rules)
    if (rule.differs && !bluetile::wang_setting_used(w, rule.setting))
      throw bluetile::Error(std::string(rule.setting) + "=" + rule.value + ": only with " + rule.needs + " (this call: " +
                            rule.this_call + ")");
  std::string text;
  {
    nb::gil_scoped_release release;
    SignalChecks signal_checks;  // Ctrl-C inside the loops
    auto e = make_engine(choice);
    w.level.on_iteration = [](const bluetile::WangIteration&) { raise_pending_signals(); };
    w.level.fill.on_round = [](std::size_t, std::size_t) { raise_pending_signals(); };
    w.level.on_filled_lattice_step = [](int, int) { raise_pending_signals(); };
    bluetile::TileSet tiles;
    try {
      tiles = bluetile::relax_wang_tiles(*e, w);
    } catch (const bluetile::Error& error) {
      // The library's message names neither the argument nor what to do. No count is a minimum:
      // whether a cell outgrows its block depends on the set and the random start (seed 1, the
      // other defaults: wang8 fails with 1, 3 and 4 points and works with 2 and 5 to 16;
      // corner16 fails with 8, 9, and 12 at seed 3; wang16 with 10 at seeds 2 to 5).
      std::string_view message = error.what();
      if (message.find("reaches beyond its 3x3 block") == std::string_view::npos) throw;
      message = message.substr(0, message.find(": too few points per tile"));  // said again, by name
      throw bluetile::Error("points=" + std::to_string(points) + ": too few points per tile for this set and seed: " +
                            std::string(message) + "; give more points (the default is " + std::to_string(d.points) +
                            "; how few work depends on the set and the seed)");
    }
    tiles.header.push_back("made by: pybluetile.wang_tiles(set='" + set + "', points=" + std::to_string(points) +
                           ", iterations=" + std::to_string(iterations) + ", warm=" + std::to_string(warm) +
                           ", levels=" + std::to_string(levels) + ", strategy='" +
                           std::string(bluetile::wang_strategy_name(w.level.strategy)) +
                           "', lattice_steps=" + std::to_string(lattice_steps) +
                           ", lattice_steps_per_iteration=" + std::to_string(lattice_steps_per_iteration) + ", seam_steps=" + std::to_string(seam_steps) + ", rank_order='" + rank_order + "'" +
                           (w.level.rank_order == bluetile::RankOrder::fill && levels > 1
                                ? ", filled_lattice_steps=" + std::to_string(filled_lattice_steps)
                                : std::string()) +
                           ", seed=" + std::to_string(seed) + ", engine='" + engine + "')");
    text = bluetile::format_tile_set(tiles);
  }
  return text;
}

nb::dict tile_set(const std::optional<PathArg>& tiles) {
  const bluetile::TileSet set = load_tile_set(tile_source(tiles));
  nb::list list;
  for (std::size_t id = 0; id < set.tiles.size(); ++id) {
    const bluetile::Tile& t = set.tiles[id];
    const std::size_t n = t.points.size();
    std::vector<double> xy;
    xy.reserve(2 * n);
    for (const bluetile::Point& p : t.points) xy.insert(xy.end(), {p.x, p.y});
    nb::dict d;
    d["id"] = id;
    d["colours"] = nb::make_tuple(int{t.colours[0]}, int{t.colours[1]}, int{t.colours[2]}, int{t.colours[3]});
    d["points"] = to_numpy(std::move(xy), {n, 2});
    d["levels"] = to_numpy(std::vector<std::int32_t>(t.levels.begin(), t.levels.end()), {n});
    d["ranks"] = to_numpy(std::vector<std::uint32_t>(t.ranks), {n});
    list.append(d);
  }
  nb::dict out;
  out["kind"] = std::string(bluetile::tile_set_kind_name(set.kind));
  out["tiles"] = list;
  return out;
}

// The region argument: read with window_of().
class RegionArg : public nb::object {
  NB_OBJECT_DEFAULT(RegionArg, nb::object, "tuple[float, float, float, float]", detail::any_object)
};

// (x0, y0, x1, y1): a tuple (or another sequence) of 4 numbers; TypeError naming `region` else.
bluetile::Window window_of(const RegionArg& region) {
  PyObject* r = region.ptr();
  const std::string expected = "region: expected a tuple of 4 numbers (x0, y0, x1, y1), got ";
  if (region.is_none()) throw nb::type_error((expected + "None").c_str());
  if (!PySequence_Check(r) || PyUnicode_Check(r) || PyBytes_Check(r) || PyByteArray_Check(r))
    throw nb::type_error((expected + nb::type_name(region.type()).c_str()).c_str());
  const Py_ssize_t size = PySequence_Size(r);
  if (size < 0) throw nb::python_error();
  if (size != 4) throw nb::type_error((expected + std::to_string(size) + " values").c_str());
  double v[4];
  for (Py_ssize_t i = 0; i < 4; ++i) {
    const nb::object item = nb::steal(PySequence_GetItem(r, i));
    if (!item.is_valid()) throw nb::python_error();
    const std::string name = "region[" + std::to_string(i) + "]";
    if (item.is_none()) throw nb::type_error((name + ": expected a number (int or float), got None").c_str());
    v[i] = real_or(nb::borrow<Real>(item), 0.0, name.c_str());
  }
  return {v[0], v[1], v[2], v[3]};
}

// The module's names for a request's fields, in the library's messages.
constexpr bluetile::TilingNames kArgumentNames{"tile_size", "density", "max_density", "count", "density_map", "="};

nb::object tile(const RegionArg& region, const std::optional<PathArg>& tiles_arg, const Real& tile_size,
                const Real& density, const Whole& seed, std::optional<ArrayArg> density_map, const Real& max_density,
                const Real& count, const Text& fit_arg, const Flag& columns_arg) {
  const bluetile::Window window = window_of(region);
  const TileSource tiles = tile_source(tiles_arg);
  // The request as `bluetile tile` reads it (tiling/tiling_plan.h); bad values raise
  // pybluetile.Error (a ValueError) naming them.
  const auto [x0, y0, x1, y1] = window;
  bluetile::TilingRequest request;
  request.window = window;
  request.tile_size = real_or(tile_size, request.tile_size, "tile_size");
  request.density = real_or(density, request.density, "density");
  request.max_density = real_or(max_density, request.max_density, "max_density");
  request.count = real_or(count, request.count, "count");
  request.seed = seed_or(seed, request.seed);
  const std::string fit = text_or(fit_arg, "contain", "fit");
  const bool columns = flag_or(columns_arg, false, "columns");
  request.fit = bluetile::parse_map_fit(fit);
  // As the tool's --fit without --density-map: refused, not ignored.
  if (!density_map && fit != "contain") throw nb::value_error(("fit='" + fit + "' places a density_map: give one").c_str());
  bluetile::check_tiling_request(request, density_map.has_value(), kArgumentNames);
  std::optional<bluetile::DensityGrid> map;
  if (density_map) map = density_grid(array_arg(*density_map, "density_map", ArrayKind::density), "density_map");

  std::vector<bluetile::TiledPoint> points;
  {
    nb::gil_scoped_release release;
    SignalChecks signal_checks;  // Ctrl-C inside the loops
    bluetile::TilingPlan plan =
        bluetile::plan_tiling(load_tile_set(tiles), map ? &*map : nullptr, request, kArgumentNames);
    bluetile::check_tiling_size(plan, "region", "tile_size");  // as the tool: refused, not a MemoryError
    // The tool streams its points; here they are held: the tiler's (with the slack of a growing
    // vector), the (M, 2) array and with `columns` i, j, tile, level and rank.
    const double points_held = plan.window.area() * plan.mean_density;
    const double bytes_per_point = 2.0 * sizeof(bluetile::TiledPoint) + 16.0 + (columns ? 28.0 : 0.0);
    bluetile::check_memory(points_held * bytes_per_point,
                           "region " + bluetile::number_text(x0) + " " + bluetile::number_text(y0) + " " +
                               bluetile::number_text(x1) + " " + bluetile::number_text(y1) + " of about " +
                               bluetile::count_text(points_held) + " points");
    points = plan.tiler->tiled_points(plan.window, plan.thinning.get());
  }
  const std::size_t n = points.size();
  std::vector<double> xy;
  xy.reserve(2 * n);
  for (const bluetile::TiledPoint& p : points) xy.insert(xy.end(), {p.position.x, p.position.y});
  nb::object array = nb::cast(to_numpy(std::move(xy), {n, 2}));
  if (!columns) return array;
  std::vector<std::int64_t> i(n), j(n);
  std::vector<std::int32_t> tile_id(n), level(n);
  std::vector<std::uint32_t> rank(n);
  for (std::size_t k = 0; k < n; ++k) {
    i[k] = points[k].i;
    j[k] = points[k].j;
    tile_id[k] = points[k].tile;
    level[k] = points[k].level;
    rank[k] = points[k].rank;
  }
  nb::dict d;
  d["points"] = array;
  d["i"] = to_numpy(std::move(i), {n});
  d["j"] = to_numpy(std::move(j), {n});
  d["tile"] = to_numpy(std::move(tile_id), {n});
  d["level"] = to_numpy(std::move(level), {n});
  d["rank"] = to_numpy(std::move(rank), {n});
  return d;
}

}  // namespace

void bind_tiling(nb::module_& m) {
  m.def("wang_tiles", &wang_tiles,
        nb::sig("def wang_tiles(set: str = 'wang8', *, points: int = 52, iterations: int = 100, warm: int = 10, "
                "levels: int = 1, ratio: float = 2.0, strategy: str = 'auto', period: int = 16, margin: float = 0.0, "
                "lattice_steps: int = 5, lattice_steps_per_iteration: int = 3, lattice_step: float = 0.005, seam_steps: int = 20, seam_spacing: float = 0.8, level_seam_spacing: float = 0.65, "
                "rank_order: str = 'fill', void_sigma: float = 0.5, filled_lattice_steps: int = 150, "
                "filled_lattice_spacing: float = 0.62, filled_lattice_up_to: int = 128, seed: int = 1, "
                "engine: str = 'exact') -> str"),
        "set"_a.none() = "wang8", nb::kw_only(), "points"_a.none() = 52, "iterations"_a.none() = 100, "warm"_a.none() = 10, "levels"_a.none() = 1,
        "ratio"_a.none() = 2.0, "strategy"_a.none() = "auto", "period"_a.none() = 16, "margin"_a.none() = 0.0, "lattice_steps"_a.none() = 5, "lattice_steps_per_iteration"_a.none() = 3, "lattice_step"_a.none() = 0.005, "seam_steps"_a.none() = 20,
        "seam_spacing"_a.none() = 0.8, "level_seam_spacing"_a.none() = 0.65, "rank_order"_a.none() = "fill", "void_sigma"_a.none() = 0.5,
        "filled_lattice_steps"_a.none() = 150, "filled_lattice_spacing"_a.none() = 0.62, "filled_lattice_up_to"_a.none() = 128,
        "seed"_a.none() = 1, "engine"_a.none() = "exact",
        R"(A Wang-tile sample set relaxed as ``bluetile wang`` relaxes it (the same options, the same
points bit for bit), returned as the text of its tile-set file: write it to a file for
``bluetile tile --tiles``, or pass it to ``tile_set`` and ``tile``. The paper's section 3: every
tile's points are relaxed by Lloyd's method under the constraints of the tiles that can border it.
None for any argument means its default. Each argument is the tool's option of the same name
(``--lattice-steps`` for lattice_steps). A setting the call would not use (ratio with one level,
period without "instances", void_sigma without "voids", level_seam_spacing where the fill order
fills the later levels, ...) is refused where it differs from its default, as the tool refuses it.

set: the tile set, "wang8" (the paper's: 8 tiles, 2 colours per edge), "wang16" (every edge
    combination), "corner16" (corner colours) or "corner81" (3 corner colours: 81 tiles).
points: points per tile in level 0, 1 to 1000000 (default 52). Few points make large cells, and a
    run in which a cell reaches beyond the 3x3 block of tiles around it is refused, naming
    ``points``; how few points work depends on the set and the seed (wang8 with seed 1: 2, and 5
    and up; some corner16 and wang16 runs of 10 to 12 fail).
iterations: constrained Lloyd iterations per level, 0 to 100000000 (default 100).
warm: periodic iterations of each tile alone before them, 0 to 100000000 (default 10).
levels: levels of a hierarchical set that tiles, 1 to 32 (default 1).
ratio: each level after the first brings a tile's count to round(ratio x count), above 1 up to
    100000000 (default 2).
strategy: the neighbour configurations each point is relaxed in: "exact" (every admissible 3x3
    block), "instances" (random torus tilings of period x period tiles), "rounds" (one block per
    fitting neighbour) or "auto" (the default: exact, instances for corner81).
period: instances: the torus tiling's side in tiles, 2 to 1024 (default 16).
margin: keeps points this far inside their tile, 0 to 0.25 tile units (default 0).
lattice_steps: lattice decorrelation steps after each level's iterations, which lower the
    tile-lattice peaks, 0 (none) to 100000 (default 5).
lattice_steps_per_iteration: lattice steps after each constrained iteration of the second half,
    0 (none) to 1000 (default 3).
lattice_step: the largest move of one lattice step, 0.0001 to 0.1 hexagonal spacings (default 0.005).
seam_steps: repulsion steps after each level's iterations for points closer than the seam spacing
    to a point they can meet in a tiling, 0 (none) to 100000 (default 20).
seam_spacing: the seam spacing of level 0, 0.01 to 2 hexagonal spacings of the tile's points
    (default 0.8).
level_seam_spacing: the seam spacing of levels 1 and up, 0.01 to 2 (default 0.65).
rank_order: the progressive order inside each level: "farthest" (greedy farthest point),
    "voids" (tiled void-and-cluster) or "fill" (the default: levels after the first are not
    relaxed but filled point by point, each in the deepest void of the points before it).
void_sigma: voids: the kernel width, 0.1 to 4 hexagonal spacings of the prefix (default 0.5).
filled_lattice_steps: fill: lattice steps on each filled level's points against the tile-lattice
    peaks of its middle and its boundary, each move kept only where the points keep the filled
    spacing, 0 (none) to 100000 (default 150).
filled_lattice_spacing: fill: the spacing those moves keep, 0.01 to 2 hexagonal spacings of the
    prefix each pair completes (default 0.62).
filled_lattice_up_to: fill: lattice steps only on filled levels of at most this many points per
    tile, 1 to 1000000 (default 128; a step costs as the square of the count).
seed: any unsigned 64-bit integer (default 1); the same seed gives the tool's points.
engine: the centroid engine, "exact" (CPU, the default) or "raster" (Vulkan; on a CPU device such
    as lavapipe many times slower than exact).)");

  m.def("tile_set", &tile_set, nb::sig("def tile_set(tiles: str | bytes | os.PathLike[str] | None = None) -> dict[str, object]"),
        "tiles"_a = nb::none(),
        R"(A tile set's tiles as arrays: {'kind': str, 'tiles': [{'id', 'colours' (N, E, S, W, or the
corners NW, NE, SE, SW), 'points' (n, 2) tile-local, 'levels' (n,), 'ranks' (n,)}]}. ``tiles``:
the text of a tile-set file, a path to one (str or os.PathLike), or None for the set built into the library.
A str (or bytes) is text when it holds a line break or starts with '# bluetile tiles' (after spaces
and a byte-order mark), else a path.)");

  m.def("tile", &tile,
        nb::sig("def tile(region: tuple[float, float, float, float], *, tiles: str | bytes | os.PathLike[str] | None = None, tile_size: float = 0, "
                "density: float = 0, seed: int = 1, density_map: numpy.typing.ArrayLike | None = None, "
                "max_density: float = 0, count: float = 0, fit: str = 'contain', columns: bool = False) -> "
                "NDArray[numpy.float64] | "
                "dict[str, NDArray]"),
        "region"_a.none(), nb::kw_only(), "tiles"_a = nb::none(), "tile_size"_a.none() = 0.0, "density"_a.none() = 0.0, "seed"_a.none() = 1,
        "density_map"_a = nb::none(), "max_density"_a.none() = 0.0, "count"_a.none() = 0.0, "fit"_a.none() = "contain", "columns"_a.none() = false,
        R"(The points of the window ``region`` = (x0, y0, x1, y1) (half-open) of the aperiodic tiling of
the plane by a tile set, as ``bluetile tile --region``: the same points on every overlap for the
same seed. ``tile_size`` (plane units per tile) or ``density`` (points per unit area; the tile
size follows from it, and a lower density than the tiles hold thins every tile by rank); with
``density_map`` (2-D array, row 0 at the top, placed on the region by ``fit`` as ``--fit`` does:
'contain', the whole map centred with its aspect kept and no points beside it; 'cover', the region
filled with the aspect kept; 'stretch') points are kept by rank where the map is dense,
``max_density`` where it is highest, or about ``count`` points over the region (neither: 30000,
as the tool). Returns an (M, 2) array, or with
``columns=True`` a dict of 'points', 'i', 'j' (cells), 'tile', 'level', 'rank'.)");
}

}  // namespace pybluetile
