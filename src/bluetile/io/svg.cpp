// SVG 1.1 (W3C Recommendation, 2011) writer. Embedded images are PNG (png_encoder.h) in
// base64 data URIs.
#include "bluetile/io/svg.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "bluetile/core/error.h"
#include "bluetile/core/output_file.h"
#include "bluetile/io/png_encoder.h"

namespace bluetile {
namespace {

constexpr const char* kFontFamily = "DejaVu Sans, Helvetica, Arial, sans-serif";

void append_colour(std::string& out, Colour c) {
  static constexpr char hex[] = "0123456789abcdef";
  out += '#';
  for (float v : {c.r, c.g, c.b}) {
    const int byte = static_cast<int>(std::lround(std::clamp(static_cast<double>(v), 0.0, 1.0) * 255.0));
    out += hex[byte >> 4];
    out += hex[byte & 15];
  }
}

// Appends s with XML's five special characters escaped, forbidden control characters and
// invalid UTF-8 replaced by '?'.
void append_escaped(std::string& out, std::string_view s) {
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        case '\'': out += "&apos;"; break;
        default: out += (c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f ? '?' : static_cast<char>(c);
      }
      ++i;
      continue;
    }
    // A UTF-8 sequence: lead byte, then 1-3 continuation bytes; overlong forms, surrogates and
    // code points above U+10FFFF are invalid.
    const int length = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 ? 2 : 0;
    bool valid = length > 0 && c < 0xf5 && i + static_cast<std::size_t>(length) <= s.size();
    std::uint32_t code = length == 4 ? c & 0x07u : length == 3 ? c & 0x0fu : c & 0x1fu;
    for (int k = 1; valid && k < length; ++k) {
      const auto next = static_cast<unsigned char>(s[i + static_cast<std::size_t>(k)]);
      valid = (next & 0xc0) == 0x80;
      code = (code << 6) | (next & 0x3fu);
    }
    if (valid) {
      valid = !(length == 3 && (code < 0x800 || (code >= 0xd800 && code <= 0xdfff) || code == 0xfffe || code == 0xffff)) &&
              !(length == 4 && (code < 0x10000 || code > 0x10ffff));
    }
    if (valid) {
      out.append(s.substr(i, static_cast<std::size_t>(length)));
      i += static_cast<std::size_t>(length);
    } else {
      out += '?';
      ++i;
    }
  }
}

void append_base64(std::string& out, const std::vector<std::uint8_t>& bytes) {
  static constexpr char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const std::uint32_t v = (std::uint32_t{bytes[i]} << 16) | (std::uint32_t{bytes[i + 1]} << 8) | bytes[i + 2];
    for (int shift = 18; shift >= 0; shift -= 6) out += digits[(v >> shift) & 63];
  }
  if (i + 1 == bytes.size()) {
    const std::uint32_t v = std::uint32_t{bytes[i]} << 16;
    out += digits[(v >> 18) & 63];
    out += digits[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == bytes.size()) {
    const std::uint32_t v = (std::uint32_t{bytes[i]} << 16) | (std::uint32_t{bytes[i + 1]} << 8);
    out += digits[(v >> 18) & 63];
    out += digits[(v >> 12) & 63];
    out += digits[(v >> 6) & 63];
    out += '=';
  }
}

// Serialises a document as SVG text.
class SvgWriter final : public SvgVisitor {
 public:
  // With `stream`, the text gathered in `out` goes there whenever it passes kSpillBytes.
  SvgWriter(std::string& out, int decimals, OutputStream* stream = nullptr)
      : out_(out), decimals_(decimals), stream_(stream) {}

