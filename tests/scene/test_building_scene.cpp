// ground_motion.building (issue 50): the table as the floor of storey k of a shear building. Read and
// written back unchanged; every bad value an error naming its key and the value; the table's motion the
// storey's (excitation/building.hpp) under the ground record as this test scales it itself (scale_to
// and level apply to the ground), the vertical passed through; input_motion.csv with the ground's
// columns beside the table's only when a building is set. Records are written here (no ../shared).
#include <catch2/catch.hpp>

#include <furniture_fem/excitation/building.hpp>
#include <furniture_fem/scene/scene_runner.hpp>

#include "../support/block_scene.hpp"
#include "../support/input_errors.hpp"
#include "../support/stop_after.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

using namespace furniture_fem;
using nlohmann::json;
using Catch::Matchers::Contains;

namespace building_scene_tests {  // this file's own names (its group compiles files in batches)

namespace {

std::string scratch(const std::string& name) {
  const auto dir = std::filesystem::path(FFEM_TEST_TMP) / "building_scene" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

// A decaying two-tone record of n samples dt apart (m/s^2), one per axis by `phase`.
std::vector<double> samples(double amplitude, int n, double dt, double phase) {
  std::vector<double> a(n);
  for (int i = 0; i < n; ++i) {
    const double t = i * dt;
    a[i] = amplitude * std::exp(-0.2 * t) * (std::sin(2.1 * t + phase) + 0.4 * std::sin(9.7 * t + 2 * phase));
  }
  return a;
}

void write_record(const std::string& path, const std::vector<double>& a, double dt) {
  std::ofstream out(path);
  char buf[64];
  for (std::size_t i = 0; i < a.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.17g %.17g\n", dt * double(i), a[i]);
    out << buf;
  }
}

using ffem_test::block_scene;

const json tower = {{"storeys", 30}, {"period_s", 3.0}, {"damping_ratio", 0.02}, {"storey", 20}};

json with_building(const json& building) {
  return {{"source", "synthetic"}, {"seed", 3}, {"pga", 2.0}, {"duration", 2.0}, {"building", building}};
}

std::string error_of(const json& scene) {
  return ffem_test::input_error([&] { validate(parse_scene_json(scene, "scene.json")); });
}

std::string validate_error(const SceneSpec& s) {
  return ffem_test::input_error([&] { validate(s); });
}

}  // namespace

TEST_CASE("building: read, written and read back unchanged, both forms", "[scene][building]") {
  json rayleigh = tower;
  rayleigh["rayleigh_modes"] = {1, 3};
  const json arrays = {{"floor_mass", {3.0e5, 2.5e5, 2.0e5}},
                       {"storey_stiffness", {4.0e8, 3.0e8, 2.0e8}},
                       {"damping_ratio", 0.05},
                       {"storey", 2}};
  for (const json& b : {tower, rayleigh, arrays}) {
    INFO(b.dump());
    const SceneSpec s = parse_scene_json(block_scene(with_building(b)), "scene.json");
    REQUIRE(s.ground_motion.building);
    const BuildingSpec& read = *s.ground_motion.building;
    CHECK(read.storey == b.at("storey").get<int>());
    CHECK(read.damping_ratio == b.at("damping_ratio").get<double>());
    CHECK(read.floors() == (b.contains("storeys") ? 30 : 3));
    const json written = to_json(s);
    CHECK(written.at("ground_motion").at("building") == b);
    CHECK(to_json(parse_scene_json(written, "again.json")) == written);
  }
  // No building: no key written (files written before are unchanged).
  CHECK_FALSE(to_json(parse_scene_json(block_scene(json{{"source", "synthetic"}}), "s.json"))
                  .at("ground_motion")
                  .contains("building"));
}

TEST_CASE("building: each bad value is an error naming the key and the value", "[scene][building]") {
  struct Case {
    json building;
    std::string key, value;
  };
  const auto patched = [](json b, const std::string& key, const json& v) {
    if (v.is_null()) b.erase(key);
    else b[key] = v;
    return b;
  };
  const json small = {{"floor_mass", {1.0, 1.0, 1.0}}, {"storey_stiffness", {1e3, 1e3, 1e3}}, {"storey", 1}};
  const std::vector<Case> cases{
      {patched(tower, "period_s", -3.0), "ground_motion.building.period_s:", "got -3"},
      {patched(tower, "period_s", 0.0), "ground_motion.building.period_s:", "got 0"},
      {patched(tower, "storey", 31), "ground_motion.building.storey:", "got 31"},
      {patched(tower, "storey", 0), "ground_motion.building.storey:", "got 0"},
      {patched(tower, "storeys", 0), "ground_motion.building.storeys:", "got 0"},
      {patched(tower, "storeys", 2.5), "ground_motion.building.storeys:", "2.5"},
      {patched(tower, "damping_ratio", 1.5), "ground_motion.building.damping_ratio:", "got 1.5"},
      {patched(tower, "damping_ratio", -0.01), "ground_motion.building.damping_ratio:", "got -0.01"},
      {patched(tower, "rayleigh_modes", json{3, 2}), "ground_motion.building.rayleigh_modes:", "got [3, 2]"},
      {patched(tower, "rayleigh_modes", json{1, 31}), "ground_motion.building.rayleigh_modes:", "got [1, 31]"},
      // 60 % at modes 1 and 2 overdamps the higher modes (Rayleigh's a1 w / 2 grows with w)
      {patched(patched(tower, "damping_ratio", 0.6), "rayleigh_modes", json{1, 2}), "ground_motion.building.rayleigh_modes:",
       "overdamps mode"},
      {patched(tower, "storey", nullptr), "ground_motion.building.storey:", "required"},
      {patched(tower, "period_s", nullptr), "ground_motion.building:", "give storeys and period_s"},
      {patched(tower, "floor_mass", json{1.0}), "ground_motion.building.storey_stiffness:", "required with floor_mass"},
      {patched(small, "storey_stiffness", json{1e3, 1e3}), "ground_motion.building.storey_stiffness:",
       "has 2 values for the 3 floors"},
      {patched(small, "floor_mass", json{1.0, -1.0, 1.0}), "ground_motion.building.floor_mass[1]:", "got -1"},
      {patched(small, "storey_stiffness", json{1e3, 0.0, 1e3}), "ground_motion.building.storey_stiffness[1]:", "got 0"},
      {patched(small, "floor_mass", json{1.0, "heavy", 1.0}), "ground_motion.building.floor_mass[1]:", "\"heavy\""},
      {patched(small, "storey", 4), "ground_motion.building.storey:", "got 4"},
      {patched(small, "storeys", 3), "ground_motion.building.storeys:", "not both"},
      {patched(tower, "height_m", 90.0), "ground_motion.building.height_m:", "unknown key"},
  };
  for (const Case& c : cases) {
    const std::string e = error_of(block_scene(with_building(c.building)));
    INFO(c.building.dump() << "\n -> " << e);
    CHECK_THAT(e, Contains("scene.json: " + c.key) && Contains(c.value));
  }
  SECTION("a building under a \"points\" motion (the table's acceleration as given) is an error") {
    const json points = {{"source", "points"}, {"x", {{0, 0}, {0.1, 1.0}}}, {"building", tower}};
    CHECK_THAT(error_of(block_scene(points)), Contains("ground_motion.building") && Contains("\"points\""));
  }
  SECTION("NaN (no JSON value, but a SceneSpec made in code) is an error naming the key") {
    SceneSpec s = parse_scene_json(block_scene(with_building(tower)), "scene.json");
    s.ground_motion.building->period_s = std::numeric_limits<double>::quiet_NaN();
    CHECK_THAT(validate_error(s), Contains("ground_motion.building.period_s") && Contains("got nan"));
    CHECK_THROWS_WITH(scene_table_motion(s), Contains("ground_motion.building.period_s") && Contains("got nan"));
    s = parse_scene_json(block_scene(with_building(small)), "scene.json");
    s.ground_motion.building->floor_mass[2] = std::numeric_limits<double>::quiet_NaN();
    CHECK_THAT(validate_error(s), Contains("ground_motion.building.floor_mass[2]") && Contains("got nan"));
    s.ground_motion.building->floor_mass[2] = 1.0;
    s.ground_motion.building->damping_ratio = std::numeric_limits<double>::quiet_NaN();
    CHECK_THAT(validate_error(s), Contains("ground_motion.building.damping_ratio") && Contains("got nan"));
  }
}

TEST_CASE("building: the table's motion is the storey's under the ground record as scaled", "[scene][building]") {
  // Three components in m/s^2; scale_to brings the ground's horizontal peak to 2 m/s^2, level halves it.
  const std::string dir = scratch("motion");
  const double dt = 0.01;
  const int n = 2001;
  std::array<std::vector<double>, 3> a{samples(1.3, n, dt, 0.0), samples(1.7, n, dt, 0.9), samples(0.6, n, dt, 2.0)};
  for (int c = 0; c < 3; ++c) write_record(dir + "/" + "xyz"[c] + ".txt", a[c], dt);
  json motion = {{"source", "file"}, {"format", "columns"}, {"units", "m/s2"}, {"lowpass_hz", 0},
                 {"dimensions", "3d"}, {"files", {{"x", "x.txt"}, {"y", "y.txt"}, {"z", "z.txt"}}},
                 {"scale_to", {{"pga", 2.0}}}, {"level", 0.5}, {"building", tower}};
  SceneSpec s = parse_scene_json(block_scene(motion, 10.0), dir + "/scene.json");
  s.base_dir = dir;
  validate(s);
  double k = 0;
  const TableMotion table = scene_table_motion(s, &k);

  // The ground as the test scales it: the horizontal peak (X, Y) to 2 m/s^2, then half.
  double peak = 0;
  for (int c = 0; c < 2; ++c)
    for (double v : a[c]) peak = std::max(peak, std::abs(v));
  CHECK(k == Approx(2.0 / peak).epsilon(1e-15));
  const ShearBuilding b = ShearBuilding::uniform(30, 3.0, 0.02);
  for (int c = 0; c < 3; ++c) {
    Record ground;
    ground.dt = dt;
    for (double v : a[c]) ground.acc.push_back(v * (2.0 / peak * 0.5));
    const Record expected = c == 2 ? ground : storey_motion(b, 20, ground);
    const Record& got = c == 0 ? table.x : c == 1 ? table.y : table.z;
    REQUIRE(got.acc.size() == expected.acc.size());
    double worst = 0, top = 0;
    for (std::size_t i = 0; i < got.acc.size(); ++i) {
      worst = std::max(worst, std::abs(got.acc[i] - expected.acc[i]));
      top = std::max(top, std::abs(expected.acc[i]));
    }
    INFO("component " << c << ": largest difference " << worst << " m/s^2 of a peak " << top);
    CHECK(worst <= 1e-12 * top);  // the same arithmetic but for the scale factor's rounding
  }
  // The building changes the table's motion: storey 20 of a 3 s tower under a 3 s and 0.65 s record.
  const TableMotion ground = scene_ground_motion(s);
  CHECK(std::max(ground.x.peak(), ground.y.peak()) == Approx(1.0).epsilon(1e-12));
  CHECK(std::abs(table.x.peak() - ground.x.peak()) > 0.05 * ground.x.peak());
}

TEST_CASE("building: input_motion.csv gives the ground beside the floor; without a building, as before",
          "[scene][building][input_motion]") {
  const std::string dir = scratch("run");
  json b = tower;
  b["storey"] = 30;
  json motion = {{"source", "synthetic"}, {"seed", 5}, {"pga", 3.0}, {"duration", 1.0}, {"dimensions", "3d"},
                 {"building", b}};
  const std::vector<std::string> table_cols{"t", "ax", "ay", "az", "vx", "vy", "vz", "dx", "dy", "dz"};
  for (const bool building : {true, false}) {
    if (!building) motion.erase("building");
    json scene = block_scene(motion, 0.5);
    scene["outputs"] = {{"figures", true}};
    const SceneSpec s = parse_scene_json(scene, dir + "/scene.json");
    RunOptions o;
    o.out_dir = dir + (building ? "/with" : "/without");
    o.progress = false;
    REQUIRE(run_scene(s, o).status == "completed");
    const CsvTable m = read_csv(o.out_dir + "/input_motion.csv");
    std::vector<std::string> expected = table_cols;
    if (building)
      for (const char* c : {"ground_ax", "ground_ay", "ground_az", "ground_vx", "ground_vy", "ground_vz", "ground_dx",
                            "ground_dy", "ground_dz"})
        expected.push_back(c);
    CHECK(m.columns() == expected);
    CHECK(std::filesystem::exists(o.out_dir + "/input_spectra.png") == building);
    CHECK(std::filesystem::exists(o.out_dir + "/input_motion.png"));
    if (!building) continue;
    const TableMotion floor = scene_table_motion(s), ground = scene_ground_motion(s);
    REQUIRE(m.rows() == 51);
    for (std::size_t i = 0; i < m.rows(); ++i) {
      const double t = m.column("t")[i];
      INFO("t = " << t);
      // Printed with 15 digits: 1e-13 of the peaks (about 3 m/s^2).
      CHECK(m.column("ax")[i] == Approx(floor.at(t).x()).margin(1e-12));
      CHECK(m.column("ay")[i] == Approx(floor.at(t).y()).margin(1e-12));
      CHECK(m.column("ground_ax")[i] == Approx(ground.at(t).x()).margin(1e-12));
      CHECK(m.column("ground_ay")[i] == Approx(ground.at(t).y()).margin(1e-12));
      CHECK(m.column("az")[i] == m.column("ground_az")[i]);  // the vertical passes through
    }
    // The roof of a 3 s tower lags the ground: in the first 0.5 s its horizontal acceleration is not
    // the ground's (the difference is of the ground's own size).
    double diff = 0, top = 0;
    for (std::size_t i = 0; i < m.rows(); ++i) {
      diff = std::max(diff, std::abs(m.column("ax")[i] - m.column("ground_ax")[i]));
      top = std::max(top, std::abs(m.column("ground_ax")[i]));
    }
    CHECK(diff > 0.3 * top);
  }
}

namespace {
std::string bytes_of(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}
}  // namespace

TEST_CASE("building: a run stopped and resumed writes the uninterrupted run's input_motion.csv",
          "[scene][building][resume]") {
  // The ground's integrator goes into the checkpoint beside the table's.
  json motion = {{"source", "synthetic"}, {"seed", 9}, {"pga", 3.0}, {"duration", 1.0}, {"dimensions", "3d"},
                 {"building", tower}};
  const SceneSpec s = parse_scene_json(block_scene(motion, 0.3), "scene.json");
  const std::string dir = scratch("resume");
  std::atomic<bool> never{false}, stop{false};
  RunOptions o;
  o.progress = false;
  o.out_dir = dir + "/whole";
  o.stop = &never;
  REQUIRE(run_scene(s, o).status == "completed");
  o.out_dir = dir + "/part";
  o.stop = &stop;
  ffem_test::StopAfter stopper(stop, 137);
  REQUIRE(run_scene(s, o, {&stopper}).status == "stopped");
  o.stop = &never;
  o.resume = true;
  ffem_test::StopAfter none(never, -1);  // the stopped run's observers, again
  REQUIRE(run_scene(s, o, {&none}).status == "completed");
  const std::string whole = bytes_of(dir + "/whole/input_motion.csv");
  CHECK(whole.find("ground_dz") != std::string::npos);
  CHECK(bytes_of(dir + "/part/input_motion.csv") == whole);
}

}  // namespace building_scene_tests
