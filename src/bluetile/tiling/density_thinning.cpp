#include "bluetile/tiling/density_thinning.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace {

// Keeps dithers of different cells and seeds independent of the tile-set bits (another stream).
constexpr std::uint64_t kDitherStream = 0x6469746865720001ull;

void check_fraction(double fraction, const char* what) {
  if (!(fraction > 0.0 && fraction <= 1.0))
    throw Error(std::string(what) + " must lie in (0, 1], got " + exact_text(fraction));
}

// A window or map rectangle of no area or with a NaN side placed nothing, or NaN coordinates.
void check_map_rectangle(const Window& w, std::string_view what) {
  if (!(std::isfinite(w.x0) && std::isfinite(w.y0) && std::isfinite(w.x1) && std::isfinite(w.y1) && w.x1 > w.x0 &&
        w.y1 > w.y0))
    throw Error(std::string(what) + " must be finite with x1 > x0 and y1 > y0");
}

}  // namespace

MapFit parse_map_fit(const std::string& name) {
  for (MapFit fit : {MapFit::contain, MapFit::cover, MapFit::stretch})
    if (name == map_fit_name(fit)) return fit;
  throw Error("map fit '" + name + "': expected contain, cover or stretch");
}

const char* map_fit_name(MapFit fit) {
  switch (fit) {
    case MapFit::contain: return "contain";
    case MapFit::cover: return "cover";
    case MapFit::stretch: return "stretch";
  }
  return "stretch";
}

Window fit_map_rectangle(const Window& window, int width, int height, MapFit fit) {
  check_map_rectangle(window, "map window");
  if (width < 1 || height < 1)
    throw Error("density map of " + std::to_string(width) + " x " + std::to_string(height) +
                " texels: expected at least 1 x 1");
  if (fit == MapFit::stretch) return window;
  const double map_aspect = static_cast<double>(width) / height;
  const double window_aspect = window.width() / window.height();
  // contain spans the window's width when the map is the wider one; cover spans it otherwise.
  const bool full_width = (fit == MapFit::contain) == (map_aspect > window_aspect);
  Window fitted = window;
  if (full_width) {
    const double side = window.width() / map_aspect, middle = 0.5 * (window.y0 + window.y1);
    // A map of the window's aspect, up to rounding, covers the window exactly.
    if (std::abs(side - window.height()) > 1e-12 * window.height())
      fitted.y0 = middle - 0.5 * side, fitted.y1 = middle + 0.5 * side;
  } else {
    const double side = window.height() * map_aspect, middle = 0.5 * (window.x0 + window.x1);
    if (std::abs(side - window.width()) > 1e-12 * window.width())
      fitted.x0 = middle - 0.5 * side, fitted.x1 = middle + 0.5 * side;
  }
  return fitted;
}

Thinning Thinning::from_fitted_map(int width, int height, std::span<const float> texels, const Window& window,
                                   MapFit fit, double max_fraction) {
  const Window rectangle = fit_map_rectangle(window, width, height, fit);
  const bool pad_x = fit == MapFit::contain && (rectangle.x0 > window.x0 || rectangle.x1 < window.x1);
  const bool pad_y = fit == MapFit::contain && (rectangle.y0 > window.y0 || rectangle.y1 < window.y1);
  Thinning t = from_map(width, height, texels, rectangle, max_fraction);
  if (pad_x) t.support_.x0 = rectangle.x0, t.support_.x1 = rectangle.x1;
  if (pad_y) t.support_.y0 = rectangle.y0, t.support_.y1 = rectangle.y1;
  return t;
}

Thinning Thinning::uniform(double fraction) {
  check_fraction(fraction, "thinning fraction");
  Thinning t;
  t.fraction_ = fraction;
  return t;
}

