#include "cli/command_files.h"

namespace bluetile::cli {

std::span<const CommandFiles> command_files() {
  using K = InputKind;
  static const std::vector<CommandFiles> table = {
      {"relax",
       {"-k", "1", "--engine", "exact"},
       {{"-i", K::points, true}, {"--density-map", K::image}},
       {{"-o", "points.txt", false, true}, {"--log", "log.csv"}, {"--id-image", "cells.png"}},
       {"--name", "--device"}},
      {"centroids",
       {"--engine", "exact"},
       {{"-i", K::points, true}},
       {{"-o", "centroids.txt", false, true}},
       {"--name", "--device"}},
      {"analyze",
       {"--no-psa-measures", "--no-discrepancy", "--no-centroids"},
       {{"-i", K::points, true}, {"--from", K::points}},
       {{"-o", "analysis", true, true}, {"--summary", "summary.svg"}, {"--psa-points", "psa.txt"}},
       {"--label", "--title", "--by-rank"}},
      {"dart", {"-n", "30"}, {}, {{"-o", "points.txt", false, true}}, {"--name"}},
      {"progressive",
       {"--add", "10", "-k", "1", "--engine", "exact"},
       {{"-i", K::points, true}},
       {{"-o", "points.txt", false, true}},
       {"--name", "--device"}},
      {"devices", {}, {}, {}, {}},
      {"wang",
       {"-n", "4", "-k", "1", "--warm", "0", "--lattice-steps", "0", "--lattice-steps-per-iteration", "0", "--strategy",
        "rounds"},
       {},
       {{"-o", "tiles.txt", false, true}},
       {"--device"}},
      {"wang-check", {}, {{"", K::tiles, true}}, {{"-o", "check", true}}, {}},
      {"tile",
       {"--region", "0", "0", "2", "2"},
       {{"--tiles", K::tiles, true}, {"--density-map", K::image}},
       {{"-o", "plane.txt", false, true}},
       {"--columns"}},
      {"stipple",
       {"-n", "20", "-k", "1"},
       {{"--image", K::image, true}},
       {{"-o", "dots.txt", false, true}, {"--svg", "dots.svg"}, {"--png", "dots.png"}, {"--log", "log.csv"}},
       {"--device", "--name"}},
  };
  return table;
}

}  // namespace bluetile::cli
