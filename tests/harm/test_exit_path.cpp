// An exit's clear width and the floor area covered (harm/exit_path.hpp), against hand-computed geometry.
// Every exit here needs 0.75 m: its band reaches 0.375 m to each side of the path.
// Tolerances: every number below is a sum or a quotient of a few exact decimals, so they agree to
// rounding (1e-12); a station's position on a boundary is allowed 1e-9 (its arc length is a product).
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include <furniture_fem/harm/exit_path.hpp>

#include "test_boxes.hpp"

using namespace furniture_fem;
using test::cabinet;

namespace {
// The 4 m x 4 m table, no walls unless given.
ExitRoom table_room() {
  ExitRoom r;
  r.table_min = Vec2(-2, -2);
  r.table_max = Vec2(2, 2);
  return r;
}
// The cabinet W 0.9, D 0.4, H 1.8 standing at (0, 0.5), front towards -y, and tipped forward by 90
// degrees about its front bottom edge (y = 0.3, z = 0), as tests/harm/test_item_box.cpp tips it.
const ItemInfo tall = cabinet(0.9, 0.4, 1.8, Vec3(0.0, 0.5, 0.0));
PlanObstacle standing() { return {"cabinet", plan_outline(placed_box(tall))}; }
PlanObstacle tipped() {
  const Mat3 Q = Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitX()).matrix();
  const Vec3 pivot(0.0, 0.3, 0.0), Xc(0.0, 0.5, 0.9);
  return {"cabinet", plan_outline(item_box(tall, Q, Xc, pivot + Q * (Xc - pivot)))};
}
const std::vector<Vec2> along_x = {Vec2(-1, 0), Vec2(1, 0)};
const CrossSection& station_at(const ExitMeasure& m, const Vec2& p) {
  for (const CrossSection& x : m.sections)
    if ((x.station.at - p).norm() < 1e-9) return x;
  FAIL("no station at (" << p.x() << ", " << p.y() << ")");
  return m.sections.front();
}
}  // namespace

TEST_CASE("Stations cover a path every 0.05 m and at its ends, with the normal to the left", "[harm][exit]") {
  const auto st = path_stations({Vec2(0, 0), Vec2(1, 0), Vec2(1, 0.12)});
  // 20 parts of 0.05 m, then 3 parts of 0.04 m: 21 + 4 stations (the corner in both segments).
  REQUIRE(st.size() == 25);
  CHECK(st[20].at.isApprox(Vec2(1, 0)));
  CHECK(st[20].normal.isApprox(Vec2(0, 1)));
  CHECK(st[21].at.isApprox(Vec2(1, 0)));
  CHECK(st[21].normal.isApprox(Vec2(-1, 0)));
  CHECK(st.back().s == Approx(1.12).epsilon(1e-12));
  CHECK(st[22].s - st[21].s == Approx(0.04).epsilon(1e-12));
}

TEST_CASE("A cabinet standing beside a corridor narrows it to the gap between it and the wall", "[harm][exit]") {
  // A wall along y = -0.5 on the right of the path (it runs along x); 1 m counts to each side. Beside
  // the cabinet (|x| <= 0.45) the section is [-0.5, 1]: free [-0.5, 0.3] (0.8 m) and [0.7, 1] (0.3 m).
  ExitRoom room = table_room();
  room.walls.push_back({"south", Vec2(-2, -0.5), Vec2(2, -0.5)});
  room.side_reach = 1.0;
  const ExitMeasure m = measure_exit(along_x, 0.75, room, {standing()});
  const CrossSection& n = m.at_narrowest();
  CHECK(n.clear_width == Approx(0.8).epsilon(1e-12));
  CHECK(n.from == Approx(-0.5).epsilon(1e-12));
  CHECK(n.to == Approx(0.3).epsilon(1e-12));
  CHECK(n.low.kind == SectionBound::Kind::wall);
  CHECK(n.low.name == "south");
  CHECK(n.narrowed_by() == std::vector<std::string>{"cabinet"});
  CHECK(n.station.at.x() >= -0.45 - 1e-9);
  CHECK(n.station.at.x() <= 0.45 + 1e-9);
  // Away from it: the wall 0.5 m to the right, the reach 1 m to the left.
  const CrossSection& clear = station_at(m, Vec2(-0.8, 0));
  CHECK(clear.clear_width == Approx(1.5).epsilon(1e-12));
  CHECK(clear.high.kind == SectionBound::Kind::reach);
  CHECK(clear.narrowed_by().empty());
}

