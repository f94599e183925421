#pragma once
// furniture_fem/figures/plot.hpp: figures drawn with cairo and written as PNG, SVG or PDF.
//
//   LinePlot      time histories; stacked panels sharing x (the paper's X/Y/Z displacement figures),
//                 dashed reference series (experiment), legend, 1-2-5 ticks, optional log axes.
//   ScatterPlot   labelled points, log axes, Pareto front (wall time vs error).
//   Wireframe3D   beam segments in 3-D (orthographic or perspective), floor grid, translucent walls,
//                 thin reference segments (e.g. initial positions) and text labels at 3-D points.
//
// Every figure has save_png, save_svg and save_pdf (the same layout; SVG and PDF sizes are in points,
// one per pixel) and render() (the pixels, for tests). Text is set in "sans-serif" through cairo's
// text API and measured before it is placed: titles wrap onto a second line, then shrink, so they are
// never clipped. Drawing goes through detail/canvas.hpp, the only header that includes cairo's.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "../core/errors.hpp"

#define FURNITURE_FEM_FIGURES_INTERNAL
#include "detail/canvas.hpp"
#undef FURNITURE_FEM_FIGURES_INTERNAL

namespace furniture_fem {

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
  double legend_font = 0;  // px
};

// A block of text as laid out: its lines, its font size (px) and the box it occupies.
struct TextBlock {
  std::vector<std::string> lines;
  double size = 0;
  Rect box;
};

struct PlotLayout {
  int width = 0, height = 0;
  TextBlock title;  // no lines when the figure has no title
  std::vector<PanelLayout> panels;
};

enum class LegendPos { none, top_right, top_left, bottom_right, bottom_left };

struct PlotStyle {
  double font_size = 0;  // px of tick labels, axis labels and legends; 0: 14 when both sides are at least 450 px, else 11
  RGB background = colors::white, foreground = colors::black, grid = colors::light_grey;
  bool grid_lines = true;
  bool antialias = true;
  double line_width = 2.0;  // default series width in px
  LegendPos legend = LegendPos::top_right;
  double font_for(int w, int h) const { return font_size > 0 ? font_size : (std::min(w, h) >= 450 ? 14.0 : 11.0); }
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

// Sizes derived from the font size: text line height, padding, gaps, tick length (px).
struct Metrics {
  double fs, title_fs;
  int th, pad, gap, tick;
  Metrics(const Canvas& c, double font)
      : fs(font), title_fs(std::round(1.3 * font)), th(int(std::ceil(c.line_height(font)))),
        pad(std::max(3, int(std::lround(0.5 * font)))), gap(std::max(2, int(std::lround(0.25 * font)))),
        tick(std::max(3, int(std::lround(0.35 * font)))) {}
};

// `text` laid out in at most `max_lines` lines no wider than max_w: on one line at `size` if it fits,
// else wrapped at spaces, shrinking the size (down to 70 %) until the wrapped lines fit; as a last
// resort one line shrunk to the width. The block's box is placed centred on `cx`, its top at `top`.
inline TextBlock fit_text(const Canvas& c, const std::string& text, double max_w, double size, int max_lines, bool bold,
                          double cx, int top) {
  TextBlock b;
  if (text.empty()) return b;
  std::vector<std::string> words;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t j = std::min(text.find(' ', i), text.size());
    if (j > i) words.push_back(text.substr(i, j - i));
    i = j + 1;
  }
  auto wrap = [&](double sz) {
    std::vector<std::string> lines;
    std::string cur;
    for (const auto& w : words) {
      const std::string trial = cur.empty() ? w : cur + " " + w;
      if (cur.empty() || c.text_width(trial, sz, bold) <= max_w) cur = trial;
      else lines.push_back(cur), cur = w;
    }
    if (!cur.empty()) lines.push_back(cur);
    return lines;
  };
  auto fits = [&](const std::vector<std::string>& lines, double sz) {
    if (int(lines.size()) > max_lines) return false;
    for (const auto& l : lines)
      if (c.text_width(l, sz, bold) > max_w) return false;
    return true;
  };
  b.size = size;
  b.lines = {text};
  if (!fits(b.lines, size)) {
    bool ok = false;
    for (double sz = size; sz >= 0.7 * size - 1e-9 && !ok; sz -= std::max(0.5, 0.05 * size)) {
      const auto lines = wrap(sz);
      if (fits(lines, sz)) b.lines = lines, b.size = sz, ok = true;
    }
    if (!ok) {
      b.lines = {text};
      b.size = std::max(1.0, std::floor(size * max_w / c.text_width(text, size, bold) * 10) / 10);
    }
  }
  double w = 0;
  for (const auto& l : b.lines) w = std::max(w, c.text_width(l, b.size, bold));
  const int h = int(std::ceil(c.line_height(b.size, bold) * double(b.lines.size())));
  b.box = {int(std::floor(cx - 0.5 * w)), top, int(std::ceil(cx + 0.5 * w)), top + h - 1};
  return b;
}

