#pragma once
// The figures' drawing surface: cairo (PNG through an image surface, SVG and PDF through cairo's vector
// surfaces), text in a real font through cairo's text API, anti-aliased strokes. The only header of the
// library that includes cairo's; cairo.h, cairo-svg.h and cairo-pdf.h are plain C (about 1 900 lines
// preprocessed) and add no measurable compile time (docs/performance.md).
// Convention: pixel (x, y) is the unit square centred on the integer point (x, y); y grows downwards
// (every surface is translated by half a pixel, so 1-px lines on integer coordinates are crisp).
#ifndef FURNITURE_FEM_FIGURES_INTERNAL
#error "furniture_fem/figures/detail/canvas.hpp is internal: include <furniture_fem/figures/plot.hpp>"
#endif
#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include "../../core/errors.hpp"

namespace furniture_fem {

struct RGB {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const RGB&, const RGB&) = default;
};

namespace colors {
inline constexpr RGB white{255, 255, 255}, black{0, 0, 0}, grey{128, 128, 128}, light_grey{225, 225, 225},
    dark_grey{64, 64, 64};
}

// Inclusive pixel rectangle.
struct Rect {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  bool empty() const { return x1 < x0 || y1 < y0; }
  bool contains(int x, int y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
  int width() const { return x1 - x0 + 1; }
  int height() const { return y1 - y0 + 1; }
};

// A rendered figure's pixels (row-major RGB8), copied out of the cairo image surface by render().
struct Image {
  int w = 0, h = 0;
  std::vector<std::uint8_t> rgb;

  Image() = default;
  Image(int width, int height, RGB background = colors::white)
      : w(std::max(0, width)), h(std::max(0, height)), rgb(std::size_t(w) * std::size_t(h) * 3) {
    for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) rgb[i] = background.r, rgb[i + 1] = background.g, rgb[i + 2] = background.b;
  }
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < w && y < h; }
  Rect bounds() const { return {0, 0, w - 1, h - 1}; }
  // Out-of-range reads give white (the background), so callers can probe near the edges.
  RGB get(int x, int y) const {
    if (!inside(x, y)) return colors::white;
    const std::size_t i = (std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

enum class HAlign { left, center, right };
enum class VAlign { top, middle, bottom };

// The three kinds of file a figure is written as.
enum class FigureFormat { png, svg, pdf };

namespace detail {

inline constexpr const char* font_family = "sans-serif";

struct CairoDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
using CairoPtr = std::unique_ptr<cairo_t, CairoDeleter>;
using SurfacePtr = std::unique_ptr<cairo_surface_t, CairoDeleter>;

// Liang-Barsky: clips the segment to [xmin,xmax]x[ymin,ymax]; false if nothing is left. Keeps huge
// (off-screen) coordinates away from cairo's 24.8 fixed-point arithmetic.
inline bool clip_segment(double& x0, double& y0, double& x1, double& y1, double xmin, double ymin, double xmax,
                         double ymax) {
  if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1)) return false;
  double t0 = 0, t1 = 1;
  const double dx = x1 - x0, dy = y1 - y0;
  const double p[4] = {-dx, dx, -dy, dy}, q[4] = {x0 - xmin, xmax - x0, y0 - ymin, ymax - y0};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;
    } else {
      const double t = q[i] / p[i];
      if (p[i] < 0) t0 = std::max(t0, t);
      else t1 = std::min(t1, t);
      if (t0 > t1) return false;
    }
  }
  const double ax = x0 + t0 * dx, ay = y0 + t0 * dy, bx = x0 + t1 * dx, by = y0 + t1 * dy;
  x0 = ax, y0 = ay, x1 = bx, y1 = by;
  return true;
}

