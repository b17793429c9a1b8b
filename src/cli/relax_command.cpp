// bluetile relax: Lloyd relaxation of a random or given point set.
#include <cstdio>
#include <limits>
#include <memory>

#include "cli/commands.h"
#include "cli/engine_options.h"
#include "cli/memory_budget.h"
#include "cli/numeric_options.h"
#include "cli/progress.h"
#include "bluetile/core/error.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/rng.h"
#include "bluetile/relax/lloyd.h"

namespace bluetile::cli {
namespace {

struct RelaxOptions {
  long long count = 0;
  std::string input;
  int iterations = 80;
  std::uint64_t seed = 1;
  long long fixed = 0;
  double tolerance = 0.0;
  long long sets = 1;
  std::string output;
  std::string log;
  std::string id_image;
  bool verbose = false;
  EngineOptions engine;
};

// Set k of a batch: its own seed, so set 0 of any batch equals the single set of that seed.
std::vector<Point> random_points(std::uint64_t seed, std::size_t set, std::size_t count) {
  Rng rng(derive_seed(seed, set));
  std::vector<Point> points(count);
  for (Point& p : points) p = rng.point(Domain{});
  return points;
}

// `pattern` with every "{}" replaced by the set's index, zero-padded to the width of the last.
std::string set_file_name(const std::string& pattern, std::size_t set, std::size_t sets) {
  std::string index = std::to_string(set);
  std::string width = std::to_string(sets - 1);
  index.insert(0, width.size() - index.size(), '0');
  std::string name = pattern;
  for (std::size_t at = name.find("{}"); at != std::string::npos; at = name.find("{}", at + index.size()))
    name.replace(at, 2, index);
  return name;
}

void run_relax(const RelaxOptions& o) {
  const bool one_file_each = o.output.find("{}") != std::string::npos;
  if (o.sets > 1 && !one_file_each && o.output.find('#') != std::string::npos)
    throw Error("--output '" + o.output + "': file names with '#' cannot hold several sets");
  if (o.input.empty()) {
    check_memory(static_cast<double>(o.sets) * static_cast<double>(o.count) * kRelaxBytesPerSite,
                 "--count " + std::to_string(o.count) + " x --sets " + std::to_string(o.sets));
  }

  // Every output is declared, and so checked, before any work.
  OutputSet outputs;
  if (!o.input.empty()) outputs.add_input(o.input);
  std::vector<OutputFile*> point_files;
  if (one_file_each) {
    for (long long k = 0; k < o.sets; ++k)
      point_files.push_back(&outputs.add(set_file_name(o.output, static_cast<std::size_t>(k), static_cast<std::size_t>(o.sets))));
  } else {
    point_files.push_back(&outputs.add(o.output, {.allow_stdout = true}));
  }
  OutputFile* log_file = o.log.empty() ? nullptr : &outputs.add(o.log, {.allow_stdout = true});
  OutputFile* id_image = o.id_image.empty() ? nullptr : &outputs.add(o.id_image);

  std::vector<PointSet> inputs;
  if (!o.input.empty()) {
    inputs.push_back(read_point_file(o.input));
    if (inputs[0].points.empty()) throw Error(input_name(o.input) + ": no points");
  } else {
    for (long long k = 0; k < o.sets; ++k)
      inputs.push_back({random_points(o.seed, static_cast<std::size_t>(k), static_cast<std::size_t>(o.count)), {}});
  }
  const std::size_t n = inputs[0].points.size();
  if (static_cast<std::size_t>(o.fixed) > n) {
    throw Error("--fixed " + std::to_string(o.fixed) + " is more than the " + std::to_string(n) + " points");
  }

  std::vector<Scene> scenes;
  for (PointSet& set : inputs) {
    Scene scene = make_scene(std::move(set.points));
    scene.wanted_begin = static_cast<std::size_t>(o.fixed);
    scenes.push_back(std::move(scene));
  }

  auto engine = make_engine(o.engine);
  // The log is streamed while the run goes: its memory does not grow with the iterations.
  OutputStream* log = log_file ? &log_file->open() : nullptr;
  if (log) log->write("iteration,energy,max_displacement,mean_displacement,coincident,fallbacks\n");
  Progress progress("relax", o.iterations);
  LloydOptions lloyd;
  lloyd.iterations = o.iterations;
  lloyd.tolerance = o.tolerance;
  lloyd.on_iteration = [&](const LloydIteration& it) {
    if (log) {
      log->print("%d,%.17g,%.17g,%.17g,%zu,%zu\n", it.iteration, it.energy, it.max_displacement, it.mean_displacement,
                 it.coincident, it.fallbacks);
    }
    if (o.verbose) {
      progress.finish();
      std::fprintf(stderr, "iteration %d: energy %.9e, max displacement %.3e, mean %.3e%s\n", it.iteration,
                   it.energy, it.max_displacement, it.mean_displacement,
                   it.coincident ? (", " + std::to_string(it.coincident) + " coincident").c_str() : "");
    }
    char detail[64];
    std::snprintf(detail, sizeof detail, "max displacement %.2e", it.max_displacement);
    progress.update(it.iteration, detail);
  };
  LloydResult result = relax_lloyd(*engine, scenes, lloyd);
  progress.finish();

  std::vector<std::string> header = {
      "bluetile relax: " + std::to_string(n) + " points, " + std::to_string(result.iterations) +
      " iterations, engine " + std::string(engine->name()) +
      (o.input.empty() ? ", seed " + std::to_string(o.seed) : ", input " + input_name(o.input)) +
      (o.fixed ? ", first " + std::to_string(o.fixed) + " fixed" : "")};
  if (one_file_each) {
    for (std::size_t k = 0; k < scenes.size(); ++k) {
      point_files[k]->write([&](OutputStream& out) { write_points(out, PointSet{scenes[k].sites, {}}, header); });
    }
  } else if (scenes.size() == 1) {
    PointSet set{scenes[0].sites, std::move(inputs[0].levels)};
    point_files[0]->write([&](OutputStream& out) { write_points(out, set, header); });
  } else {
    // UTK's convention: one file, a '#' line before each set.
    point_files[0]->write([&](OutputStream& out) {
      write_points(out, PointSet{}, header);
      for (std::size_t k = 0; k < scenes.size(); ++k) {
        out.print("# set %zu\n", k);
        write_points(out, PointSet{scenes[k].sites, {}});
      }
    });
  }
  if (log_file) log_file->close();
  if (id_image) write_id_image(o.engine, *engine, scenes[0], *id_image);
  outputs.publish();

  if (result.last.coincident) {
    std::fprintf(stderr, "bluetile: warning: %zu sites coincide with another site and were not moved\n",
                 result.last.coincident);
  }
  if (o.tolerance > 0.0 && !result.converged) {
    std::fprintf(stderr, "bluetile: note: max displacement %.3e still above --tolerance %.3e after %d iterations\n",
                 result.last.max_displacement, o.tolerance, o.iterations);
  }
}

}  // namespace

void add_relax_command(CLI::App& app) {
  auto o = std::make_shared<RelaxOptions>();
  CLI::App* cmd = app.add_subcommand("relax", "Relax a random (--count) or given (--input) point set by Lloyd's method");
  auto* count = add_integer_option(cmd, "-n,--count", o->count, 1LL, kMaxCount, "Number of random points to start from");
  auto* input = cmd->add_option("-i,--input", o->input, "Point file to start from ('-': standard input)");
  count->excludes(input);
  input->excludes(count);
  add_integer_option(cmd, "-k,--iterations", o->iterations, 0, kMaxIterations, "Lloyd iterations");
  add_integer_option(cmd, "-s,--seed", o->seed, std::uint64_t{0}, std::numeric_limits<std::uint64_t>::max(),
                     "Seed of the random start");
  add_integer_option(cmd, "--fixed", o->fixed, 0LL, kMaxCount, "Keep the first M sites in place (they still shape the cells)");
  add_real_option(cmd, "--tolerance", o->tolerance, {}, "Stop early once no site moves more than this (domain units)");
  auto* sets = add_integer_option(cmd, "--sets", o->sets, 1LL, kMaxSets,
                                  "Relax K independent sets (seeds derived from --seed); --output with {} writes one "
                                  "file each, else one file with '#' lines between sets");
  sets->needs(count);
  cmd->add_option("-o,--output", o->output, "Output point file ('-': standard output; {} is replaced by the set index)")
      ->required();
  cmd->add_option("--log", o->log, "Write a CSV log of energy and displacement per iteration");
  cmd->add_option("--id-image", o->id_image, "Write the raster ID buffer of the result as an image (cells coloured, sites drawn)");
  cmd->add_flag("-v,--verbose", o->verbose, "Print energy and displacement of every iteration on stderr");
  add_engine_options(cmd, o->engine);
  cmd->callback([o] {
    if (o->count == 0 && o->input.empty()) throw CLI::RequiredError("--count or --input");
    run_relax(*o);
  });
}

}  // namespace bluetile::cli