  void begin_group(const SvgStyle& style, const SvgTransform& t) override {
    out_ += "<g";
    attributes(style);
    if (!t.identity()) {
      out_ += " transform=\"matrix(";
      const double values[6] = {t.a, t.b, t.c, t.d, t.e, t.f};
      for (int k = 0; k < 6; ++k) {
        if (k) out_ += ' ';
        // Matrix entries scale coordinates: keep more digits than the coordinates have.
        number(values[k], std::max(decimals_, 9));
      }
      out_ += ")\"";
    }
    out_ += ">\n";
    spill();
  }
  void end_group() override {
    out_ += "</g>\n";
    spill();
  }
  void rect(double x, double y, double width, double height, const SvgStyle& style) override {
    out_ += "<rect";
    attribute("x", x), attribute("y", y), attribute("width", width), attribute("height", height);
    close(style);
  }
  void circle(Point centre, double radius, const SvgStyle& style) override {
    out_ += "<circle";
    attribute("cx", centre.x), attribute("cy", centre.y), attribute("r", radius);
    close(style);
  }
  void line(Point a, Point b, const SvgStyle& style) override {
    out_ += "<line";
    attribute("x1", a.x), attribute("y1", a.y), attribute("x2", b.x), attribute("y2", b.y);
    close(style);
  }
  void polyline(std::span<const Point> points, bool closed, const SvgStyle& style) override {
    out_ += closed ? "<polygon points=\"" : "<polyline points=\"";
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (i) out_ += ' ';
      number(points[i].x, decimals_);
      out_ += ',';
      number(points[i].y, decimals_);
    }
    out_ += '"';
    close(style);
  }
  void text(Point at, std::string_view s, const SvgText& style) override {
    out_ += "<text";
    attribute("x", at.x), attribute("y", at.y);
    out_ += " font-family=\"";
    out_ += kFontFamily;
    out_ += '"';
    attribute("font-size", style.size);
    if (style.bold) out_ += " font-weight=\"bold\"";
    out_ += " fill=\"";
    append_colour(out_, style.colour);
    out_ += '"';
    if (style.anchor != Align::start) out_ += style.anchor == Align::centre ? " text-anchor=\"middle\"" : " text-anchor=\"end\"";
    if (style.rotate_degrees != 0.0) {
      // SVG rotates clockwise with y down; the style's angle is counter-clockwise on the page.
      out_ += " transform=\"rotate(";
      number(-style.rotate_degrees, 6);
      out_ += ' ';
      number(at.x, decimals_);
      out_ += ' ';
      number(at.y, decimals_);
      out_ += ")\"";
    }
    out_ += '>';
    append_escaped(out_, s);
    out_ += "</text>\n";
    spill();
  }
  void image(double x, double y, double width, double height, const SvgImage& image) override {
    out_ += "<image";
    attribute("x", x), attribute("y", y), attribute("width", width), attribute("height", height);
    out_ += " preserveAspectRatio=\"none\"";
    if (!image.smooth) out_ += " image-rendering=\"optimizeSpeed\" style=\"image-rendering:pixelated\"";
    out_ += " xlink:href=\"data:image/png;base64,";
    append_base64(out_, encode_png(image));
    out_ += "\"/>\n";
    spill();
  }

 private:
  void number(double v, int decimals) { out_ += SvgDocument::format_number(v, decimals); }
  void attribute(const char* name, double v) {
    out_ += ' ';
    out_ += name;
    out_ += "=\"";
    number(v, decimals_);
    out_ += '"';
  }
  void paint(const char* name, const SvgPaint& p) {
    if (p.inherited()) return;
    out_ += ' ';
    out_ += name;
    out_ += "=\"";
    if (p.is_none()) out_ += "none";
    else append_colour(out_, p.colour());
    out_ += '"';
  }
  void attributes(const SvgStyle& s) {
    paint("fill", s.fill);
    paint("stroke", s.stroke);
    if (s.stroke_width) attribute("stroke-width", *s.stroke_width);
    if (s.opacity) {
      out_ += " opacity=\"";
      number(*s.opacity, 4);
      out_ += '"';
    }
    if (!s.dash.empty()) {
      out_ += " stroke-dasharray=\"";
      for (std::size_t i = 0; i < s.dash.size(); ++i) {
        if (i) out_ += ' ';
        number(s.dash[i], decimals_);
      }
      out_ += '"';
    }
    if (s.round_caps) out_ += " stroke-linecap=\"round\" stroke-linejoin=\"round\"";
  }
  void close(const SvgStyle& style) {
    attributes(style);
    out_ += "/>\n";
    spill();
  }
  void spill() {
    if (stream_ == nullptr || out_.size() < kSpillBytes) return;
    stream_->write(out_);
    out_.clear();
  }

  // Text gathered before a write to the stream: large enough that writes are few.
  static constexpr std::size_t kSpillBytes = 1 << 16;
  std::string& out_;
  int decimals_;
  OutputStream* stream_;
};

