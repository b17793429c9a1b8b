// PDF through cairo (cairographics.org), opened at run time: the only file that uses cairo.
#include "bluetile/io/pdf.h"

#include <cmath>
#include <cstring>
#include <exception>
#include <mutex>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <dlfcn.h>

#include "bluetile/core/error.h"
#include "bluetile/core/process_limits.h"

#if BLUETILE_HAVE_CAIRO
#include <cairo-pdf.h>
#include <cairo.h>
#endif

namespace bluetile {

#if BLUETILE_HAVE_CAIRO
namespace {

// `text` as valid UTF-8, which cairo requires of every string it draws: each byte that does not
// begin a well-formed sequence becomes U+FFFD. Valid text comes back unchanged.
std::string valid_utf8(std::string_view text) {
  std::string result;
  result.reserve(text.size());
  auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  auto continuation = [&](std::size_t i, unsigned char low = 0x80, unsigned char high = 0xBF) {
    return i < text.size() && byte(i) >= low && byte(i) <= high;
  };
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char b = byte(i);
    std::size_t length = 0;
    if (b < 0x80) length = 1;
    else if (b >= 0xC2 && b <= 0xDF) length = continuation(i + 1) ? 2 : 0;
    else if (b >= 0xE0 && b <= 0xEF)
      length = continuation(i + 1, b == 0xE0 ? 0xA0 : 0x80, b == 0xED ? 0x9F : 0xBF) && continuation(i + 2) ? 3 : 0;
    else if (b >= 0xF0 && b <= 0xF4)
      length = continuation(i + 1, b == 0xF0 ? 0x90 : 0x80, b == 0xF4 ? 0x8F : 0xBF) && continuation(i + 2) &&
                       continuation(i + 3)
                   ? 4
                   : 0;
    if (length == 0) {
      result += "\xEF\xBF\xBD";
      ++i;
    } else {
      result.append(text.substr(i, length));
      i += length;
    }
  }
  return result;
}

// The cairo functions used, looked up by name in libcairo.so.2.
#define BLUETILE_CAIRO_FUNCTIONS(X)                                                                                \
  X(cairo_pdf_surface_create_for_stream) X(cairo_create) X(cairo_destroy) X(cairo_status)                          \
  X(cairo_status_to_string) X(cairo_surface_destroy) X(cairo_surface_finish) X(cairo_surface_status)               \
  X(cairo_surface_flush) X(cairo_surface_mark_dirty) X(cairo_save) X(cairo_restore) X(cairo_transform)             \
  X(cairo_scale) X(cairo_translate) X(cairo_rotate) X(cairo_rectangle) X(cairo_arc) X(cairo_new_path)              \
  X(cairo_new_sub_path) X(cairo_move_to) X(cairo_line_to) X(cairo_close_path) X(cairo_set_source_rgba)             \
  X(cairo_fill_preserve) X(cairo_stroke_preserve) X(cairo_set_line_width) X(cairo_set_dash)                        \
  X(cairo_set_line_cap) X(cairo_set_line_join) X(cairo_select_font_face) X(cairo_set_font_size)                    \
  X(cairo_text_extents) X(cairo_show_text) X(cairo_image_surface_create) X(cairo_image_surface_get_data)           \
  X(cairo_image_surface_get_stride) X(cairo_set_source_surface) X(cairo_get_source) X(cairo_pattern_set_filter)    \
  X(cairo_paint) X(cairo_show_page) X(cairo_pdf_surface_set_metadata)

struct Cairo {
#define BLUETILE_CAIRO_MEMBER(name) decltype(&::name) name = nullptr;
  BLUETILE_CAIRO_FUNCTIONS(BLUETILE_CAIRO_MEMBER)
#undef BLUETILE_CAIRO_MEMBER
  std::string failure;
};

const Cairo& cairo() {
  static Cairo c;
  static std::once_flag once;
  std::call_once(once, [] {
    void* handle = dlopen("libcairo.so.2", RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      c.failure = std::string("PDF output needs cairo (libcairo2): ") + dlerror();
      // cairo and the X libraries it pulls in are there but do not fit ("failed to map segment").
      if (const std::optional<ProcessLimit> limit = address_space_limit())
        c.failure += ": out of memory for it under the limit (ulimit -v " + std::to_string(limit->limit >> 10) +
                     ", " + std::to_string(limit->left() >> 20) + " MiB left); raise the limit";
      return;
    }
#define BLUETILE_CAIRO_LOOKUP(name)                                                   \
  c.name = reinterpret_cast<decltype(&::name)>(dlsym(handle, #name));                 \
  if (!c.name && c.failure.empty()) c.failure = "libcairo.so.2 lacks " #name;
    BLUETILE_CAIRO_FUNCTIONS(BLUETILE_CAIRO_LOOKUP)
#undef BLUETILE_CAIRO_LOOKUP
  });
  return c;
}

// Points per unit of the document's display size.
double points_per(const std::string& unit) {
  if (unit == "pt") return 1.0;
  if (unit == "mm") return 72.0 / 25.4;
  if (unit == "cm") return 72.0 / 2.54;
  if (unit == "in") return 72.0;
  return 0.75;  // px and user units: CSS's 96 px per inch
}

// The style in force: SVG's initial values, then each group's and shape's own.
struct Effective {
  SvgPaint fill = colours::black;
  SvgPaint stroke = SvgPaint::none();
  double stroke_width = 1.0;
  double opacity = 1.0;
  std::vector<double> dash;
  bool round_caps = false;

  Effective with(const SvgStyle& s) const {
    Effective e = *this;
    if (!s.fill.inherited()) e.fill = s.fill;
    if (!s.stroke.inherited()) e.stroke = s.stroke;
    if (s.stroke_width) e.stroke_width = *s.stroke_width;
    if (s.opacity) e.opacity *= *s.opacity;
    if (!s.dash.empty()) e.dash = s.dash;
    if (s.round_caps) e.round_caps = true;
    return e;
  }
};

class PdfPainter final : public SvgVisitor {
 public:
  PdfPainter(const Cairo& c, cairo_t* cr) : c_(c), cr_(cr) { styles_.push_back({}); }

  void begin_group(const SvgStyle& style, const SvgTransform& t) override {
    c_.cairo_save(cr_);
    cairo_matrix_t m{t.a, t.b, t.c, t.d, t.e, t.f};
    c_.cairo_transform(cr_, &m);
    styles_.push_back(styles_.back().with(style));
  }
  void end_group() override {
    c_.cairo_restore(cr_);
    styles_.pop_back();
  }
  void rect(double x, double y, double width, double height, const SvgStyle& style) override {
    c_.cairo_rectangle(cr_, x, y, width, height);
    paint(style, true);
  }
  void circle(Point centre, double radius, const SvgStyle& style) override {
    c_.cairo_new_sub_path(cr_);
    c_.cairo_arc(cr_, centre.x, centre.y, radius, 0.0, 2.0 * std::numbers::pi);
    paint(style, true);
  }
  void line(Point a, Point b, const SvgStyle& style) override {
    c_.cairo_move_to(cr_, a.x, a.y);
    c_.cairo_line_to(cr_, b.x, b.y);
    paint(style, false);
  }
  void polyline(std::span<const Point> points, bool closed, const SvgStyle& style) override {
    if (points.empty()) return;
    c_.cairo_move_to(cr_, points[0].x, points[0].y);
    for (std::size_t i = 1; i < points.size(); ++i) c_.cairo_line_to(cr_, points[i].x, points[i].y);
    if (closed) c_.cairo_close_path(cr_);
    paint(style, true);
  }
  void text(Point at, std::string_view s, const SvgText& style) override {
    const std::string text = valid_utf8(s);
    c_.cairo_select_font_face(cr_, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                              style.bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    c_.cairo_set_font_size(cr_, style.size);
    cairo_text_extents_t extents;
    c_.cairo_text_extents(cr_, text.c_str(), &extents);
    const double shift = style.anchor == Align::start ? 0.0 : style.anchor == Align::centre ? 0.5 * extents.x_advance
                                                                                            : extents.x_advance;
    c_.cairo_save(cr_);
    c_.cairo_translate(cr_, at.x, at.y);
    c_.cairo_rotate(cr_, -style.rotate_degrees * std::numbers::pi / 180.0);  // counter-clockwise on the page
    c_.cairo_move_to(cr_, -shift, 0.0);
    c_.cairo_set_source_rgba(cr_, style.colour.r, style.colour.g, style.colour.b, styles_.back().opacity);
    c_.cairo_show_text(cr_, text.c_str());
    c_.cairo_new_path(cr_);
    c_.cairo_restore(cr_);
  }
  void image(double x, double y, double width, double height, const SvgImage& image) override {
    cairo_surface_t* surface = c_.cairo_image_surface_create(CAIRO_FORMAT_RGB24, image.width, image.height);
    c_.cairo_surface_flush(surface);
    unsigned char* data = c_.cairo_image_surface_get_data(surface);
    const int stride = c_.cairo_image_surface_get_stride(surface);
    if (!data) {
      c_.cairo_surface_destroy(surface);
      throw Error("cairo could not make a " + std::to_string(image.width) + "x" + std::to_string(image.height) + " image");
    }
    for (int j = 0; j < image.height; ++j) {
      auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(j) * stride);
      for (int i = 0; i < image.width; ++i) {
        const std::size_t at = (static_cast<std::size_t>(j) * static_cast<std::size_t>(image.width) +
                                static_cast<std::size_t>(i)) * static_cast<std::size_t>(image.channels);
        const std::uint32_t r = image.pixels[at];
        const std::uint32_t g = image.channels == 3 ? image.pixels[at + 1] : r;
        const std::uint32_t b = image.channels == 3 ? image.pixels[at + 2] : r;
        row[i] = (r << 16) | (g << 8) | b;  // CAIRO_FORMAT_RGB24: native-endian xRGB
      }
    }
    c_.cairo_surface_mark_dirty(surface);
    c_.cairo_save(cr_);
    c_.cairo_translate(cr_, x, y);
    c_.cairo_scale(cr_, width / image.width, height / image.height);
    c_.cairo_set_source_surface(cr_, surface, 0.0, 0.0);
    c_.cairo_pattern_set_filter(c_.cairo_get_source(cr_), image.smooth ? CAIRO_FILTER_GOOD : CAIRO_FILTER_NEAREST);
    c_.cairo_paint(cr_);
    c_.cairo_restore(cr_);
    c_.cairo_surface_destroy(surface);
  }

 private:
  // Fills (closed shapes) and strokes the current path with the effective style, then clears it.
  void paint(const SvgStyle& own, bool fillable) {
    const Effective e = styles_.back().with(own);
    if (fillable && e.fill.is_colour()) {
      const Colour col = e.fill.colour();
      c_.cairo_set_source_rgba(cr_, col.r, col.g, col.b, e.opacity);
      c_.cairo_fill_preserve(cr_);
    }
    if (e.stroke.is_colour() && e.stroke_width > 0.0) {
      const Colour col = e.stroke.colour();
      c_.cairo_set_source_rgba(cr_, col.r, col.g, col.b, e.opacity);
      c_.cairo_set_line_width(cr_, e.stroke_width);
      c_.cairo_set_dash(cr_, e.dash.data(), static_cast<int>(e.dash.size()), 0.0);
      c_.cairo_set_line_cap(cr_, e.round_caps ? CAIRO_LINE_CAP_ROUND : CAIRO_LINE_CAP_BUTT);
      c_.cairo_set_line_join(cr_, e.round_caps ? CAIRO_LINE_JOIN_ROUND : CAIRO_LINE_JOIN_MITER);
      c_.cairo_stroke_preserve(cr_);
    }
    c_.cairo_new_path(cr_);
  }

  const Cairo& c_;
  cairo_t* cr_;
  std::vector<Effective> styles_;
};

// cairo's write callback: the bytes into the output's checked stream. A failed write is kept (its
// Error names the user's path) and reported to cairo, which then stops writing.
struct PdfSink {
  OutputStream* stream;
  std::exception_ptr failed;
};

cairo_status_t write_to_sink(void* closure, const unsigned char* data, unsigned int length) {
  auto* sink = static_cast<PdfSink*>(closure);
  if (sink->failed) return CAIRO_STATUS_WRITE_ERROR;
  try {
    sink->stream->write(data, length);
  } catch (...) {
    sink->failed = std::current_exception();
    return CAIRO_STATUS_WRITE_ERROR;
  }
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

std::string pdf_unavailable_reason() { return cairo().failure; }

void write_pdf(const SvgDocument& document, OutputFile& out) {
  const std::string& path = out.path();
  const Cairo& c = cairo();
  if (!c.failure.empty()) throw Error(path + ": " + c.failure);
  const double scale = points_per(document.unit());
  const double width_pt = document.display_width() * scale, height_pt = document.display_height() * scale;
  // Straight into the output (a staged file, or a device, FIFO or standard output itself): no
  // temporary copy of the document anywhere.
  out.write([&](OutputStream& stream) {
    PdfSink sink{&stream, nullptr};
    cairo_surface_t* surface = c.cairo_pdf_surface_create_for_stream(write_to_sink, &sink, width_pt, height_pt);
    // cairo stamps the clock's time as the creation date unless told one: an empty date leaves
    // it out, so the same input gives the same bytes.
    c.cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATE_DATE, "");
    cairo_t* cr = c.cairo_create(surface);
    std::string failure;
    try {
      // The view box onto the page.
      c.cairo_scale(cr, width_pt / document.width(), height_pt / document.height());
      c.cairo_translate(cr, -document.view_x(), -document.view_y());
      PdfPainter painter(c, cr);
      document.visit(painter);
      c.cairo_show_page(cr);
    } catch (const Error& e) {
      failure = e.what();
    }
    if (failure.empty() && c.cairo_status(cr) != CAIRO_STATUS_SUCCESS) failure = c.cairo_status_to_string(c.cairo_status(cr));
    c.cairo_destroy(cr);
    c.cairo_surface_finish(surface);
    if (failure.empty() && c.cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS)
      failure = c.cairo_status_to_string(c.cairo_surface_status(surface));
    c.cairo_surface_destroy(surface);
    if (sink.failed) std::rethrow_exception(sink.failed);
    if (!failure.empty()) throw Error(path + ": cannot write PDF: " + failure);
  });
}

#else

std::string pdf_unavailable_reason() {
  return "PDF output needs cairo, which this build lacks (install libcairo2-dev and rebuild)";
}

void write_pdf(const SvgDocument&, OutputFile& out) { throw Error(out.path() + ": " + pdf_unavailable_reason()); }

#endif

void write_pdf(const SvgDocument& document, const std::string& path) {
  OutputSet outputs;
  write_pdf(document, outputs.add(path));
  outputs.publish();
}

}  // namespace bluetile
