#pragma once
// Raster primitives on an RGB8 image: pixels, lines (Bresenham or anti-aliased), rectangles, circles,
// polygons, bitmap text, and anti-aliased polylines (solid or dashed) clipped to a rectangle.
// Convention: pixel (x, y) is the unit square centred on the integer point (x, y); y grows downwards.
#ifndef FURNITURE_FEM_FIGURES_INTERNAL
#error "furniture_fem/figures/detail/raster.hpp is internal: include <furniture_fem/figures/plot.hpp>"
#endif
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string_view>
#include <vector>

#include "font5x7.hpp"

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

// Row-major RGB8 image; out-of-range writes are ignored so drawing code can clip by omission.
struct Image {
  int w = 0, h = 0;
  std::vector<std::uint8_t> rgb;

  Image() = default;
  Image(int width, int height, RGB background = colors::white)
      : w(std::max(0, width)), h(std::max(0, height)), rgb(std::size_t(w) * std::size_t(h) * 3) {
    fill(background);
  }
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < w && y < h; }
  Rect bounds() const { return {0, 0, w - 1, h - 1}; }
  RGB get(int x, int y) const {
    const std::size_t i = index(x, y);
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
  void set(int x, int y, RGB c) {
    if (!inside(x, y)) return;
    const std::size_t i = index(x, y);
    rgb[i] = c.r;
    rgb[i + 1] = c.g;
    rgb[i + 2] = c.b;
  }
  // Alpha-composites c over the pixel; alpha is clamped to [0, 1].
  void blend(int x, int y, RGB c, double alpha) {
    if (!inside(x, y) || !(alpha > 0)) return;
    if (alpha >= 1) return set(x, y, c);
    const std::size_t i = index(x, y);
    auto mix = [alpha](std::uint8_t dst, std::uint8_t src) {
      return std::uint8_t(std::lround(dst + (double(src) - dst) * alpha));
    };
    rgb[i] = mix(rgb[i], c.r);
    rgb[i + 1] = mix(rgb[i + 1], c.g);
    rgb[i + 2] = mix(rgb[i + 2], c.b);
  }
  void fill(RGB c) {
    for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) {
      rgb[i] = c.r;
      rgb[i + 1] = c.g;
      rgb[i + 2] = c.b;
    }
  }

 private:
  std::size_t index(int x, int y) const { return (std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3; }
};

inline Rect intersect(const Rect& a, const Rect& b) {
  return {std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
}

inline void fill_rect(Image& img, Rect r, RGB c, double alpha = 1.0) {
  r = intersect(r, img.bounds());
  for (int y = r.y0; y <= r.y1; ++y)
    for (int x = r.x0; x <= r.x1; ++x) img.blend(x, y, c, alpha);
}

// One-pixel outline of an inclusive rectangle.
inline void draw_rect(Image& img, const Rect& r, RGB c) {
  for (int x = r.x0; x <= r.x1; ++x) {
    img.set(x, r.y0, c);
    img.set(x, r.y1, c);
  }
  for (int y = r.y0; y <= r.y1; ++y) {
    img.set(r.x0, y, c);
    img.set(r.x1, y, c);
  }
}

namespace detail {
inline double segment_distance(double px, double py, double x0, double y0, double x1, double y1) {
  const double dx = x1 - x0, dy = y1 - y0, len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((px - x0) * dx + (py - y0) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - (x0 + t * dx), py - (y0 + t * dy));
}

// Liang-Barsky: clips the segment to [xmin,xmax]x[ymin,ymax]; false if nothing is left. Keeps huge
// (off-screen) coordinates from turning into huge loops or integer overflow.
inline bool clip_segment(double& x0, double& y0, double& x1, double& y1, double xmin, double ymin, double xmax,
                         double ymax) {
  if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1)) return false;
  double t0 = 0, t1 = 1;
  const double dx = x1 - x0, dy = y1 - y0;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {x0 - xmin, xmax - x0, y0 - ymin, ymax - y0};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;
    } else {
      const double t = q[i] / p[i];
      if (p[i] < 0) t0 = std::max(t0, t);
      else t1 = std::min(t1, t);
    }
  }
  if (t0 > t1) return false;
  const double ax = x0 + t0 * dx, ay = y0 + t0 * dy, bx = x0 + t1 * dx, by = y0 + t1 * dy;
  x0 = ax, y0 = ay, x1 = bx, y1 = by;
  return true;
}