bool known_unit(const std::string& unit) {
  return unit.empty() || unit == "px" || unit == "pt" || unit == "mm" || unit == "cm" || unit == "in";
}

}  // namespace

SvgDocument::SvgDocument(double x, double y, double width, double height, double display_width,
                         double display_height, std::string unit)
    : view_{x, y, width, height}, display_{display_width, display_height}, unit_(std::move(unit)) {
  for (double v : {x, y, width, height, display_width, display_height})
    if (!std::isfinite(v)) throw Error("SVG document: view box and display size must be finite");
  if (!(width > 0.0 && height > 0.0 && display_width > 0.0 && display_height > 0.0))
    throw Error("SVG document: view box and display size must be positive");
  if (!known_unit(unit_)) throw Error("SVG document: unknown unit '" + unit_ + "' (px, pt, mm, cm, in or none)");
  // A millionth of the larger side, in whole decimals.
  const double larger = std::max(width, height);
  decimals_ = std::clamp(static_cast<int>(std::ceil(6.0 - std::log10(larger))), 0, 12);
}

SvgDocument::SvgDocument(double width, double height) : SvgDocument(0.0, 0.0, width, height, width, height, "px") {}

void SvgDocument::set_decimals(int decimals) {
  if (decimals < 0 || decimals > 12) throw Error("SVG document: decimals must be 0 to 12");
  decimals_ = decimals;
}

void SvgDocument::set_title(std::string title) { title_ = std::move(title); }

std::string SvgDocument::format_number(double value, int decimals) {
  char buffer[64];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals);
  if (ec != std::errc()) return "0";  // beyond 1e50: no drawing has such coordinates
  std::string_view s(buffer, static_cast<std::size_t>(end - buffer));
  if (s.find('.') != std::string_view::npos) {
    while (s.back() == '0') s.remove_suffix(1);
    if (s.back() == '.') s.remove_suffix(1);
  }
  if (s == "-0") return "0";
  return std::string(s);
}

void SvgDocument::check_finite(std::initializer_list<double> values, const char* what) const {
  for (double v : values)
    if (!std::isfinite(v)) throw Error(std::string("SVG document: ") + what + " has a coordinate that is not finite");
}

std::uint32_t SvgDocument::intern(const SvgStyle& style) {
  if (style.stroke_width && (!std::isfinite(*style.stroke_width) || *style.stroke_width < 0.0))
    throw Error("SVG document: stroke width must be finite and >= 0");
  if (style.opacity && !(*style.opacity >= 0.0 && *style.opacity <= 1.0))
    throw Error("SVG document: opacity must be in [0, 1]");
  for (double d : style.dash)
    if (!std::isfinite(d) || d < 0.0) throw Error("SVG document: dash lengths must be finite and >= 0");
  // Drawings use a handful of styles: a linear search from the most recent is enough.
  for (std::size_t i = styles_.size(); i-- > 0;)
    if (styles_[i] == style) return static_cast<std::uint32_t>(i);
  styles_.push_back(style);
  return static_cast<std::uint32_t>(styles_.size() - 1);
}

void SvgDocument::add(Kind kind, const SvgStyle& style, std::initializer_list<double> numbers) {
  const std::uint32_t s = intern(style);
  items_.push_back({kind, s, static_cast<std::uint32_t>(numbers_.size()), static_cast<std::uint32_t>(numbers.size())});
  numbers_.insert(numbers_.end(), numbers);
}

