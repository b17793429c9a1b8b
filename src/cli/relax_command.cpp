// bluetile relax: Lloyd relaxation of a random or given point set.
#include <cstdio>
#include <limits>
#include <memory>

#include "cli/commands.h"
#include "cli/density_options.h"
#include "cli/engine_options.h"
#include "cli/file_options.h"
#include "cli/numeric_options.h"
#include "cli/point_output.h"
#include "cli/output_names.h"
#include "cli/relax_log.h"
#include "bluetile/core/error.h"
#include "bluetile/core/memory_budget.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/point_table.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/text.h"
#include "bluetile/io/image_file.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/sampling/density_sampling.h"

namespace bluetile::cli {
namespace {

struct RelaxOptions {
  long long count = 0;
  std::string input;
  int iterations = kDefaultIterations;
  std::uint64_t seed = 1;
  long long fixed = 0;
  double tolerance = 0.0;
  long long sets = 1;
  PointOutputOptions output;
  std::string log;
  std::string id_image;
  bool verbose = false;
  std::string density_map;
  bool bounded = false;
  DensityMapOptions transfer;
  double weight_exponent = kDefaultWeightExponent;
  EngineOptions engine;
};

// Set k of a batch: its own seed, so set 0 of any batch equals the single set of that seed.
// Uniform, or drawn in proportion to the density when there is one.
std::vector<Point> random_points(std::uint64_t seed, std::size_t set, std::size_t count, const DensityGrid* density) {
  return density ? density_random_points(*density, count, seed, set) : uniform_random_points(count, seed, set);
}

void run_relax(RelaxOptions o, const CLI::App& command) {
  // The image plugin is loaded, and an image's format checked, before any output is staged.
  if (!o.density_map.empty() || !o.id_image.empty()) load_image_plugin();
  if (!o.id_image.empty()) output_format("--id-image", o.id_image, kImageFormats);
  if (!o.id_image.empty()) check_image_output(o.id_image);
  OutputSet outputs;
  add_declared_inputs(outputs, command);
  // The input's sets (UTK's '#' lines, .npy, .bpt: each set is relaxed on its own), or the
  // random starts below.
  std::vector<PointSet> inputs;
  bool declared_bounded = false;
  if (!o.input.empty()) {
    // With --bounded the points lie in the square: one outside it is refused, not wrapped into it.
    ReadOptions read;
    read.wrap = !o.bounded;
    try {
      inputs = read_input_sets(o.input, "relax", read);
    } catch (const Error& e) {
      const std::string message = e.what();
      if (!o.bounded || message.find("is outside [") == std::string::npos || message.find(kBoundedNotWrapped) != std::string::npos)
        throw;
      throw Error(message + " (--bounded: the points lie in the unit square, and are not wrapped onto a torus)");
    }
    // A bounded set (relax --bounded, stipple) stays bounded, as analyze measures it.
    const std::optional<Boundary> declared = declared_domain(inputs, o.input);
    if (declared == Boundary::periodic && o.bounded)
      throw Error("--bounded, but " + input_name(o.input) + " declares '# domain periodic'");
    declared_bounded = declared == Boundary::bounded && !o.bounded;
    o.bounded = o.bounded || declared_bounded;
  }
  // Both engines weight cells and bound domains, the raster one only on its host per-pixel
  // path, measured 5x slower than the exact engine on stipples (docs/BENCHMARKS.md): exact is
  // the default there.
  std::string why_exact;
  if (command.count("--engine") == 0 && (!o.density_map.empty() || o.bounded)) {
    o.engine.engine = "exact";
    why_exact = declared_bounded ? ", the default for a set declared '# domain bounded'"
                : o.bounded      ? ", the default with --bounded"
                                 : ", the default with --density-map";
  }
  refuse_unused_raster_options(command, o.engine, why_exact, !o.id_image.empty());
  // Refused before anything is drawn or relaxed: the engine, which the estimate depends on, is
  // known now. An input's points are in memory already; its relaxation is not.
  if (o.input.empty()) {
    check_memory(relax_memory_bytes(static_cast<double>(o.sets) * static_cast<double>(o.count), o.engine.engine),
                 "--count " + std::to_string(o.count) + " x --sets " + std::to_string(o.sets));
  } else {
    check_cells_memory(inputs, o.engine.engine, "relax", o.input);
  }
  // Every output is declared, and so checked, before any work.
  const std::size_t set_count = o.input.empty() ? static_cast<std::size_t>(o.sets) : inputs.size();
  PointOutput point_output(outputs, o.output, set_count);
  if (!o.log.empty()) check_text_output_name("--log", o.log, "a CSV log");
  OutputFile* log_file = o.log.empty() ? nullptr : &outputs.add(o.log, {.allow_stdout = true});
  // The ID image of the first set, or with '{}' in the name one image per set, as --output.
  std::vector<OutputFile*> id_images;
  if (!o.id_image.empty()) {
    const bool each = o.id_image.find("{}") != std::string::npos;
    for (std::size_t k = 0; k < (each ? set_count : 1); ++k)
      id_images.push_back(&outputs.add(each ? set_file_name(o.id_image, k, set_count) : o.id_image,
                                       {.binary_format = binary_output_format(OutputFormat::image)}));
  }

  // The map is stretched over the unit square, whatever its aspect ratio. Random starts follow
  // it; the cells are weighted so that the relaxed set keeps following it.
  std::shared_ptr<const DensityGrid> density, weight;
  if (!o.density_map.empty()) {
    density = std::make_shared<DensityGrid>(load_density_map(o.density_map, density_transfer(o.transfer)));
    weight = std::make_shared<DensityGrid>(weight_for_point_density(*density, o.weight_exponent));
  }
  if (o.input.empty()) {
    for (long long k = 0; k < o.sets; ++k)
      inputs.push_back({random_points(o.seed, static_cast<std::size_t>(k), static_cast<std::size_t>(o.count),
                                      density.get()),
                        {}});
  }
  const std::size_t n = inputs[0].points.size();
  for (const PointSet& set : inputs) {
    if (static_cast<std::size_t>(o.fixed) > set.points.size()) {
      throw Error("--fixed " + std::to_string(o.fixed) + " is more than the " + std::to_string(set.points.size()) +
                  " points" + (inputs.size() > 1 ? " of a set" : ""));
    }
  }

  std::vector<Scene> scenes;
  for (PointSet& set : inputs) {
    Scene scene = make_scene(std::move(set.points));
    scene.wanted_begin = static_cast<std::size_t>(o.fixed);
    scene.boundary = o.bounded ? Boundary::bounded : Boundary::periodic;
    scene.density = weight;
    scenes.push_back(std::move(scene));
  }

  auto engine = make_engine(o.engine);
  double cells = 0.0;
  for (const Scene& scene : scenes) cells += static_cast<double>(scene.wanted_count());
  note_faster_engine(*engine, cells * o.iterations);
  // The log is streamed while the run goes: its memory does not grow with the iterations.
  RelaxLog log("relax", o.iterations, o.verbose, log_file ? &log_file->open() : nullptr);
  LloydResult result = relax_lloyd(*engine, scenes, log.lloyd_options(o.iterations, o.tolerance));
  log.finish(result, o.tolerance, o.iterations);
  note_exact_hand_over(*engine);

  const std::string what = inputs.size() == 1 ? counted(static_cast<long long>(n), "point")
                                              : std::to_string(inputs.size()) + " sets of " + counted(static_cast<long long>(n), "point");
  std::vector<std::string> header = {
      "bluetile relax: " + what + ", " + counted(result.iterations, "iteration") + ", engine " + engine_text(*engine, o.engine) +
      (o.input.empty() ? ", seed " + std::to_string(o.seed) : ", input " + input_name(o.input)) +
      (o.fixed ? ", first " + std::to_string(o.fixed) + " fixed" : "") +
      (o.density_map.empty() ? "" : ", density map " + o.density_map) + (o.bounded ? ", bounded" : "")};
  // The line analyze reads to measure a bounded set in the unit square, not on the torus.
  if (o.bounded) header.push_back("domain bounded");
  for (std::size_t k = 0; k < scenes.size(); ++k) inputs[k].points = scenes[k].sites;
  point_output.write(inputs, header);
  if (log_file) log_file->close();
  for (std::size_t k = 0; k < id_images.size(); ++k) write_id_image(o.engine, *engine, scenes[k], *id_images[k]);
  outputs.publish();
}

}  // namespace

void add_relax_command(CLI::App& app) {
  auto o = std::make_shared<RelaxOptions>();
  CLI::App* cmd = app.add_subcommand("relax", "Relax a random (--count) or given (--input) point set by Lloyd's method");
  auto* count = add_integer_option(cmd, "-n,--count", o->count, 1LL, kMaxCount, "Number of random points to start from");
  auto* input = add_input_option(cmd, "-i,--input", o->input, InputKind::points,
                                 "Points to start from: text (each '#'-separated set relaxed on its own), .npy, .bpt "
                                 "or .csv ('-': standard input)");
  count->excludes(input);
  input->excludes(count);
  add_integer_option(cmd, "-k,--iterations", o->iterations, 0, kMaxIterations, "Lloyd iterations");
  add_seed_option(cmd, o->seed, "Seed of the random start");
  add_integer_option(cmd, "--fixed", o->fixed, 0LL, kMaxCount, "Keep the first M sites in place (they still shape the cells)");
  add_real_option(cmd, "--tolerance", o->tolerance, {}, "Stop early once no site moves more than this (domain units)");
  auto* sets = add_integer_option(cmd, "--sets", o->sets, 1LL, kMaxSets,
                                  "Relax K independent sets (seeds derived from --seed); --output with {} writes one "
                                  "file each, else one table (text: '#' lines between sets)");
  sets->needs(count);
  add_point_output_options(cmd, o->output, "Output points ('-': standard output)");
  add_output_option(cmd, "--log", o->log, kCsvLog, "Write a CSV log of energy and displacement per iteration");
  add_output_option(cmd, "--id-image", o->id_image, {.formats = kImageFormats},
                    "Write the raster ID buffer of the result as an image (cells coloured, sites drawn): of the first "
                    "set, or with {} in the name one image per set");
  cmd->add_flag("-v,--verbose", o->verbose, "Print energy and displacement of every iteration on stderr");
  add_input_option(cmd, "--density-map", o->density_map, InputKind::image,
                   "Relax toward this image's density (bright means dense unless --invert), stretched over the unit "
                   "square; random starts are drawn from it ('-': standard input)");
  cmd->add_flag("--bounded", o->bounded,
                "Cells end at the unit square's border instead of wrapping around (also chosen by the input's '# "
                "domain bounded' line, which the output gets)");
  add_density_transfer_options(cmd, o->transfer);
  add_weight_exponent_option(cmd, o->weight_exponent);
  add_engine_options(cmd, o->engine);
  cmd->get_option("--engine")->description(
      "Centroid engine: raster (Vulkan) or exact (CPU); exact is the default with --density-map or a bounded domain");
  cmd->callback([o, cmd] {
    if (o->count == 0 && o->input.empty()) throw CLI::RequiredError("--count or --input");
    if (!o->input.empty() && cmd->count("--seed") > 0)
      throw Error("--seed " + std::to_string(o->seed) + ": only with --count (it draws the random start; the input is the "
                  "start)");
    refuse_transfer_without_map(*cmd, !o->density_map.empty());
    run_relax(*o, *cmd);
  });
}

}  // namespace bluetile::cli