// Coverage of a capsule of radius r around a segment at each pixel centre in `clip`, handed to
// `plot(x, y, coverage)`. Anti-aliased: linear ramp over one pixel at the edge; otherwise hard edge.
template <class Plot>
void stroke_segment(double x0, double y0, double x1, double y1, double r, bool antialias, const Rect& clip,
                    Plot&& plot) {
  const double m = r + 1.0;
  if (!clip_segment(x0, y0, x1, y1, clip.x0 - m, clip.y0 - m, clip.x1 + m, clip.y1 + m)) return;
  const int xa = std::max(clip.x0, int(std::floor(std::min(x0, x1) - m)));
  const int xb = std::min(clip.x1, int(std::ceil(std::max(x0, x1) + m)));
  const int ya = std::max(clip.y0, int(std::floor(std::min(y0, y1) - m)));
  const int yb = std::min(clip.y1, int(std::ceil(std::max(y0, y1) + m)));
  for (int y = ya; y <= yb; ++y)
    for (int x = xa; x <= xb; ++x) {
      const double d = segment_distance(x, y, x0, y0, x1, y1);
      const double cov = antialias ? std::clamp(r + 0.5 - d, 0.0, 1.0) : (d <= r + 1e-9 ? 1.0 : 0.0);
      if (cov > 0) plot(x, y, cov);
    }
}
}  // namespace detail

// Line between pixel centres. thickness 1 without anti-aliasing is exact Bresenham (the pixels a
// test can predict); thicker plain lines stamp a square brush; anti-aliased lines are capsules.
inline void draw_line(Image& img, double x0, double y0, double x1, double y1, RGB c, double thickness = 1.0,
                      bool antialias = false) {
  if (antialias) {
    detail::stroke_segment(x0, y0, x1, y1, std::max(thickness, 0.5) * 0.5, true, img.bounds(),
                           [&](int x, int y, double a) { img.blend(x, y, c, a); });
    return;
  }
  const double m = thickness + 2;
  if (!detail::clip_segment(x0, y0, x1, y1, -m, -m, img.w + m, img.h + m)) return;
  int ax = int(std::lround(x0)), ay = int(std::lround(y0));
  const int bx = int(std::lround(x1)), by = int(std::lround(y1));
  const int t = std::max(1, int(std::lround(thickness)));
  const int lo = -(t - 1) / 2, hi = t / 2;  // square brush offsets, e.g. t = 3 -> -1..1
  const int dx = std::abs(bx - ax), sx = ax < bx ? 1 : -1;
  const int dy = -std::abs(by - ay), sy = ay < by ? 1 : -1;
  int err = dx + dy;
  for (;;) {
    for (int oy = lo; oy <= hi; ++oy)
      for (int ox = lo; ox <= hi; ++ox) img.set(ax + ox, ay + oy, c);
    if (ax == bx && ay == by) break;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      ax += sx;
    }
    if (e2 <= dx) {
      err += dx;
      ay += sy;
    }
  }
}

inline void fill_circle(Image& img, double cx, double cy, double r, RGB c, bool antialias = true,
                        double alpha = 1.0) {
  if (!std::isfinite(cx) || !std::isfinite(cy) || !(r > 0)) return;
  const int xa = std::max(0, int(std::floor(cx - r - 1))), xb = std::min(img.w - 1, int(std::ceil(cx + r + 1)));
  const int ya = std::max(0, int(std::floor(cy - r - 1))), yb = std::min(img.h - 1, int(std::ceil(cy + r + 1)));
  for (int y = ya; y <= yb; ++y)
    for (int x = xa; x <= xb; ++x) {
      const double d = std::hypot(x - cx, y - cy);
      const double cov = antialias ? std::clamp(r + 0.5 - d, 0.0, 1.0) : (d <= r ? 1.0 : 0.0);
      img.blend(x, y, c, cov * alpha);
    }
}

