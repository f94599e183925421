#pragma once
// furniture_fem/figures/plot.hpp: figures written straight to PNG, with no plotting program behind them.
//
//   LinePlot      time histories; stacked panels sharing x (the paper's X/Y/Z displacement figures),
//                 dashed reference series (experiment), legend, 1-2-5 ticks, optional log axes.
//   ScatterPlot   labelled points, log axes, Pareto front (wall time vs error).
//   Wireframe3D   beam segments in 3-D (orthographic or perspective), floor grid, translucent walls.
//
// Everything is rasterised by detail/raster.hpp and encoded by detail/png_writer.hpp.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "../core/errors.hpp"

#define FURNITURE_FEM_FIGURES_INTERNAL
#include "detail/png_writer.hpp"
#include "detail/raster.hpp"
#undef FURNITURE_FEM_FIGURES_INTERNAL

namespace furniture_fem {

// ================================ PNG ============================================================

enum class PngCompression {
  stored,         // uncompressed deflate blocks: ~3 bytes per pixel, trivially checkable
  fixed_huffman,  // one fixed-Huffman block with LZ77: flat-colour plots shrink 20-100x
};

// The bytes of a PNG file (RGB, 8 bits per channel, no interlace, filter 0 on every row).
inline std::vector<std::uint8_t> encode_png(const Image& img, PngCompression mode = PngCompression::fixed_huffman) {
  if (img.w <= 0 || img.h <= 0 || img.rgb.size() != std::size_t(img.w) * std::size_t(img.h) * 3)
    throw InputError("encode_png: image is " + std::to_string(img.w) + "x" + std::to_string(img.h) +
                                " px but holds " + std::to_string(img.rgb.size()) + " bytes");
  const std::size_t row = std::size_t(img.w) * 3;
  std::vector<std::uint8_t> raw;
  raw.reserve((row + 1) * std::size_t(img.h));
  for (int y = 0; y < img.h; ++y) {
    raw.push_back(0);  // filter type None
    raw.insert(raw.end(), img.rgb.begin() + std::ptrdiff_t(row * y), img.rgb.begin() + std::ptrdiff_t(row * (y + 1)));
  }
  const std::vector<std::uint8_t> z = detail::png::zlib_compress(raw, mode == PngCompression::fixed_huffman, row + 1);

  std::vector<std::uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  out.reserve(z.size() + 128);
  std::vector<std::uint8_t> ihdr;
  detail::png::put_be32(ihdr, std::uint32_t(img.w));
  detail::png::put_be32(ihdr, std::uint32_t(img.h));
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // bit depth 8, colour type 2 (RGB), deflate, filter 0, no interlace
  detail::png::put_chunk(out, "IHDR", ihdr.data(), ihdr.size());
  // Several IDAT chunks keep each one small; decoders concatenate them.
  constexpr std::size_t idat_max = std::size_t(1) << 18;
  for (std::size_t pos = 0; pos < z.size(); pos += idat_max)
    detail::png::put_chunk(out, "IDAT", z.data() + pos, std::min(idat_max, z.size() - pos));
  detail::png::put_chunk(out, "IEND", nullptr, 0);
  return out;
}

// Writes `img` to `path`; throws InputError (a bad image) or OutputError (a file that cannot be
// written), naming the path.
inline void write_png(const std::string& path, const Image& img, PngCompression mode = PngCompression::fixed_huffman) {
  std::vector<std::uint8_t> bytes;
  try {
    bytes = encode_png(img, mode);
  } catch (const std::exception& e) {
    throw InputError("write_png '" + path + "': " + e.what());
  }
  errno = 0;
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f)
    throw OutputError("write_png: cannot open '" + path + "' for writing" +
                             (errno ? std::string(": ") + std::strerror(errno) : std::string()));
  f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  f.close();
  if (!f) throw OutputError("write_png: error while writing '" + path + "'");
}

// ================================ colours and ticks ==============================================

// Ten distinguishable colours (the Tableau 10 set); palette_color wraps around.
inline constexpr std::array<RGB, 10> palette = {{{31, 119, 180},
                                                 {255, 127, 14},
                                                 {44, 160, 44},
                                                 {214, 39, 40},
                                                 {148, 103, 189},
                                                 {140, 86, 75},
                                                 {227, 119, 194},
                                                 {127, 127, 127},
                                                 {188, 189, 34},
                                                 {23, 190, 207}}};
inline RGB palette_color(std::size_t i) { return palette[i % palette.size()]; }

// Step of 1, 2 or 5 times a power of ten giving about `target` intervals over `range`.
inline double nice_step(double range, int target = 5) {
  if (!(range > 0) || !std::isfinite(range)) return 1.0;
  const double raw = range / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / mag;
  // Geometric midpoints between 1, 2, 5, 10 keep the chosen step within a factor ~1.6 of raw.
  const double m = f < std::sqrt(2.0) ? 1 : f < std::sqrt(10.0) ? 2 : f < std::sqrt(50.0) ? 5 : 10;
  return m * mag;
}

// Multiples of nice_step(hi - lo, target) inside [lo, hi], e.g. (0, 9.3) -> 0 2 4 6 8. When that
// step leaves fewer than two ticks (a range straddling one multiple), the next smaller 1-2-5 step is used.
inline std::vector<double> nice_ticks(double lo, double hi, int target = 5) {
  std::vector<double> t;
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo)) return t;
  double step = nice_step(hi - lo, target);
  for (int attempt = 0; attempt < 4; ++attempt) {
    t.clear();
    const double k0 = std::ceil(lo / step - 1e-9), k1 = std::floor(hi / step + 1e-9);
    for (double k = k0; k <= k1 && t.size() < 1000; ++k) {
      const double v = k * step;  // computed from k, not accumulated, so 0.1 steps stay clean
      t.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
    }
    if (t.size() >= 2) break;
    const double mag = std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    const double m = std::round(step / mag);  // 1, 2 or 5
    step = m == 5 ? 2 * mag : m == 2 ? mag : 0.5 * mag;
  }
  return t;
}

