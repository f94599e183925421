// The cairo back end as a user sees it: pixels where an independent axis mapping puts them, titles
// that fit, SVG and PDF files with their signatures, errors that name the file, Wireframe3D's
// reference segments and labels.
#include <catch2/catch.hpp>

#include <cairo.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "furniture_fem/figures/plot.hpp"
#include "png_reader.hpp"
#include "../support/test_files.hpp"

namespace cairo_output_tests {  // this file's own names (its group compiles files in batches)

namespace fs = std::filesystem;
using namespace furniture_fem;
using ffem_test::slurp;
using ffem_test::tmp;

namespace {
RGB px(const png_test::Png& p, int x, int y) { return {p.at(x, y, 0), p.at(x, y, 1), p.at(x, y, 2)}; }
bool dark(RGB c) { return c.r + c.g + c.b < 3 * 160; }
// Width of `text` in cairo's "sans-serif" at `size` px, measured here, not through the library.
double measured_width(const std::string& text, double size, bool bold) {
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
  cairo_t* cr = cairo_create(s);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, text.c_str(), &e);
  cairo_destroy(cr);
  cairo_surface_destroy(s);
  return std::max(e.x_advance, e.x_bearing + e.width);
}
template <class F>
std::string thrown_message(F&& f) {
  try {
    f();
  } catch (const OutputError& e) {
    return e.what();
  }
  return "(nothing thrown)";
}
}  // namespace

TEST_CASE("cairo LinePlot: a line of a known colour through the pixels of the axis mapping", "[plot][cairo]") {
  const RGB red{230, 20, 20};
  LinePlot plot;
  plot.style().legend = LegendPos::none;
  plot.style().grid_lines = false;
  plot.xlim(0, 10).ylim(0, 4);
  Series s;
  s.x = {0, 10}, s.y = {0, 4}, s.color = red, s.width = 3;  // the diagonal of the axes box
  plot.add(s);
  Series flat;
  flat.x = {0, 10}, flat.y = {3, 3}, flat.color = red, flat.width = 3;
  plot.add(flat);
  const std::string path = tmp("cairo_diagonal.png");
  plot.save_png(path, 640, 480);
  const png_test::Png p = png_test::decode_file(path);
  REQUIRE(p.width == 640);
  REQUIRE(p.height == 480);

  // The mapping written out from the frame alone: x 0..10 -> frame.x0..x1, y 0..4 -> frame.y1..y0.
  const Rect f = plot.layout(640, 480).panels.at(0).frame;
  REQUIRE(f.width() > 400);
  REQUIRE(f.height() > 300);
  auto X = [&](double x) { return f.x0 + x / 10.0 * (f.x1 - f.x0); };
  auto Y = [&](double y) { return f.y1 - y / 4.0 * (f.y1 - f.y0); };
  // A 3 px line covers the pixel nearest to any point on it completely: exactly its colour.
  for (double x : {1.0, 2.5, 4.0, 5.0, 6.5, 8.0, 9.0}) {
    INFO("x = " << x);
    const int u = int(std::lround(X(x))), v = int(std::lround(Y(0.4 * x)));
    CHECK(px(p, u, v) == red);
    CHECK(px(p, u, v - 8) == colors::white);  // 8 px above the diagonal: background
    CHECK(px(p, u, v + 8) == colors::white);
    const int w = int(std::lround(Y(3)));
    CHECK(px(p, u, w) == red);                // the horizontal line at y = 3
    CHECK(px(p, u, w - 4) == colors::white);  // and nothing 4 px above or below it
    CHECK(px(p, u, w + 4) == colors::white);
  }
  // Nothing is drawn outside the axes box but text and ticks: the line is clipped to the frame.
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x)
      if (!f.contains(x, y)) CHECK_FALSE(px(p, x, y) == red);
  // render() gives the same pixels as the file.
  const Image img = plot.render(640, 480);
  CHECK(img.get(int(std::lround(X(5))), int(std::lround(Y(2)))) == red);
}