TEST_CASE("A cabinet tipped across a corridor leaves the gap beyond its back", "[harm][exit]") {
  // Walls at y = -0.6 and y = 0.6. Tipped forward, the cabinet covers y in [-1.5, 0.3] for |x| <= 0.45:
  // only [0.3, 0.6] is free, 0.3 m, between its back and the north wall.
  ExitRoom room = table_room();
  room.walls.push_back({"south", Vec2(-2, -0.6), Vec2(2, -0.6)});
  room.walls.push_back({"north", Vec2(2, 0.6), Vec2(-2, 0.6)});
  const ExitMeasure m = measure_exit(along_x, 0.75, room, {tipped()});
  const CrossSection& n = m.at_narrowest();
  CHECK(n.clear_width == Approx(0.3).epsilon(1e-12));
  CHECK(n.low.kind == SectionBound::Kind::obstacle);
  CHECK(n.high.name == "north");
  CHECK(n.narrowed_by() == std::vector<std::string>{"cabinet"});
  CHECK(station_at(m, Vec2(0.5, 0)).clear_width == Approx(1.2).epsilon(1e-12));
  // With a second cabinet lying over the rest, nothing is free: both cover it.
  PlanObstacle other = tipped();
  other.name = "other";
  for (Vec2& p : other.outline) p.y() += 0.9;  // y in [-0.6, 1.2]
  const ExitMeasure both = measure_exit(along_x, 0.75, room, {tipped(), other});
  const CrossSection& shut = both.at_narrowest();
  CHECK(shut.clear_width == 0.0);
  CHECK(shut.narrowed_by() == std::vector<std::string>{"cabinet", "other"});
}

TEST_CASE("A gap across an open room is not the exit's: only gaps that reach into its band count", "[harm][exit]") {
  // The tipped cabinet moved 0.2 m to +y covers y in [-1.3, 0.5] over the path; the table runs from -2 to
  // 2. Free: [-2, -1.3] and [0.5, 2] (1.5 m), neither reaching into the band |y| < 0.375: nothing is
  // clear, the cabinet covers the band. An exit needing 1.2 m (band 0.6) reaches the 1.5 m gap.
  PlanObstacle lying = tipped();
  for (Vec2& p : lying.outline) p.y() += 0.2;
  const ExitMeasure m = measure_exit(along_x, 0.75, table_room(), {lying});
  CHECK(m.at_narrowest().clear_width == 0.0);
  CHECK(m.at_narrowest().narrowed_by() == std::vector<std::string>{"cabinet"});
  CHECK(station_at(m, Vec2(0.8, 0)).clear_width == Approx(4.0).epsilon(1e-12));
  const ExitMeasure wide = measure_exit(along_x, 1.2, table_room(), {lying});
  CHECK(wide.at_narrowest().clear_width == Approx(1.5).epsilon(1e-12));
  CHECK(wide.at_narrowest().from == Approx(0.5).epsilon(1e-12));
}

TEST_CASE("A bent path: each segment's sections are perpendicular to it", "[harm][exit]") {
  // (-1, 0) -> (0, 0) -> (0, 1); 0.6 m count to each side. A box x in [0.3, 0.5], y in [0.4, 0.8] beside
  // the second segment cuts its sections (along -x) at u in [-0.5, -0.3]: free [-0.3, 0.6], 0.9 m.
  ExitRoom room = table_room();
  room.side_reach = 0.6;
  const PlanObstacle box{"box", {Vec2(0.3, 0.4), Vec2(0.5, 0.4), Vec2(0.5, 0.8), Vec2(0.3, 0.8)}};
  const ExitMeasure m = measure_exit({Vec2(-1, 0), Vec2(0, 0), Vec2(0, 1)}, 0.75, room, {box});
  const CrossSection& n = m.at_narrowest();
  CHECK(n.clear_width == Approx(0.9).epsilon(1e-12));
  CHECK(n.station.s >= 1.4 - 1e-9);
  CHECK(n.station.s <= 1.8 + 1e-9);
  CHECK(n.from == Approx(-0.3).epsilon(1e-12));
  // On the first segment the box is out of reach: 1.2 m; so it is at the second's start.
  CHECK(station_at(m, Vec2(-0.5, 0)).clear_width == Approx(1.2).epsilon(1e-12));
  CHECK(m.sections[21].clear_width == Approx(1.2).epsilon(1e-12));
}