// Decades inside [lo, hi] (thinned to about `target`), or 1-2-5 multiples when fewer than three
// decades fit (two labels alone would leave most of the axis unlabelled).
inline std::vector<double> log_ticks(double lo, double hi, int target = 6) {
  std::vector<double> t;
  if (!(lo > 0) || !(hi > lo) || !std::isfinite(hi)) return t;
  const int k0 = int(std::ceil(std::log10(lo) - 1e-9)), k1 = int(std::floor(std::log10(hi) + 1e-9));
  if (k1 - k0 + 1 >= 3) {
    const int every = std::max(1, (k1 - k0 + target) / std::max(1, target));
    for (int k = k0; k <= k1; ++k)
      if ((k - k0) % every == 0) t.push_back(std::pow(10.0, k));
    return t;
  }
  for (int k = k0 - 1; k <= k1; ++k)
    for (double m : {1.0, 2.0, 5.0}) {
      const double v = m * std::pow(10.0, k);
      if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) t.push_back(v);
    }
  if (t.size() < 2) return nice_ticks(lo, hi, target);
  return t;
}

// Label of a linear tick: as many decimals as the step needs; scientific for very large/small values.
inline std::string format_tick(double v, double step) {
  if (!(step > 0) || !std::isfinite(step)) step = std::abs(v) > 0 ? std::abs(v) : 1.0;
  if (std::abs(v) < step * 1e-6) v = 0;
  const int k = int(std::floor(std::log10(step) + 1e-9));
  const double mag = std::max(std::abs(v), step);
  char buf[64];
  if (mag >= 1e-4 && mag < 1e6) std::snprintf(buf, sizeof buf, "%.*f", std::max(0, -k), v);
  else std::snprintf(buf, sizeof buf, "%.*e", std::clamp(int(std::floor(std::log10(mag))) - k, 0, 8), v);
  return buf;
}

// Label of a log-axis tick: plain for 0.001..99999, otherwise "1e-05".
inline std::string format_log_tick(double v) {
  char buf[64];
  if (v >= 1e-3 && v < 1e5) std::snprintf(buf, sizeof buf, "%g", v);
  else std::snprintf(buf, sizeof buf, "%.0e", v);
  return buf;
}

// ================================ layout =========================================================

// Maps data values to pixel positions: lo -> p0, hi -> p1 (p1 < p0 on a y axis).
struct Axis {
  double lo = 0, hi = 1;
  double p0 = 0, p1 = 1;
  bool log = false;
  double to_pixel(double v) const {
    const double t = log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) : (v - lo) / (hi - lo);
    return p0 + t * (p1 - p0);
  }
};

// Where one panel landed in a rendered image; layout() returns it so tests and callers can locate data.
struct PanelLayout {
  Rect frame;  // the axes box, border included
  Axis x, y;
  std::vector<double> xticks, yticks, xminor, yminor;
  std::vector<std::string> xtick_labels, ytick_labels;  // empty labels on panels that share x
  Rect legend;  // empty when there is no legend
};

struct PlotLayout {
  int width = 0, height = 0;
  std::vector<PanelLayout> panels;
};

enum class LegendPos { none, top_right, top_left, bottom_right, bottom_left };

struct PlotStyle {
  int text_scale = 0;  // font magnification; 0 picks 2 for images at least 450 px in both sides, else 1
  RGB background = colors::white, foreground = colors::black, grid = colors::light_grey;
  bool grid_lines = true;
  bool antialias = true;
  double line_width = 2.0;  // default series width in px
  LegendPos legend = LegendPos::top_right;
  int scale_for(int w, int h) const { return text_scale > 0 ? text_scale : (std::min(w, h) >= 450 ? 2 : 1); }
};

