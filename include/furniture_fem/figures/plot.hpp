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
#include "axes.hpp"
#define FURNITURE_FEM_FIGURES_INTERNAL
#include "detail/plot_layout.hpp"
#undef FURNITURE_FEM_FIGURES_INTERNAL

namespace furniture_fem {


// ================================ LinePlot =======================================================

struct Series {
  std::vector<double> x, y;
  std::string label;            // empty: not in the legend
  std::optional<RGB> color;     // default: the panel's next palette colour (references: black)
  double width = 0;             // px; 0 uses PlotStyle::line_width
  bool dashed = false;
  double marker = 0;            // radius in px of a dot at every point; 0: none
  double fill = 0;              // opacity of a fill of the polygon the points close (a plan's outline); 0: none
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
        if (s.fill > 0) c.fill_polygon(pts, *s.color, s.fill);
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

}  // namespace furniture_fem

#include "wireframe.hpp"
