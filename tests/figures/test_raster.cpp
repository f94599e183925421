// Raster primitives, tick generation and axis mapping.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <set>
#include <utility>

#include "furniture_fem/figures/plot.hpp"

using namespace furniture_fem;

namespace {
std::set<std::pair<int, int>> pixels_not(const Image& img, RGB bg = colors::white) {
  std::set<std::pair<int, int>> s;
  for (int y = 0; y < img.h; ++y)
    for (int x = 0; x < img.w; ++x)
      if (!(img.get(x, y) == bg)) s.insert({x, y});
  return s;
}
}  // namespace

TEST_CASE("Image set, get, blend and clipping", "[raster]") {
  Image img(4, 3, RGB{10, 20, 30});
  CHECK(img.rgb.size() == 36);
  CHECK(img.get(3, 2) == RGB{10, 20, 30});
  img.set(1, 1, RGB{200, 100, 0});
  CHECK(img.get(1, 1) == RGB{200, 100, 0});
  img.set(-1, 0, colors::black);  // ignored, no crash
  img.set(4, 0, colors::black);
  img.blend(0, 0, RGB{110, 220, 130}, 0.5);
  CHECK(img.get(0, 0) == RGB{60, 120, 80});
  img.blend(0, 1, colors::black, 0.0);
  CHECK(img.get(0, 1) == RGB{10, 20, 30});
}

TEST_CASE("plain line drawing sets exactly the Bresenham pixels", "[raster]") {
  SECTION("horizontal (10,10)-(50,10)") {
    Image img(64, 32);
    draw_line(img, 10, 10, 50, 10, colors::black);
    std::set<std::pair<int, int>> expect;
    for (int x = 10; x <= 50; ++x) expect.insert({x, 10});
    CHECK(pixels_not(img) == expect);
    for (int x = 10; x <= 50; ++x) CHECK(img.get(x, 10) == colors::black);
  }
  SECTION("diagonal, both directions") {
    Image a(16, 16), b(16, 16);
    draw_line(a, 0, 0, 7, 7, colors::black);
    draw_line(b, 7, 7, 0, 0, colors::black);
    std::set<std::pair<int, int>> expect;
    for (int i = 0; i <= 7; ++i) expect.insert({i, i});
    CHECK(pixels_not(a) == expect);
    CHECK(pixels_not(b) == expect);
  }
  SECTION("steep line: one pixel per row, 8-connected, endpoints included") {
    Image img(32, 32);
    draw_line(img, 3, 2, 9, 27, colors::black);
    const auto px = pixels_not(img);
    CHECK(px.size() == 26);
    CHECK(px.count({3, 2}) == 1);
    CHECK(px.count({9, 27}) == 1);
    int prev_x = 3;
    for (int y = 2; y <= 27; ++y) {
      int n = 0, xr = -1;
      for (int x = 0; x < 32; ++x)
        if (px.count({x, y})) ++n, xr = x;
      CHECK(n == 1);
      CHECK(std::abs(xr - prev_x) <= 1);
      prev_x = xr;
    }
  }
  SECTION("thickness 3 covers three rows") {
    Image img(64, 32);
    draw_line(img, 10, 10, 50, 10, colors::black, 3);
    std::set<std::pair<int, int>> expect;
    for (int x = 9; x <= 51; ++x)
      for (int y = 9; y <= 11; ++y) expect.insert({x, y});
    CHECK(pixels_not(img) == expect);
  }
  SECTION("lines far outside the image do not crash or draw") {
    Image img(20, 20);
    draw_line(img, -1e12, -5, 1e12, -5, colors::black, 1);
    draw_line(img, -1e12, 30, 1e12, 40, colors::black, 1, true);
    CHECK(pixels_not(img).empty());
  }
}

TEST_CASE("anti-aliased line: solid core, soft edge, nothing far away", "[raster]") {
  Image img(40, 40);
  draw_line(img, 5, 20.25, 35, 20.25, colors::black, 2.0, true);
  CHECK(img.get(20, 20) == colors::black);       // within the core
  CHECK(img.get(20, 21).r > 0);                  // 0.75 px from the axis: partially covered
  CHECK(img.get(20, 21).r < 255);
  CHECK(img.get(20, 21).r < img.get(20, 19).r);  // ... more than row 19, 1.25 px from the axis
  CHECK(img.get(20, 22) == colors::white);       // beyond the edge
  CHECK(img.get(20, 10) == colors::white);
}