namespace detail {

struct AxisSpec {
  std::string label;
  bool log = false;
  std::optional<std::pair<double, double>> lim;
};

inline std::pair<double, double> checked_lim(double lo, double hi, const char* who) {
  if (!(lo < hi) || !std::isfinite(lo) || !std::isfinite(hi))
    throw InputError(std::string(who) + ": bad limits [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return {lo, hi};
}

struct LegendItem {
  std::string label;
  RGB color;
  double width = 2;
  bool dashed = false;
  bool line = true;
  double marker = 0;
};

struct PanelInput {
  double lo = 0, hi = 1;  // resolved y range
  AxisSpec y;
  std::string title;
  std::vector<LegendItem> legend;
};

struct LayoutInput {
  std::string title, xlabel;
  double xlo = 0, xhi = 1;
  bool xlog = false;
  std::vector<PanelInput> panels;
};

struct Metrics {
  int s, th, pad, gap, tick;
  explicit Metrics(int scale) : s(scale), th(text_height(scale)), pad(6 * scale), gap(3 * scale), tick(3 * scale) {}
};

// Min and max of the finite (and, on a log axis, positive) values; {+inf, -inf} when there are none.
inline std::pair<double, double> finite_range(const std::vector<double>& v, bool log) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double x : v)
    if (std::isfinite(x) && (!log || x > 0)) {
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  return {lo, hi};
}

// Axis limits: the user's, else the data's widened by `margin` (fraction of the span, in log space
// on log axes). Degenerate data (one value) gets a span so the axis stays drawable.
inline std::pair<double, double> resolve_range(const AxisSpec& spec, double dmin, double dmax, double margin) {
  if (spec.lim) {
    if (spec.log && !(spec.lim->first > 0))
      throw InputError("plot: log axis limits must be positive, got [" + std::to_string(spec.lim->first) +
                                  ", " + std::to_string(spec.lim->second) + "]");
    return *spec.lim;
  }
  if (spec.log) {
    if (!(dmin <= dmax) || !(dmin > 0)) return {1, 10};
    double a = std::log10(dmin), b = std::log10(dmax);
    if (b - a < 1e-9) a -= 0.5, b += 0.5;
    const double m = (b - a) * margin;
    return {std::pow(10.0, a - m), std::pow(10.0, b + m)};
  }
  if (!(dmin <= dmax)) return {0, 1};
  if (dmax - dmin <= 1e-12 * std::max(std::abs(dmin), std::abs(dmax))) {
    const double pad = dmin == 0 ? 1.0 : 0.1 * std::abs(dmin);
    dmin -= pad, dmax += pad;
  }
  const double m = (dmax - dmin) * margin;
  return {dmin - m, dmax + m};
}

inline void make_ticks(double lo, double hi, bool log, int target, std::vector<double>& major,
                       std::vector<std::string>& labels, std::vector<double>& minor) {
  major.clear(), labels.clear(), minor.clear();
  if (log) {
    major = log_ticks(lo, hi, target);
    for (double v : major) labels.push_back(format_log_tick(v));
    if (std::log10(hi / lo) <= 8)
      for (int k = int(std::floor(std::log10(lo))); k <= int(std::ceil(std::log10(hi))); ++k)
        for (int m = 2; m <= 9; ++m) {
          const double v = m * std::pow(10.0, k);
          if (v > lo && v < hi) minor.push_back(v);
        }
    return;
  }
  major = nice_ticks(lo, hi, target);
  const double step = major.size() >= 2 ? major[1] - major[0] : nice_step(hi - lo, target);
  for (double v : major) labels.push_back(format_tick(v, step));
}

inline int max_width(const std::vector<std::string>& labels, int s) {
  int w = 0;
  for (const auto& l : labels) w = std::max(w, text_width(l, s));
  return w;
}

inline Rect legend_rect(const std::vector<LegendItem>& items, const Rect& frame, LegendPos pos, const Metrics& m) {
  std::vector<std::string> labels;
  for (const auto& it : items)
    if (!it.label.empty()) labels.push_back(it.label);
  if (labels.empty() || pos == LegendPos::none) return {};
  const int row = m.th + 2 * m.gap, sample = 14 * m.s;
  const int w = m.pad + sample + m.pad + max_width(labels, m.s) + m.pad;
  const int h = int(labels.size()) * row + 2 * m.gap;
  const int inset = m.pad;
  const bool right = pos == LegendPos::top_right || pos == LegendPos::bottom_right;
  const bool top = pos == LegendPos::top_right || pos == LegendPos::top_left;
  const int x0 = right ? frame.x1 - inset - w : frame.x0 + inset;
  const int y0 = top ? frame.y0 + inset : frame.y1 - inset - h;
  return {x0, y0, x0 + w - 1, y0 + h - 1};
}

// Stacked panels sharing x: title on top, x tick labels and x label under the bottom panel only.
inline PlotLayout build_layout(int W, int H, const PlotStyle& st, const LayoutInput& in) {
  const Metrics m(st.scale_for(W, H));
  const int n = int(in.panels.size());
  PlotLayout L;
  L.width = W, L.height = H;
  L.panels.resize(std::size_t(n));

  const int top = m.pad + (in.title.empty() ? 0 : text_height(m.s + 1) + 2 * m.pad);
  const int bottom = m.pad + m.tick + m.gap + m.th + (in.xlabel.empty() ? 0 : 3 * m.gap + m.th) + m.gap;
  const int panel_gap = 3 * m.pad;
  const int panel_h = (H - top - bottom - (n - 1) * panel_gap) / std::max(1, n);
  if (panel_h < 4 * m.th)
    throw InputError("plot: " + std::to_string(W) + "x" + std::to_string(H) + " px is too small for " +
                                std::to_string(n) + " panel(s)");

  bool any_ylabel = false;
  int ytick_w = 0;
  const int ytarget = std::clamp(panel_h / (5 * m.th), 2, 8);
  for (int i = 0; i < n; ++i) {
    const PanelInput& p = in.panels[std::size_t(i)];
    PanelLayout& pl = L.panels[std::size_t(i)];
    pl.y = Axis{p.lo, p.hi, 0, 1, p.y.log};
    make_ticks(p.lo, p.hi, p.y.log, ytarget, pl.yticks, pl.ytick_labels, pl.yminor);
    ytick_w = std::max(ytick_w, max_width(pl.ytick_labels, m.s));
    any_ylabel = any_ylabel || !p.y.label.empty();
  }
  const int left = m.pad + (any_ylabel ? m.th + 3 * m.gap : 0) + ytick_w + m.gap + m.tick;

  // x ticks: fewer until the labels fit side by side with a two-character gap.
  std::vector<double> xt, xminor;
  std::vector<std::string> xl;
  int right = 2 * m.pad, fw = W - left - right;
  for (int target = std::clamp(fw / (80 * m.s), 2, 10); target >= 1; --target) {
    make_ticks(in.xlo, in.xhi, in.xlog, target, xt, xl, xminor);
    right = std::max(2 * m.pad, (xl.empty() ? 0 : text_width(xl.back(), m.s) / 2) + m.pad);
    fw = W - left - right;
    int need = 0;
    for (const auto& l : xl) need += text_width(l, m.s) + 2 * detail::font_cell_w * m.s;
    if (need <= fw) break;
  }
  if (fw < 4 * m.th) throw InputError("plot: " + std::to_string(W) + " px is too narrow");

  for (int i = 0; i < n; ++i) {
    PanelLayout& pl = L.panels[std::size_t(i)];
    const int y0 = top + i * (panel_h + panel_gap);
    pl.frame = {left, y0, W - right - 1, y0 + panel_h - 1};
    pl.x = Axis{in.xlo, in.xhi, double(pl.frame.x0), double(pl.frame.x1), in.xlog};
    pl.y.p0 = pl.frame.y1, pl.y.p1 = pl.frame.y0;
    pl.xticks = xt, pl.xminor = xminor;
    if (i == n - 1) pl.xtick_labels = xl;
    pl.legend = legend_rect(in.panels[std::size_t(i)].legend, pl.frame, st.legend, m);
  }
  return L;
}

inline void draw_grid(Image& img, const PlotLayout& L, const PlotStyle& st) {
  if (!st.grid_lines) return;
  for (const PanelLayout& p : L.panels) {
    for (double v : p.xticks) {
      const int x = int(std::lround(p.x.to_pixel(v)));
      if (x > p.frame.x0 && x < p.frame.x1) draw_line(img, x, p.frame.y0, x, p.frame.y1, st.grid);
    }
    for (double v : p.yticks) {
      const int y = int(std::lround(p.y.to_pixel(v)));
      if (y > p.frame.y0 && y < p.frame.y1) draw_line(img, p.frame.x0, y, p.frame.x1, y, st.grid);
    }
  }
}

inline void draw_legend(Image& img, const Rect& r, const std::vector<LegendItem>& items, const PlotStyle& st,
                        const Metrics& m) {
  if (r.empty()) return;
  fill_rect(img, r, st.background, 0.85);
  draw_rect(img, r, colors::grey);
  StrokeCanvas canvas(img);
  const int row = m.th + 2 * m.gap, sample = 14 * m.s;
  int k = 0;
  for (const LegendItem& it : items) {
    if (it.label.empty()) continue;
    const int cy = r.y0 + m.gap + k * row + row / 2;
    const int sx = r.x0 + m.pad;
    if (it.line) {
      const std::array<double, 2> dash = it.dashed ? std::array<double, 2>{3 * it.width + 2, 2 * it.width + 2}
                                                   : std::array<double, 2>{0, 0};
      canvas.polyline({{double(sx), double(cy)}, {double(sx + sample), double(cy)}}, it.color, it.width, r, dash,
                      st.antialias);
    }
    if (it.marker > 0) fill_circle(img, sx + sample / 2.0, cy, it.marker, it.color, st.antialias);
    draw_text(img, sx + sample + m.pad, cy, it.label, st.foreground, m.s, HAlign::left, VAlign::middle);
    ++k;
  }
}

// Frame, ticks, tick labels, axis labels, panel titles, legends and the figure title: everything
// drawn over the data.
inline void draw_decorations(Image& img, const PlotLayout& L, const PlotStyle& st, const LayoutInput& in) {
  const Metrics m(st.scale_for(L.width, L.height));
  const RGB fg = st.foreground;
  for (std::size_t i = 0; i < L.panels.size(); ++i) {
    const PanelLayout& p = L.panels[i];
    const PanelInput& pin = in.panels[i];
    draw_rect(img, p.frame, fg);
    for (std::size_t k = 0; k < p.xticks.size(); ++k) {
      const int x = int(std::lround(p.x.to_pixel(p.xticks[k])));
      draw_line(img, x, p.frame.y1, x, p.frame.y1 + m.tick, fg);
      if (k < p.xtick_labels.size())
        draw_text(img, x, p.frame.y1 + m.tick + m.gap, p.xtick_labels[k], fg, m.s, HAlign::center, VAlign::top);
    }
    for (double v : p.xminor) {
      const int x = int(std::lround(p.x.to_pixel(v)));
      draw_line(img, x, p.frame.y1, x, p.frame.y1 + m.tick / 2, fg);
    }
    for (std::size_t k = 0; k < p.yticks.size(); ++k) {
      const int y = int(std::lround(p.y.to_pixel(p.yticks[k])));
      draw_line(img, p.frame.x0 - m.tick, y, p.frame.x0, y, fg);
      draw_text(img, p.frame.x0 - m.tick - m.gap, y, p.ytick_labels[k], fg, m.s, HAlign::right, VAlign::middle);
    }
    for (double v : p.yminor) {
      const int y = int(std::lround(p.y.to_pixel(v)));
      draw_line(img, p.frame.x0 - m.tick / 2, y, p.frame.x0, y, fg);
    }
    if (!pin.y.label.empty())
      draw_text_vertical(img, m.pad + m.th / 2, (p.frame.y0 + p.frame.y1) / 2, pin.y.label, fg, m.s);
    if (!pin.title.empty()) {
      const int tx = p.frame.x0 + m.pad, ty = p.frame.y0 + m.pad;
      fill_rect(img, {tx - m.gap, ty - m.gap, tx + text_width(pin.title, m.s) + m.gap, ty + m.th + m.gap},
                st.background, 0.85);
      draw_text(img, tx, ty, pin.title, fg, m.s);
    }
    draw_legend(img, p.legend, pin.legend, st, m);
  }
  if (!L.panels.empty() && !in.xlabel.empty()) {
    const Rect& f = L.panels.back().frame;
    draw_text(img, (f.x0 + f.x1) / 2, L.height - m.gap - m.pad / 2, in.xlabel, fg, m.s, HAlign::center, VAlign::bottom);
  }
  if (!in.title.empty()) draw_text(img, L.width / 2, m.pad, in.title, fg, m.s + 1, HAlign::center, VAlign::top);
}

// Pixel positions of a series; non-finite (or non-positive on a log axis) points become gaps.
inline std::vector<std::array<double, 2>> to_pixels(const std::vector<double>& x, const std::vector<double>& y,
                                                    const PanelLayout& p) {
  std::vector<std::array<double, 2>> pts(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) pts[i] = {p.x.to_pixel(x[i]), p.y.to_pixel(y[i])};
  return pts;
}

}  // namespace detail