TEST_CASE("Walls and the table's edge bound a section: a short wall, an oblique one", "[harm][exit]") {
  // A wall along y = 0.5 for x in [0, 2] only: left of it the section runs edge to edge (4 m), beside it
  // from the table's edge at y = -2 to the wall (2.5 m).
  ExitRoom room = table_room();
  room.walls.push_back({"short", Vec2(0, 0.5), Vec2(2, 0.5)});
  const ExitMeasure m = measure_exit(along_x, 0.75, room, {});
  CHECK(station_at(m, Vec2(-0.5, 0)).clear_width == Approx(4.0).epsilon(1e-12));
  const CrossSection& beside = station_at(m, Vec2(0.5, 0));
  CHECK(beside.clear_width == Approx(2.5).epsilon(1e-12));
  CHECK(beside.low.kind == SectionBound::Kind::table_edge);
  CHECK(beside.high.name == "short");
  // An oblique wall from (-2, 1.5) to (2, 0.5): y = 1 - x / 4 over the path, 0.875 at x = 0.5.
  ExitRoom oblique = table_room();
  oblique.walls.push_back({"oblique", Vec2(-2, 1.5), Vec2(2, 0.5)});
  const ExitMeasure o = measure_exit(along_x, 0.75, oblique, {});
  CHECK(station_at(o, Vec2(0.5, 0)).clear_width == Approx(2.875).epsilon(1e-12));
  CHECK(o.at_narrowest().station.at.x() == Approx(1.0).epsilon(1e-12));  // nearest the wall at x = 1
  CHECK(o.at_narrowest().clear_width == Approx(2.75).epsilon(1e-12));
}

TEST_CASE("The union area of overlapping outlines against hand computations", "[harm][area]") {
  const auto square = [](double x0, double y0, double side) {
    return std::vector<Vec2>{Vec2(x0, y0), Vec2(x0 + side, y0), Vec2(x0 + side, y0 + side), Vec2(x0, y0 + side)};
  };
  // Two unit squares overlapping in a 0.5 x 0.5 corner: 2 - 0.25.
  CHECK(union_area({square(0, 0, 1), square(0.5, 0.5, 1)}) == Approx(1.75).epsilon(1e-12));
  // A square inside another: the outer one's area.
  CHECK(union_area({square(0, 0, 2), square(0.5, 0.5, 0.5)}) == Approx(4.0).epsilon(1e-12));
  // Disjoint: the sum.
  CHECK(union_area({square(0, 0, 1), square(3, 0, 0.5)}) == Approx(1.25).epsilon(1e-12));
  // The unit square and a diamond of diagonal 1 centred on its right edge at (1, 0.5): the diamond's left
  // half (a triangle of area 0.25) lies inside the square. 1 + 0.5 - 0.25.
  const std::vector<Vec2> diamond = {Vec2(1, 0), Vec2(1.5, 0.5), Vec2(1, 1), Vec2(0.5, 0.5)};
  CHECK(union_area({square(0, 0, 1), diamond}) == Approx(1.25).epsilon(1e-12));
  // One outline alone: its shoelace area (a tilted box's hexagon).
  const Mat3 tilt = Eigen::AngleAxisd(0.3, Vec3(1.0, 1.0, 0.0).normalized()).matrix();
  const auto hexagon = plan_outline(item_box(cabinet(1.0, 0.5, 1.2, Vec3::Zero()), tilt, Vec3::Zero(), Vec3::Zero()));
  REQUIRE(hexagon.size() == 6);
  CHECK(union_area({hexagon}) == Approx(polygon_area(hexagon)).epsilon(1e-12));
  // The tipped cabinet (0.9 x 1.8 on the plan) over the standing one (0.9 x 0.4), sharing y in [0.3, 0.3]
  // only: the sum, 1.62 + 0.36.
  CHECK(union_area({standing().outline, tipped().outline}) == Approx(1.98).epsilon(1e-12));
}
