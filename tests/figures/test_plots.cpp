// LinePlot, ScatterPlot and Wireframe3D: files (read back through cairo) have the requested size and
// data land where the published layout says they should.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "furniture_fem/figures/plot.hpp"
#include "png_reader.hpp"
#include "../support/test_files.hpp"

namespace plots_tests {  // this file's own names (its group compiles files in batches)

namespace fs = std::filesystem;
using namespace furniture_fem;

using ffem_test::tmp;

namespace {
RGB px(const png_test::Png& p, int x, int y) { return {p.at(x, y, 0), p.at(x, y, 1), p.at(x, y, 2)}; }
bool near_colour(const png_test::Png& p, int x, int y, RGB c, int radius = 1) {
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx)
      if (x + dx >= 0 && y + dy >= 0 && x + dx < p.width && y + dy < p.height && px(p, x + dx, y + dy) == c) return true;
  return false;
}
std::vector<double> linspace(double a, double b, int n) {
  std::vector<double> v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) v[std::size_t(i)] = a + (b - a) * i / (n - 1);
  return v;
}
int non_background(const png_test::Png& p, const Rect& r) {
  int n = 0;
  for (int y = std::max(0, r.y0); y <= std::min(p.height - 1, r.y1); ++y)
    for (int x = std::max(0, r.x0); x <= std::min(p.width - 1, r.x1); ++x) n += !(px(p, x, y) == colors::white);
  return n;
}
}  // namespace

TEST_CASE("LinePlot: a constant series lands on one row", "[plot]") {
  const RGB red = palette[3];
  LinePlot plot("Constant");
  Series s;
  s.x = linspace(0, 10, 201);
  s.y.assign(201, 1.0);
  s.label = "y = 1";
  s.color = red;
  plot.add(s).xlabel("time (s)").ylabel("y (m)");
  const std::string path = tmp("lineplot_constant.png");
  plot.save_png(path, 800, 500);
  REQUIRE(fs::exists(path));
  const png_test::Png p = png_test::decode_file(path);
  REQUIRE(p.width == 800);
  REQUIRE(p.height == 500);

  const PlotLayout L = plot.layout(800, 500);
  REQUIRE(L.panels.size() == 1);
  const PanelLayout& pl = L.panels[0];
  const int row = int(std::lround(pl.y.to_pixel(1.0)));
  CHECK(row > pl.frame.y0 + 10);  // the 5% margin keeps it off the frame
  CHECK(row < pl.frame.y1 - 10);
  int on_row = 0, elsewhere = 0, in_legend = 0;
  for (int y = pl.frame.y0; y <= pl.frame.y1; ++y)
    for (int x = pl.frame.x0; x <= pl.frame.x1; ++x) {
      if (!(px(p, x, y) == red)) continue;
      if (pl.legend.contains(x, y)) ++in_legend;
      else if (std::abs(y - row) <= 1) on_row += y == row;
      else ++elsewhere;
    }
  CHECK(elsewhere == 0);
  CHECK(on_row >= pl.frame.width() - 2 - (pl.legend.empty() ? 0 : pl.legend.width()));
  CHECK(in_legend > 0);  // the legend shows the line sample
  CHECK_FALSE(pl.legend.empty());
  // Tick labels and the y label live left of the frame, the x label below it, the title above.
  CHECK(non_background(p, {0, pl.frame.y0, pl.frame.x0 - 2, pl.frame.y1}) > 100);
  CHECK(non_background(p, {pl.frame.x0, pl.frame.y1 + 2, pl.frame.x1, p.height - 1}) > 100);
  CHECK(non_background(p, {0, 0, p.width - 1, pl.frame.y0 - 2}) > 50);
}