inline void draw_circle(Image& img, double cx, double cy, double r, RGB c, double thickness = 1.0) {
  if (!std::isfinite(cx) || !std::isfinite(cy) || !(r > 0)) return;
  const double hw = thickness * 0.5;
  const int xa = std::max(0, int(std::floor(cx - r - hw - 1))), xb = std::min(img.w - 1, int(std::ceil(cx + r + hw + 1)));
  const int ya = std::max(0, int(std::floor(cy - r - hw - 1))), yb = std::min(img.h - 1, int(std::ceil(cy + r + hw + 1)));
  for (int y = ya; y <= yb; ++y)
    for (int x = xa; x <= xb; ++x)
      img.blend(x, y, c, std::clamp(hw + 0.5 - std::abs(std::hypot(x - cx, y - cy) - r), 0.0, 1.0));
}

// Even-odd scanline fill of a polygon (vertices in pixel coordinates), sampled at pixel centres.
inline void fill_polygon(Image& img, const std::vector<std::array<double, 2>>& pts, RGB c, double alpha = 1.0) {
  if (pts.size() < 3) return;
  double ymin = pts[0][1], ymax = pts[0][1];
  for (const auto& p : pts) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1])) return;
    ymin = std::min(ymin, p[1]);
    ymax = std::max(ymax, p[1]);
  }
  std::vector<double> xs;
  for (int y = std::max(0, int(std::ceil(ymin))); y <= std::min(img.h - 1, int(std::floor(ymax))); ++y) {
    xs.clear();
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const auto& a = pts[i];
      const auto& b = pts[(i + 1) % pts.size()];
      // Half-open rule on y so a vertex shared by two edges is counted once.
      if ((a[1] <= y && b[1] > y) || (b[1] <= y && a[1] > y))
        xs.push_back(a[0] + (y - a[1]) / (b[1] - a[1]) * (b[0] - a[0]));
    }
    std::sort(xs.begin(), xs.end());
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2)
      for (int x = std::max(0, int(std::ceil(xs[k]))); x <= std::min(img.w - 1, int(std::ceil(xs[k + 1])) - 1); ++x)
        img.blend(x, y, c, alpha);
  }
}

// ---- text --------------------------------------------------------------------------------------

enum class HAlign { left, center, right };
enum class VAlign { top, middle, bottom };

inline int text_width(std::string_view s, int scale = 1) {
  return s.empty() ? 0 : int(s.size()) * detail::font_cell_w * scale - scale;
}
inline int text_height(int scale = 1) { return detail::font_h * scale; }

// Horizontal text; (x, y) is the anchor chosen by the alignments (top-left by default).
inline void draw_text(Image& img, int x, int y, std::string_view s, RGB c, int scale = 1,
                      HAlign ha = HAlign::left, VAlign va = VAlign::top) {
  scale = std::max(1, scale);
  if (ha == HAlign::center) x -= text_width(s, scale) / 2;
  else if (ha == HAlign::right) x -= text_width(s, scale);
  if (va == VAlign::middle) y -= text_height(scale) / 2;
  else if (va == VAlign::bottom) y -= text_height(scale);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const std::uint8_t* g = detail::glyph(s[i]);
    const int gx = x + int(i) * detail::font_cell_w * scale;
    for (int col = 0; col < detail::font_w; ++col)
      for (int row = 0; row < detail::font_rows; ++row)
        if (g[col] >> row & 1)
          fill_rect(img, {gx + col * scale, y + row * scale, gx + col * scale + scale - 1, y + row * scale + scale - 1}, c);
  }
}