// `s` with every byte that is not part of a well-formed UTF-8 sequence replaced by '?': cairo refuses
// invalid UTF-8 (and would then fail the whole figure).
inline std::string utf8_or_question_marks(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    const std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    bool ok = n > 0 && i + n <= s.size() && !(n == 2 && c < 0xC2) && !(n == 4 && c > 0xF4);
    for (std::size_t k = 1; ok && k < n; ++k) ok = (static_cast<unsigned char>(s[i + k]) & 0xC0) == 0x80;
    if (ok && n == 3) {  // no overlong forms, no surrogates
      const unsigned char d = static_cast<unsigned char>(s[i + 1]);
      ok = !(c == 0xE0 && d < 0xA0) && !(c == 0xED && d >= 0xA0);
    }
    if (ok && n == 4) {
      const unsigned char d = static_cast<unsigned char>(s[i + 1]);
      ok = !(c == 0xF0 && d < 0x90) && !(c == 0xF4 && d >= 0x90);
    }
    if (ok) out.append(s.substr(i, n)), i += n;
    else out.push_back('?'), ++i;
  }
  return out;
}

// Drawing and text measurement on one cairo context (not owned).
class Canvas {
 public:
  explicit Canvas(cairo_t* cr, bool antialias = true) : cr_(cr) {
    cairo_set_antialias(cr_, antialias ? CAIRO_ANTIALIAS_DEFAULT : CAIRO_ANTIALIAS_NONE);
    // Unhinted metrics on every surface: text measured on the layout's image surface is as wide on a
    // PDF or SVG surface (whose metrics are never hinted), so what fits in the PNG fits there too.
    cairo_font_options_t* fo = cairo_font_options_create();
    cairo_font_options_set_hint_metrics(fo, CAIRO_HINT_METRICS_OFF);
    cairo_set_font_options(cr_, fo);
    cairo_font_options_destroy(fo);
    cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
    cairo_set_line_cap(cr_, CAIRO_LINE_CAP_BUTT);
  }
  cairo_t* context() const { return cr_; }