// ================================ LinePlot =======================================================

struct Series {
  std::vector<double> x, y;
  std::string label;            // empty: not in the legend
  std::optional<RGB> color;     // default: the panel's next palette colour (references: black)
  double width = 0;             // px; 0 uses PlotStyle::line_width
  bool dashed = false;
  double marker = 0;            // radius in px of a dot at every point; 0: none
};

class LinePlot {
 public:
  explicit LinePlot(std::string title = "") : title_(std::move(title)), panels_(1) {}

  LinePlot& title(std::string t) { return title_ = std::move(t), *this; }
  LinePlot& xlabel(std::string t) { return x_.label = std::move(t), *this; }
  LinePlot& ylabel(std::string t, int panel = 0) { return at(panel).y.label = std::move(t), *this; }
  LinePlot& panel_title(std::string t, int panel) { return at(panel).title = std::move(t), *this; }
  // n stacked panels sharing the x axis; existing panels and their series are kept.
  LinePlot& panels(int n) {
    if (n < 1) throw InputError("LinePlot::panels: need at least one panel, got " + std::to_string(n));
    panels_.resize(std::size_t(n));
    return *this;
  }
  LinePlot& xlim(double lo, double hi) { return x_.lim = detail::checked_lim(lo, hi, "LinePlot::xlim"), *this; }
  LinePlot& ylim(double lo, double hi, int panel = 0) {
    return at(panel).y.lim = detail::checked_lim(lo, hi, "LinePlot::ylim"), *this;
  }
  LinePlot& log_x(bool on = true) { return x_.log = on, *this; }
  LinePlot& log_y(bool on = true, int panel = 0) { return at(panel).y.log = on, *this; }