// Text rotated 90 degrees counter-clockwise (reads bottom to top), centred on (cx, cy): y-axis labels.
inline void draw_text_vertical(Image& img, int cx, int cy, std::string_view s, RGB c, int scale = 1) {
  scale = std::max(1, scale);
  const int x0 = cx - text_height(scale) / 2, y0 = cy + text_width(s, scale) / 2;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const std::uint8_t* g = detail::glyph(s[i]);
    for (int col = 0; col < detail::font_w; ++col)
      for (int row = 0; row < detail::font_rows; ++row)
        if (g[col] >> row & 1) {
          // Text-space (u along, v down) maps to image (x0 + v, y0 - u).
          const int u = (int(i) * detail::font_cell_w + col) * scale, v = row * scale;
          fill_rect(img, {x0 + v, y0 - u - scale + 1, x0 + v + scale - 1, y0 - u}, c);
        }
  }
}

// ---- anti-aliased polylines ----------------------------------------------------------------------

// Accumulates the coverage of a whole polyline (max over its segments) before compositing once, so
// joints and densely sampled signals do not darken where segments overlap.
class StrokeCanvas {
 public:
  explicit StrokeCanvas(Image& img) : img_(img), cov_(std::size_t(img.w) * std::size_t(img.h), 0.0f) {}

  // Points with a non-finite coordinate break the line. dash = {on, off} lengths in pixels, or {0, 0}.
  void polyline(const std::vector<std::array<double, 2>>& pts, RGB c, double width, const Rect& clip,
                std::array<double, 2> dash = {0, 0}, bool antialias = true) {
    const Rect cl = intersect(clip, img_.bounds());
    if (cl.empty()) return;
    dirty_ = {cl.x1 + 1, cl.y1 + 1, cl.x0 - 1, cl.y0 - 1};
    const double r = std::max(width, 0.5) * 0.5;
    auto stamp = [&](double xa, double ya, double xb, double yb) {
      detail::stroke_segment(xa, ya, xb, yb, r, antialias, cl, [&](int x, int y, double a) {
        float& v = cov_[std::size_t(y) * std::size_t(img_.w) + std::size_t(x)];
        v = std::max(v, float(a));
        dirty_ = {std::min(dirty_.x0, x), std::min(dirty_.y0, y), std::max(dirty_.x1, x), std::max(dirty_.y1, y)};
      });
    };
    const bool dashed = dash[0] > 0 && dash[1] > 0;
    double phase = 0;  // distance travelled within the current on+off period
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
      double xa = pts[i][0], ya = pts[i][1], xb = pts[i + 1][0], yb = pts[i + 1][1];
      if (!std::isfinite(xa) || !std::isfinite(ya) || !std::isfinite(xb) || !std::isfinite(yb)) continue;
      if (!dashed) {
        stamp(xa, ya, xb, yb);
        continue;
      }
      const double len = std::hypot(xb - xa, yb - ya);
      if (len > 4.0 * (img_.w + img_.h)) {  // far off-screen: clip first so the dash loop stays short
        if (!detail::clip_segment(xa, ya, xb, yb, cl.x0 - 2.0 * r, cl.y0 - 2.0 * r, cl.x1 + 2.0 * r, cl.y1 + 2.0 * r))
          continue;
      }
      const double seg = std::hypot(xb - xa, yb - ya);
      double s = 0;
      while (s < seg) {
        const bool on = phase < dash[0];
        const double left = on ? dash[0] - phase : dash[0] + dash[1] - phase;
        const double step = std::min(left, seg - s);
        if (on) {
          const double t0 = s / seg, t1 = (s + step) / seg;
          stamp(xa + t0 * (xb - xa), ya + t0 * (yb - ya), xa + t1 * (xb - xa), ya + t1 * (yb - ya));
        }
        s += step;
        phase += step;
        if (phase >= dash[0] + dash[1]) phase = 0;
      }
    }
    composite(c);
  }

 private:
  void composite(RGB c) {
    for (int y = dirty_.y0; y <= dirty_.y1; ++y)
      for (int x = dirty_.x0; x <= dirty_.x1; ++x) {
        float& v = cov_[std::size_t(y) * std::size_t(img_.w) + std::size_t(x)];
        if (v > 0) img_.blend(x, y, c, v);
        v = 0;
      }
  }
  Image& img_;
  std::vector<float> cov_;
  Rect dirty_;
};

}  // namespace furniture_fem
