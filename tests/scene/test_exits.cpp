// Exits in scenes (issue 50; docs/harm/harm.md, "Exits"): a corridor between two blocks standing still
// has the hand-computed clear width in exits.csv and summary.json; a slender block tipped over the path
// by a strong pulse blocks it, named, and covers its own plan area of floor. The scene key: read,
// written back, and each bad value named with its exit and key.
#include <catch2/catch.hpp>

#include <furniture_fem/io/csv.hpp>
#include <furniture_fem/scene/scene_runner.hpp>

#include "../support/scene_input.hpp"

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace furniture_fem;
using nlohmann::json;
using Catch::Matchers::Contains;

namespace exit_scene_tests {  // this file's own names (its group compiles files in batches)

namespace {

json block(const std::string& name, double x, double y, double W, double D, double H) {
  return {{"kind", "block"},
          {"name", name},
          {"fidelity", "rigid"},
          {"x", x},
          {"y", y},
          {"params", {{"width", W}, {"depth", D}, {"height", H}, {"mass_kg", 40.0}, {"mu_floor_long", 0.9}, {"mu_floor_short", 0.9}}}};
}

// Two blocks 0.6 x 0.4 m on the plan either side of a path along x at y = 0: the north one over
// y in [0.4, 0.8], the south one over y in [-0.7, -0.3]; 1 m counts to each side. The gap between them
// is 0.7 m (the sections' other free intervals, [0.8, 1] and [-1, -0.7], are narrower): wide enough for
// "corridor" (0.6 m), not for "tight" (the default 0.75 m).
json corridor_scene(double duration) {
  return {{"name", "corridor"},
          {"items", {block("north", 0.0, 0.6, 0.6, 0.4, 1.0), block("south", 0.0, -0.5, 0.6, 0.4, 1.0)}},
          {"exits", {{{"name", "corridor"}, {"path", {{-1.5, 0.0}, {1.5, 0.0}}}, {"width", 0.6}, {"side_reach", 1.0}},
                     {{"name", "tight"}, {"path", {{-1.5, 0.0}, {1.5, 0.0}}}, {"side_reach", 1.0}}}},
          {"ground_motion", {{"source", "points"}, {"x", {{0.0, 0.0}, {1.0, 0.0}}}}},
          {"contact", {{"law", "stiff"}}},
          {"duration", duration},
          {"dt", 0.001},
          {"outputs", {{"figures", true}}}};
}

SceneSpec read(const json& j) { return ffem_test::validated_scene(j, "exits.json"); }

std::string read_error(const json& j) { return ffem_test::scene_error(j, "exits.json"); }

RunSummary run(const SceneSpec& s, const std::string& out) {
  std::filesystem::remove_all(out);
  RunOptions o;
  o.out_dir = out;
  o.progress = false;
  o.forecast = false;
  o.threads = 1;
  return run_scene(s, o);
}

}  // namespace

TEST_CASE("A corridor between two standing blocks has the gap's width; a narrower exit is blocked from the start",
          "[scene][exits]") {
  const std::string out = std::string(FFEM_TEST_TMP) + "/exits_corridor";
  const RunSummary sum = run(read(corridor_scene(0.2)), out);
  REQUIRE(sum.status == "completed");
  REQUIRE(sum.exits.size() == 2);
  // The blocks stand still (no motion): their outlines move only by their settling into the floor's
  // springs, well under 0.1 mm on the plan.
  const double tol = 1e-4;
  const ExitOutcome& wide = sum.exits[0];
  CHECK_FALSE(wide.blocked);
  CHECK_FALSE(wide.first_blocked);
  CHECK(wide.at_end.clear_width == Approx(0.7).margin(tol));
  CHECK(wide.narrowest.clear_width == Approx(0.7).margin(tol));
  CHECK(wide.at_end.by == std::vector<std::string>{"south", "north"});  // its low bound first
  CHECK(std::abs(wide.at_end.x) <= 0.3 + tol);  // beside the blocks
  const ExitOutcome& tight = sum.exits[1];
  CHECK(tight.required_width == 0.75);
  CHECK(tight.blocked);
  REQUIRE(tight.first_blocked);
  CHECK(tight.first_blocked->t == 0.0);
  CHECK(tight.first_blocked->clear_width == Approx(0.7).margin(tol));
  CHECK(sum.floor_covered_by_fallen_items == 0.0);
  // exits.csv: a row at every history row, the same width; summary.json: the same outcome.
  const CsvTable csv = CsvTable::read(out + "/exits.csv");
  CHECK(csv.columns() == std::vector<std::string>{"t", "corridor_clear_width", "corridor_s", "tight_clear_width", "tight_s"});
  REQUIRE(csv.rows() >= 2);
  for (double w : csv.column("corridor_clear_width")) CHECK(w == Approx(0.7).margin(tol));
  for (double s : csv.column("corridor_s")) CHECK(std::abs(s - 1.5) <= 0.3 + tol);
  std::ifstream in(out + "/summary.json");
  const json summary = json::parse(in);
  CHECK(summary.at("exits")[1].at("blocked") == true);
  CHECK(summary.at("exits")[1].at("first_blocked_at_s") == 0.0);
  CHECK(summary.at("exits")[0].at("at_end").at("clear_width_m").get<double>() == Approx(0.7).margin(tol));
  CHECK(summary.at("floor_covered_by_fallen_items_m2") == 0.0);
  CHECK(exit_outcome_from_json(summary.at("exits")[1]).first_blocked->by == tight.first_blocked->by);
  CHECK(std::filesystem::exists(out + "/plan.png"));
  CHECK_THAT(exit_outcome_text(tight), Contains("exit tight blocked at 0.00 s by south and north"));
}

TEST_CASE("A slender block tipped over the path by a pulse blocks it, named, and covers its plan area",
          "[scene][exits]") {
  // A 0.2 x 0.2 x 1.2 m block at x = 1 (mu 0.9: it tips, it does not slide) under a 15 m/s^2 pulse along
  // +x for 0.3 s (seven times the 1.6 m/s^2 that tips it, g b / h): it topples towards -x and lies over
  // x in about [-0.3, 0.9], y in [-0.1, 0.1]. The path crosses it along y at x = 0.3, 0.4 m counting to
  // each side (0.8 m: enough for the 0.75 m exit while the post stands at x in [0.9, 1.1]): the sections
  // through the fallen post, x in [-0.1, 0.7], lie within it, nothing of them is free.
  json j = {{"name", "toppled"},
            {"items", {block("post", 1.0, 0.0, 0.2, 0.2, 1.2)}},
            {"exits", {{{"name", "door"}, {"path", {{0.3, -0.8}, {0.3, 0.8}}}, {"side_reach", 0.4}}}},
            {"ground_motion", {{"source", "points"}, {"x", {{0.0, 0.0}, {0.01, 15.0}, {0.3, 15.0}, {0.31, 0.0}}}}},
            {"contact", {{"law", "stiff"}}},
            {"duration", 2.5},
            {"dt", 0.001},
            {"outputs", {{"figures", true}}}};
  const std::string out = std::string(FFEM_TEST_TMP) + "/exits_toppled";
  const RunSummary sum = run(read(j), out);
  REQUIRE(sum.status == "completed");
  REQUIRE(sum.items.size() == 1);
  INFO("final state " << sum.items[0].state << ", tilt " << sum.items[0].tilt_deg);
  REQUIRE(sum.items[0].state == "overturned");
  const ExitOutcome& door = sum.exits.at(0);
  CHECK(door.blocked);
  // Lying across the sections once it lands (their 0.8 m all covered); it then slides on towards -x, so
  // at the end a strip of the sections beyond its foot may be free, far below the exit's 0.75 m.
  CHECK(door.narrowest.clear_width == 0.0);
  CHECK(door.narrowest.by == std::vector<std::string>{"post"});
  CHECK(door.at_end.clear_width < 0.3);
  CHECK(door.at_end.by == std::vector<std::string>{"post"});
  REQUIRE(door.first_blocked);
  CHECK(door.first_blocked->by == std::vector<std::string>{"post"});
  CHECK(door.first_blocked->t > 0.1);  // upright, it stood 0.6 m away
  CHECK(door.first_blocked->t < 1.5);
  // Lying on a face, its outline is 0.2 x 1.2 m; 1 % for the tilt of a face resting on penalty springs.
  REQUIRE(sum.floor_covered_by_fallen_items);
  CHECK(*sum.floor_covered_by_fallen_items == Approx(0.24).epsilon(0.01));
  CHECK(std::filesystem::exists(out + "/plan.png"));
}

TEST_CASE("Exits are read, written back, and each bad value is named with its exit and key", "[scene][exits][json]") {
  const json good = corridor_scene(0.2);
  const SceneSpec s = read(good);
  REQUIRE(s.exits.size() == 2);
  CHECK(s.exits[0].path.size() == 2);
  CHECK(s.exits[0].path[1].x() == 1.5);
  CHECK(s.exits[1].width == ExitSpec::default_width);
  CHECK(s.exits[1].side_reach == 1.0);
  const json once = to_json(s);
  const SceneSpec back = parse_scene_json(once, "again");
  CHECK(to_json(back) == once);
  REQUIRE(back.exits.size() == 2);
  CHECK(back.exits[0].name == "corridor");
  CHECK(back.exits[0].width == 0.6);
  CHECK(back.exits[0].path == s.exits[0].path);
  json without = good;
  without.erase("exits");
  CHECK_FALSE(to_json(read(without)).contains("exits"));  // scene.json without exits unchanged

  const auto with = [&](const char* key, const json& value) {
    json j = good;
    j["exits"][0][key] = value;
    return read_error(j);
  };
  CHECK_THAT(with("width", -0.5), Contains("exits[0].width") && Contains("must be positive") && Contains("-0.5"));
  CHECK_THAT(with("side_reach", 0), Contains("exits[0].side_reach") && Contains("must be positive"));
  CHECK_THAT(with("door", 1), Contains("exits[0].door") && Contains("allowed here"));
  CHECK_THAT(with("path", json::array({{0.0, 0.0}})), Contains("exits[0].path") && Contains("two or more points"));
  CHECK_THAT(with("path", json::array({{0.0, 0.0}, {2.5, 0.0}})), Contains("exits[0].path[1]") && Contains("off the table") && Contains("2.5"));
  CHECK_THAT(with("path", json::array({{0.0, 0.0}, {0.0, 0.0}, {1.0, 0.0}})),
             Contains("exits[0].path[1]") && Contains("zero length"));
  CHECK_THAT(with("path", json::array({{0.0, 0.0}, {"a", 0.0}})), Contains("exits[0].path[1]") && Contains("[x, y]"));
  CHECK_THAT(with("name", "tight"), Contains("exits[1].name") && Contains("duplicate exit name \"tight\""));
  // A SceneSpec made in code gets the same checks from validate().
  SceneSpec code = s;
  code.exits[1].width = -1;
  CHECK_THROWS_WITH(validate(code), Contains("exits[1].width"));
  code = s;
  code.exits[1].name = "corridor";
  CHECK_THROWS_WITH(validate(code), Contains("exits[1].name") && Contains("duplicate"));
}

}  // namespace exit_scene_tests