  LinePlot& add(Series s, int panel = 0) {
    Panel& p = at(panel);
    if (s.x.size() != s.y.size())
      throw InputError("LinePlot::add: series '" + s.label + "' has " + std::to_string(s.x.size()) +
                                  " x values and " + std::to_string(s.y.size()) + " y values");
    if (!s.color) s.color = s.dashed ? colors::black : palette_color(p.next_color++);
    p.series.push_back(std::move(s));
    return *this;
  }
  LinePlot& add(std::vector<double> x, std::vector<double> y, std::string label = "", int panel = 0) {
    Series s;
    s.x = std::move(x), s.y = std::move(y), s.label = std::move(label);
    return add(std::move(s), panel);
  }
  // A dashed series, e.g. the measured response the simulations are compared with.
  LinePlot& add_reference(std::vector<double> x, std::vector<double> y, std::string label = "", int panel = 0) {
    Series s;
    s.x = std::move(x), s.y = std::move(y), s.label = std::move(label), s.dashed = true;
    return add(std::move(s), panel);
  }

  PlotStyle& style() { return style_; }
  const PlotStyle& style() const { return style_; }
  int num_panels() const { return int(panels_.size()); }
  const std::vector<Series>& series(int panel = 0) const { return panels_.at(std::size_t(panel)).series; }

  PlotLayout layout(int width = 1000, int height = 600) const { return detail::build_layout(width, height, style_, input()); }

  Image render(int width = 1000, int height = 600) const {
    const detail::LayoutInput in = input();
    const PlotLayout L = detail::build_layout(width, height, style_, in);
    Image img(width, height, style_.background);
    detail::draw_grid(img, L, style_);
    StrokeCanvas canvas(img);
    for (std::size_t i = 0; i < panels_.size(); ++i) {
      const PanelLayout& pl = L.panels[i];
      for (const Series& s : panels_[i].series) {
        const double w = s.width > 0 ? s.width : style_.line_width;
        const auto pts = detail::to_pixels(s.x, s.y, pl);
        const std::array<double, 2> dash = s.dashed ? std::array<double, 2>{3 * w + 2, 2 * w + 2} : std::array<double, 2>{0, 0};
        canvas.polyline(pts, *s.color, w, pl.frame, dash, style_.antialias);
        if (s.marker > 0)
          for (const auto& q : pts)
            if (pl.frame.contains(int(std::lround(q[0])), int(std::lround(q[1]))))
              fill_circle(img, q[0], q[1], s.marker, *s.color, style_.antialias);
      }
    }
    detail::draw_decorations(img, L, style_, in);
    return img;
  }

  void save_png(const std::string& path, int width = 1000, int height = 600) const { write_png(path, render(width, height)); }

 private:
  struct Panel {
    detail::AxisSpec y;
    std::string title;
    std::vector<Series> series;
    std::size_t next_color = 0;
  };
  Panel& at(int panel) {
    if (panel < 0 || panel >= int(panels_.size()))
      throw InputError("LinePlot: panel " + std::to_string(panel) + " does not exist (the plot has " +
                              std::to_string(panels_.size()) + "; call panels(n) first)");
    return panels_[std::size_t(panel)];
  }

  // Resolves ranges: x tight to the data (time axes start and end at the data), y from the points
  // visible in the x range, widened by 5% so curves do not run along the frame.
  detail::LayoutInput input() const {
    detail::LayoutInput in;
    in.title = title_, in.xlabel = x_.label, in.xlog = x_.log;
    double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin;
    for (const Panel& p : panels_)
      for (const Series& s : p.series) {
        const auto r = detail::finite_range(s.x, x_.log);
        xmin = std::min(xmin, r.first), xmax = std::max(xmax, r.second);
      }
    std::tie(in.xlo, in.xhi) = detail::resolve_range(x_, xmin, xmax, 0.0);
    for (const Panel& p : panels_) {
      detail::PanelInput pi;
      pi.y = p.y, pi.title = p.title;
      double ymin = std::numeric_limits<double>::infinity(), ymax = -ymin;
      for (const Series& s : p.series) {
        for (std::size_t k = 0; k < s.y.size(); ++k)
          if (s.x[k] >= in.xlo && s.x[k] <= in.xhi && std::isfinite(s.y[k]) && (!p.y.log || s.y[k] > 0))
            ymin = std::min(ymin, s.y[k]), ymax = std::max(ymax, s.y[k]);
        pi.legend.push_back({s.label, *s.color, s.width > 0 ? s.width : style_.line_width, s.dashed, true, s.marker});
      }
      std::tie(pi.lo, pi.hi) = detail::resolve_range(p.y, ymin, ymax, 0.05);
      in.panels.push_back(std::move(pi));
    }
    return in;
  }

  std::string title_;
  detail::AxisSpec x_;
  std::vector<Panel> panels_;
  PlotStyle style_;
};

// ================================ ScatterPlot / Pareto ===========================================

// Indices of the points not dominated when minimising both x and y, sorted by increasing x.
// Non-finite points are ignored; of exact duplicates only the first is kept.
inline std::vector<std::size_t> pareto_front(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i)
    if (std::isfinite(x[i]) && std::isfinite(y[i])) idx.push_back(i);
  std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    return x[a] < x[b] || (x[a] == x[b] && y[a] < y[b]);
  });
  // Sweep by x: a point is on the front iff its y is below every y seen so far.
  std::vector<std::size_t> front;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i : idx)
    if (y[i] < best) {
      front.push_back(i);
      best = y[i];
    }
  return front;
}

struct ScatterPoint {
  double x = 0, y = 0;
  std::string label;         // drawn next to the marker
  std::string group;         // points of a group share a colour and one legend entry
  std::optional<RGB> color;  // overrides the group colour
};