TEST_CASE("rectangles, circles and polygons cover the expected pixels", "[raster]") {
  Image img(50, 50);
  fill_rect(img, {5, 6, 9, 8}, colors::black);
  CHECK(pixels_not(img).size() == 5 * 3);
  fill_rect(img, {45, 45, 80, 80}, colors::black);  // clipped to the image
  CHECK(pixels_not(img).size() == 15 + 25);

  Image c(64, 64);
  fill_circle(c, 32, 32, 10, colors::black, false);
  const double n = double(pixels_not(c).size());
  CHECK(n == Approx(3.14159 * 100).epsilon(0.05));
  for (int d = 0; d <= 10; ++d) {  // four-fold symmetric
    CHECK(c.get(32 + d, 32) == c.get(32 - d, 32));
    CHECK(c.get(32, 32 + d) == c.get(32, 32 - d));
  }
  CHECK(c.get(32, 43) == colors::white);

  Image p(12, 12);
  fill_polygon(p, {{2, 2}, {6, 2}, {6, 6}, {2, 6}}, colors::black);
  std::set<std::pair<int, int>> expect;
  for (int x = 2; x <= 5; ++x)
    for (int y = 2; y <= 5; ++y) expect.insert({x, y});
  CHECK(pixels_not(p) == expect);
}

TEST_CASE("bitmap text", "[raster]") {
  CHECK(text_width("abc", 1) == 17);
  CHECK(text_width("abc", 2) == 34);
  CHECK(text_height(2) == 14);

  Image img(20, 20);
  draw_text(img, 3, 4, "I", colors::black);  // 'I': middle column full, serifs top and bottom
  std::set<std::pair<int, int>> expect;
  for (int r = 0; r < 7; ++r) expect.insert({3 + 2, 4 + r});
  for (int c : {1, 3}) expect.insert({3 + c, 4}), expect.insert({3 + c, 4 + 6});
  CHECK(pixels_not(img) == expect);

  // Scale 2 doubles every glyph pixel; the right anchor ends the text at x ('H' fills its last column).
  Image s(40, 40);
  draw_text(s, 30, 5, "H", colors::black, 2, HAlign::right);
  const auto px = pixels_not(s);
  CHECK(px.size() == 4 * (7 + 3 + 7));
  int xmin = 99, xmax = 0;
  for (auto [x, y] : px) xmin = std::min(xmin, x), xmax = std::max(xmax, x);
  CHECK(xmin == 30 - text_width("H", 2));
  CHECK(xmax == 29);

  // Descenders use the cell's spacing row, so 'p' is not a small 'P'.
  Image d(20, 20);
  draw_text(d, 0, 0, "p", colors::black);
  draw_text(d, 10, 0, "P", colors::black);
  CHECK(d.get(0, 7) == colors::black);
  for (int x = 10; x < 15; ++x) CHECK(d.get(x, 7) == colors::white);

  // Rotated text reads bottom to top: 'L' turns into a bar along the bottom and a bar up the right.
  Image v(30, 30);
  draw_text_vertical(v, 15, 15, "L", colors::black);
  const auto vp = pixels_not(v);
  int x0 = 99, x1 = -1, y0 = 99, y1 = -1;
  for (auto [x, y] : vp) x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  CHECK(x1 - x0 + 1 == 7);  // glyph height lies along x
  CHECK(y1 - y0 + 1 == 5);  // glyph width lies along y
  for (int x = x0; x <= x1; ++x) CHECK(vp.count({x, y1}) == 1);  // the stem, at the bottom
  for (int y = y0; y <= y1; ++y) CHECK(vp.count({x1, y}) == 1);  // the foot, up the right side
  CHECK(vp.size() == 7 + 5 - 1);
}

TEST_CASE("dashed polylines have gaps, solid ones do not", "[raster]") {
  Image img(200, 20);
  StrokeCanvas canvas(img);
  canvas.polyline({{10, 5}, {190, 5}}, colors::black, 2, img.bounds(), {8, 6});
  canvas.polyline({{10, 15}, {190, 15}}, colors::black, 2, img.bounds());
  auto runs = [&](int y) {
    int n = 0;
    bool on = false;
    for (int x = 0; x < img.w; ++x) {
      const bool dark = img.get(x, y).r < 128;
      if (dark && !on) ++n;
      on = dark;
    }
    return n;
  };
  CHECK(runs(5) >= 12);  // 180 px / 14 px period
  CHECK(runs(15) == 1);
  // A NaN point breaks the line.
  Image g(100, 10);
  StrokeCanvas(g).polyline({{5, 5}, {40, 5}, {NAN, NAN}, {60, 5}, {95, 5}}, colors::black, 2, g.bounds());
  CHECK(g.get(50, 5) == colors::white);
  CHECK(g.get(20, 5) == colors::black);
  CHECK(g.get(80, 5) == colors::black);
}