inline void draw_text_block(const Canvas& c, const TextBlock& b, RGB colour, bool bold) {
  const double lh = c.line_height(b.size, bold), cx = 0.5 * (b.box.x0 + b.box.x1);
  for (std::size_t k = 0; k < b.lines.size(); ++k)
    c.text(cx, b.box.y0 + double(k) * lh, b.lines[k], colour, b.size, HAlign::center, VAlign::top, bold);
}

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

inline double max_width(const Canvas& c, const std::vector<std::string>& labels, double size) {
  double w = 0;
  for (const auto& l : labels) w = std::max(w, c.text_width(l, size));
  return w;
}

// The legend box in a corner of `frame`; its font shrinks (down to 60 %) when the box would be wider
// than 60 % of the frame.
inline Rect legend_rect(const Canvas& c, const std::vector<LegendItem>& items, const Rect& frame, LegendPos pos,
                        const Metrics& m, double& font) {
  std::vector<std::string> labels;
  for (const auto& it : items)
    if (!it.label.empty()) labels.push_back(it.label);
  font = m.fs;
  if (labels.empty() || pos == LegendPos::none) return {};
  const int sample = int(std::lround(2.2 * m.fs));
  auto width = [&](double f) { return int(std::ceil(3 * m.pad + sample + max_width(c, labels, f))); };
  while (width(font) > 0.6 * frame.width() && font > 0.6 * m.fs) font -= 0.5;
  const int row = int(std::ceil(c.line_height(font))) + m.gap;
  const int w = width(font), h = int(labels.size()) * row + 2 * m.gap;
  const int inset = m.pad;
  const bool right = pos == LegendPos::top_right || pos == LegendPos::bottom_right;
  const bool top = pos == LegendPos::top_right || pos == LegendPos::top_left;
  const int x0 = right ? frame.x1 - inset - w : frame.x0 + inset;
  const int y0 = top ? frame.y0 + inset : frame.y1 - inset - h;
  return {x0, y0, x0 + w - 1, y0 + h - 1};
}