TEST_CASE("LinePlot: data points map to the pixels the layout predicts", "[plot]") {
  LinePlot plot;
  plot.style().legend = LegendPos::none;
  plot.add({0, 5, 10}, {0, 2, 0}, "tent");
  const Image img = plot.render(600, 400);
  const PlotLayout L = plot.layout(600, 400);
  const PanelLayout& pl = L.panels[0];
  const RGB c = plot.series(0)[0].color.value();
  CHECK(c == palette[0]);
  // x is tight to the data; y is widened by 5% on each side.
  CHECK(pl.x.lo == 0);
  CHECK(pl.x.hi == 10);
  CHECK(pl.y.lo == Approx(-0.1));
  CHECK(pl.y.hi == Approx(2.1));
  CHECK(pl.x.to_pixel(0) == pl.frame.x0);
  CHECK(pl.x.to_pixel(10) == pl.frame.x1);
  // A 2 px line covers the pixel nearest to each point it passes through fully (within one pixel).
  auto near = [&](double x, double y) {
    const int xp = int(std::lround(pl.x.to_pixel(x))), yp = int(std::lround(pl.y.to_pixel(y)));
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (img.get(xp + dx, yp + dy) == c) return true;
    return false;
  };
  CHECK(near(5, 2));    // the apex
  CHECK(near(2.5, 1));  // the middle of the rising edge
  CHECK(near(7.5, 1));
  CHECK_FALSE(near(2.5, 1.5));
  CHECK_FALSE(near(5, 1));
  // Ticks are 1-2-5 multiples inside the axis range, labelled only on the bottom panel.
  CHECK(pl.xticks == std::vector<double>{0, 2, 4, 6, 8, 10});
  CHECK(pl.xtick_labels == std::vector<std::string>{"0", "2", "4", "6", "8", "10"});
  CHECK(pl.yticks.front() >= pl.y.lo);
  CHECK(pl.yticks.back() <= pl.y.hi);
}

TEST_CASE("LinePlot: stacked panels share x and keep their series apart", "[plot]") {
  LinePlot plot("Displacement of the top node");
  plot.panels(3).xlabel("time (s)");
  const char* axis[3] = {"X", "Y", "Z"};
  const auto t = linspace(0, 20, 400);
  for (int k = 0; k < 3; ++k) {
    std::vector<double> sim(t.size()), exp(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) {
      sim[i] = (k + 1) * 0.01 * std::sin(t[i] * (k + 1));
      exp[i] = (k + 1) * 0.012 * std::sin(t[i] * (k + 1) + 0.3);
    }
    Series s;
    s.x = t, s.y = sim, s.label = "ASI-Gauss", s.color = palette[std::size_t(k)];
    plot.add(s, k).add_reference(t, exp, "experiment", k);
    plot.ylabel(std::string(axis[k]) + " (m)", k).panel_title(std::string(axis[k]) + " direction", k);
  }
  const std::string path = tmp("lineplot_panels.png");
  plot.save_png(path, 1000, 900);
  const png_test::Png p = png_test::decode_file(path);
  REQUIRE(p.width == 1000);
  REQUIRE(p.height == 900);
  const PlotLayout L = plot.layout(1000, 900);
  REQUIRE(L.panels.size() == 3);
  for (int k = 0; k < 3; ++k) {
    const PanelLayout& a = L.panels[std::size_t(k)];
    CHECK(a.frame.x0 == L.panels[0].frame.x0);
    CHECK(a.frame.x1 == L.panels[0].frame.x1);
    if (k) CHECK(a.frame.y0 > L.panels[std::size_t(k - 1)].frame.y1);
    CHECK(a.xtick_labels.empty() == (k < 2));
    CHECK(a.y.hi == Approx(0.012 * (k + 1) * 1.1).epsilon(0.02));  // each panel scales to its own data
    // Each panel's colour appears inside its own frame only.
    int inside = 0, outside = 0;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x)
        if (px(p, x, y) == palette[std::size_t(k)]) (a.frame.contains(x, y) ? inside : outside)++;
    CHECK(inside > 300);
    CHECK(outside == 0);
  }
  CHECK_THROWS_AS(plot.add({0, 1}, {0, 1}, "x", 3), InputError);
}

TEST_CASE("LinePlot: reference series is dashed", "[plot]") {
  LinePlot plot;
  plot.style().legend = LegendPos::none;
  plot.add_reference({0, 10}, {0, 0}, "measured");
  plot.add({0, 10}, {1, 1}, "simulated");  // sets the y range so the dashed line is inside
  const Image img = plot.render(600, 400);
  const PanelLayout pl = plot.layout(600, 400).panels[0];
  const int row = int(std::lround(pl.y.to_pixel(0)));
  int runs = 0;
  bool on = false;
  for (int x = pl.frame.x0 + 2; x < pl.frame.x1 - 1; ++x) {
    const bool dark = img.get(x, row) == colors::black;
    runs += dark && !on;
    on = dark;
  }
  CHECK(runs >= 10);
}

