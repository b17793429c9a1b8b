// bluetile centroids: one Lloyd step's measurements, "cx cy area" per input point in order.
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/engine_options.h"
#include "bluetile/core/error.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/point_file.h"

namespace bluetile::cli {
namespace {

struct CentroidsOptions {
  std::string input;
  std::string output;
  EngineOptions engine;
};

void run_centroids(const CentroidsOptions& o) {
  OutputSet outputs;
  outputs.add_input(o.input);
  OutputFile& output = outputs.add(o.output, {.allow_stdout = true});
  PointSet set = read_point_file(o.input);
  if (set.points.empty()) throw Error(input_name(o.input) + ": no points");
  auto engine = make_engine(o.engine);
  SceneCells result = engine->compute(make_scene(std::move(set.points)));

  output.write([&](OutputStream& out) {
    out.print("# bluetile centroids of %s, engine %s: cx cy area\n", input_name(o.input).c_str(),
              std::string(engine->name()).c_str());
    for (const Cell& cell : result.cells) out.print("%.17g %.17g %.17g\n", cell.centroid.x, cell.centroid.y, cell.area);
  });
  outputs.publish();
  if (result.coincident_count) {
    std::fprintf(stderr, "bluetile: warning: %zu sites coincide with an earlier site: area 0, centroid = site\n",
                 result.coincident_count);
  }
}

}  // namespace

void add_centroids_command(CLI::App& app) {
  auto o = std::make_shared<CentroidsOptions>();
  CLI::App* cmd = app.add_subcommand("centroids", "Write the Voronoi cell centroid and area of every point (cx cy area)");
  cmd->add_option("-i,--input", o->input, "Point file ('-': standard input)")->required();
  cmd->add_option("-o,--output", o->output, "Output file ('-': standard output)")->required();
  add_engine_options(cmd, o->engine);
  cmd->callback([o] { run_centroids(*o); });
}

}  // namespace bluetile::cli