void SvgDocument::rect(double x, double y, double width, double height, const SvgStyle& style) {
  check_finite({x, y, width, height}, "rectangle");
  if (width < 0.0 || height < 0.0) throw Error("SVG document: rectangle with a negative size");
  add(Kind::rect, style, {x, y, width, height});
}

void SvgDocument::circle(Point centre, double radius, const SvgStyle& style) {
  check_finite({centre.x, centre.y, radius}, "circle");
  if (radius < 0.0) throw Error("SVG document: circle with a negative radius");
  add(Kind::circle, style, {centre.x, centre.y, radius});
}

void SvgDocument::line(Point a, Point b, const SvgStyle& style) {
  check_finite({a.x, a.y, b.x, b.y}, "line");
  add(Kind::line, style, {a.x, a.y, b.x, b.y});
}

void SvgDocument::polyline(std::span<const Point> points, const SvgStyle& style) {
  for (const Point& p : points) check_finite({p.x, p.y}, "polyline");
  add(Kind::polyline, style, {});
  for (const Point& p : points) numbers_.push_back(p.x), numbers_.push_back(p.y);
  items_.back().count = static_cast<std::uint32_t>(2 * points.size());
}

void SvgDocument::polygon(std::span<const Point> points, const SvgStyle& style) {
  polyline(points, style);
  items_.back().kind = Kind::polygon;
}

void SvgDocument::text(Point at, std::string_view text, const SvgText& style) {
  check_finite({at.x, at.y, style.size, style.rotate_degrees}, "text");
  if (!(style.size > 0.0)) throw Error("SVG document: font size must be positive");
  std::uint32_t s = 0;
  for (std::size_t i = texts_.size(); i-- > 0;) {
    if (texts_[i] == style) {
      s = static_cast<std::uint32_t>(i) + 1;
      break;
    }
  }
  if (s == 0) texts_.push_back(style), s = static_cast<std::uint32_t>(texts_.size());
  items_.push_back({Kind::text, s - 1, static_cast<std::uint32_t>(numbers_.size()), static_cast<std::uint32_t>(text.size())});
  numbers_.push_back(at.x), numbers_.push_back(at.y);
  numbers_.push_back(static_cast<double>(strings_.size()));
  strings_.append(text);
}

void SvgDocument::image(double x, double y, double width, double height, SvgImage image) {
  check_finite({x, y, width, height}, "image");
  if (width < 0.0 || height < 0.0) throw Error("SVG document: image with a negative size");
  if ((image.channels != 1 && image.channels != 3) || image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) *
                                  static_cast<std::size_t>(image.channels))
    throw Error("SVG document: image pixels do not match its size and channels (1 or 3)");
  items_.push_back({Kind::image, 0, static_cast<std::uint32_t>(numbers_.size()), static_cast<std::uint32_t>(images_.size())});
  numbers_.insert(numbers_.end(), {x, y, width, height});
  images_.push_back(std::move(image));
}

void SvgDocument::begin_group(const SvgStyle& style, const SvgTransform& transform) {
  check_finite({transform.a, transform.b, transform.c, transform.d, transform.e, transform.f}, "group transform");
  const std::uint32_t s = intern(style);
  items_.push_back({Kind::begin_group, s, static_cast<std::uint32_t>(transforms_.size()), 0});
  transforms_.push_back(transform);
  ++open_groups_;
}

void SvgDocument::end_group() {
  if (open_groups_ == 0) throw Error("SVG document: end_group without begin_group");
  --open_groups_;
  items_.push_back({Kind::end_group, 0, 0, 0});
}