TEST_CASE("LinePlot rejects bad input", "[plot]") {
  LinePlot plot;
  CHECK_THROWS_AS(plot.add({0, 1, 2}, {0, 1}, "short"), InputError);
  CHECK_THROWS_AS(plot.add({0}, {0}, "p", 1), InputError);
  CHECK_THROWS_AS(plot.panels(0), InputError);
  CHECK_THROWS_AS(plot.xlim(1, 1), InputError);
  plot.add({0, 1}, {0, 1});
  CHECK_THROWS_AS(plot.render(60, 40), InputError);
  // Empty plots, NaN and log axes with non-positive data still render.
  LinePlot empty("nothing");
  CHECK(empty.render(300, 200).w == 300);
  LinePlot logp;
  logp.log_y().add({0, 1, 2, 3}, {-1, 0.01, NAN, 100});
  const PanelLayout pl = logp.layout(500, 400).panels[0];
  CHECK(pl.y.lo < 0.01);
  CHECK(pl.y.hi > 100);
  CHECK(pl.yticks == std::vector<double>{0.01, 0.1, 1, 10, 100});
  CHECK(logp.render(500, 400).h == 400);
  LinePlot badlog;
  badlog.log_x().xlim(-1, 10).add({1, 2}, {1, 2});
  CHECK_THROWS_AS(badlog.render(500, 400), InputError);
}

TEST_CASE("pareto_front keeps the non-dominated points", "[plot]") {
  const std::vector<double> x = {1, 2, 3, 4, 5, 2, NAN, 0.5};
  const std::vector<double> y = {5, 3, 4, 1, 2, 3, 0, 9};
  CHECK(pareto_front(x, y) == std::vector<std::size_t>{7, 0, 1, 3});
  CHECK(pareto_front({}, {}).empty());
}

TEST_CASE("ScatterPlot: log x, labelled points and Pareto front", "[plot]") {
  ScatterPlot sp("Wall time vs error");
  sp.xlabel("wall time (s)").ylabel("error (%)").log_x().show_pareto_front(true, colors::black);
  sp.add(0.5, 9, "coarse", "ASI-Gauss");
  sp.add(4, 2, "fine", "ASI-Gauss");
  sp.add(60, 1.5, "very fine", "ASI-Gauss");
  sp.add(3, 9.5, "linear", "conventional");  // dominated by "coarse"
  sp.add(40, 3, "cubic", "conventional");
  const std::string path = tmp("scatter_pareto.png");
  sp.save_png(path, 900, 600);
  const png_test::Png p = png_test::decode_file(path);
  REQUIRE(p.width == 900);
  REQUIRE(p.height == 600);
  const PanelLayout pl = sp.layout(900, 600).panels[0];
  CHECK(pl.x.log);
  REQUIRE(pl.xticks.size() == 7);  // two decades: 1-2-5 multiples 0.5 ... 50
  CHECK(pl.xticks[0] == Approx(0.5));
  CHECK(pl.xticks[3] == Approx(5));
  CHECK(pl.xticks[6] == Approx(50));
  CHECK(sp.front() == std::vector<std::size_t>{0, 1, 2});
  for (const auto& pt : sp.points()) {
    INFO(pt.label);
    CHECK(near_colour(p, int(std::lround(pl.x.to_pixel(pt.x))), int(std::lround(pl.y.to_pixel(pt.y))), sp.color_of(pt)));
  }
  CHECK(sp.color_of(sp.points()[0]) == palette[0]);
  CHECK(sp.color_of(sp.points()[3]) == palette[1]);
  // Midway between two front points in screen space lies the front line.
  const double mx = 0.5 * (pl.x.to_pixel(0.5) + pl.x.to_pixel(4)), my = 0.5 * (pl.y.to_pixel(9) + pl.y.to_pixel(2));
  CHECK(near_colour(p, int(std::lround(mx)), int(std::lround(my)), colors::black));
}