TEST_CASE("cairo LinePlot: long titles wrap, then shrink, and stay inside the image", "[plot][cairo]") {
  const std::string long_title =
      "Displacement relative to the table of the upper cabinet's top-front-left corner under the JMA Kobe "
      "record scaled to 80 % with the stick-slip law";
  LinePlot plot(long_title);
  plot.xlabel("time (s)").ylabel("X (m)");
  plot.add({0, 1, 2}, {0, 1, 0}, "a");
  const std::string path = tmp("cairo_long_title.png");
  plot.save_png(path, 600, 400);
  const png_test::Png p = png_test::decode_file(path);
  const PlotLayout L = plot.layout(600, 400);
  REQUIRE_FALSE(L.title.lines.empty());
  CHECK(L.title.lines.size() <= 2);
  CHECK(L.title.box.x0 >= 0);
  CHECK(L.title.box.x1 < 600);
  CHECK(L.title.box.y1 < L.panels[0].frame.y0);  // above the axes
  for (const auto& line : L.title.lines) {
    INFO(line);
    CHECK(measured_width(line, L.title.size, true) <= 600);
  }
  // Title ink reaches neither side of the image: nothing was cut off.
  int ink = 0;
  for (int y = L.title.box.y0; y <= L.title.box.y1; ++y) {
    for (int x : {0, 1, 2, 597, 598, 599}) CHECK_FALSE(dark(px(p, x, y)));
    for (int x = 0; x < 600; ++x) ink += dark(px(p, x, y));
  }
  CHECK(ink > 200);
  // One word longer than the image: one line, shrunk to the width.
  LinePlot word(std::string(80, 'W'));
  word.add({0, 1}, {0, 1});
  const PlotLayout W = word.layout(500, 300);
  REQUIRE(W.title.lines.size() == 1);
  CHECK(measured_width(W.title.lines[0], W.title.size, true) <= 500);
  // A short title is left alone, on one line at the title size.
  LinePlot shorter("Short");
  shorter.add({0, 1}, {0, 1});
  const PlotLayout S = shorter.layout(600, 400);
  CHECK(S.title.lines == std::vector<std::string>{"Short"});
  CHECK(S.title.size > shorter.style().font_for(600, 400));
}

TEST_CASE("cairo: SVG and PDF files with the same layout, and their signatures", "[plot][cairo]") {
  LinePlot plot("Vector output");
  plot.panels(2).xlabel("t (s)").ylabel("a", 0).ylabel("b", 1);
  plot.add({0, 1, 2}, {0, 1, 0}, "a", 0).add({0, 1, 2}, {1, 0, 1}, "b", 1);
  const std::string svg = tmp("cairo_plot.svg"), pdf = tmp("cairo_plot.pdf");
  fs::remove(svg), fs::remove(pdf);
  plot.save_svg(svg, 800, 500);
  plot.save_pdf(pdf, 800, 500);
  const std::string s = slurp(svg), d = slurp(pdf);
  CHECK(s.rfind("<?xml", 0) == 0);
  CHECK(s.find("<svg") != std::string::npos);
  CHECK(s.find("width=\"800pt\"") != std::string::npos);
  CHECK(s.find("height=\"500pt\"") != std::string::npos);
  CHECK(d.rfind("%PDF-", 0) == 0);
  CHECK(d.find("%%EOF") != std::string::npos);
  CHECK(d.size() > 1000);
  Wireframe3D w("cube");
  w.add_segments({{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1)}}, colors::black);
  const std::string wsvg = tmp("cairo_wire.svg"), wpdf = tmp("cairo_wire.pdf");
  w.save_svg(wsvg, 400, 300);
  w.save_pdf(wpdf, 400, 300);
  CHECK(slurp(wsvg).find("<svg") != std::string::npos);
  CHECK(slurp(wpdf).rfind("%PDF-", 0) == 0);
}