class ScatterPlot {
 public:
  explicit ScatterPlot(std::string title = "") : title_(std::move(title)) {}

  ScatterPlot& title(std::string t) { return title_ = std::move(t), *this; }
  ScatterPlot& xlabel(std::string t) { return x_.label = std::move(t), *this; }
  ScatterPlot& ylabel(std::string t) { return y_.label = std::move(t), *this; }
  ScatterPlot& log_x(bool on = true) { return x_.log = on, *this; }
  ScatterPlot& log_y(bool on = true) { return y_.log = on, *this; }
  ScatterPlot& xlim(double lo, double hi) { return x_.lim = detail::checked_lim(lo, hi, "ScatterPlot::xlim"), *this; }
  ScatterPlot& ylim(double lo, double hi) { return y_.lim = detail::checked_lim(lo, hi, "ScatterPlot::ylim"), *this; }
  // Connects the non-dominated points (minimising x and y) with a line, listed as "Pareto front".
  ScatterPlot& show_pareto_front(bool on = true, RGB color = colors::dark_grey) {
    pareto_ = on, pareto_color_ = color;
    return *this;
  }
  ScatterPlot& add(ScatterPoint p) {
    if (!p.group.empty() && std::find(groups_.begin(), groups_.end(), p.group) == groups_.end())
      groups_.push_back(p.group);
    points_.push_back(std::move(p));
    return *this;
  }
  ScatterPlot& add(double x, double y, std::string label = "", std::string group = "") {
    return add(ScatterPoint{x, y, std::move(label), std::move(group), std::nullopt});
  }

  PlotStyle& style() { return style_; }
  const PlotStyle& style() const { return style_; }
  const std::vector<ScatterPoint>& points() const { return points_; }

  // Colour a point is drawn with: its own, else its group's palette colour, else the first colour.
  RGB color_of(const ScatterPoint& p) const {
    if (p.color) return *p.color;
    const auto it = std::find(groups_.begin(), groups_.end(), p.group);
    return it == groups_.end() ? palette_color(0) : palette_color(std::size_t(it - groups_.begin()));
  }
  // Indices into points() of the Pareto front (only points drawable on the axes are considered).
  std::vector<std::size_t> front() const {
    std::vector<double> xs, ys;
    for (const auto& p : points_) {
      const bool ok = (!x_.log || p.x > 0) && (!y_.log || p.y > 0);
      xs.push_back(ok ? p.x : std::numeric_limits<double>::quiet_NaN());
      ys.push_back(p.y);
    }
    return pareto_front(xs, ys);
  }

  PlotLayout layout(int width = 1000, int height = 600) const {
    return detail::build_layout(width, height, style_, input(width, height));
  }

  Image render(int width = 1000, int height = 600) const {
    const detail::LayoutInput in = input(width, height);
    const PlotLayout L = detail::build_layout(width, height, style_, in);
    const PanelLayout& pl = L.panels[0];
    const detail::Metrics m(style_.scale_for(width, height));
    Image img(width, height, style_.background);
    detail::draw_grid(img, L, style_);
    if (pareto_) {
      std::vector<std::array<double, 2>> pts;
      for (std::size_t i : front()) pts.push_back({pl.x.to_pixel(points_[i].x), pl.y.to_pixel(points_[i].y)});
      StrokeCanvas(img).polyline(pts, pareto_color_, style_.line_width, pl.frame, {0, 0}, style_.antialias);
    }
    const double r = marker_radius(m);
    for (const ScatterPoint& p : points_) {
      const double px = pl.x.to_pixel(p.x), py = pl.y.to_pixel(p.y);
      if (!std::isfinite(px) || !std::isfinite(py) || !pl.frame.contains(int(std::lround(px)), int(std::lround(py))))
        continue;
      fill_circle(img, px, py, r + 1, style_.foreground, style_.antialias);
      fill_circle(img, px, py, r, color_of(p), style_.antialias);
      if (p.label.empty()) continue;
      // Right of the marker unless that leaves the frame, then left.
      const int tw = text_width(p.label, m.s);
      const bool right = px + r + m.gap + tw < pl.frame.x1 - m.gap;
      draw_text(img, int(std::lround(right ? px + r + m.gap : px - r - m.gap)), int(std::lround(py - r)), p.label,
                style_.foreground, m.s, right ? HAlign::left : HAlign::right, VAlign::bottom);
    }
    detail::draw_decorations(img, L, style_, in);
    return img;
  }

  void save_png(const std::string& path, int width = 1000, int height = 600) const { write_png(path, render(width, height)); }

 private:
  double marker_radius(const detail::Metrics& m) const { return 2.5 * m.s; }
  detail::LayoutInput input(int width, int height) const {
    detail::LayoutInput in;
    in.title = title_, in.xlabel = x_.label, in.xlog = x_.log;
    std::vector<double> xs, ys;
    for (const auto& p : points_)
      if ((!x_.log || p.x > 0) && (!y_.log || p.y > 0)) xs.push_back(p.x), ys.push_back(p.y);
    const auto rx = detail::finite_range(xs, x_.log), ry = detail::finite_range(ys, y_.log);
    std::tie(in.xlo, in.xhi) = detail::resolve_range(x_, rx.first, rx.second, 0.08);
    detail::PanelInput pi;
    pi.y = y_;
    std::tie(pi.lo, pi.hi) = detail::resolve_range(y_, ry.first, ry.second, 0.08);
    const double r = marker_radius(detail::Metrics(style_.scale_for(width, height)));
    for (std::size_t g = 0; g < groups_.size(); ++g) pi.legend.push_back({groups_[g], palette_color(g), 2, false, false, r});
    if (pareto_) pi.legend.push_back({"Pareto front", pareto_color_, style_.line_width, false, true, 0});
    in.panels.push_back(std::move(pi));
    return in;
  }

  std::string title_;
  detail::AxisSpec x_, y_;
  std::vector<ScatterPoint> points_;
  std::vector<std::string> groups_;
  bool pareto_ = false;
  RGB pareto_color_ = colors::dark_grey;
  PlotStyle style_;
};

// ================================ Wireframe3D ====================================================