namespace {
std::vector<Segment3> cube_edges() {
  std::vector<Segment3> e;
  for (int a = 0; a < 8; ++a)
    for (int k = 0; k < 3; ++k) {
      const int b = a | (1 << k);
      if (b != a) e.push_back({Eigen::Vector3d(a & 1, a >> 1 & 1, a >> 2 & 1), Eigen::Vector3d(b & 1, b >> 1 & 1, b >> 2 & 1)});
    }
  return e;
}
}  // namespace

TEST_CASE("Wireframe3D: segments appear where project() puts them", "[plot]") {
  const auto edges = cube_edges();
  REQUIRE(edges.size() == 12);
  const RGB red = palette[3], blue = palette[0];
  Wireframe3D w("Final state of the room");
  w.add_segments(edges, red).add_segments({{Eigen::Vector3d(0.5, 0.5, 0), Eigen::Vector3d(0.5, 0.5, 1.5)}}, {blue});
  w.floor_grid(-1, 2, -1, 2, 0, 0.5).legend("cabinet", red).legend("post", blue);
  const std::string path = tmp("wireframe.png");
  w.save_png(path, 700, 600);
  const png_test::Png p = png_test::decode_file(path);
  REQUIRE(p.width == 700);
  REQUIRE(p.height == 600);

  // Auto-fit: the floor corners (the widest part) are inside and span most of the width.
  double xmin = 1e9, xmax = -1e9;
  for (double x : {-1.0, 2.0})
    for (double y : {-1.0, 2.0}) {
      const Eigen::Vector2d q = w.project(Eigen::Vector3d(x, y, 0), 700, 600);
      CHECK(q.x() >= 0);
      CHECK(q.x() < 700);
      CHECK(q.y() >= 0);
      CHECK(q.y() < 600);
      xmin = std::min(xmin, q.x()), xmax = std::max(xmax, q.x());
    }
  CHECK(xmax - xmin > 0.7 * 700);
  // z is up on screen.
  CHECK(w.project(Eigen::Vector3d(0.5, 0.5, 1.5), 700, 600).y() < w.project(Eigen::Vector3d(0.5, 0.5, 0), 700, 600).y());
  int hits = 0;
  for (const auto& e : edges) {
    const Eigen::Vector2d m = w.project(0.5 * (e[0] + e[1]), 700, 600);
    hits += near_colour(p, int(std::lround(m.x())), int(std::lround(m.y())), red);
  }
  CHECK(hits >= 10);  // a post or a nearer edge may cover one or two midpoints
  const Eigen::Vector2d top = w.project(Eigen::Vector3d(0.5, 0.5, 1.4), 700, 600);
  CHECK(near_colour(p, int(std::lround(top.x())), int(std::lround(top.y())), blue));
  // The translucent floor tints the background without hiding it.
  const Eigen::Vector2d f = w.project(Eigen::Vector3d(1.75, -0.75, 0), 700, 600);
  const RGB floor = px(p, int(std::lround(f.x())), int(std::lround(f.y())));
  CHECK(floor.r < 255);
  CHECK(floor.r > 200);
}

TEST_CASE("Wireframe3D: perspective shrinks far edges, orthographic does not", "[plot]") {
  const auto edges = cube_edges();
  Wireframe3D w;
  w.add_segments(edges, std::vector<RGB>(edges.size(), colors::black)).camera(-60, 25);
  // The eye is towards (cos -60, sin -60): corner (1,0) is nearest, (0,1) farthest.
  auto height = [&](double x, double y) {
    return (w.project(Eigen::Vector3d(x, y, 0)) - w.project(Eigen::Vector3d(x, y, 1))).norm();
  };
  CHECK(height(1, 0) == Approx(height(0, 1)).epsilon(1e-9));
  w.perspective(true, 2.5);
  CHECK(height(1, 0) > 1.1 * height(0, 1));
  CHECK(w.render(400, 300).w == 400);
  CHECK_THROWS_AS(w.perspective(true, 0.5), InputError);
  CHECK_THROWS_AS(w.add_segments(edges, std::vector<RGB>(3, colors::black)), InputError);
}

}  // namespace plots_tests
