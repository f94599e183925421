#pragma once
// furniture_fem/figures/detail/plot_layout.hpp: the layout of a plot: its axes' ranges and ticks, text fitted to its room,
// the legend, the frame and its decorations. Internal: include <furniture_fem/figures/plot.hpp>.
#ifndef FURNITURE_FEM_FIGURES_INTERNAL
#error "furniture_fem/figures/detail/plot_layout.hpp is internal: include <furniture_fem/figures/plot.hpp>"
#endif
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

#include "../../core/errors.hpp"

#include "canvas.hpp"
#include "../axes.hpp"

namespace furniture_fem {

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

}  // namespace furniture_fem
