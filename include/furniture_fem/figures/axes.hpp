#pragma once
// furniture_fem/figures/axes.hpp: colours, ticks, axes and the layout and style of a plot (used by every figure).
// Part of furniture_fem/figures/plot.hpp, which includes it.
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

}  // namespace furniture_fem