// Stacked panels sharing x: title on top, x tick labels and x label under the bottom panel only.
inline PlotLayout build_layout(int W, int H, const PlotStyle& st, const LayoutInput& in) {
  const Measurer meas;
  const Canvas& c = meas.canvas();
  const Metrics m(c, st.font_for(W, H));
  const int n = int(in.panels.size());
  PlotLayout L;
  L.width = W, L.height = H;
  L.panels.resize(std::size_t(n));

  L.title = fit_text(c, in.title, W - 2.0 * m.pad, m.title_fs, 2, true, 0.5 * (W - 1), m.pad);
  const int top = m.pad + (in.title.empty() ? 0 : L.title.box.height() + m.pad) + m.gap;
  const int bottom = m.pad + m.tick + m.gap + m.th + (in.xlabel.empty() ? 0 : m.gap + m.th);
  const int panel_gap = 2 * m.pad;
  const int panel_h = (H - top - bottom - (n - 1) * panel_gap) / std::max(1, n);
  if (panel_h < 3 * m.th)
    throw InputError("plot: " + std::to_string(W) + "x" + std::to_string(H) + " px is too small for " +
                                std::to_string(n) + " panel(s)");

  bool any_ylabel = false;
  double ytick_w = 0;
  const int ytarget = std::clamp(panel_h / (3 * m.th), 2, 8);
  for (int i = 0; i < n; ++i) {
    const PanelInput& p = in.panels[std::size_t(i)];
    PanelLayout& pl = L.panels[std::size_t(i)];
    pl.y = Axis{p.lo, p.hi, 0, 1, p.y.log};
    make_ticks(p.lo, p.hi, p.y.log, ytarget, pl.yticks, pl.ytick_labels, pl.yminor);
    ytick_w = std::max(ytick_w, max_width(c, pl.ytick_labels, m.fs));
    any_ylabel = any_ylabel || !p.y.label.empty();
  }
  const int left = m.pad + (any_ylabel ? m.th + 2 * m.gap : 0) + int(std::ceil(ytick_w)) + m.gap + m.tick;

  // x ticks: fewer until the labels fit side by side with two spaces' gap.
  std::vector<double> xt, xminor;
  std::vector<std::string> xl;
  const double space = c.text_width("  ", m.fs);
  int right = 2 * m.pad, fw = W - left - right;
  for (int target = std::clamp(fw / int(11 * m.fs), 3, 10); target >= 1; --target) {
    make_ticks(in.xlo, in.xhi, in.xlog, target, xt, xl, xminor);
    right = std::max(2 * m.pad, (xl.empty() ? 0 : int(std::ceil(c.text_width(xl.back(), m.fs) / 2))) + m.pad);
    fw = W - left - right;
    double need = 0;
    for (const auto& l : xl) need += c.text_width(l, m.fs) + space;
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
    pl.legend = legend_rect(c, in.panels[std::size_t(i)].legend, pl.frame, st.legend, m, pl.legend_font);
  }
  return L;
}

inline void draw_grid(const Canvas& c, const PlotLayout& L, const PlotStyle& st) {
  if (!st.grid_lines) return;
  for (const PanelLayout& p : L.panels) {
    for (double v : p.xticks) {
      const double x = std::round(p.x.to_pixel(v));
      if (x > p.frame.x0 && x < p.frame.x1) c.line(x, p.frame.y0, x, p.frame.y1, st.grid);
    }
    for (double v : p.yticks) {
      const double y = std::round(p.y.to_pixel(v));
      if (y > p.frame.y0 && y < p.frame.y1) c.line(p.frame.x0, y, p.frame.x1, y, st.grid);
    }
  }
}

inline void draw_legend(const Canvas& c, const Rect& r, double font, const std::vector<LegendItem>& items,
                        const PlotStyle& st, const Metrics& m) {
  if (r.empty()) return;
  c.fill_rect(r, st.background, 0.85);
  c.stroke_rect(r, colors::grey);
  const int row = int(std::ceil(c.line_height(font))) + m.gap, sample = int(std::lround(2.2 * m.fs));
  int k = 0;
  for (const LegendItem& it : items) {
    if (it.label.empty()) continue;
    const double cy = r.y0 + m.gap + k * row + 0.5 * row;
    const double sx = r.x0 + m.pad;
    if (it.line) c.polyline({{sx, cy}, {sx + sample, cy}}, it.color, it.width, r, it.dashed);
    if (it.marker > 0) c.fill_circle(sx + 0.5 * sample, cy, it.marker, it.color);
    c.text(sx + sample + m.pad, cy, it.label, st.foreground, font, HAlign::left, VAlign::middle);
    ++k;
  }
}

