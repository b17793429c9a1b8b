// Vector drawings, written as SVG 1.1 text (and drawn as PDF by pdf.h): a document with a view
// box holding rectangles, circles, lines, polylines, polygons, text, embedded raster images and
// nested groups, in the order they were added (later ones on top).
//
// What it guarantees:
// - The text is well-formed XML (UTF-8, one root <svg> element with the SVG namespace). Text
//   content is escaped (& < > " '); control characters XML forbids and bytes that are not valid
//   UTF-8 become '?'. Unclosed groups are closed by str().
// - Numbers are written in fixed point, never in exponent notation, locale-independent, with
//   `decimals()` digits after the point at most (trailing zeros trimmed; "-0" written as "0").
//   The default resolves a millionth of the view box's larger side (6 decimals for a unit view
//   box, 3 for 1000 units); set_decimals() changes it. A NaN or infinite coordinate, size or
//   width is refused with Error when it is added.
// - Colours are written #rrggbb (each channel clamped to [0, 1] and rounded to 8 bits).
// - Coordinates are user units of the view box: x to the right, y down (SVG's convention). A
//   group with SvgTransform::flip_y(...) draws a y-up drawing (points on the unit torus).
// - The same calls give the same bytes on every platform.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "bluetile/core/output_file.h"
#include "bluetile/core/torus.h"
#include "bluetile/io/image.h"

namespace bluetile {

// Fill or stroke of a shape: inherited from the enclosing group (the default; at the top level
// SVG's initial values apply: fill black, stroke none), none, or a colour.
class SvgPaint {
 public:
  SvgPaint() = default;                                      // inherited
  SvgPaint(Colour c) : kind_(Kind::colour), colour_(c) {}    // NOLINT: implicit on purpose
  static SvgPaint none() {
    SvgPaint p;
    p.kind_ = Kind::none;
    return p;
  }
  bool inherited() const { return kind_ == Kind::inherited; }
  bool is_none() const { return kind_ == Kind::none; }
  bool is_colour() const { return kind_ == Kind::colour; }
  Colour colour() const { return colour_; }
  bool operator==(const SvgPaint&) const = default;

 private:
  enum class Kind { inherited, none, colour };
  Kind kind_ = Kind::inherited;
  Colour colour_{};
};

// Presentation attributes of a shape or group. Absent values are inherited from the group.
struct SvgStyle {
  SvgPaint fill{};
  SvgPaint stroke{};
  std::optional<double> stroke_width{};  // user units
  std::optional<double> opacity{};       // [0, 1], multiplies the group's
  std::vector<double> dash{};            // stroke dash pattern (user units); empty: inherited/solid
  bool round_caps = false;               // round line caps and joins (else SVG's butt/miter)

  static SvgStyle filled(Colour c) { return {.fill = c, .stroke = SvgPaint::none()}; }
  static SvgStyle stroked(Colour c, double width) {
    return {.fill = SvgPaint::none(), .stroke = c, .stroke_width = width};
  }
  bool operator==(const SvgStyle&) const = default;
};

// An affine map x' = a x + c y + e, y' = b x + d y + f (SVG's matrix(a b c d e f)).
struct SvgTransform {
  double a = 1.0, b = 0.0, c = 0.0, d = 1.0, e = 0.0, f = 0.0;

  static SvgTransform translate(double x, double y) { return {1.0, 0.0, 0.0, 1.0, x, y}; }
  static SvgTransform scale(double sx, double sy) { return {sx, 0.0, 0.0, sy, 0.0, 0.0}; }
  // Maps the y-up rectangle [x, x + width] x [y, y + height] (domain units) onto the view-box
  // rectangle at (left, top) of size box_width x box_height (y down): for drawings of points.
  static SvgTransform fit_y_up(double x, double y, double width, double height, double left, double top,
                               double box_width, double box_height) {
    const double sx = box_width / width, sy = box_height / height;
    return {sx, 0.0, 0.0, -sy, left - x * sx, top + (y + height) * sy};
  }
  // This map after `inner`: (this * inner)(p) = this(inner(p)).
  SvgTransform operator*(const SvgTransform& inner) const {
    return {a * inner.a + c * inner.b, b * inner.a + d * inner.b, a * inner.c + c * inner.d,
            b * inner.c + d * inner.d, a * inner.e + c * inner.f + e, b * inner.e + d * inner.f + f};
  }
  Point apply(Point p) const { return {a * p.x + c * p.y + e, b * p.x + d * p.y + f}; }
  bool identity() const { return a == 1.0 && b == 0.0 && c == 0.0 && d == 1.0 && e == 0.0 && f == 0.0; }
  bool operator==(const SvgTransform&) const = default;
};

struct SvgText {
  double size = 12.0;  // font size, user units (the em box)
  Colour colour = colours::black;
  Align anchor = Align::start;  // horizontal: the anchor point is the text's start, centre or end
  bool bold = false;
  double rotate_degrees = 0.0;  // counter-clockwise on the page (90: reads bottom to top)
  bool operator==(const SvgText&) const = default;
};

// A raster image placed in the drawing (embedded as PNG). 1 (grey) or 3 (RGB) channels of 8
// bits, row 0 at the top; `smooth` false keeps pixels crisp when enlarged (a periodogram).
struct SvgImage {
  int width = 0, height = 0, channels = 1;
  std::vector<std::uint8_t> pixels;
  bool smooth = false;
};

// Receives a document's content in order (SvgDocument::visit); the SVG writer and the PDF
// renderer are two of them. Coordinates are the document's user units, before any group
// transforms (which come with begin_group).
class SvgVisitor {
 public:
  virtual ~SvgVisitor() = default;
  virtual void begin_group(const SvgStyle& style, const SvgTransform& transform) = 0;
  virtual void end_group() = 0;
  virtual void rect(double x, double y, double width, double height, const SvgStyle& style) = 0;
  virtual void circle(Point centre, double radius, const SvgStyle& style) = 0;
  virtual void line(Point a, Point b, const SvgStyle& style) = 0;
  // closed: a polygon (last vertex joined to the first).
  virtual void polyline(std::span<const Point> points, bool closed, const SvgStyle& style) = 0;
  // Baseline at `at`, before rotation about `at`.
  virtual void text(Point at, std::string_view text, const SvgText& style) = 0;
  virtual void image(double x, double y, double width, double height, const SvgImage& image) = 0;
};

class SvgDocument {
 public:
  // The view box [x, x + width] x [y, y + height] in user units, shown as `display_width` x
  // `display_height` in `unit` ("px", "pt", "mm", "cm", "in", or "" for user units). Throws
  // Error unless the sizes are positive and finite and the unit is one of those.
  SvgDocument(double x, double y, double width, double height, double display_width, double display_height,
              std::string unit = "");
  // View box [0, width] x [0, height], shown at that size in px.
  SvgDocument(double width, double height);

