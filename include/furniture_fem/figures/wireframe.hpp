#pragma once
// furniture_fem/figures/wireframe.hpp: Wireframe3D, beam segments in 3-D (orthographic or perspective), floor
// grid, translucent walls, reference segments and labels. Part of furniture_fem/figures/plot.hpp, which includes it.
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