TEST_CASE("nice ticks follow the 1-2-5 rule", "[ticks]") {
  CHECK(nice_ticks(0, 9.3) == std::vector<double>{0, 2, 4, 6, 8});
  CHECK(nice_step(9.3) == 2);
  CHECK(nice_step(1.0) == Approx(0.2));
  CHECK(nice_step(100, 4) == 20);
  const auto t = nice_ticks(-0.3, 0.3);
  REQUIRE(t.size() == 7);
  CHECK(t[3] == 0.0);  // exact zero, not 1e-17
  CHECK(nice_ticks(1, 1).empty());

  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1), e(-8, 8);
  for (int trial = 0; trial < 2000; ++trial) {
    const double scale = std::pow(10.0, e(rng));
    const double lo = u(rng) * scale, hi = lo + (0.01 + std::abs(u(rng))) * scale;
    for (int target : {3, 5, 8}) {
      const auto ticks = nice_ticks(lo, hi, target);
      REQUIRE(ticks.size() >= 2);
      const double step = ticks[1] - ticks[0];
      const double mant = step / std::pow(10.0, std::floor(std::log10(step) + 1e-12));
      INFO("lo " << lo << " hi " << hi << " target " << target << " step " << step);
      CHECK((std::abs(mant - 1) < 1e-6 || std::abs(mant - 2) < 1e-6 || std::abs(mant - 5) < 1e-6));
      CHECK(step <= nice_step(hi - lo, target) * (1 + 1e-9));  // the nominal step, or smaller if needed
      CHECK(int(ticks.size()) <= 2 * target + 1);
      CHECK(ticks.front() >= lo - 1e-9 * step);
      CHECK(ticks.back() <= hi + 1e-9 * step);
      CHECK(ticks.front() - lo < step * (1 + 1e-9));  // no multiple of step missed at either end
      CHECK(hi - ticks.back() < step * (1 + 1e-9));
      for (std::size_t k = 0; k < ticks.size(); ++k) {
        CHECK(std::abs(ticks[k] / step - std::round(ticks[k] / step)) < 1e-6);  // multiples of the step
        if (k) CHECK(ticks[k] - ticks[k - 1] == Approx(step).epsilon(1e-6));
      }
    }
  }
}

TEST_CASE("tick labels and log ticks", "[ticks]") {
  CHECK(format_tick(0.30000000000000004, 0.1) == "0.3");
  CHECK(format_tick(4, 2) == "4");
  CHECK(format_tick(-1e-17, 0.5) == "0.0");
  CHECK(format_tick(0.025, 0.005) == "0.025");
  CHECK(format_tick(2e-6, 1e-6) == "2e-06");
  CHECK(format_tick(1.5e6, 5e5) == "1.5e+06");

  CHECK(log_ticks(1e-3, 1e2) == std::vector<double>{1e-3, 1e-2, 1e-1, 1, 10, 100});
  const auto few = log_ticks(2, 30);  // less than three decades: 1-2-5 multiples
  REQUIRE(few.size() == 4);
  CHECK(few[0] == Approx(2));
  CHECK(few[1] == Approx(5));
  CHECK(few[2] == Approx(10));
  CHECK(few[3] == Approx(20));
  const auto many = log_ticks(1e-12, 1e12, 6);  // 25 decades thinned
  CHECK(many.size() <= 7);
  CHECK(many.front() == Approx(1e-12));
  CHECK(format_log_tick(0.01) == "0.01");
  CHECK(format_log_tick(1e-5) == "1e-05");
}

TEST_CASE("axis mapping", "[ticks]") {
  const Axis x{0, 10, 100, 200};
  CHECK(x.to_pixel(0) == 100);
  CHECK(x.to_pixel(5) == 150);
  CHECK(x.to_pixel(10) == 200);
  const Axis y{-1, 1, 300, 100};  // y grows upwards on screen
  CHECK(y.to_pixel(1) == 100);
  CHECK(y.to_pixel(0) == 200);
  const Axis l{1, 100, 0, 200, true};
  CHECK(l.to_pixel(10) == Approx(100));
  CHECK(std::isnan(l.to_pixel(-1)));
}

TEST_CASE("palette colours are distinct", "[raster]") {
  for (std::size_t i = 0; i < palette.size(); ++i)
    for (std::size_t j = i + 1; j < palette.size(); ++j) {
      const int d = std::abs(palette[i].r - palette[j].r) + std::abs(palette[i].g - palette[j].g) +
                    std::abs(palette[i].b - palette[j].b);
      CHECK(d > 60);
    }
  CHECK(palette_color(10) == palette_color(0));
}