  void color(RGB c, double alpha = 1.0) const {
    cairo_set_source_rgba(cr_, c.r / 255.0, c.g / 255.0, c.b / 255.0, std::clamp(alpha, 0.0, 1.0));
  }
  void line(double x0, double y0, double x1, double y1, RGB c, double width = 1.0) const {
    if (!clip_segment(x0, y0, x1, y1, -1e5, -1e5, 1e5, 1e5)) return;
    cairo_move_to(cr_, x0, y0);
    cairo_line_to(cr_, x1, y1);
    stroke(c, width);
  }
  // A polyline broken at non-finite points, clipped to `clip` (cairo's clip, plus a coarse geometric
  // clip keeping coordinates finite and small), solid or dashed.
  void polyline(const std::vector<std::array<double, 2>>& pts, RGB c, double width, const Rect& clip,
                bool dashed = false) const {
    cairo_save(cr_);
    cairo_rectangle(cr_, clip.x0 - 0.5, clip.y0 - 0.5, clip.width(), clip.height());
    cairo_clip(cr_);
    const double m = 4 * width + 10;
    bool open = false;
    double lx = 0, ly = 0;
    for (std::size_t i = 1; i < pts.size(); ++i) {
      double x0 = pts[i - 1][0], y0 = pts[i - 1][1], x1 = pts[i][0], y1 = pts[i][1];
      if (!clip_segment(x0, y0, x1, y1, clip.x0 - m, clip.y0 - m, clip.x1 + m, clip.y1 + m)) {
        open = false;
        continue;
      }
      if (!open || x0 != lx || y0 != ly) cairo_move_to(cr_, x0, y0);
      cairo_line_to(cr_, x1, y1);
      open = true, lx = x1, ly = y1;
    }
    if (dashed) {
      const double d[2] = {3 * width + 2, 2 * width + 2};
      cairo_set_dash(cr_, d, 2, 0);
    }
    stroke(c, width);
    cairo_restore(cr_);
  }
  void fill_rect(const Rect& r, RGB c, double alpha = 1.0) const {
    if (r.empty()) return;
    cairo_rectangle(cr_, r.x0 - 0.5, r.y0 - 0.5, r.width(), r.height());
    color(c, alpha);
    cairo_fill(cr_);
  }
  // One-pixel outline through the centres of the rectangle's border pixels.
  void stroke_rect(const Rect& r, RGB c, double width = 1.0) const {
    if (r.empty()) return;
    cairo_rectangle(cr_, r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0);
    stroke(c, width);
  }
  void fill_circle(double x, double y, double radius, RGB c, double alpha = 1.0) const {
    if (!std::isfinite(x) || !std::isfinite(y) || !(radius > 0)) return;
    cairo_new_sub_path(cr_);
    cairo_arc(cr_, x, y, radius, 0, 2 * std::numbers::pi);
    color(c, alpha);
    cairo_fill(cr_);
  }
  void fill_polygon(const std::vector<std::array<double, 2>>& pts, RGB c, double alpha = 1.0) const {
    bool first = true;
    for (const auto& p : pts) {
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || std::abs(p[0]) > 1e5 || std::abs(p[1]) > 1e5) {
        cairo_new_path(cr_);
        return;
      }
      first ? cairo_move_to(cr_, p[0], p[1]) : cairo_line_to(cr_, p[0], p[1]);
      first = false;
    }
    cairo_close_path(cr_);
    color(c, alpha);
    cairo_fill(cr_);
  }

  // ---- text ("sans-serif", through fontconfig) ----
  void font(double size, bool bold = false) const {
    cairo_select_font_face(cr_, font_family, CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr_, size);
  }
  // Advance width of `s` at `size` px.
  double text_width(std::string_view s, double size, bool bold = false) const {
    font(size, bold);
    cairo_text_extents_t e;
    const std::string str = utf8_or_question_marks(s);
    cairo_text_extents(cr_, str.c_str(), &e);
    return std::max(e.x_advance, e.x_bearing + e.width);
  }
  // Height of a line of text (the font's ascent plus descent) at `size` px.
  double line_height(double size, bool bold = false) const {
    font(size, bold);
    cairo_font_extents_t f;
    cairo_font_extents(cr_, &f);
    return f.ascent + f.descent;
  }
  // Text anchored at (x, y): HAlign picks the left end, centre or right end; VAlign the top, middle
  // or bottom of the line box. angle_deg rotates about the anchor (-90: reading upwards).
  void text(double x, double y, std::string_view s, RGB c, double size, HAlign h = HAlign::left, VAlign v = VAlign::top,
            bool bold = false, double angle_deg = 0) const {
    if (s.empty() || !std::isfinite(x) || !std::isfinite(y)) return;
    font(size, bold);
    cairo_font_extents_t f;
    cairo_font_extents(cr_, &f);
    const double w = text_width(s, size, bold);
    const double dx = h == HAlign::left ? 0 : h == HAlign::center ? -0.5 * w : -w;
    const double base = v == VAlign::top ? f.ascent : v == VAlign::middle ? 0.5 * (f.ascent - f.descent) : -f.descent;
    cairo_save(cr_);
    cairo_translate(cr_, x, y);
    if (angle_deg != 0) cairo_rotate(cr_, angle_deg * std::numbers::pi / 180);
    cairo_move_to(cr_, dx - 0.5, base - 0.5);  // text is not pixel-centred: undo the half-pixel shift
    color(c);
    const std::string str = utf8_or_question_marks(s);
    cairo_show_text(cr_, str.c_str());
    cairo_new_path(cr_);
    cairo_restore(cr_);
  }

 private:
  void stroke(RGB c, double width) const {
    color(c);
    cairo_set_line_width(cr_, width);
    cairo_stroke(cr_);
  }
  cairo_t* cr_;
};

// A context on a 1x1 image surface for measuring text before anything is drawn (layouts).
class Measurer {
 public:
  Measurer()
      : surface_(cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1)), cr_(cairo_create(surface_.get())), canvas_(cr_.get()) {}
  const Canvas& canvas() const { return canvas_; }

 private:
  SurfacePtr surface_;
  CairoPtr cr_;
  Canvas canvas_;
};

inline std::string cairo_error(cairo_status_t s) { return cairo_status_to_string(s); }