  double view_x() const { return view_[0]; }
  double view_y() const { return view_[1]; }
  double width() const { return view_[2]; }   // of the view box, user units
  double height() const { return view_[3]; }
  double display_width() const { return display_[0]; }
  double display_height() const { return display_[1]; }
  const std::string& unit() const { return unit_; }
  int decimals() const { return decimals_; }
  void set_decimals(int decimals);  // 0 to 12
  void set_title(std::string title);  // <title>: what viewers show as the name

  // Shapes. Throw Error for a non-finite coordinate, a negative size or radius.
  void rect(double x, double y, double width, double height, const SvgStyle& style = {});
  void circle(Point centre, double radius, const SvgStyle& style = {});
  void line(Point a, Point b, const SvgStyle& style = {});
  void polyline(std::span<const Point> points, const SvgStyle& style = {});
  void polygon(std::span<const Point> points, const SvgStyle& style = {});
  void text(Point at, std::string_view text, const SvgText& style = {});
  // Throws Error unless the pixel count matches width x height x channels (1 or 3).
  void image(double x, double y, double width, double height, SvgImage image);

  // Everything added until the matching end_group() inherits `style` and is mapped by
  // `transform` (after the transforms of enclosing groups). end_group() without an open
  // group throws Error.
  void begin_group(const SvgStyle& style = {}, const SvgTransform& transform = {});
  void end_group();

  // Adds the content of `other` (not its view box or title) as one group mapped by
  // `transform`: for composing a page from drawings made on their own.
  void include(const SvgDocument& other, const SvgTransform& transform = {});

  // The content in order, to another renderer. Unclosed groups are closed at the end.
  void visit(SvgVisitor& visitor) const;
  // The SVG text.
  std::string str() const;
  // Writes str() to `path` atomically; throws Error naming the path on failure.
  void write(const std::string& path) const;
  // Writes str() to `out`, with the items `more` draws into the visitor it is given appended after
  // the document's own, inside its open groups: the bytes str() gives when the same items are
  // added to the document, written as they are drawn (a drawing too large to hold, 10^8 dots,
  // in bounded memory). Throws Error naming the output on a failed write.
  void write(OutputStream& out, const std::function<void(SvgVisitor& more)>& more = {}) const;

  // Number formatting used by str(), for tests and other writers: fixed point, at most
  // `decimals` digits after the point, trailing zeros trimmed, no "-0".
  static std::string format_number(double value, int decimals);

 private:
  enum class Kind : std::uint8_t { begin_group, end_group, rect, circle, line, polyline, polygon, text, image };
  struct Item {
    Kind kind;
    std::uint32_t style;  // index into styles_ (text: into texts_)
    std::uint32_t first;  // index into numbers_ (begin_group: into transforms_)
    std::uint32_t count;  // numbers used (text: bytes of strings_; image: index into images_)
  };
  std::uint32_t intern(const SvgStyle& style);
  void add(Kind kind, const SvgStyle& style, std::initializer_list<double> numbers);
  void check_finite(std::initializer_list<double> values, const char* what) const;
  void visit_items(SvgVisitor& visitor) const;  // without closing the open groups
  void append_head(std::string& out) const;     // the XML declaration, <svg ...> and the title

  double view_[4];
  double display_[2];
  std::string unit_;
  int decimals_ = 6;
  std::string title_;
  int open_groups_ = 0;
  std::vector<Item> items_;
  std::vector<double> numbers_;
  std::vector<SvgStyle> styles_;
  std::vector<SvgText> texts_;
  std::vector<SvgTransform> transforms_;
  std::string strings_;
  std::vector<SvgImage> images_;
};

}  // namespace bluetile
