// relax, stipple, centroids and progressive: the loops over either engine.
#include "engines.h"

#include <optional>
#include <utility>
#include <vector>

#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>

#include "arrays.h"
#include "bindings.h"
#include "bluetile/core/memory_budget.h"
#include "bluetile/core/point_table.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/text.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/relax/progressive.h"
#include "bluetile/relax/stipple.h"
#include "bluetile/sampling/density_sampling.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/raster/raster_engine.h"

namespace pybluetile {

using namespace nb::literals;

namespace {

// The raster settings of `choice` that differ from their defaults, as "name" and the value as
// Python writes it ("100", "'point'"); the value is empty for those left alone.
std::vector<std::pair<const char*, std::string>> raster_settings(const EngineChoice& choice) {
  const EngineChoice defaults;
  auto quoted = [](const std::string& v) { return "'" + v + "'"; };
  return {{"resolution", choice.resolution != defaults.resolution ? std::to_string(choice.resolution) : ""},
          {"coverage", choice.coverage != defaults.coverage ? quoted(choice.coverage) : ""},
          {"cone", choice.cone != defaults.cone ? quoted(choice.cone) : ""},
          {"device", choice.device != defaults.device ? quoted(choice.device) : ""},
          {"pixel_work", choice.pixel_work != defaults.pixel_work ? quoted(choice.pixel_work) : ""}};
}

}  // namespace

void check_engine_choice(const EngineChoice& choice) {
  bluetile::validate(choice);
  if (choice.engine != "exact") return;
  for (const auto& [name, value] : raster_settings(choice))
    if (!value.empty())
      throw nb::value_error((std::string(name) + "=" + value +
                             ": a raster engine setting, and the exact engine runs here; engine=\"raster\" uses it")
                                .c_str());
}

namespace {

// The library's limits and defaults, as the tool takes them (relax --count, --sets, --iterations).
constexpr long long kMaxCount = static_cast<long long>(bluetile::kMaxSetPoints);
constexpr long long kMaxSets = static_cast<long long>(bluetile::kMaxSets);
using bluetile::kDefaultIterations, bluetile::kDefaultStippleIterations, bluetile::kDefaultWeightExponent,
    bluetile::kMaxIterations;
constexpr std::uint64_t kDefaultSeed = 1;

void check_non_negative(const char* name, double value) {
  if (!(value >= 0.0) || !std::isfinite(value))
    throw nb::value_error(
        (std::string(name) + ": expected a finite number >= 0, got " + bluetile::shortest_text(value)).c_str());
}

nb::dict history_dict(const std::vector<bluetile::LloydIteration>& history) {
  std::vector<std::int64_t> iteration, coincident, fallbacks, zero_density;
  std::vector<double> energy, max_displacement, mean_displacement;
  for (const auto& it : history) {
    iteration.push_back(it.iteration);
    energy.push_back(it.energy);
    max_displacement.push_back(it.max_displacement);
    mean_displacement.push_back(it.mean_displacement);
    coincident.push_back(static_cast<std::int64_t>(it.coincident));
    fallbacks.push_back(static_cast<std::int64_t>(it.fallbacks));
    zero_density.push_back(static_cast<std::int64_t>(it.zero_density));
  }
  const std::size_t n = history.size();
  nb::dict d;
  d["iteration"] = to_numpy(std::move(iteration), {n});
  d["energy"] = to_numpy(std::move(energy), {n});
  d["max_displacement"] = to_numpy(std::move(max_displacement), {n});
  d["mean_displacement"] = to_numpy(std::move(mean_displacement), {n});
  d["coincident"] = to_numpy(std::move(coincident), {n});
  d["fallbacks"] = to_numpy(std::move(fallbacks), {n});
  d["zero_density"] = to_numpy(std::move(zero_density), {n});
  return d;
}

// As the tool's relax -i and centroids -i: the cells of the points given, before any work
// ("relax of 5000000 points needs about ..."); the points themselves are in memory already.
void check_cells_memory(const PointSets& input, const std::string& engine, const char* function) {
  std::size_t n = 0;
  for (const auto& set : input.sets) n += set.size();
  bluetile::check_memory(bluetile::relax_memory_bytes(static_cast<double>(n), engine),
                         std::string(function) + " of " + std::to_string(n) + " points");
}

// As the tool: the raster engine, or the exact one for weighted or bounded cells, which the
// raster engine computes several times slower (docs/BENCHMARKS.md), unless one is named.
std::string default_engine(const std::optional<std::string>& engine, bool weighted_or_bounded) {
  return engine ? *engine : weighted_or_bounded ? "exact" : "raster";
}

nb::object relax(std::optional<ArrayArg> points_arg, const Whole& count_arg, const Whole& sets_arg,
                 const Whole& iterations_arg, const Whole& seed_arg, const Whole& fixed_arg, const Real& tolerance_arg,
                 std::optional<ArrayArg> density_map, const Real& weight_exponent_arg, const Flag& bounded_arg,
                 const Text& engine, const Whole& resolution, const Text& coverage, const Text& cone,
                 const Text& device, const Text& pixel_work, const Flag& history_arg) {
  const bool bounded = flag_or(bounded_arg, false, "bounded"), history = flag_or(history_arg, false, "history");
  const std::optional<std::string> engine_name =
      engine.is_none() ? std::nullopt : std::optional<std::string>(text_or(engine, {}, "engine"));
  EngineChoice choice = engine_choice(default_engine(engine_name, density_map.has_value() || bounded), resolution,
                                      coverage, cone, device, pixel_work);
  check_engine_choice(choice);
  const int iterations = whole_or<int>(iterations_arg, kDefaultIterations, "iterations", 0, kMaxIterations);
  const std::uint64_t seed = seed_or(seed_arg, kDefaultSeed);
  // 0: not given (points are); "sets" 0: one set of shape (N, 2).
  const long long count =
      whole_or<long long>(count_arg, 0, "count", 0, kMaxCount, "1 to " + std::to_string(kMaxCount));
  const long long sets = whole_or<long long>(sets_arg, 0, "sets", 0, kMaxSets);
  const double tolerance = real_or(tolerance_arg, 0.0, "tolerance");
  const double weight_exponent = real_or(weight_exponent_arg, kDefaultWeightExponent, "weight_exponent");
  check_non_negative("tolerance", tolerance);
  bluetile::check_weight_exponent(weight_exponent, "weight_exponent");
  // The map is stretched over the unit square, as `relax --density-map` stretches it; random
  // starts follow it and the cells are weighted so that the relaxed set keeps following it.
  std::shared_ptr<const bluetile::DensityGrid> density, weight;
  if (density_map) {
    density = std::make_shared<bluetile::DensityGrid>(
        density_grid(array_arg(*density_map, "density_map", ArrayKind::density), "density_map"));
    weight = std::make_shared<bluetile::DensityGrid>(bluetile::weight_for_point_density(*density, weight_exponent));
  }
  // Read (not yet checked) before the checks between arguments: a wrong type is named first.
  const std::optional<AnyArray> points_array =
      points_arg ? std::optional(array_arg(*points_arg, "points", ArrayKind::points)) : std::nullopt;
  if (points_arg.has_value() == (count != 0)) throw nb::value_error("give either points or count");
  if (sets != 0 && points_arg) throw nb::value_error("sets: only with count (an array of shape (K, N, 2) has its sets)");
  // Refused where they would change nothing, as the tool refuses --gamma without a map.
  if (seed != kDefaultSeed && points_arg)
    throw nb::value_error(("seed=" + std::to_string(seed) + ": only with count (it draws the random start; the points "
                           "given are the start)").c_str());
  if (weight_exponent != kDefaultWeightExponent && !density_map)
    throw nb::value_error(("weight_exponent=" + bluetile::shortest_text(weight_exponent) +
                           " weights the cells by a density_map: give one").c_str());
  PointSets input;
  if (points_arg) {
    input = point_sets(*points_array, "points", bounded ? OutsideTorus::square : OutsideTorus::wrap);
    check_cells_memory(input, choice.engine, "relax");
  } else {
    // As the tool's relax --count --sets: refused at once with the estimate, not a MemoryError
    // after seconds of work.
    bluetile::check_memory(
        bluetile::relax_memory_bytes(static_cast<double>(std::max(sets, 1LL)) * static_cast<double>(count), choice.engine),
        "count=" + std::to_string(count) + (sets != 0 ? " x sets=" + std::to_string(sets) : ""));
    input.batched = sets != 0;
    for (long long k = 0; k < std::max(sets, 1LL); ++k) {
      const auto n = static_cast<std::size_t>(count);
      const auto set = static_cast<std::uint64_t>(k);
      input.sets.push_back(density ? bluetile::density_random_points(*density, n, seed, set)
                                   : bluetile::uniform_random_points(n, seed, set));
    }
  }
  const std::size_t n = input.sets[0].size();
  const auto fixed = whole_or<std::size_t>(fixed_arg, 0, "fixed", 0, n, "0 to " + std::to_string(n) + " (the points)");

  bluetile::LloydResult result;
  std::vector<bluetile::Scene> scenes;
  {
    nb::gil_scoped_release release;
    for (auto& set : input.sets) {
      bluetile::Scene scene = bluetile::make_scene(std::move(set));
      scene.wanted_begin = fixed;
      scene.boundary = bounded ? bluetile::Boundary::bounded : bluetile::Boundary::periodic;
      scene.density = weight;
      scenes.push_back(std::move(scene));
    }
    auto e = make_engine(choice);
    bluetile::LloydOptions options;
    options.iterations = iterations;
    options.tolerance = tolerance;
    options.keep_history = history;
    options.on_iteration = [](const bluetile::LloydIteration&) { raise_pending_signals(); };
    result = bluetile::relax_lloyd(*e, scenes, options);
  }
  std::vector<std::vector<bluetile::Point>> relaxed;
  for (auto& scene : scenes) relaxed.push_back(std::move(scene.sites));
  nb::object array = nb::cast(points_to_numpy(relaxed, input.batched));
  if (!history) return array;
  return nb::make_tuple(array, history_dict(result.history));
}

nb::object stipple(const ArrayArg& density_map, const Whole& count, const Whole& iterations_arg, const Whole& seed,
                   const Real& tolerance_arg, const Flag& periodic, const Real& weight_exponent_arg, const Text& engine,
                   const Whole& resolution, const Text& coverage, const Text& cone, const Text& device,
                   const Text& pixel_work, const Flag& info_arg) {
  EngineChoice choice =
      engine_choice(text_or(engine, "exact", "engine"), resolution, coverage, cone, device, pixel_work);
  check_engine_choice(choice);
  const bool info = flag_or(info_arg, false, "info");
  bluetile::StippleStart start;
  start.count = whole<std::size_t>(count, "count", 1, kMaxCount);
  bluetile::check_memory(bluetile::relax_memory_bytes(static_cast<double>(start.count), choice.engine),
                         "count=" + std::to_string(start.count));  // as the tool's stipple --count
  const int iterations = whole_or<int>(iterations_arg, kDefaultStippleIterations, "iterations", 0, kMaxIterations);
  const double tolerance = real_or(tolerance_arg, 0.0, "tolerance");
  const double weight_exponent = real_or(weight_exponent_arg, kDefaultWeightExponent, "weight_exponent");
  check_non_negative("tolerance", tolerance);
  bluetile::check_weight_exponent(weight_exponent, "weight_exponent");
  const bluetile::DensityGrid map =
      density_grid(array_arg(density_map, "density_map", ArrayKind::density), "density_map");
  start.seed = seed_or(seed, kDefaultSeed);
  start.periodic = flag_or(periodic, false, "periodic");
  start.weight_exponent = weight_exponent;
  bluetile::Scene scene;
  bluetile::LloydResult result;
  {
    nb::gil_scoped_release release;
    scene = bluetile::stipple_scene(map, start);
    bluetile::LloydOptions options;
    options.iterations = iterations;
    options.tolerance = tolerance;
    options.on_iteration = [](const bluetile::LloydIteration&) { raise_pending_signals(); };
    result = bluetile::relax_lloyd(*make_engine(choice), scene, options);
  }
  nb::object points = nb::cast(points_to_numpy({scene.sites}, false));
  if (!info) return points;
  nb::dict d;
  d["width"] = scene.domain.size.x;
  d["height"] = scene.domain.size.y;
  d["dot_radius"] = bluetile::stipple_dot_radius(map, scene.domain, start.count);
  d["iterations"] = result.iterations;
  return nb::make_tuple(points, d);
}

nb::tuple centroids(const ArrayArg& points, const Text& engine, const Whole& resolution, const Text& coverage,
                    const Text& cone, const Text& device, const Text& pixel_work) {
  EngineChoice choice =
      engine_choice(text_or(engine, "raster", "engine"), resolution, coverage, cone, device, pixel_work);
  check_engine_choice(choice);
  PointSets input = point_sets(array_arg(points, "points", ArrayKind::points), "points");
  check_cells_memory(input, choice.engine, "centroids");
  std::vector<bluetile::SceneCells> cells(input.sets.size());
  {
    nb::gil_scoped_release release;
    std::vector<bluetile::Scene> scenes;
    for (auto& set : input.sets) scenes.push_back(bluetile::make_scene(std::move(set)));
    make_engine(choice)->compute(scenes, cells);
  }
  const std::size_t k = cells.size(), n = cells[0].cells.size();
  std::vector<double> centre, area;
  centre.reserve(k * n * 2);
  area.reserve(k * n);
  for (const auto& scene : cells)
    for (const bluetile::Cell& c : scene.cells) {
      centre.insert(centre.end(), {c.centroid.x, c.centroid.y});
      area.push_back(c.area);
    }
  if (input.batched) return nb::make_tuple(to_numpy(std::move(centre), {k, n, 2}), to_numpy(std::move(area), {k, n}));
  return nb::make_tuple(to_numpy(std::move(centre), {n, 2}), to_numpy(std::move(area), {n}));
}

nb::tuple progressive(std::optional<ArrayArg> base, std::optional<ArrayArg> base_levels, const Whole& count_arg,
                      const Whole& add_arg, const Real& ratio_arg, const Whole& levels_arg, const Whole& iterations_arg,
                      const Real& tolerance_arg, const Whole& seed, const Text& placement_arg, const Text& rank_order_arg,
                      const Text& engine_arg, const Whole& resolution, const Text& coverage, const Text& cone,
                      const Text& device, const Text& pixel_work) {
  const std::string engine = text_or(engine_arg, "raster", "engine");
  EngineChoice choice = engine_choice(engine, resolution, coverage, cone, device, pixel_work);
  const int iterations = whole_or<int>(iterations_arg, kDefaultIterations, "iterations", 0, kMaxIterations);
  const int levels = whole_or<int>(levels_arg, 0, "levels", 0, 64);
  // 0: not given.
  const long long count =
      whole_or<long long>(count_arg, 0, "count", 0, kMaxCount, "1 to " + std::to_string(kMaxCount));
  const long long add = whole_or<long long>(add_arg, 0, "add", 0, kMaxCount, "1 to " + std::to_string(kMaxCount));
  const double tolerance = real_or(tolerance_arg, 0.0, "tolerance"), ratio = real_or(ratio_arg, 0.0, "ratio");
  check_non_negative("tolerance", tolerance);
  check_non_negative("ratio", ratio);
  const std::string placement = text_or(placement_arg, "gaps", "placement");
  const std::string rank_order = text_or(rank_order_arg, "voids", "rank_order");
  if (placement != "gaps" && placement != "random")
    throw nb::value_error(("placement: expected one of 'gaps', 'random', got '" + placement + "'").c_str());
  const bluetile::ProgressiveOrder order = bluetile::parse_rank_order(rank_order);
  if (order == bluetile::ProgressiveOrder::fill) {
    // As the tool's --rank-order fill: it relaxes nothing and runs no engine, so these would
    // change nothing; refused where they differ from their defaults.
    std::vector<std::pair<const char*, std::string>> settings = {
        {"iterations", iterations != kDefaultIterations ? std::to_string(iterations) : ""},
        {"tolerance", tolerance != 0.0 ? bluetile::shortest_text(tolerance) : ""},
        {"placement", placement != "gaps" ? "'" + placement + "'" : ""},
        {"engine", engine != EngineChoice{}.engine ? "'" + engine + "'" : ""}};
    for (auto& setting : raster_settings(choice)) settings.push_back(std::move(setting));
    for (const auto& [name, value] : settings)
      if (!value.empty())
        throw nb::value_error((std::string(name) + "=" + value +
                               ": rank_order='fill' relaxes nothing and runs no engine; this is for the orders that "
                               "relax ('voids', 'placement')")
                                  .c_str());
  } else {
    check_engine_choice(choice);
  }
  // Read (not yet checked) before the checks between arguments: a wrong type is named first.
  const std::optional<AnyArray> base_array =
      base ? std::optional(array_arg(*base, "base", ArrayKind::points)) : std::nullopt;
  const std::optional<AnyArray> base_levels_array =
      base_levels ? std::optional(array_arg(*base_levels, "base_levels", ArrayKind::levels)) : std::nullopt;
  if (base.has_value() == (count != 0)) throw nb::value_error("give either base or count");
  if (add != 0 && ratio != 0.0) throw nb::value_error("give add or ratio, not both");
  bluetile::PointSet set;
  if (base) {
    PointSets input = point_sets(*base_array, "base");
    if (input.batched) throw nb::value_error("base: expected shape (N, 2): one set");
    set.points = std::move(input.sets[0]);
    if (base_levels)
      set.levels = levels_array(*base_levels_array, set.points.size(), "base_levels", bluetile::kMaxTableLevel);
  } else if (base_levels) {
    throw nb::value_error("base_levels: only with base");
  }
  bluetile::HierarchyOptions options;
  options.count = static_cast<std::size_t>(count);
  options.add = static_cast<std::size_t>(add);
  options.ratio = ratio;
  options.levels = levels;
  options.iterations = iterations;
  options.tolerance = tolerance;
  options.seed = seed_or(seed, kDefaultSeed);
  options.placement = placement == "random" ? bluetile::Placement::random : bluetile::Placement::gaps;
  options.rank_order = order;
  {
    // The levels' sizes and the memory of them all, checked before any work as the tool checks
    // them (the fill order's grid included).
    const std::vector<std::size_t> sizes = bluetile::hierarchy_level_sizes(set, options);
    double total = static_cast<double>(set.points.size());
    for (std::size_t add : sizes) total += static_cast<double>(add);
    const double fill = order == bluetile::ProgressiveOrder::fill
                            ? bluetile::band_fill_cost(0, static_cast<std::size_t>(total), 1, options.fill).bytes
                            : 0.0;
    const int target_levels = bluetile::count_levels(set) + static_cast<int>(sizes.size());
    // The fill order runs no engine: the points' memory is the exact engine's figure.
    const std::string engine_memory = order == bluetile::ProgressiveOrder::fill ? "exact" : choice.engine;
    bluetile::check_memory(bluetile::progressive_memory_bytes(total, engine_memory) + fill,
                           std::to_string(static_cast<long long>(total)) + " points in " + std::to_string(target_levels) +
                               " levels");
  }
  {
    nb::gil_scoped_release release;
    // The fill order relaxes nothing: no engine of the choice is made for it (no Vulkan device
    // is opened), as the tool's --rank-order fill.
    const bool filled = options.rank_order == bluetile::ProgressiveOrder::fill;
    std::unique_ptr<bluetile::CentroidEngine> engine =
        filled ? std::make_unique<bluetile::ExactEngine>() : make_engine(choice);
    options.on_iteration = [](int, const bluetile::LloydIteration&) { raise_pending_signals(); };
    options.fill.on_round = [](std::size_t, std::size_t) { raise_pending_signals(); };
    set = bluetile::add_levels(*engine, std::move(set), options);
  }
  const std::size_t n = set.points.size();
  std::vector<std::int32_t> level(set.levels.begin(), set.levels.end());
  return nb::make_tuple(points_to_numpy({set.points}, false), to_numpy(std::move(level), {n}));
}

}  // namespace

void bind_engines(nb::module_& m) {
  m.def("relax", &relax,
        nb::sig("def relax(points: numpy.typing.ArrayLike | None = None, *, count: int = 0, sets: int = 0, iterations: int = 80, "
                "seed: int = 1, fixed: int = 0, tolerance: float = 0.0, density_map: numpy.typing.ArrayLike | None = None, "
                "weight_exponent: float = 2.0, bounded: bool = False, engine: str | None = None, resolution: int = 0, coverage: str = 'area', cone: str = 'quad', device: str = '', pixel_work: str = 'auto', "
                "history: bool = False) -> NDArray[numpy.float64] | tuple[NDArray[numpy.float64], dict[str, NDArray]]"),
        "points"_a = nb::none(), nb::kw_only(), "count"_a.none() = 0, "sets"_a.none() = 0, "iterations"_a.none() = kDefaultIterations,
        "seed"_a.none() = kDefaultSeed, "fixed"_a.none() = 0, "tolerance"_a.none() = 0.0, "density_map"_a = nb::none(), "weight_exponent"_a.none() = kDefaultWeightExponent,
        "bounded"_a.none() = false, "engine"_a = nb::none(), "resolution"_a.none() = 0,
        "coverage"_a.none() = "area", "cone"_a.none() = "quad", "device"_a.none() = "", "pixel_work"_a.none() = "auto", "history"_a.none() = false,
        R"(Lloyd relaxation, as ``bluetile relax``.

Start from ``points`` (shape (N, 2), or (K, N, 2) for K sets relaxed each on its own) or from
``count`` random points (the same as ``bluetile relax --count N --seed S``; with ``sets=K``, K
sets of shape (K, N, 2), set k seeded as the tool seeds it; ``seed`` is refused with ``points``,
which need none). Every wanted site moves to the
centroid of its periodic Voronoi cell, ``iterations`` times, or until no site moves more than
``tolerance``. The first ``fixed`` sites shape the cells but stay in place.

With ``density_map`` (a 2-D array of densities, row 0 at the top, stretched over the unit square,
as ``--density-map`` with the image's densities) random starts follow the map and the cells are
weighted by map^``weight_exponent`` (2 keeps the point density proportional to the map; refused
without a map), as ``bluetile relax --density-map``. ``bounded=True``: cells end at the square's border (``--bounded``),
and points outside [0, 1)^2 are refused, not wrapped onto the torus as they are otherwise.

engine: "raster" (Vulkan, lavapipe by default) or "exact" (CPU, exact polygons); None picks the
tool's default: raster, or exact with a density map or bounded cells. resolution,
coverage ("area" | "point"), cone ("quad" | "fan"), device and pixel_work ("auto" | "device" |
"host": where the per-pixel work runs, as ``--pixel-work``; the same bits) set the raster engine,
and are refused with the exact one.
With ``history=True`` returns (points, history) where history holds one array per column of
``--log``: iteration, energy, max_displacement, mean_displacement, coincident, fallbacks and
zero_density (sites whose cell has no density, left in place).
The same seed gives the same bits as the tool. Releases the GIL while it runs.)");

  m.def("stipple", &stipple,
        nb::sig("def stipple(density_map: numpy.typing.ArrayLike, *, count: int, iterations: int = 50, seed: int = 1, "
                "tolerance: float = 0.0, periodic: bool = False, weight_exponent: float = 2.0, engine: str = 'exact', "
                "resolution: int = 0, coverage: str = 'area', cone: str = 'quad', device: str = '', pixel_work: str = 'auto', "
                "info: bool = False) -> NDArray[numpy.float64] | tuple[NDArray[numpy.float64], dict[str, float | int]]"),
        "density_map"_a.none(), nb::kw_only(), "count"_a.none(), "iterations"_a.none() = kDefaultStippleIterations, "seed"_a.none() = kDefaultSeed, "tolerance"_a.none() = 0.0,
        "periodic"_a.none() = false, "weight_exponent"_a.none() = 2.0, "engine"_a.none() = "exact", "resolution"_a.none() = 0,
        "coverage"_a.none() = "area", "cone"_a.none() = "quad", "device"_a.none() = "", "pixel_work"_a.none() = "auto", "info"_a.none() = false,
        R"(A stipple drawing by weighted Lloyd relaxation (Secord 2002), as ``bluetile stipple``.

``density_map``: a 2-D array of densities, row 0 at the top (for a grey image with dark meaning
dense, as the tool's default ``--invert``, pass 1 - luminance). The drawing spans the map's aspect
ratio with its longer side 1: points lie in [0, W) x [0, H), y up. ``count`` dots start in
proportion to the map and relax with cells weighted by map^``weight_exponent``; the cells end at
the picture's border unless ``periodic``. The same map, count, seed and options give the tool's
points bit for bit. With ``info=True`` returns (points, dict of width, height, dot_radius (dots
that just touch where the map is densest, the tool's default) and iterations).)");

  m.def("centroids", &centroids,
        nb::sig("def centroids(points: numpy.typing.ArrayLike, *, engine: str = 'raster', resolution: int = 0, "
                "coverage: str = 'area', cone: str = 'quad', device: str = '', pixel_work: str = 'auto') "
                "-> tuple[NDArray[numpy.float64], NDArray[numpy.float64]]"),
        "points"_a.none(), nb::kw_only(), "engine"_a.none() = "raster", "resolution"_a.none() = 0,
        "coverage"_a.none() = "area", "cone"_a.none() = "quad", "device"_a.none() = "", "pixel_work"_a.none() = "auto",
        R"(Cell centroids and areas of every point, as ``bluetile centroids``.

Returns (centroids, areas): shapes (N, 2) and (N,) for points of shape (N, 2), or (K, N, 2) and
(K, N) for K sets, each set its own diagram. A site that coincides with an earlier one gets area
0 and its own position as centroid.)");

  m.def("progressive", &progressive,
        nb::sig("def progressive(base: numpy.typing.ArrayLike | None = None, base_levels: numpy.typing.ArrayLike | None = None, *, "
                "count: int = 0, add: int = 0, ratio: float = 0.0, levels: int = 0, iterations: int = 80, "
                "tolerance: float = 0.0, seed: int = 1, placement: str = 'gaps', rank_order: str = 'voids', engine: str = 'raster', resolution: int = 0, coverage: str = 'area', cone: str = 'quad', device: str = '', pixel_work: str = 'auto') "
                "-> tuple[NDArray[numpy.float64], NDArray[numpy.int32]]"),
        "base"_a = nb::none(), "base_levels"_a = nb::none(), nb::kw_only(),
        "count"_a.none() = 0, "add"_a.none() = 0, "ratio"_a.none() = 0.0, "levels"_a.none() = 0, "iterations"_a.none() = kDefaultIterations, "tolerance"_a.none() = 0.0,
        "seed"_a.none() = 1, "placement"_a.none() = "gaps", "rank_order"_a.none() = "voids", "engine"_a.none() = "raster", "resolution"_a.none() = 0, "coverage"_a.none() = "area",
        "cone"_a.none() = "quad", "device"_a.none() = "", "pixel_work"_a.none() = "auto",
        R"(Hierarchical point sets, as ``bluetile progressive`` (the paper, section 2.1).

From scratch (``count``: level 0 has N relaxed random points, then ``levels`` levels in all,
4 by default), or on a ``base`` of shape (N, 2) with optional ``base_levels`` (N,), kept bit for
bit. Each level adds ``add`` points (default ``count``) or multiplies the total by ``ratio``;
new points start in the gaps (``placement="gaps"``, best candidate) or at random, and are
relaxed around the fixed earlier levels. ``rank_order="voids"`` (the default, as the tool's
``--rank-order``) relaxes the levels in stages of at least 64 points and orders each stage's points
by voids, so that every prefix of the rows is well spread; ``"placement"`` keeps each level as
placed and relaxed alone (the paper); ``"fill"`` relaxes nothing and places every point after the
base in the deepest void of the band-limited density of the points before it, so that every prefix
is about as even as every other (a ranked sample table); it takes no iterations, tolerance,
placement or engine settings, as the tool's ``--rank-order fill``. Returns (points (M, 2), levels (M,) int32), rows in rank order.)");
}

}  // namespace pybluetile