// Paints the background, then runs draw(canvas) with the half-pixel shift; cairo's status after.
template <class Draw>
cairo_status_t paint_surface(cairo_surface_t* surface, bool antialias, RGB background, Draw&& draw) {
  CairoPtr cr(cairo_create(surface));
  Canvas c(cr.get(), antialias);
  c.color(background);
  cairo_paint(cr.get());
  cairo_translate(cr.get(), 0.5, 0.5);
  draw(c);
  return cairo_status(cr.get());
}

// Runs draw(canvas) on a width x height surface of the given kind and writes it to `path`; throws
// OutputError naming `who` and the file when the file cannot be created or written.
template <class Draw>
void write_figure(const std::string& who, const std::string& path, FigureFormat kind, int width, int height,
                  bool antialias, RGB background, Draw&& draw) {
  if (width <= 0 || height <= 0)
    throw InputError(who + " '" + path + "': size " + std::to_string(width) + "x" + std::to_string(height));
  errno = 0;  // cairo opens the file with fopen: errno says why it could not
  SurfacePtr surface(kind == FigureFormat::png   ? cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height)
                     : kind == FigureFormat::svg ? cairo_svg_surface_create(path.c_str(), width, height)
                                                 : cairo_pdf_surface_create(path.c_str(), width, height));
  auto check = [&](cairo_status_t s) {
    if (s == CAIRO_STATUS_SUCCESS) return;
    const std::string why = errno ? std::string(" (") + std::strerror(errno) + ")" : std::string();
    throw OutputError(who + ": cannot write '" + path + "': " + cairo_error(s) + why);
  };
  check(cairo_surface_status(surface.get()));
  check(paint_surface(surface.get(), antialias, background, draw));
  if (kind == FigureFormat::png) {
    check(cairo_surface_write_to_png(surface.get(), path.c_str()));
  } else {
    cairo_surface_finish(surface.get());
    check(cairo_surface_status(surface.get()));
  }
}

// Runs draw(canvas) on an image surface and copies its pixels out.
template <class Draw>
Image render_image(int width, int height, bool antialias, RGB background, Draw&& draw) {
  if (width <= 0 || height <= 0) throw InputError("render: size " + std::to_string(width) + "x" + std::to_string(height));
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height));
  paint_surface(surface.get(), antialias, background, draw);
  cairo_surface_flush(surface.get());
  Image img(width, height);
  const unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::uint32_t p;  // native-endian 0x00RRGGBB
      std::memcpy(&p, data + std::size_t(y) * std::size_t(stride) + 4 * std::size_t(x), 4);
      const std::size_t i = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
      img.rgb[i] = std::uint8_t(p >> 16), img.rgb[i + 1] = std::uint8_t(p >> 8), img.rgb[i + 2] = std::uint8_t(p);
    }
  return img;
}

// render() and the three save_ functions of a figure class (CRTP): Derived has paint(canvas, width,
// height), style() and figure_name; W0 x H0 is its default size.
template <class Derived, int W0, int H0>
class FigureFiles {
 public:
  // The pixels (RGB8), without writing a file.
  Image render(int width = W0, int height = H0) const {
    return render_image(width, height, self().style().antialias, self().style().background,
                        [&](const Canvas& c) { self().paint(c, width, height); });
  }
  // Write the figure; OutputError naming the file when it cannot be written.
  void save_png(const std::string& path, int width = W0, int height = H0) const { save(path, FigureFormat::png, width, height); }
  void save_svg(const std::string& path, int width = W0, int height = H0) const { save(path, FigureFormat::svg, width, height); }
  void save_pdf(const std::string& path, int width = W0, int height = H0) const { save(path, FigureFormat::pdf, width, height); }
  void save(const std::string& path, FigureFormat kind, int width = W0, int height = H0) const {
    const char* call = kind == FigureFormat::png ? "::save_png" : kind == FigureFormat::svg ? "::save_svg" : "::save_pdf";
    write_figure(std::string(Derived::figure_name) + call, path, kind, width, height, self().style().antialias,
                 self().style().background, [&](const Canvas& c) { self().paint(c, width, height); });
  }

 private:
  const Derived& self() const { return static_cast<const Derived&>(*this); }
};

}  // namespace detail
}  // namespace furniture_fem