void check_density_map(int width, int height, std::span<const float> texels) {
  if (width < 1 || height < 1 || texels.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    throw Error("density map: " + std::to_string(width) + " x " + std::to_string(height) + " texels but " +
                std::to_string(texels.size()) + " values");
  bool any_positive = false;
  for (std::size_t k = 0; k < texels.size(); ++k) {
    const float v = texels[k];
    if (!(std::isfinite(v) && v >= 0.0f))
      throw Error("density map: texel " + std::to_string(k % static_cast<std::size_t>(width)) + ", " +
                  std::to_string(k / static_cast<std::size_t>(width)) + " is " + exact_text(v) +
                  " (must be finite and >= 0)");
    any_positive = any_positive || v > 0.0f;
  }
  if (!any_positive) throw Error("density map is zero everywhere");
}

Thinning Thinning::from_map(int width, int height, std::span<const float> texels, const Window& rectangle,
                            double max_fraction) {
  check_fraction(max_fraction, "maximum density fraction");
  check_density_map(width, height, texels);
  check_map_rectangle(rectangle, "density map rectangle");
  float largest = 0.0f;
  for (float v : texels) largest = std::max(largest, v);
  Thinning t;
  t.fraction_ = max_fraction;
  t.width_ = width;
  t.height_ = height;
  t.rectangle_ = rectangle;
  t.grid_.resize(texels.size());
  double scale = max_fraction / largest;
  for (std::size_t k = 0; k < texels.size(); ++k) t.grid_[k] = static_cast<float>(texels[k] * scale);
  // Rounding the scaled texels to float may push the largest a hair above max_fraction.
  for (float& v : t.grid_) v = std::min(v, static_cast<float>(max_fraction));
  return t;
}

Thinning::Map Thinning::map() const {
  Map m;
  m.width = width_;
  m.height = height_;
  m.values = grid_.data();
  // Relative coordinate (x - x0) / w times width, minus a half: texel centres at integers.
  m.scale_x = width_ / rectangle_.width();
  m.offset_x = -rectangle_.x0 * m.scale_x - 0.5;
  m.scale_y = height_ / rectangle_.height();
  m.offset_y = -rectangle_.y0 * m.scale_y - 0.5;
  m.support = support_;
  return m;
}

double Thinning::fraction_at(Point p) const {
  if (constant()) return fraction_;
  return sample_map(map(), p);
}

Thinning::Bounds Thinning::fraction_bounds(const Window& box) const {
  if (constant()) return {fraction_, fraction_};
  // The closed box against the half-open support: outside it f is 0.
  const Window& s = support_;
  if (box.x1 < s.x0 || box.x0 >= s.x1 || box.y1 < s.y0 || box.y0 >= s.y1) return {0.0, 0.0};
  const bool inside = box.x0 >= s.x0 && box.x1 < s.x1 && box.y0 >= s.y0 && box.y1 < s.y1;
  Map m = map();
  // Bilinear values between texel columns c and c+1 stay between those texels: take every column
  // from the one left of the box's left edge to the one right of its right edge (clamped).
  auto span = [](double lo, double hi, int count) {
    lo = std::clamp(lo, 0.0, static_cast<double>(count - 1));
    hi = std::clamp(hi, 0.0, static_cast<double>(count - 1));
    int first = static_cast<int>(std::floor(lo));
    int last = std::min(count - 1, static_cast<int>(std::floor(hi)) + 1);
    return std::pair<int, int>(first, last);
  };
  auto [c0, c1] = span(box.x0 * m.scale_x + m.offset_x, box.x1 * m.scale_x + m.offset_x, width_);
  auto [r0, r1] = span(box.y0 * m.scale_y + m.offset_y, box.y1 * m.scale_y + m.offset_y, height_);
  float smallest = grid_[static_cast<std::size_t>(r0) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(c0)];
  float largest = smallest;
  for (int r = r0; r <= r1; ++r) {
    const float* row = grid_.data() + static_cast<std::ptrdiff_t>(r) * width_;
    for (int c = c0; c <= c1; ++c) smallest = std::min(smallest, row[c]), largest = std::max(largest, row[c]);
  }
  return {inside ? smallest : 0.0, largest};
}

double Thinning::dither(std::int64_t i, std::int64_t j, std::uint64_t seed) {
  std::uint64_t h = derive_seed(derive_seed(seed ^ kDitherStream, static_cast<std::uint64_t>(i)),
                                static_cast<std::uint64_t>(j));
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

}  // namespace bluetile
