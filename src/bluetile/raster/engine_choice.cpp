#include "bluetile/raster/engine_choice.h"

#include "bluetile/core/error.h"
#include "bluetile/core/field_checks.h"
#include "bluetile/voronoi/exact_engine.h"

namespace bluetile {
const std::vector<std::string>& engine_names() {
  static const std::vector<std::string> names{"raster", "exact"};
  return names;
}

const std::vector<std::string>& coverage_names() {
  static const std::vector<std::string> names{"point", "area"};
  return names;
}

const std::vector<std::string>& cone_names() {
  static const std::vector<std::string> names{"quad", "fan"};
  return names;
}

const std::vector<std::string>& pixel_work_names() {
  static const std::vector<std::string> names{"auto", "device", "host"};
  return names;
}

void validate(const EngineChoice& choice) {
  check_name_field("engine", choice.engine, engine_names());
  check_name_field("coverage", choice.coverage, coverage_names());
  check_name_field("cone", choice.cone, cone_names());
  check_name_field("pixel_work", choice.pixel_work, pixel_work_names());
  if (choice.resolution != 0 && (choice.resolution < kMinResolution || choice.resolution > kMaxResolution))
    throw Error("resolution: expected 0 (from N) or " + std::to_string(kMinResolution) + " to " +
                std::to_string(kMaxResolution) + ", got " + std::to_string(choice.resolution));
}

RasterOptions raster_options(const EngineChoice& choice) {
  validate(choice);
  RasterOptions r;
  r.resolution = choice.resolution;
  r.coverage = choice.coverage == "point" ? Coverage::point : Coverage::area;
  r.cone = choice.cone == "fan" ? ConeShape::fan : ConeShape::quad;
  r.device = choice.device;
  r.pixel_work = choice.pixel_work == "device" ? PixelWork::device
                 : choice.pixel_work == "host" ? PixelWork::host
                                               : PixelWork::automatic;
  return r;
}

std::unique_ptr<CentroidEngine> make_engine(const EngineChoice& choice) {
  validate(choice);
  if (choice.engine == "exact") return std::make_unique<ExactEngine>();
  return std::make_unique<RasterEngine>(raster_options(choice));
}

}  // namespace bluetile