TEST_CASE("cairo: a file that cannot be written gives an error naming it", "[plot][cairo]") {
  LinePlot plot("x");
  plot.add({0, 1}, {0, 1});
  Wireframe3D w;
  w.add_segments({{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1)}}, colors::black);
  ScatterPlot sp;
  sp.add(1, 2, "p");
  const std::string dir = tmp("no_such_folder_cairo") + "/deeper";
  fs::remove_all(tmp("no_such_folder_cairo"));
  for (const char* ext : {".png", ".svg", ".pdf"}) {
    const std::string path = dir + "/figure" + ext;
    INFO(path);
    const std::string e = ext == std::string(".png") ? thrown_message([&] { plot.save_png(path); })
                          : ext == std::string(".svg") ? thrown_message([&] { plot.save_svg(path); })
                                                       : thrown_message([&] { plot.save_pdf(path); });
    CHECK(e.find("'" + path + "'") != std::string::npos);
    CHECK(e.find("LinePlot::save_") != std::string::npos);
    CHECK_FALSE(fs::exists(path));
  }
  CHECK(thrown_message([&] { w.save_png(dir + "/w.png"); }).find(dir + "/w.png") != std::string::npos);
  CHECK(thrown_message([&] { sp.save_pdf(dir + "/s.pdf"); }).find(dir + "/s.pdf") != std::string::npos);
}

TEST_CASE("Wireframe3D: reference segments under the members, labels near their points", "[plot][cairo]") {
  const RGB blue = palette[0], grey{190, 190, 190};
  Wireframe3D w("Room");
  w.show_axes(false);
  // A post that moved 1 m along x: its initial position drawn thin and grey.
  w.add_reference_segments({{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 1)}}, grey, 2.0);
  w.add_segments({{Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 0, 1)}}, blue);
  w.floor_grid(-0.5, 1.5, -0.5, 0.5, 0, 0.5);
  w.label(Eigen::Vector3d(1, 0, 1), "post", blue);
  w.label(Eigen::Vector3d(1, 0, 1), "second label, same point", blue);
  const std::string path = tmp("wire_labels.png");
  w.save_png(path, 600, 500);
  const png_test::Png p = png_test::decode_file(path);
  const Eigen::Vector2d ref = w.project(Eigen::Vector3d(0, 0, 0.6), 600, 500);
  const Eigen::Vector2d post = w.project(Eigen::Vector3d(1, 0, 0.6), 600, 500);
  CHECK(px(p, int(std::lround(ref.x())), int(std::lround(ref.y()))) == grey);
  CHECK(px(p, int(std::lround(post.x())), int(std::lround(post.y()))) == blue);
  // Text above the top of the post: dark pixels within a few rows above the point.
  const Eigen::Vector2d top = w.project(Eigen::Vector3d(1, 0, 1), 600, 500);
  int ink = 0;
  for (int y = int(top.y()) - 40; y < int(top.y()) - 2; ++y)
    for (int x = int(top.x()) - 20; x <= int(top.x()) + 20; ++x)
      if (x >= 0 && y >= 0 && x < p.width && y < p.height) ink += dark(px(p, x, y));
  CHECK(ink > 20);
  // The title fits.
  const TextBlock t = w.title_layout(600, 500);
  CHECK(t.lines == std::vector<std::string>{"Room"});
  CHECK(measured_width("Room", t.size, true) < 600);
}

TEST_CASE("cairo: UTF-8 text is drawn, invalid UTF-8 becomes '?' instead of failing the figure", "[plot][cairo]") {
  LinePlot plot("Beschleunigung \xC3\xA4 (m/s\xC2\xB2), broken: \xFF\xC3");
  plot.add({0, 1}, {0, 1}, "label \xE2\x82\xAC \xED\xA0\x80");
  const std::string path = tmp("cairo_utf8.png");
  CHECK_NOTHROW(plot.save_png(path, 500, 300));
  CHECK(png_test::decode_file(path).width == 500);
  CHECK(detail::utf8_or_question_marks("a\xC3\xA4\xFF\xC3") == "a\xC3\xA4??");
  CHECK(detail::utf8_or_question_marks("\xED\xA0\x80") == "???");  // a surrogate
  CHECK(detail::utf8_or_question_marks("\xE2\x82\xAC") == "\xE2\x82\xAC");
}

}  // namespace cairo_output_tests