// Frame, ticks, tick labels, axis labels, panel titles, legends and the figure title: everything
// drawn over the data.
inline void draw_decorations(const Canvas& c, const PlotLayout& L, const PlotStyle& st, const LayoutInput& in) {
  const Metrics m(c, st.font_for(L.width, L.height));
  const RGB fg = st.foreground;
  for (std::size_t i = 0; i < L.panels.size(); ++i) {
    const PanelLayout& p = L.panels[i];
    const PanelInput& pin = in.panels[i];
    c.stroke_rect(p.frame, fg);
    for (std::size_t k = 0; k < p.xticks.size(); ++k) {
      const double x = std::round(p.x.to_pixel(p.xticks[k]));
      c.line(x, p.frame.y1, x, p.frame.y1 + m.tick, fg);
      if (k < p.xtick_labels.size())
        c.text(x, p.frame.y1 + m.tick + m.gap, p.xtick_labels[k], fg, m.fs, HAlign::center, VAlign::top);
    }
    for (double v : p.xminor) {
      const double x = std::round(p.x.to_pixel(v));
      c.line(x, p.frame.y1, x, p.frame.y1 + m.tick / 2, fg);
    }
    for (std::size_t k = 0; k < p.yticks.size(); ++k) {
      const double y = std::round(p.y.to_pixel(p.yticks[k]));
      c.line(p.frame.x0 - m.tick, y, p.frame.x0, y, fg);
      c.text(p.frame.x0 - m.tick - m.gap, y, p.ytick_labels[k], fg, m.fs, HAlign::right, VAlign::middle);
    }
    for (double v : p.yminor) {
      const double y = std::round(p.y.to_pixel(v));
      c.line(p.frame.x0 - m.tick / 2, y, p.frame.x0, y, fg);
    }
    if (!pin.y.label.empty()) {
      // Reads upwards, centred on the panel; shrunk when longer than the panel is high.
      const double w = c.text_width(pin.y.label, m.fs);
      const double fs = w > p.frame.height() ? m.fs * p.frame.height() / w : m.fs;
      c.text(m.pad + 0.5 * m.th, 0.5 * (p.frame.y0 + p.frame.y1), pin.y.label, fg, fs, HAlign::center, VAlign::middle,
             false, -90);
    }
    if (!pin.title.empty()) {
      const TextBlock t = fit_text(c, pin.title, p.frame.width() - 4.0 * m.pad, m.fs, 1, false, 0, p.frame.y0 + m.pad);
      const double tw = c.text_width(t.lines[0], t.size);
      const int tx = p.frame.x0 + m.pad, ty = p.frame.y0 + m.pad;
      c.fill_rect({tx - m.gap, ty - m.gap, tx + int(std::ceil(tw)) + m.gap, ty + t.box.height() + m.gap}, st.background, 0.85);
      c.text(tx, ty, t.lines[0], fg, t.size);
    }
    draw_legend(c, p.legend, p.legend_font, pin.legend, st, m);
  }
  if (!L.panels.empty() && !in.xlabel.empty()) {
    const Rect& f = L.panels.back().frame;
    c.text(0.5 * (f.x0 + f.x1), L.height - 1 - m.pad, in.xlabel, fg, m.fs, HAlign::center, VAlign::bottom);
  }
  draw_text_block(c, L.title, fg, true);
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

class LinePlot : public detail::FigureFiles<LinePlot, 1000, 600> {
 public:
  static constexpr const char* figure_name = "LinePlot";
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


  // Draws the figure on a cairo canvas (what render() and the save_ functions call).
  void paint(const detail::Canvas& c, int width, int height) const {
    const detail::LayoutInput in = input();
    const PlotLayout L = detail::build_layout(width, height, style_, in);
    detail::draw_grid(c, L, style_);
    for (std::size_t i = 0; i < panels_.size(); ++i) {
      const PanelLayout& pl = L.panels[i];
      for (const Series& s : panels_[i].series) {
        const double w = s.width > 0 ? s.width : style_.line_width;
        const auto pts = detail::to_pixels(s.x, s.y, pl);
        c.polyline(pts, *s.color, w, pl.frame, s.dashed);
        if (s.marker > 0)
          for (const auto& q : pts)
            if (std::isfinite(q[0]) && std::isfinite(q[1]) && pl.frame.contains(int(std::lround(q[0])), int(std::lround(q[1]))))
              c.fill_circle(q[0], q[1], s.marker, *s.color);
      }
    }
    detail::draw_decorations(c, L, style_, in);
  }

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

class ScatterPlot : public detail::FigureFiles<ScatterPlot, 1000, 600> {
 public:
  static constexpr const char* figure_name = "ScatterPlot";
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


  // Draws the figure on a cairo canvas (what render() and the save_ functions call).
  void paint(const detail::Canvas& c, int width, int height) const {
    const detail::LayoutInput in = input(width, height);
    const PlotLayout L = detail::build_layout(width, height, style_, in);
    const PanelLayout& pl = L.panels[0];
    const detail::Metrics m(c, style_.font_for(width, height));
    detail::draw_grid(c, L, style_);
    if (pareto_) {
      std::vector<std::array<double, 2>> pts;
      for (std::size_t i : front()) pts.push_back({pl.x.to_pixel(points_[i].x), pl.y.to_pixel(points_[i].y)});
      c.polyline(pts, pareto_color_, style_.line_width, pl.frame);
    }
    const double r = marker_radius(style_.font_for(width, height));
    for (const ScatterPoint& p : points_) {
      const double px = pl.x.to_pixel(p.x), py = pl.y.to_pixel(p.y);
      if (!std::isfinite(px) || !std::isfinite(py) || !pl.frame.contains(int(std::lround(px)), int(std::lround(py))))
        continue;
      c.fill_circle(px, py, r + 1, style_.foreground);
      c.fill_circle(px, py, r, color_of(p));
      if (p.label.empty()) continue;
      // Right of the marker unless that leaves the frame, then left.
      const double tw = c.text_width(p.label, m.fs);
      const bool right = px + r + m.gap + tw < pl.frame.x1 - m.gap;
      c.text(right ? px + r + m.gap : px - r - m.gap, py - r, p.label, style_.foreground, m.fs,
             right ? HAlign::left : HAlign::right, VAlign::bottom);
    }
    detail::draw_decorations(c, L, style_, in);
  }

 private:
  static double marker_radius(double font) { return 0.36 * font; }
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
    const double r = marker_radius(style_.font_for(width, height));
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
// scaled to fill the image. Segments are drawn far to near so nearer members overlap farther ones;
// reference segments (thin, e.g. the initial positions) are drawn under all of them, and labels over.
class Wireframe3D : public detail::FigureFiles<Wireframe3D, 1000, 800> {
 public:
  static constexpr const char* figure_name = "Wireframe3D";
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
    check_colours("add_segments", segs, colours);
    for (std::size_t i = 0; i < segs.size(); ++i) segs_.push_back({segs[i], colours.size() == 1 ? colours[0] : colours[i], width_});
    return *this;
  }
  Wireframe3D& add_segments(const std::vector<Segment3>& segs, RGB colour) { return add_segments(segs, std::vector<RGB>{colour}); }
  // Segments drawn `width` px wide under every member, e.g. the initial positions in light grey.
  Wireframe3D& add_reference_segments(const std::vector<Segment3>& segs, RGB colour = RGB{190, 190, 190}, double width = 1.0) {
    for (const Segment3& s : segs) refs_.push_back({s, colour, width});
    return *this;
  }
  // Text at a 3-D point (drawn just above it, in a box outlined in `colour`); labels that would
  // overlap each other, the title or the legend are moved up or down and joined to their point.
  Wireframe3D& label(const Eigen::Vector3d& at, std::string text, RGB colour = colors::dark_grey) {
    labels_.push_back({at, std::move(text), colour});
    return *this;
  }

  // A planar quad (wall, floor, table top): translucent fill plus outline. fill_alpha 0: outline only.
  Wireframe3D& add_quad(const std::array<Eigen::Vector3d, 4>& corners, RGB colour, double fill_alpha = 0.15) {
    quads_.push_back({corners, colour, std::clamp(fill_alpha, 0.0, 1.0)});
    return *this;
  }
  // Floor rectangle [x0,x1]x[y0,y1] at height z with grid lines every `spacing` (0: about 10 cells).
  Wireframe3D& floor_grid(double x0, double x1, double y0, double y1, double z = 0, double spacing = 0) {
    if (!(x1 > x0) || !(y1 > y0)) throw InputError("Wireframe3D::floor_grid: empty rectangle");
    if (!(spacing > 0)) spacing = nice_step(std::max(x1 - x0, y1 - y0), 10);
    const RGB c{215, 215, 215};
    // Lines on multiples of the spacing (a room from -0.3 to 4.2 m gets lines at 0, 0.5, ...);
    // the rectangle's own edges are the quad outline.
    for (double k = std::ceil(x0 / spacing); k * spacing <= x1 && grid_.size() < 4000; ++k)
      grid_.push_back({Segment3{Eigen::Vector3d(k * spacing, y0, z), Eigen::Vector3d(k * spacing, y1, z)}, c, 1.0});
    for (double k = std::ceil(y0 / spacing); k * spacing <= y1 && grid_.size() < 4000; ++k)
      grid_.push_back({Segment3{Eigen::Vector3d(x0, k * spacing, z), Eigen::Vector3d(x1, k * spacing, z)}, c, 1.0});
    return add_quad({Eigen::Vector3d(x0, y0, z), Eigen::Vector3d(x1, y0, z), Eigen::Vector3d(x1, y1, z),
                     Eigen::Vector3d(x0, y1, z)},
                    RGB{150, 150, 150}, 0.12);
  }
  Wireframe3D& legend(std::string label, RGB colour, double width = 0) {
    legend_.push_back({std::move(label), colour, width > 0 ? width : width_, false, true, 0});
    return *this;
  }
  PlotStyle& style() { return style_; }
  const PlotStyle& style() const { return style_; }

  // Pixel position of a 3-D point in a width x height render (NaN when behind a perspective eye).
  Eigen::Vector2d project(const Eigen::Vector3d& p, int width = 1000, int height = 800) const {
    const detail::Measurer meas;
    return view(meas.canvas(), width, height).pixel(p);
  }
  // The title as laid out in a width x height render (lines, font size, box).
  TextBlock title_layout(int width = 1000, int height = 800) const {
    const detail::Measurer meas;
    return view(meas.canvas(), width, height).title;
  }


  // Draws the figure on a cairo canvas (what render() and the save_ functions call).
  void paint(const detail::Canvas& c, int width, int height) const {
    const View v = view(c, width, height);
    const detail::Metrics m(c, style_.font_for(width, height));
    auto px = [&](const Eigen::Vector3d& p) {
      const Eigen::Vector2d q = v.pixel(p);
      return std::array<double, 2>{q.x(), q.y()};
    };
    for (const Quad& q : quads_) {
      std::vector<std::array<double, 2>> poly;
      for (const auto& corner : q.corners) poly.push_back(px(corner));
      if (q.alpha > 0) c.fill_polygon(poly, q.color, q.alpha);
    }
    auto draw = [&](const Seg& g) {
      const auto a = px(g.s[0]), b = px(g.s[1]);
      c.line(a[0], a[1], b[0], b[1], g.color, g.width);
    };
    for (const Seg& g : grid_) draw(g);
    for (const Quad& q : quads_)
      for (int k = 0; k < 4; ++k) {
        const auto a = px(q.corners[std::size_t(k)]), b = px(q.corners[std::size_t((k + 1) % 4)]);
        c.line(a[0], a[1], b[0], b[1], q.color, 1.0);
      }
    for (const Seg& g : refs_) draw(g);
    std::vector<std::size_t> order(segs_.size());
    std::vector<double> depth(segs_.size());
    for (std::size_t i = 0; i < segs_.size(); ++i) {
      order[i] = i;
      depth[i] = v.depth(0.5 * (segs_[i].s[0] + segs_[i].s[1]));
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return depth[a] < depth[b]; });
    cairo_set_line_cap(c.context(), CAIRO_LINE_CAP_ROUND);
    for (std::size_t i : order) draw(segs_[i]);
    cairo_set_line_cap(c.context(), CAIRO_LINE_CAP_BUTT);
    if (axes_) draw_triad(c, v, m, height);
    detail::draw_text_block(c, v.title, style_.foreground, true);
    std::vector<Rect> taken;
    if (!v.title.lines.empty()) taken.push_back(v.title.box);
    if (!legend_.empty()) {
      const Rect frame{0, v.top, width - 1, height - 1};
      double font = m.fs;
      const Rect r = detail::legend_rect(c, legend_, frame, LegendPos::top_left, m, font);
      detail::draw_legend(c, r, font, legend_, style_, m);
      taken.push_back(r);
    }
    draw_labels(c, v, m, width, height, taken);
  }

 private:
  struct Seg {
    Segment3 s;
    RGB color;
    double width;
  };
  struct Quad {
    std::array<Eigen::Vector3d, 4> corners;
    RGB color;
    double alpha;
  };
  struct Label {
    Eigen::Vector3d at;
    std::string text;
    RGB color;
  };

  static void check_colours(const char* who, const std::vector<Segment3>& segs, const std::vector<RGB>& colours) {
    if (colours.size() != segs.size() && colours.size() != 1)
      throw InputError(std::string("Wireframe3D::") + who + ": " + std::to_string(segs.size()) + " segments but " +
                                  std::to_string(colours.size()) + " colours (need one per segment, or one)");
  }

  // Camera frame and the 2-D fit of everything into the image below the title.
  struct View {
    Eigen::Vector3d c, right, up, dir;  // dir points from the scene towards the eye
    bool persp = false;
    double eye = 0;  // eye distance from c (perspective)
    double scale = 1, cx = 0, cy = 0, ox = 0, oy = 0;
    int top = 0;
    TextBlock title;
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

  template <class F>
  void each_point(F&& f) const {
    for (const Seg& s : segs_) f(s.s[0]), f(s.s[1]);
    for (const Seg& s : refs_) f(s.s[0]), f(s.s[1]);
    for (const Seg& s : grid_) f(s.s[0]), f(s.s[1]);
    for (const Quad& q : quads_)
      for (const auto& corner : q.corners) f(corner);
  }

  View view(const detail::Canvas& canvas, int W, int H) const {
    const detail::Metrics m(canvas, style_.font_for(W, H));
    View v;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    each_point([&](const Eigen::Vector3d& p) {
      if (p.allFinite()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    });
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
    each_point([&](const Eigen::Vector3d& p) {
      const Eigen::Vector2d s = v.screen(p);
      if (!s.allFinite()) return;
      sx0 = std::min(sx0, s.x()), sx1 = std::max(sx1, s.x()), sy0 = std::min(sy0, s.y()), sy1 = std::max(sy1, s.y());
    });
    if (!(sx0 <= sx1)) sx0 = sy0 = -1, sx1 = sy1 = 1;
    v.title = detail::fit_text(canvas, title_, W - 2.0 * m.pad, m.title_fs, 2, true, 0.5 * (W - 1), m.pad);
    v.top = m.pad + (title_.empty() ? 0 : v.title.box.height() + m.pad);
    // Room above the scene for the labels of its highest points.
    const double margin = 2.0 * m.pad, above = labels_.empty() ? 0.0 : m.th + 2.0 * m.gap;
    const double aw = std::max(1.0, W - 2 * margin), ah = std::max(1.0, H - v.top - 2 * margin - above);
    v.scale = std::min(aw / std::max(sx1 - sx0, 1e-12 * radius), ah / std::max(sy1 - sy0, 1e-12 * radius));
    v.cx = 0.5 * (sx0 + sx1), v.cy = 0.5 * (sy0 + sy1);
    v.ox = 0.5 * W, v.oy = v.top + margin + above + 0.5 * ah;
    return v;
  }

  // x, y, z arrows in the bottom-left corner, so the viewing direction is unambiguous.
  void draw_triad(const detail::Canvas& c, const View& v, const detail::Metrics& m, int height) const {
    const double len = 2.2 * m.fs;
    const double ox = m.pad + len + m.th, oy = height - m.pad - len - m.th;
    const std::array<RGB, 3> col = {RGB{214, 39, 40}, RGB{44, 160, 44}, RGB{31, 119, 180}};
    const char* name[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d d = Eigen::Vector3d::Unit(k);
      const double dx = d.dot(v.right) * len, dy = -d.dot(v.up) * len;
      c.line(ox, oy, ox + dx, oy + dy, col[std::size_t(k)], 2.0);
      const double n = std::max(1e-9, std::hypot(dx, dy));
      c.text(ox + dx + dx / n * 0.7 * m.th, oy + dy + dy / n * 0.7 * m.th, name[k], col[std::size_t(k)], m.fs,
             HAlign::center, VAlign::middle);
    }
  }

  // Each label centred just above its point; when it would overlap one already placed (or the title,
  // or the legend), or leave the image, it moves up (else down) by whole rows and a thin line joins it
  // to its point.
  void draw_labels(const detail::Canvas& c, const View& v, const detail::Metrics& m, int W, int H,
                   std::vector<Rect>& taken) const {
    const double fs = 0.9 * m.fs;
    const int th = int(std::ceil(c.line_height(fs))), row = th + m.gap;
    auto overlaps = [](const Rect& a, const Rect& b) { return a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1; };
    struct Placed {
      const Label* label;
      Eigen::Vector2d at;
      Rect box;
    };
    std::vector<Placed> placed_labels;
    for (const Label& l : labels_) {
      const Eigen::Vector2d p = v.pixel(l.at);
      if (!p.allFinite() || l.text.empty()) continue;
      const int w = int(std::ceil(c.text_width(l.text, fs))) + 2 * m.gap;
      int x0 = int(std::lround(p.x() - 0.5 * w));
      x0 = std::clamp(x0, 1, std::max(1, W - 2 - w));
      const int y_base = int(std::lround(p.y())) - m.gap - th;
      Rect best{x0, y_base, x0 + w - 1, y_base + th - 1};
      bool placed = false;
      for (int k = 0; k < 25 && !placed; ++k) {
        const int shift = (k <= 12 ? -k : k - 12) * row;  // 0, 1, ..., 12 rows up, then 1, ..., 12 down
        const Rect r{x0, y_base + shift, x0 + w - 1, y_base + shift + th - 1};
        if (r.y0 < 1 || r.y1 > H - 2) continue;
        bool free = true;
        for (const Rect& t : taken) free = free && !overlaps(r, t);
        if (free) best = r, placed = true;
      }
      if (best.y0 < 1) best.y1 += 1 - best.y0, best.y0 = 1;
      taken.push_back(best);
      placed_labels.push_back({&l, p, best});
    }
    // Leader lines first, so that no line crosses a label's box.
    for (const auto& [l, p, r] : placed_labels)
      if (r.y1 + 1 < p.y() - m.gap || r.y0 > p.y() + 1)
        c.line(p.x(), p.y(), std::clamp(p.x(), double(r.x0), double(r.x1)), r.y1 + 1 < p.y() ? r.y1 : r.y0, l->color, 1.0);
    for (const auto& [l, p, r] : placed_labels) {
      c.fill_circle(p.x(), p.y(), 2.5, l->color);
      c.fill_rect(r, style_.background, 0.85);
      c.stroke_rect(r, l->color);
      c.text(0.5 * (r.x0 + r.x1), 0.5 * (r.y0 + r.y1), l->text, style_.foreground, fs, HAlign::center, VAlign::middle);
    }
  }

  std::string title_;
  double az_ = -60, el_ = 25;
  bool persp_ = false;
  double dist_ = 3.0;
  double width_ = 2.0;
  bool axes_ = true;
  std::vector<Seg> segs_, refs_, grid_;
  std::vector<Quad> quads_;
  std::vector<Label> labels_;
  std::vector<detail::LegendItem> legend_;
  PlotStyle style_;
};

}  // namespace furniture_fem
