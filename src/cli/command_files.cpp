#include "cli/command_files.h"

namespace bluetile::cli {

std::span<const CommandFiles> command_files() {
  using K = InputKind;
  // The harness runs the oversized requests under ulimit -v 2 GiB, standing in for a small
  // machine: a limit of the memory available then refuses them on any machine.
  static const std::vector<CommandFiles> table = {
      {"relax",
       {"-k", "1", "--engine", "exact"},
       {{"-i", K::points, true}, {"--density-map", K::image}},
       {{"-o", "points.txt", false, true}, {"--log", "log.csv"}, {"--id-image", "cells.png"}},
       {"--name", "--device"},
       {{{"-n", "100000000", "--sets", "10000000", "--engine", "exact"}, "needs about 142.1 PiB of memory"},
        {{"-i", "{points}", "--engine", "raster", "--resolution", "65536"}, "use a smaller resolution"}}},
      {"centroids",
       {"--engine", "exact"},
       {{"-i", K::points, true}},
       {{"-o", "centroids.txt", false, true}},
       {"--name", "--device"},
       {{{"-i", "{points}", "--engine", "raster", "--resolution", "65536"}, "use a smaller resolution"}}},
      {"analyze",
       {"--no-psa-measures", "--no-discrepancy", "--no-centroids"},
       {{"-i", K::points, true}, {"--from", K::points}},
       {{"-o", "analysis", true, true}, {"--summary", "summary.svg"}, {"--psa-points", "psa.txt"}},
       {"--label", "--title", "--by-rank"},
       {{{"-i", "{points}", "--bin-width", "1e-9"}, "annuli (F / 2 = 27 over the width), more than the limit of 1e+09"},
        {{"-i", "{points}", "--size", "65536"}, "analyze of 30 points needs about"}}},
      {"dart",
       {"-n", "30"},
       {},
       {{"-o", "points.txt", false, true}},
       {"--name"},
       {{{"-n", "100000000", "--sets", "10000000"}, "needs about 56.8 PiB of memory"}}},
      {"progressive",
       {"--add", "10", "-k", "1", "--engine", "exact"},
       {{"-i", K::points, true}},
       {{"-o", "points.txt", false, true}},
       {"--name", "--device"},
       {{{"-i", "{points}", "--add", "100000000"}, "would bring the set to 100000030 points, more than the limit of 100000000"},
        {{"-n", "100000000", "--levels", "40", "--ratio", "1000"}, "more than the limit of 100000000"}}},
      {"devices", {}, {}, {}, {}, {}, true},
      {"wang",
       {"-n", "4", "-k", "1", "--warm", "0", "--lattice-steps", "0", "--lattice-steps-per-iteration", "0", "--strategy",
        "rounds"},
       {},
       {{"-o", "tiles.txt", false, true}},
       {"--device"},
       {{{"--points", "13", "--levels", "2", "--ratio", "1e7"},
         "makes about 130000000 points per tile (1040000000 in the 8 tiles), more than the limit of 1000000 per tile: use "
         "fewer levels or a smaller ratio"}}},
      {"wang-check",
       {},
       {{"", K::tiles, true}},
       {{"-o", "check", true}},
       {},
       {{{"{tiles}", "--period", "1024", "-o", "{check}"}, "the spectrum of the 4194304-point plane needs about"}}},
      {"tile",
       {"--region", "0", "0", "2", "2"},
       {{"--tiles", K::tiles, true}, {"--density-map", K::image}},
       {{"-o", "plane.txt", false, true}},
       {"--columns"},
       {{{"--tiles", "{tiles}", "--region", "0", "0", "1000000", "1000000", "--density", "1"},
         "holds about 1000000000000 points (1 per unit area), more than the limit of 100000000 points: use a smaller "
         "region or a lower density"},
        {{"--tiles", "{tiles}", "--region", "0", "0", "1000", "1000", "--tile-size", "1e-3", "--density", "1"},
         "tiles of size 0.001, more than the limit of 100000000 tiles: use a larger --tile-size or a smaller region"}}},
      {"stipple",
       {"-n", "20", "-k", "1"},
       {{"--image", K::image, true}},
       {{"-o", "dots.txt", false, true}, {"--svg", "dots.svg"}, {"--png", "dots.png"}, {"--log", "log.csv"}},
       {"--device", "--name"},
       {{{"--image", "{image}", "-n", "100000000"}, "--count 100000000 needs about 14.9 GiB of memory"}}},
  };
  return table;
}

}  // namespace bluetile::cli
