// bluetile centroids: one Lloyd step's measurements, "cx cy area" per input point in order.
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/engine_options.h"
#include "bluetile/core/atomic_file.h"
#include "bluetile/core/error.h"
#include "bluetile/core/point_file.h"

namespace bluetile::cli {
namespace {

struct CentroidsOptions {
  std::string input;
  std::string output;
  EngineOptions engine;
};

void run_centroids(const CentroidsOptions& o) {
  PointSet set = read_point_file(o.input);
  if (set.points.empty()) throw Error(o.input + ": no points");
  auto engine = make_engine(o.engine);
  SceneCells result = engine->compute(make_scene(set.points));

  std::string text = "# bluetile centroids of " + o.input + ", engine " + std::string(engine->name()) + ": cx cy area\n";
  char line[96];
  for (const Cell& cell : result.cells) {
    int len = std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", cell.centroid.x, cell.centroid.y, cell.area);
    text.append(line, static_cast<std::size_t>(len));
  }
  write_text_atomically(o.output, text);
  if (result.coincident_count) {
    std::fprintf(stderr, "bluetile: warning: %zu sites coincide with an earlier site: area 0, centroid = site\n",
                 result.coincident_count);
  }
}

}  // namespace

void add_centroids_command(CLI::App& app) {
  auto o = std::make_shared<CentroidsOptions>();
  CLI::App* cmd = app.add_subcommand("centroids", "Write the Voronoi cell centroid and area of every point (cx cy area)");
  cmd->add_option("-i,--input", o->input, "Point file")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->output, "Output file")->required();
  add_engine_options(cmd, o->engine);
  cmd->callback([o] { run_centroids(*o); });
}

}  // namespace bluetile::cli
