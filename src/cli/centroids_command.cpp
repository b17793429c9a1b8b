// bluetile centroids: one Lloyd step's measurements, "cx cy area" per input point in order;
// every set of a multi-set input measured on its own and kept apart in the output.
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/engine_options.h"
#include "cli/file_options.h"
#include "cli/point_output.h"
#include "bluetile/core/error.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/point_table.h"

namespace bluetile::cli {
namespace {

struct CentroidsOptions {
  std::string input;
  PointOutputOptions output;
  EngineOptions engine;
};

void run_centroids(const CentroidsOptions& o, const CLI::App& command) {
  OutputSet outputs;
  add_declared_inputs(outputs, command);
  std::vector<PointSet> sets = read_input_sets(o.input, "centroids");
  check_cells_memory(sets, o.engine.engine, "centroids", o.input);
  PointOutput output(outputs, o.output, sets.size());

  // A bounded set (relax --bounded, stipple) is measured in the unit square, as it was made.
  const bool bounded = declared_domain(sets, o.input) == Boundary::bounded;
  std::vector<Scene> scenes;
  for (PointSet& set : sets) {
    scenes.push_back(make_scene(std::move(set.points)));
    if (bounded) scenes.back().boundary = Boundary::bounded;
  }
  auto engine = make_engine(o.engine);
  std::vector<SceneCells> results(scenes.size());
  engine->compute(scenes, results);

  TableView table;
  table.sets = results.size();
  table.columns = 3;
  table.column_names = "cx cy area";
  table.named_fields = true;  // not x y level: npy names the fields, .bpt is refused (point_table.h)
  table.rows = [&](std::size_t k) { return results[k].cells.size(); };
  table.value = [&](std::size_t k, std::size_t i, std::size_t c) {
    const Cell& cell = results[k].cells[i];
    return c == 0 ? cell.centroid.x : c == 1 ? cell.centroid.y : cell.area;
  };
  output.write(table, {"bluetile centroids of " + input_name(o.input) + ", engine " + engine_text(*engine, o.engine) +
                           (bounded ? ", bounded (its '# domain bounded' line)" : "") + ": cx cy area"});
  outputs.publish();
  std::size_t coincident = 0;
  for (const SceneCells& r : results) coincident += r.coincident_count;
  if (coincident) {
    std::fprintf(stderr, "bluetile: warning: %zu sites coincide with an earlier site: area 0, centroid = site\n",
                 coincident);
  }
}

}  // namespace

void add_centroids_command(CLI::App& app) {
  auto o = std::make_shared<CentroidsOptions>();
  CLI::App* cmd = app.add_subcommand("centroids", "Write the Voronoi cell centroid and area of every point (cx cy area)");
  add_input_option(cmd, "-i,--input", o->input, InputKind::points,
                   "Points: text (each '#'-separated set measured on its own), .npy, .bpt or .csv ('-': standard input)")
      ->required();
  o->output.named_fields = true;  // before the options: they list its formats
  add_point_output_options(cmd, o->output,
                           "Output table of cx cy area (npy: a structured array of fields cx, cy, area, shape K x N; "
                           "not .bpt, whose third column is the level)");
  add_engine_options(cmd, o->engine);
  cmd->callback([o, cmd] {
    refuse_unused_raster_options(*cmd, o->engine, "");
    run_centroids(*o, *cmd);
  });
}

}  // namespace bluetile::cli
