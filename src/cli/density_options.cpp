#include "cli/density_options.h"

#include "cli/numeric_options.h"
#include "bluetile/core/error.h"
#include "bluetile/core/text.h"
#include "bluetile/relax/lloyd.h"

namespace bluetile::cli {

void add_density_transfer_options(CLI::App* command, DensityMapOptions& options) {
  command->add_option("--transfer", options.transfer,
                      "How image samples become linear values: srgb (decode the sRGB curve), linear (as stored), "
                      "auto (srgb for 8/16-bit images such as PNG, linear for float images such as EXR)")
      ->check(CLI::IsMember({"auto", "srgb", "linear"}))
      ->capture_default_str();
  command->add_flag("--invert,!--no-invert", options.invert,
                    std::string("Dark means dense: density 1 - luminance; --no-invert: bright means dense, density = "
                                "luminance (default here: ") +
                        (options.invert ? "--invert, dark means dense)" : "--no-invert, bright means dense)"));
  add_real_option(command, "--gamma", options.gamma, {0.0, kInfinity, true, false},
                  "Density = value^gamma after decoding and --invert");
}

void add_weight_exponent_option(CLI::App* command, double& exponent) {
  add_real_option(command, "--weight-exponent", exponent, {0.0, kMaxWeightExponent},
                  "Weight Lloyd's cells by density^E: 2 keeps the point density proportional to the map (a "
                  "centroidal Voronoi diagram's point density goes as the square root of its weight), 1 is Secord "
                  "2002's weighting, whose contrast flattens as the set converges");
}

DensityTransfer density_transfer(const DensityMapOptions& options) {
  DensityTransfer t;
  t.curve = options.transfer == "srgb"     ? TransferCurve::srgb
            : options.transfer == "linear" ? TransferCurve::linear
                                           : TransferCurve::automatic;
  t.invert = options.invert;
  t.gamma = options.gamma;
  return t;
}

std::string transfer_text(const DensityMapOptions& options) {
  return "transfer " + options.transfer + (options.invert ? ", invert" : ", no invert") + ", gamma " +
         shortest_text(options.gamma);
}

void refuse_transfer_without_map(const CLI::App& command, bool has_map) {
  if (has_map) return;
  for (const char* name : {"--transfer", "--invert", "--gamma"})
    if (command.count(name) > 0) {
      // --no-invert is the same option as --invert: name the one given.
      const std::string given = std::string(name) == "--invert" && !command.get_option(name)->as<bool>() ? "--no-invert" : name;
      throw Error(given + " shapes a --density-map: give one");
    }
  if (command.get_option_no_throw("--weight-exponent") != nullptr && command.count("--weight-exponent") > 0)
    throw Error("--weight-exponent " + command.get_option("--weight-exponent")->as<std::string>() +
                " weights the cells by a --density-map: give one");
}

}  // namespace bluetile::cli
