#include "bluetile/raster/engine_choice.h"

#include <algorithm>

#include "bluetile/core/error.h"
#include "bluetile/voronoi/exact_engine.h"

namespace bluetile {
namespace {

void check_one_of(const char* field, const std::string& value, const std::vector<std::string>& names) {
  if (std::find(names.begin(), names.end(), value) != names.end()) return;
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "'" : ", '") + name + "'";
  throw Error(std::string(field) + ": expected one of " + list + ", got '" + value + "'");
}

}  // namespace

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
  check_one_of("engine", choice.engine, engine_names());
  check_one_of("coverage", choice.coverage, coverage_names());
  check_one_of("cone", choice.cone, cone_names());
  check_one_of("pixel_work", choice.pixel_work, pixel_work_names());
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
