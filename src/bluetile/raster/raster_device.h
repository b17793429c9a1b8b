// The raster engine's device side: the Vulkan context, its pipelines and buffers, and one pass
// over a group of scenes packed as tiles of one atlas: cones drawn into the ID image, the ID
// image classified and summed (classify.comp), boundary pixels split (split_f64.comp or
// split_f32.comp), all recorded into one command buffer and submitted once. Buffers persist
// between passes and grow only; nothing is allocated per pass once they are large enough.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "bluetile/gpu/raster_layout.h"
#include "bluetile/raster/raster_scene.h"

namespace bluetile {

struct RasterDeviceSettings {
  std::string device{};   // name or index; empty for the default (lavapipe first)
  bool fan = false;         // tessellated cones instead of exact-depth quads
  ConeDraw cone_draw = ConeDraw::points;
  bool force_float32 = false;  // the float32 split even where the device has shaderFloat64
  SplitKernel split_kernel = SplitKernel::lane;  // RasterOptions::split_kernel
  std::uint32_t split_guard_test = 0;            // RasterOptions::split_guard_test
};

// Why the per-pixel work cannot run on device `name` when asked for by name (PixelWork::device),
// empty when it can: the exact split needs shaderFloat64, unless the float32 split is asked for
// too. The engine throws it as an Error rather than move the work to the host.
std::string device_pixel_work_refusal(const std::string& name, bool has_float64, bool force_float32);

// Time of the last pass, seconds.
struct RasterPassTiming {
  double upload = 0.0;  // filling the input buffers on the host
  double device = 0.0;  // recording, submission and wait
  // Device timestamps (0 where the device has none): the cone pass, classify.comp, the split,
  // the copies back (the ID image; staged sums and counters).
  double cones = 0.0, classify = 0.0, split = 0.0, readback = 0.0;
  std::size_t cones_drawn = 0;  // cone instances (sites and periodic replicas)
  bool point_cones = false;     // drawn as points (ConeDraw::points and within the device's limits)
};

class RasterDevice {
 public:
  explicit RasterDevice(const RasterDeviceSettings& settings);
  ~RasterDevice();
  RasterDevice(const RasterDevice&) = delete;
  RasterDevice& operator=(const RasterDevice&) = delete;

  std::string device_name() const;
  bool is_cpu() const;  // a CPU device (lavapipe)
  bool float64_split() const;
  // The split is split_lane_f64.comp, which leaves pixels with more than BLUETILE_MAX_PIECES
  // candidates to the host; its area passes read the ID image back for them.
  bool lane_split() const;
  std::uint32_t max_side() const;           // largest atlas side (maxImageDimension2D)
  std::uint32_t max_scenes_per_pass() const;  // compute workgroup count limit
  // Pixels (samples) one pass may hold, from the device's memory budget and the largest storage
  // buffer (a pass keeps a list entry per pixel).
  std::size_t max_pass_pixels() const;
  // Sites one pass may hold: its per-site buffers (nine cone instances each) within the largest
  // storage buffer.
  std::size_t max_pass_sites() const;

  // One pass over `group`; every scene's origin_x/origin_y is its tile in a `width` x `height`
  // atlas. Sets each scene's site_begin. Without `pixel_work` only the cones are drawn (the
  // host then classifies and splits; the ID image is read back). Returns when the device has
  // finished.
  void run(std::span<RasterScene* const> group, std::uint32_t width, std::uint32_t height, bool read_ids, bool pixel_work);

  // Results of the last pass.
  std::span<const gpu::SiteSums> sums(const RasterScene& scene) const;
  std::uint32_t uncovered(std::size_t group_index) const;
  std::uint32_t boundary_pixels() const;
  std::uint32_t guard_pixels() const;  // overflow() entries the lane split's clip guard left
  // Boundary pixels the device left to the host: (group index, pixel index in its scene).
  std::span<const gpu::uvec2> overflow() const;
  // The ID image of a scene of the last pass (read_ids): scene-local site index + 1, 0 for none.
  std::vector<std::uint32_t> ids(const RasterScene& scene) const;
  const RasterPassTiming& timing() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bluetile