namespace {

// Re-adds what it visits to another document.
class Copier final : public SvgVisitor {
 public:
  explicit Copier(SvgDocument& target) : target_(target) {}
  void begin_group(const SvgStyle& style, const SvgTransform& transform) override { target_.begin_group(style, transform); }
  void end_group() override { target_.end_group(); }
  void rect(double x, double y, double width, double height, const SvgStyle& style) override {
    target_.rect(x, y, width, height, style);
  }
  void circle(Point centre, double radius, const SvgStyle& style) override { target_.circle(centre, radius, style); }
  void line(Point a, Point b, const SvgStyle& style) override { target_.line(a, b, style); }
  void polyline(std::span<const Point> points, bool closed, const SvgStyle& style) override {
    if (closed) target_.polygon(points, style);
    else target_.polyline(points, style);
  }
  void text(Point at, std::string_view text, const SvgText& style) override { target_.text(at, text, style); }
  void image(double x, double y, double width, double height, const SvgImage& image) override {
    target_.image(x, y, width, height, image);
  }

 private:
  SvgDocument& target_;
};

}  // namespace

void SvgDocument::include(const SvgDocument& other, const SvgTransform& transform) {
  if (&other == this) throw Error("SVG document: cannot include itself");
  begin_group({}, transform);
  Copier copier(*this);
  other.visit(copier);
  end_group();
}

void SvgDocument::visit(SvgVisitor& visitor) const {
  visit_items(visitor);
  for (int g = 0; g < open_groups_; ++g) visitor.end_group();
}

void SvgDocument::visit_items(SvgVisitor& visitor) const {
  for (const Item& item : items_) {
    const double* v = numbers_.data() + item.first;
    switch (item.kind) {
      case Kind::begin_group: visitor.begin_group(styles_[item.style], transforms_[item.first]); break;
      case Kind::end_group: visitor.end_group(); break;
      case Kind::rect: visitor.rect(v[0], v[1], v[2], v[3], styles_[item.style]); break;
      case Kind::circle: visitor.circle({v[0], v[1]}, v[2], styles_[item.style]); break;
      case Kind::line: visitor.line({v[0], v[1]}, {v[2], v[3]}, styles_[item.style]); break;
      case Kind::polyline:
      case Kind::polygon: {
        std::vector<Point> points(item.count / 2);
        for (std::size_t i = 0; i < points.size(); ++i) points[i] = {v[2 * i], v[2 * i + 1]};
        visitor.polyline(points, item.kind == Kind::polygon, styles_[item.style]);
        break;
      }
      case Kind::text:
        visitor.text({v[0], v[1]}, std::string_view(strings_).substr(static_cast<std::size_t>(v[2]), item.count),
                     texts_[item.style]);
        break;
      case Kind::image: visitor.image(v[0], v[1], v[2], v[3], images_[item.count]); break;
    }
  }
}

void SvgDocument::append_head(std::string& out) const {
  out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" version=\"1.1\"";
  auto size = [&](const char* name, double v) {
    out += ' ';
    out += name;
    out += "=\"";
    out += format_number(v, 6);
    out += unit_;
    out += '"';
  };
  size("width", display_[0]);
  size("height", display_[1]);
  out += " viewBox=\"";
  for (int k = 0; k < 4; ++k) {
    if (k) out += ' ';
    out += format_number(view_[k], std::max(decimals_, 6));
  }
  out += "\">\n";
  if (!title_.empty()) {
    out += "<title>";
    append_escaped(out, title_);
    out += "</title>\n";
  }
}

std::string SvgDocument::str() const {
  std::string out;
  out.reserve(256 + items_.size() * 48);
  append_head(out);
  SvgWriter writer(out, decimals_);
  visit(writer);
  out += "</svg>\n";
  return out;
}

void SvgDocument::write(OutputStream& out, const std::function<void(SvgVisitor& more)>& more) const {
  std::string text;
  append_head(text);
  SvgWriter writer(text, decimals_, &out);
  visit_items(writer);
  if (more) more(writer);
  for (int g = 0; g < open_groups_; ++g) writer.end_group();
  text += "</svg>\n";
  out.write(text);
}

void SvgDocument::write(const std::string& path) const { write_output(path, str()); }

}  // namespace bluetile