using Segment3 = std::array<Eigen::Vector3d, 2>;

// 3-D line drawing, z up. The camera looks at the centre of everything added, from `azimuth` degrees
// around z (measured from +x towards +y) and `elevation` degrees above the horizontal; the view is
// scaled to fill the image. Segments are drawn far to near so nearer members overlap farther ones.
class Wireframe3D {
 public:
  explicit Wireframe3D(std::string title = "") : title_(std::move(title)) {}

  Wireframe3D& title(std::string t) { return title_ = std::move(t), *this; }
  Wireframe3D& camera(double azimuth_deg, double elevation_deg) {
    az_ = azimuth_deg, el_ = std::clamp(elevation_deg, -89.9, 89.9);
    return *this;
  }
  // Perspective with the eye `distance` bounding-sphere radii from the centre (> 1); off: orthographic.
  Wireframe3D& perspective(bool on = true, double distance = 3.0) {
    if (on && !(distance > 1.0))
      throw InputError("Wireframe3D::perspective: distance must exceed 1 bounding radius, got " +
                                  std::to_string(distance));
    persp_ = on, dist_ = distance;
    return *this;
  }
  Wireframe3D& line_width(double px) { return width_ = px, *this; }
  Wireframe3D& show_axes(bool on = true) { return axes_ = on, *this; }

  // One colour per segment, or a single colour for all of them.
  Wireframe3D& add_segments(const std::vector<Segment3>& segs, const std::vector<RGB>& colours) {
    if (colours.size() != segs.size() && colours.size() != 1)
      throw InputError("Wireframe3D::add_segments: " + std::to_string(segs.size()) + " segments but " +
                                  std::to_string(colours.size()) + " colours (need one per segment, or one)");
    for (std::size_t i = 0; i < segs.size(); ++i) segs_.push_back({segs[i], colours.size() == 1 ? colours[0] : colours[i]});
    return *this;
  }
  Wireframe3D& add_segments(const std::vector<Segment3>& segs, RGB colour) { return add_segments(segs, std::vector<RGB>{colour}); }

  // A planar quad (wall, floor, table top): translucent fill plus outline. fill_alpha 0: outline only.
  Wireframe3D& add_quad(const std::array<Eigen::Vector3d, 4>& corners, RGB colour, double fill_alpha = 0.15) {
    quads_.push_back({corners, colour, std::clamp(fill_alpha, 0.0, 1.0)});
    return *this;
  }
  // Floor rectangle [x0,x1]x[y0,y1] at height z with grid lines every `spacing` (0: about 10 cells).
  Wireframe3D& floor_grid(double x0, double x1, double y0, double y1, double z = 0, double spacing = 0) {
    if (!(x1 > x0) || !(y1 > y0)) throw InputError("Wireframe3D::floor_grid: empty rectangle");
    if (!(spacing > 0)) spacing = nice_step(std::max(x1 - x0, y1 - y0), 10);
    const RGB c{200, 200, 200};
    // Lines on multiples of the spacing (a room from -0.3 to 4.2 m gets lines at 0, 0.5, ...);
    // the rectangle's own edges are the quad outline.
    for (double k = std::ceil(x0 / spacing); k * spacing <= x1 && grid_.size() < 4000; ++k)
      grid_.push_back({Segment3{Eigen::Vector3d(k * spacing, y0, z), Eigen::Vector3d(k * spacing, y1, z)}, c});
    for (double k = std::ceil(y0 / spacing); k * spacing <= y1 && grid_.size() < 4000; ++k)
      grid_.push_back({Segment3{Eigen::Vector3d(x0, k * spacing, z), Eigen::Vector3d(x1, k * spacing, z)}, c});
    return add_quad({Eigen::Vector3d(x0, y0, z), Eigen::Vector3d(x1, y0, z), Eigen::Vector3d(x1, y1, z),
                     Eigen::Vector3d(x0, y1, z)},
                    RGB{150, 150, 150}, 0.12);
  }
  Wireframe3D& legend(std::string label, RGB colour) {
    legend_.push_back({std::move(label), colour, width_, false, true, 0});
    return *this;
  }
  PlotStyle& style() { return style_; }

  // Pixel position of a 3-D point in a width x height render (NaN when behind a perspective eye).
  Eigen::Vector2d project(const Eigen::Vector3d& p, int width = 1000, int height = 800) const {
    return view(width, height).pixel(p);
  }

  Image render(int width = 1000, int height = 800) const {
    const View v = view(width, height);
    const detail::Metrics m(style_.scale_for(width, height));
    Image img(width, height, style_.background);
    auto px = [&](const Eigen::Vector3d& p) {
      const Eigen::Vector2d q = v.pixel(p);
      return std::array<double, 2>{q.x(), q.y()};
    };
    for (const Quad& q : quads_) {
      std::vector<std::array<double, 2>> poly;
      for (const auto& c : q.corners) poly.push_back(px(c));
      if (q.alpha > 0) fill_polygon(img, poly, q.color, q.alpha);
    }
    for (const Seg& g : grid_) {
      const auto a = px(g.s[0]), b = px(g.s[1]);
      draw_line(img, a[0], a[1], b[0], b[1], g.color, 1.0, style_.antialias);
    }
    for (const Quad& q : quads_)
      for (int k = 0; k < 4; ++k) {
        const auto a = px(q.corners[std::size_t(k)]), b = px(q.corners[std::size_t((k + 1) % 4)]);
        draw_line(img, a[0], a[1], b[0], b[1], q.color, 1.0, style_.antialias);
      }
    std::vector<std::size_t> order(segs_.size());
    std::vector<double> depth(segs_.size());
    for (std::size_t i = 0; i < segs_.size(); ++i) {
      order[i] = i;
      depth[i] = v.depth(0.5 * (segs_[i].s[0] + segs_[i].s[1]));
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return depth[a] < depth[b]; });
    for (std::size_t i : order) {
      const auto a = px(segs_[i].s[0]), b = px(segs_[i].s[1]);
      draw_line(img, a[0], a[1], b[0], b[1], segs_[i].color, width_, style_.antialias);
    }
    if (axes_) draw_triad(img, v, m);
    if (!title_.empty()) draw_text(img, width / 2, m.pad, title_, style_.foreground, m.s + 1, HAlign::center);
    if (!legend_.empty()) {
      const Rect frame{0, v.top, width - 1, height - 1};
      detail::draw_legend(img, detail::legend_rect(legend_, frame, LegendPos::top_left, m), legend_, style_, m);
    }
    return img;
  }

  void save_png(const std::string& path, int width = 1000, int height = 800) const { write_png(path, render(width, height)); }

 private:
  struct Seg {
    Segment3 s;
    RGB color;
  };
  struct Quad {
    std::array<Eigen::Vector3d, 4> corners;
    RGB color;
    double alpha;
  };

  // Camera frame and the 2-D fit of everything into the image below the title.
  struct View {
    Eigen::Vector3d c, right, up, dir;  // dir points from the scene towards the eye
    bool persp = false;
    double eye = 0;  // eye distance from c (perspective)
    double scale = 1, cx = 0, cy = 0, ox = 0, oy = 0;
    int top = 0;
    Eigen::Vector2d screen(const Eigen::Vector3d& p) const {
      const Eigen::Vector3d q = p - c;
      Eigen::Vector2d s(q.dot(right), q.dot(up));
      if (persp) {
        const double d = eye - q.dot(dir);
        if (!(d > 1e-9 * eye)) return Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
        s *= eye / d;
      }
      return s;
    }
    double depth(const Eigen::Vector3d& p) const { return (p - c).dot(dir); }
    Eigen::Vector2d pixel(const Eigen::Vector3d& p) const {
      const Eigen::Vector2d s = screen(p);
      return {ox + (s.x() - cx) * scale, oy - (s.y() - cy) * scale};
    }
  };

  View view(int W, int H) const {
    const detail::Metrics m(style_.scale_for(W, H));
    View v;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    auto grow = [&](const Eigen::Vector3d& p) {
      if (p.allFinite()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    };
    for (const Seg& s : segs_) grow(s.s[0]), grow(s.s[1]);
    for (const Seg& s : grid_) grow(s.s[0]), grow(s.s[1]);
    for (const Quad& q : quads_)
      for (const auto& c : q.corners) grow(c);
    if (!(lo.x() <= hi.x())) lo.setZero(), hi.setOnes();
    v.c = 0.5 * (lo + hi);
    const double radius = std::max(0.5 * (hi - lo).norm(), 1e-12);
    const double a = az_ * std::numbers::pi / 180, e = el_ * std::numbers::pi / 180;
    v.dir = Eigen::Vector3d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
    // Cross products written out: Eigen's cross() lives in Eigen/Geometry, which this header avoids.
    v.right = Eigen::Vector3d(-v.dir.y(), v.dir.x(), 0).normalized();  // z x dir
    v.up = Eigen::Vector3d(v.dir.y() * v.right.z() - v.dir.z() * v.right.y(), v.dir.z() * v.right.x() - v.dir.x() * v.right.z(),
                           v.dir.x() * v.right.y() - v.dir.y() * v.right.x());  // dir x right
    v.persp = persp_;
    v.eye = dist_ * radius;
    // Fit the projected points into the drawing area with equal scale on both axes.
    double sx0 = std::numeric_limits<double>::infinity(), sx1 = -sx0, sy0 = sx0, sy1 = -sx0;
    auto fit = [&](const Eigen::Vector3d& p) {
      const Eigen::Vector2d s = v.screen(p);
      if (!s.allFinite()) return;
      sx0 = std::min(sx0, s.x()), sx1 = std::max(sx1, s.x()), sy0 = std::min(sy0, s.y()), sy1 = std::max(sy1, s.y());
    };
    for (const Seg& s : segs_) fit(s.s[0]), fit(s.s[1]);
    for (const Seg& s : grid_) fit(s.s[0]), fit(s.s[1]);
    for (const Quad& q : quads_)
      for (const auto& c : q.corners) fit(c);
    if (!(sx0 <= sx1)) sx0 = sy0 = -1, sx1 = sy1 = 1;
    v.top = m.pad + (title_.empty() ? 0 : text_height(m.s + 1) + m.pad);
    const double margin = 2.0 * m.pad;
    const double aw = std::max(1.0, W - 2 * margin), ah = std::max(1.0, H - v.top - 2 * margin);
    v.scale = std::min(aw / std::max(sx1 - sx0, 1e-12 * radius), ah / std::max(sy1 - sy0, 1e-12 * radius));
    v.cx = 0.5 * (sx0 + sx1), v.cy = 0.5 * (sy0 + sy1);
    v.ox = 0.5 * W, v.oy = v.top + margin + 0.5 * ah;
    return v;
  }

  // x, y, z arrows in the bottom-left corner, so the viewing direction is unambiguous.
  void draw_triad(Image& img, const View& v, const detail::Metrics& m) const {
    const double len = 16.0 * m.s;
    const double ox = m.pad + len + m.th, oy = img.h - m.pad - len - m.th;
    const std::array<RGB, 3> col = {RGB{214, 39, 40}, RGB{44, 160, 44}, RGB{31, 119, 180}};
    const char* name[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d d = Eigen::Vector3d::Unit(k);
      const double dx = d.dot(v.right) * len, dy = -d.dot(v.up) * len;
      draw_line(img, ox, oy, ox + dx, oy + dy, col[std::size_t(k)], 2.0, style_.antialias);
      const double n = std::max(1e-9, std::hypot(dx, dy));
      draw_text(img, int(std::lround(ox + dx + dx / n * m.th)), int(std::lround(oy + dy + dy / n * m.th)), name[k],
                col[std::size_t(k)], m.s, HAlign::center, VAlign::middle);
    }
  }

  std::string title_;
  double az_ = -60, el_ = 25;
  bool persp_ = false;
  double dist_ = 3.0;
  double width_ = 2.0;
  bool axes_ = true;
  std::vector<Seg> segs_, grid_;
  std::vector<Quad> quads_;
  std::vector<detail::LegendItem> legend_;
  PlotStyle style_;
};

}  // namespace furniture_fem
