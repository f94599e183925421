// The scene runner end to end (scene_runner.hpp): a small scene writes every output and each one
// parses; the paper's configuration 2 runs a second of synthetic motion with a small energy-ledger
// imbalance; broken scene files fail before the run starts, naming the key; a stop request ends the
// run with readable outputs; and the final-state classification tells a sliding item from a standing
// one. A run that writes no files returns the same outcome to the bit, and extra observers see every step;
// output_interval is a time. No test reads ../shared: motions are synthetic or written here.
#include <catch2/catch.hpp>

#include <furniture_fem/scene/scene_runner.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

using namespace furniture_fem;
using nlohmann::json;

namespace run_scene_tests {  // this file's own names (its group compiles files in batches)
namespace fs = std::filesystem;

namespace {

// A fresh, empty folder under the test temp folder.
std::string fresh_dir(const std::string& name) {
  const fs::path p = fs::path(FFEM_TEST_TMP) / "runner" / name;
  fs::remove_all(p);
  fs::create_directories(p.parent_path());
  return p.string();
}

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  REQUIRE(f.good());
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

json read_json(const std::string& path) { return json::parse(slurp(path)); }

std::string write_json(const std::string& path, const json& j) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path) << j.dump(2);
  return path;
}

RunOptions quiet(const std::string& out) {
  RunOptions o;
  o.out_dir = out;
  o.progress = false;
  return o;
}

// Every value of every column finite; `t` strictly increasing (or non-decreasing when a time has
// several rows, as in contact_forces.csv); the named columns present.
CsvTable check_csv(const std::string& path, const std::vector<std::string>& columns, bool strictly = true) {
  INFO(path);
  const CsvTable t = read_csv(path);
  CHECK_FALSE(t.truncated());
  REQUIRE(t.has("t"));
  for (const auto& c : columns) {
    INFO("column " << c);
    CHECK(t.has(c));
  }
  for (std::size_t c = 0; c < t.columns().size(); ++c)
    for (double v : t.column(c)) REQUIRE(std::isfinite(v));
  const auto& time = t.column("t");
  for (std::size_t i = 1; i < time.size(); ++i) {
    if (strictly) REQUIRE(time[i] > time[i - 1]);
    else REQUIRE(time[i] >= time[i - 1]);
  }
  return t;
}

// PNG signature, then the IHDR chunk first with the expected size.
void check_png(const std::string& path, std::uint32_t width, std::uint32_t height) {
  INFO(path);
  REQUIRE(fs::is_regular_file(path));
  const std::string b = slurp(path);
  REQUIRE(b.size() > 33);
  const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  for (int i = 0; i < 8; ++i) REQUIRE(static_cast<unsigned char>(b[i]) == sig[i]);
  const auto be32 = [&](std::size_t at) {
    return std::uint32_t(static_cast<unsigned char>(b[at])) << 24 | std::uint32_t(static_cast<unsigned char>(b[at + 1])) << 16 |
           std::uint32_t(static_cast<unsigned char>(b[at + 2])) << 8 | std::uint32_t(static_cast<unsigned char>(b[at + 3]));
  };
  CHECK(be32(8) == 13);
  CHECK(b.substr(12, 4) == "IHDR");
  CHECK(be32(16) == width);
  CHECK(be32(20) == height);
}

// The files a PVD collection lists, in order.
std::vector<std::string> pvd_files(const std::string& path) {
  const std::string text = slurp(path);
  std::vector<std::string> files;
  const std::regex re("file=\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
    files.push_back((*it)[1].str());
  return files;
}

long vtu_points(const std::string& path) {
  const std::string text = slurp(path);
  std::smatch m;
  REQUIRE(std::regex_search(text, m, std::regex("NumberOfPoints=\"([0-9]+)\"")));
  return std::stol(m[1].str());
}

// Node count of the scene's model, built independently of the runner.
int model_nodes(const SceneSpec& s) {
  Model m;
  build_scene(s, m);
  return m.num_nodes();
}

// The small scene of the first test: the chair and the side table (276 elements) under the built-in
// synthetic 3-D motion, a marker on each and the chair column's sectional forces.
json small_scene_json(const std::string& folder) {
  json j = json::parse(R"({
    "name": "runner smoke test",
    "items": [
      {"kind": "office_chair", "x": -0.8, "y": 0.0, "yaw_deg": 90},
      {"kind": "side_table", "x": 0.6, "y": -1.0, "yaw_deg": 0}
    ],
    "ground_motion": {"source": "synthetic", "seed": 3, "pga": 6.0, "dimensions": "3d"},
    "contact": {"law": "paper_anisotropic"},
    "duration": 0.3,
    "dt": 0.001,
    "outputs": {
      "markers": ["office_chair.seat_centre",
                  {"name": "table_top", "item": "side_table", "marker": "top_centre"}],
      "sectional_forces": [{"item": "office_chair", "member": "column:0", "element": 0}],
      "vtu_every": 100,
      "figures": true
    }
  })");
  j["outputs"]["folder"] = folder;
  return j;
}

// Checks the outputs of a run (completed or not) parse, and returns the summary.
json check_outputs(const std::string& out, const SceneSpec& spec, bool expect_figures) {
  const CsvTable markers = check_csv(out + "/markers.csv", {});
  for (const auto& m : spec.outputs.markers)
    for (const char* c : {"_x", "_y", "_z"}) CHECK(markers.has(m.name + c));
  const CsvTable sections = check_csv(out + "/sectional_forces.csv", {});
  const CsvTable energy = check_csv(out + "/energy.csv", {"kinetic", "strain", "gravity_potential", "external_work",
                                                         "contact_work", "damping_work", "plastic_work", "imbalance",
                                                         "contact_work_applied"});
  // The first row is the state before any step: nothing has been gained or lost yet.
  CHECK(energy.column("imbalance").front() == 0.0);
  const json fin = read_json(out + "/final_state.json");
  REQUIRE(fin.is_array());
  std::size_t bodies = 0;
  for (const auto& it : spec.items) bodies += it.kind == ItemKind::separated_cabinets ? 2 : 1;
  CHECK(fin.size() == bodies);
  // contact_forces.csv names the items: every item against the floor and the walls, every pair of items.
  std::vector<std::string> contact_columns;
  for (std::size_t a = 0; a < fin.size(); ++a) {
    const std::string name = fin[a].at("item");
    for (const char* c : {"_fx", "_fy", "_fz"}) {
      contact_columns.push_back(name + "|floor" + c);
      contact_columns.push_back(name + "|walls" + c);
      for (std::size_t b = a + 1; b < fin.size(); ++b) contact_columns.push_back(name + "|" + fin[b].at("item").get<std::string>() + c);
    }
  }
  const CsvTable contacts = check_csv(out + "/contact_forces.csv", contact_columns);
  CHECK(contacts.columns().size() == 1 + contact_columns.size() + (spec.obstacles.empty() ? 0 : 3 * fin.size()));
  CHECK(contacts.rows() == energy.rows());
  for (const auto& it : fin) {
    CHECK(it.at("item").is_string());
    CHECK(std::set<std::string>{"standing", "slid", "tilted", "fell", "overturned", "resting_on_item"}.count(
              it.at("state").get<std::string>()) == 1);
    CHECK(std::isfinite(it.at("slide_m").get<double>()));
    CHECK(std::isfinite(it.at("tilt_deg").get<double>()));
  }
  const CsvTable motion = check_csv(out + "/input_motion.csv", {"ax", "ay", "az", "vx", "vy", "vz", "dx", "dy", "dz"});
  CHECK(motion.rows() == energy.rows());
  const json sum = read_json(out + "/summary.json");
  CHECK(sum.at("scene").at("name") == spec.name);
  const json& verdict = sum.at("energy_verdict");
  CHECK(verdict.at("closes").is_boolean());
  CHECK(verdict.at("tolerance_relative").get<double>() > 0);
  CHECK(verdict.at("text").get<std::string>().find("the energy ledger") == 0);
  CHECK(sum.at("nodes").get<int>() == model_nodes(spec));
  // The peaks over every step bound every sampled row, and each is reached at a sampled time or
  // between two (so a 10 ms sampling can only under-report them).
  const json& peaks = sum.at("sectional_force_peaks");
  REQUIRE(peaks.size() == spec.outputs.sectional_forces.size());
  for (const auto& pk : peaks) {
    const std::string name = pk.at("section");
    for (const char* c : {"N", "Qy", "Qz", "Mx", "My", "Mz"}) {
      INFO(name << " " << c);
      const auto& col = sections.column(name + "_" + c);
      REQUIRE_FALSE(col.empty());
      const double lo = *std::min_element(col.begin(), col.end()), hi = *std::max_element(col.begin(), col.end());
      const double tol = 1e-9 * std::max(1.0, std::max(std::abs(lo), std::abs(hi)));
      CHECK(pk.at(c).at("max").get<double>() >= hi - tol);
      CHECK(pk.at(c).at("min").get<double>() <= lo + tol);
    }
  }
  // The PVD lists the VTU files, which exist and hold every node.
  if (spec.outputs.vtu_every > 0) {
    const auto files = pvd_files(out + "/room.pvd");
    CHECK_FALSE(files.empty());
    for (const auto& f : files) {
      INFO(f);
      REQUIRE(fs::is_regular_file(fs::path(out) / f));
      CHECK(vtu_points((fs::path(out) / f).string()) == sum.at("nodes").get<long>());
    }
  }
  if (expect_figures) {
    check_png(out + "/room_final.png", 1000, 800);
    check_png(out + "/energy.png", 1000, 800);
  }
  return sum;
}

}  // namespace

TEST_CASE("run_scene on a small scene writes every output, and each parses", "[runner]") {
  const std::string out = fresh_dir("small");
  const std::string scene_file = write_json(fresh_dir("small_scene") + "/scene.json", small_scene_json(out));
  const SceneSpec spec = parse_scene(scene_file);
  const RunSummary s = run_scene(spec, quiet(""));  // the folder from the scene file
  CHECK(s.status == "completed");
  CHECK(s.diagnosis.empty());
  CHECK(s.t_end == Approx(0.3).margin(1e-9));
  CHECK(s.steps == 300);
  CHECK(s.out_dir == out);
  const int nodes = model_nodes(spec);
  CHECK(s.nodes == nodes);
  CHECK(s.bodies == 2);

  for (const char* f : {"markers.csv", "contact_forces.csv", "sectional_forces.csv", "energy.csv", "final_state.json",
                        "summary.json", "room.pvd", "room_final.png", "marker_office_chair.seat_centre.png",
                        "marker_table_top.png", "shear_0.png"}) {
    INFO(f);
    CHECK(fs::is_regular_file(fs::path(out) / f));
  }
  const json sum = check_outputs(out, spec, true);
  CHECK(sum.at("status") == "completed");
  CHECK(sum.at("steps") == 300);
  CHECK(sum.at("t_end_s").get<double>() == Approx(0.3).margin(1e-9));
  CHECK(std::isfinite(sum.at("energy_imbalance_relative").get<double>()));
  // The summary's scene reads back as the same scene.
  CHECK(to_json(parse_scene_json(sum.at("scene"), "summary.json")) == sum.at("scene"));

  // History rows every 10 steps, from t = 0 to t = 0.3 s.
  const CsvTable m = read_csv(out + "/markers.csv");
  REQUIRE(m.rows() == 31);
  CHECK(m.column("t").front() == 0.0);
  CHECK(m.column("t").back() == Approx(0.3).margin(1e-9));
  CHECK(m.columns().size() == 13);  // t, then x, y, z, ax, ay, az per marker
  CHECK(m.column("office_chair.seat_centre_x").front() == 0.0);  // displacement at t = 0
  const CsvTable sf = read_csv(out + "/sectional_forces.csv");
  CHECK(sf.rows() == 31);
  for (const char* c : {"_N", "_Qy", "_Qz", "_Mx", "_My", "_Mz"}) CHECK(sf.has(std::string("office_chair:column:0#0") + c));
  // The chair's column carries (most of) the seat's weight in compression once it has settled.
  CHECK(std::abs(sf.column("office_chair:column:0#0_N").back()) > 1.0);
  CHECK(read_csv(out + "/energy.csv").rows() == 31);

  // VTU frames at steps 0, 100, 200 and 300.
  const auto files = pvd_files(out + "/room.pvd");
  CHECK(files == std::vector<std::string>{"vtu/room_0.vtu", "vtu/room_100.vtu", "vtu/room_200.vtu", "vtu/room_300.vtu"});
  CHECK(vtu_points(out + "/vtu/room_300.vtu") == nodes);

  check_png(out + "/marker_office_chair.seat_centre.png", 1000, 750);
  check_png(out + "/marker_table_top.png", 1000, 750);
  check_png(out + "/shear_0.png", 1000, 600);
}

TEST_CASE("configuration 2 runs one second of synthetic motion", "[runner][slow]") {
  SceneSpec spec = configuration(2, "");
  spec.name = "configuration 2, synthetic 1-D, 1 s";
  spec.ground_motion = GroundMotionSpec{};  // synthetic: the built-in motion, X peak 8 m/s^2
  spec.ground_motion.pga = 8.0;
  spec.duration = 1.0;
  spec.outputs.vtu_every = 0;
  spec.outputs.figures = false;
  const std::string out = fresh_dir("configuration2");
  const RunSummary s = run_scene(spec, quiet(out));
  CHECK(s.status == "completed");
  CHECK(s.t_end == Approx(1.0).margin(1e-9));
  CHECK(s.steps == 1000);
  CHECK(s.elements == 994);  // docs/furniture/furniture.md
  CHECK(s.bodies == 3);
  // The ledger closes: measured 1.2e-4 of its scale at the end and 1.3e-4 at worst (Release, g++ 12);
  // the bound leaves a factor of 15 for other compilers, platforms and solver changes.
  INFO("energy imbalance " << s.energy_imbalance << " (max " << s.max_energy_imbalance << "), wall " << s.wall_seconds
                           << " s");
  CHECK(std::isfinite(s.energy_imbalance));
  CHECK(s.energy_imbalance < 2e-3);
  CHECK(s.max_energy_imbalance < 2e-3);
  // Nothing overturns in the first second (the envelope builds up over 1.5 s).
  REQUIRE(s.items.size() == 3);
  for (const auto& it : s.items) {
    INFO(it.name << ": " << it.state << ", tilt " << it.tilt_deg << " deg");
    CHECK(it.state != "overturned");
    CHECK(it.tilt_deg < 30);
  }
  const json sum = check_outputs(out, spec, false);
  CHECK(sum.at("elements") == 994);
  const CsvTable e = read_csv(out + "/energy.csv");
  CHECK(e.rows() == 101);
  // Markers of configuration(2): the desk and the chair (Figures 17, 18), and Figure 19's shear.
  CHECK(read_csv(out + "/markers.csv").has("desk.top_back_centre_x"));
  CHECK(read_csv(out + "/markers.csv").has("office_chair.seat_centre_x"));
  CHECK(read_csv(out + "/sectional_forces.csv").columns().size() == 7);
}

TEST_CASE("a broken scene file gives an InputError naming the key before the run starts", "[runner]") {
  const std::string dir = fresh_dir("broken");
  fs::create_directories(dir);
  const std::string out = dir + "/out";
  const auto attempt = [&](const json& j) -> std::string {
    const std::string file = write_json(dir + "/scene.json", j);
    try {
      const SceneSpec spec = parse_scene(file);
      run_scene(spec, quiet(out));
    } catch (const InputError& e) {
      CHECK_FALSE(fs::exists(out));  // nothing was written: the run never started
      return e.what();
    }
    FAIL("no InputError for " << j.dump());
    return {};
  };
  const json good = small_scene_json(out);

  SECTION("unknown key") {
    json j = good;
    j["duraton"] = 1.0;
    const std::string msg = attempt(j);
    CHECK_THAT(msg, Catch::Contains("duraton"));
    CHECK_THAT(msg, Catch::Contains("scene.json"));
  }
  SECTION("unknown key inside an item") {
    json j = good;
    j["items"][1]["colour"] = "grey";
    CHECK_THAT(attempt(j), Catch::Contains("items[1].colour"));
  }
  SECTION("wrong type") {
    json j = good;
    j["dt"] = "fast";
    const std::string msg = attempt(j);
    CHECK_THAT(msg, Catch::Contains("dt"));
    CHECK_THAT(msg, Catch::Contains("fast"));
  }
  SECTION("wrong type in an item") {
    json j = good;
    j["items"][0]["yaw_deg"] = "ninety";
    CHECK_THAT(attempt(j), Catch::Contains("items[0].yaw_deg"));
  }
  SECTION("marker on no item") {
    json j = good;
    j["outputs"]["markers"].push_back("sofa.top_centre");
    const std::string msg = attempt(j);
    CHECK_THAT(msg, Catch::Contains("outputs.markers[2]"));
    CHECK_THAT(msg, Catch::Contains("sofa"));
  }
  SECTION("marker name not on the item") {
    json j = good;
    j["outputs"]["markers"][0] = "office_chair.armrest";
    const std::string msg = attempt(j);
    CHECK_THAT(msg, Catch::Contains("outputs.markers[0]"));
    CHECK_THAT(msg, Catch::Contains("armrest"));
  }
  SECTION("sectional force on a member that does not exist") {
    json j = good;
    j["outputs"]["sectional_forces"][0]["member"] = "no_such_member";
    CHECK_THAT(attempt(j), Catch::Contains("outputs.sectional_forces[0].member"));
  }
  SECTION("missing record file") {
    json j = good;
    j["ground_motion"] = json::parse(R"({"source": "file", "format": "at2", "files": {"x": "no_such_record.AT2"}})");
    const std::string msg = attempt(j);
    CHECK_THAT(msg, Catch::Contains("ground_motion.files.x"));
    CHECK_THAT(msg, Catch::Contains("no_such_record.AT2"));
  }
  SECTION("missing record file for a 3-D component") {
    const std::string rec = dir + "/x.txt";
    std::ofstream(rec) << "0 0\n0.01 0.1\n0.02 0\n";
    json j = good;
    j["ground_motion"] = {{"source", "file"},
                          {"format", "columns"},
                          {"units", "m/s2"},
                          {"dimensions", "3d"},
                          {"files", {{"x", rec}, {"y", rec}, {"z", dir + "/z_missing.txt"}}}};
    CHECK_THAT(attempt(j), Catch::Contains("ground_motion.files.z"));
  }
  SECTION("items overlapping") {
    json j = good;
    j["items"][1]["x"] = -0.8;
    j["items"][1]["y"] = 0.1;
    CHECK_THAT(attempt(j), Catch::Contains("items[1]"));
  }
}

TEST_CASE("a run length that is not a finite number of steps is refused before the run starts", "[runner][errors]") {
  // Issue 13: --duration -1, 0 and nan "completed after 0 steps" (exit 0); 1e300 ran forever; a
  // scene refresh_every of 1e300 became "every step" (lround out of range).
  const std::string dir = fresh_dir("run_length");
  const std::string out = dir + "/out";
  const SceneSpec spec = parse_scene(write_json(dir + "/scene.json", small_scene_json(out)));
  for (const double d : {-1.0, 0.0, 1e-9, std::nan(""), std::numeric_limits<double>::infinity(), 1e300}) {
    RunOptions opt = quiet(out);
    opt.duration = d;
    try {
      run_scene(spec, opt);
      FAIL("no InputError for duration " << d);
    } catch (const InputError& e) {
      INFO("duration " << d << ": " << e.what());
      CHECK_THAT(std::string(e.what()), Catch::Contains("duration"));
      CHECK_FALSE(fs::exists(out));
    }
  }
  SceneSpec rare = spec;
  rare.refresh_every = 1e300;
  CHECK(rare.refresh_interval_steps() == 1000000000);
}

TEST_CASE("stiff law: stacked cabinets stand on each other, rigid and full, with no energy made", "[runner][stiff]") {
  // Configuration 3 under `stiff` stopped with "energy is being created" at every fidelity (2026-11-25,
  // docs/contact/contact.md): item-item contact is explicit, and the stiff spring (2.5 um under the
  // item's weight) was past the explicit stable step of the cabinets' nodes; full items' floor contact
  // was explicit too. Now the pair spring and dashpot are capped at a fraction of the lightest node's
  // explicit limits (omega dt = 0.5, c dt / m = 0.2) and `stiff` puts every item's floor contact
  // inside the implicit step. Before the fix: full diverged at 0.12 s (uncapped: at 0.01 s).
  // Still table, 0.5 s: the run completes, the upper cabinet stays upright on the lower one (tilt
  // below 0.1 deg), sinking by less than 1 mm (the capped spring: 0.2 mm measured). Horizontally the
  // upper cabinet walks on the lower one at about 4.5 mm/s with either law, paper or stiff (measured
  // 2026-11-25: 0.5 s 1-3 mm, 2 s 5-11 mm; more with more item friction): an open problem of explicit
  // item-item contact between crossing panel grids (docs/contact/contact.md). Bounded here at 4 mm for
  // full items; rigid items have their pair inside the step (rigid groups, 2026-11-26): 0.036 mm
  // measured (was 9 mm in 2 s), bounded at the issue's 0.1 mm.
  for (const char* fidelity : {"rigid", "full"}) {
    const std::string dir = fresh_dir(std::string("stacked_stiff_") + fidelity);
    json j = json::parse(R"({
      "name": "stacked cabinets, stiff",
      "items": [{"kind": "separated_cabinets", "x": 0.0, "y": 0.0, "yaw_deg": 0}],
      "ground_motion": {"source": "points", "x": [[0, 0], [1, 0]]},
      "contact": {"law": "stiff"},
      "duration": 0.5,
      "dt": 0.001,
      "outputs": {"figures": false, "vtu_every": 0}
    })");
    j["items"][0]["fidelity"] = fidelity;
    j["outputs"]["folder"] = dir + "/out";
    const SceneSpec spec = parse_scene(write_json(dir + "/scene.json", j));
    CHECK(implicit_contact(spec.contact) == ImplicitContact::all);  // the default
    const RunSummary sum = run_scene(spec, quiet(dir + "/out"));
    INFO(fidelity << ": " << sum.status << " " << sum.diagnosis);
    REQUIRE(sum.status == "completed");
    for (const auto& it : sum.items) {
      INFO(it.name << ": tilt " << it.tilt_deg << " deg, cog moved " << it.cog_displacement.transpose());
      CHECK(it.tilt_deg < 0.1);
      CHECK(std::abs(it.cog_displacement.z()) < 1e-3);
      CHECK(it.cog_displacement.head<2>().norm() < (std::string(fidelity) == "rigid" ? 1e-4 : 4e-3));
    }
  }
}

TEST_CASE("a wall normal is kept as written: read and to_json round-trip to the bit", "[scene][json]") {
  const std::string dir = fresh_dir("wall_normal");
  json j = small_scene_json(dir + "/out");
  j["walls"] = json::parse(R"([{"name": "slanted", "point": [1.9, 0, 0], "normal": [-1, 1, 0]},
                               {"name": "odd", "point": [-1.9, 0, 0], "normal": [0.3, 0.1, 0]}])");
  const SceneSpec once = parse_scene(write_json(dir + "/a.json", j));
  const json first = to_json(once);
  const SceneSpec twice = parse_scene(write_json(dir + "/b.json", first));
  CHECK(to_json(twice) == first);
  CHECK(twice.walls.at(0).normal == Vec3(-1, 1, 0));  // normalised it moved by an ulp each time
  CHECK(twice.walls.at(1).normal == Vec3(0.3, 0.1, 0));
}

TEST_CASE("a stop request ends the run with status 'stopped' and readable outputs", "[runner]") {
  SECTION("stop already requested once the motion is read: nothing built, nothing written") {
    // As Ctrl-C while a long record is read: the program says "nothing run, nothing written".
    const std::string out = fresh_dir("stop_now");
    const SceneSpec spec = parse_scene_json(small_scene_json(out), "stop_now");
    std::atomic<bool> stop{true};
    RunOptions o = quiet(out);
    o.stop = &stop;
    const RunSummary s = run_scene(spec, o);
    CHECK(s.status == "stopped");
    CHECK(s.steps == 0);
    CHECK(s.t_end == 0.0);
    CHECK(s.out_dir.empty());
    CHECK_THAT(s.diagnosis, Catch::Contains("while the ground motion was read") &&
                                Catch::Contains("nothing run, nothing written"));
    CHECK_FALSE(fs::exists(out));
  }
  SECTION("stop requested from another thread during the run") {
    const std::string out = fresh_dir("stop_later");
    SceneSpec spec = parse_scene_json(small_scene_json(out), "stop_later");
    spec.duration = 60.0;  // far longer than the test waits
    spec.ground_motion.pad_after_end = true;  // past the synthetic motion's 10 s
    std::atomic<bool> stop{false};
    RunOptions o = quiet(out);
    o.stop = &stop;
    // Stop once the energy history holds a few flushed rows (the CSV writer flushes every second).
    std::thread stopper([&] {
      const auto t0 = std::chrono::steady_clock::now();
      while (!stop && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(120)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        std::error_code ec;
        if (!fs::is_regular_file(out + "/energy.csv", ec)) continue;
        std::ifstream f(out + "/energy.csv");
        const auto lines = std::count(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>(), '\n');
        if (lines >= 5) break;
      }
      stop = true;
    });
    RunSummary s;
    try {
      s = run_scene(spec, o);
    } catch (...) {
      stop = true;  // the stopper must be joined before the failure is reported
      stopper.join();
      throw;
    }
    stopper.join();
    CHECK(s.status == "stopped");
    CHECK(s.t_end > 0.0);
    CHECK(s.t_end < 60.0);
    CHECK(s.steps == std::lround(s.t_end / spec.dt));
    // The diagnosis says where: the time it stopped at.
    char where[64];
    std::snprintf(where, sizeof where, "t = %f s", s.t_end);
    CHECK_THAT(s.diagnosis, Catch::Contains(where));
    const json sum = check_outputs(out, spec, true);
    CHECK(sum.at("status") == "stopped");
    CHECK(sum.at("t_end_s").get<double>() == Approx(s.t_end));
    CHECK(read_json(out + "/run.json").at("status") == "interrupted");
    const CsvTable m = read_csv(out + "/markers.csv");
    CHECK(m.rows() >= 4);
    CHECK(m.column("t").back() <= s.t_end + 1e-12);
  }
}

TEST_CASE("final states: an item on a slippery floor under a strong pulse slides; an unshaken one stands",
          "[runner]") {
  const std::string dir = fresh_dir("final_state");
  fs::create_directories(dir);
  SECTION("slid") {
    // One sine cycle of 4 m/s^2 over 0.6 s along X: a squat table with mu = 0.03 cannot follow it
    // (it would need 0.4 g) and slides while it cannot tip (0.03 g is far below its b/h).
    Record pulse;
    pulse.dt = 0.005;
    pulse.name = "sine pulse";
    for (int i = 0; i <= 240; ++i) {
      const double t = pulse.dt * i;
      pulse.acc.push_back(t >= 0.1 && t <= 0.7 ? 4.0 * std::sin(2 * std::numbers::pi * (t - 0.1) / 0.6) : 0.0);
    }
    write_columns(dir + "/pulse.txt", pulse);
    const json j = {{"name", "sliding table"},
                    {"items", {{{"kind", "table"},
                                {"name", "low_table"},
                                {"fidelity", "coarse"},
                                {"params", {{"width", 0.8}, {"depth", 0.6}, {"height", 0.4}}}}}},
                    {"ground_motion",
                     {{"source", "file"}, {"format", "columns"}, {"units", "m/s2"}, {"files", {{"x", "pulse.txt"}}}}},
                    {"contact", {{"law", "paper"}, {"floor", {{"mu", 0.03}}}}},
                    {"duration", 1.2},
                    {"outputs", {{"figures", false}}}};
    const SceneSpec spec = parse_scene(write_json(dir + "/slide.json", j));
    const RunSummary s = run_scene(spec, quiet(dir + "/slide_out"));
    REQUIRE(s.status == "completed");
    REQUIRE(s.items.size() == 1);
    const auto& it = s.items[0];
    INFO("slide " << it.slide << " m, tilt " << it.tilt_deg << " deg, cog displacement " << it.cog_displacement.transpose());
    CHECK(it.state == "slid");
    CHECK(it.slide > 0.05);
    CHECK(it.tilt_deg < 5);
    // Relative to the table the item lags behind the table's first push: it moves towards -X.
    CHECK(it.cog_displacement.x() < -0.05);
    CHECK(std::abs(it.cog_displacement.y()) < 0.2 * std::abs(it.cog_displacement.x()));
    const json fin = read_json(dir + "/slide_out/final_state.json");
    CHECK(fin.at(0).at("state") == "slid");
  }
  SECTION("slid into a placed obstacle") {
    // The same push with a mesh block 80 mm behind the table's -X edge: without it the table's top
    // lags up to 0.19 m behind (at 0.6 s), so the block (placed by position, yaw and scale) must stop
    // it at 80 mm plus the contact's indentation. The OBJ file
    // is a 2 x 1 x 1 box in its own units, turned by 90 degrees and scaled by 0.4: 0.4 m along X,
    // 0.8 m along Y (both legs of the -X side hit it), 0.4 m high, its +X face at x = -0.48 m.
    Record pulse;
    pulse.dt = 0.005;
    for (int i = 0; i <= 240; ++i) {
      const double t = pulse.dt * i;
      pulse.acc.push_back(t >= 0.1 && t <= 0.7 ? 4.0 * std::sin(2 * std::numbers::pi * (t - 0.1) / 0.6) : 0.0);
    }
    write_columns(dir + "/pulse.txt", pulse);
    {
      std::ofstream obj(dir + "/block.obj");
      obj << "# 2 x 1 x 1 box\n";
      for (double z : {0.0, 1.0})
        for (double y : {-0.5, 0.5})
          for (double x : {-1.0, 1.0}) obj << "v " << x << ' ' << y << ' ' << z << '\n';
      // vertex index = 1 + ix + 2 iy + 4 iz
      obj << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
    }
    const json j = {{"name", "sliding table and a block"},
                    {"items", {{{"kind", "table"},
                                {"name", "low_table"},
                                {"fidelity", "coarse"},
                                {"params", {{"width", 0.8}, {"depth", 0.6}, {"height", 0.4}}}}}},
                    {"obstacles", {{{"name", "block"}, {"file", "block.obj"}, {"position", {-0.68, 0.0, 0.0}},
                                    {"yaw_deg", 90.0}, {"scale", 0.4}}}},
                    {"ground_motion",
                     {{"source", "file"}, {"format", "columns"}, {"units", "m/s2"}, {"files", {{"x", "pulse.txt"}}}}},
                    {"contact", {{"law", "paper"}, {"floor", {{"mu", 0.03}}}}},
                    {"duration", 1.2},
                    {"outputs",
                     {{"figures", false},
                      {"markers", {{{"name", "top"}, {"item", "low_table"}, {"point", {0.0, 0.0, 0.4}}}}}}}};
    const SceneSpec spec = parse_scene(write_json(dir + "/block.json", j));
    const RunSummary s = run_scene(spec, quiet(dir + "/block_out"));
    REQUIRE(s.status == "completed");
    const CsvTable markers = read_csv(dir + "/block_out/markers.csv");  // kept: column() returns a reference into it
    const auto& x = markers.column("top_x");
    const double furthest = *std::min_element(x.begin(), x.end());
    INFO("furthest -X excursion " << furthest << " m, final state " << s.items.at(0).state);
    CHECK(furthest < -0.07);   // it slides up to the block (80 mm) ...
    CHECK(furthest > -0.11);   // ... which stops it: measured -0.084 m (free: -0.189 m)
    CHECK(s.items.at(0).tilt_deg < 5);
    // The same box as an OFF file (extension in capitals): read by the OFF reader, the same run.
    // Until 2026-11-26 a scene refused .off although the reader existed (issue 13).
    {
      std::ofstream off(dir + "/block.OFF");
      off << "OFF\n8 6 0\n";
      for (double z : {0.0, 1.0})
        for (double y : {-0.5, 0.5})
          for (double x : {-1.0, 1.0}) off << x << ' ' << y << ' ' << z << '\n';
      off << "4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n";
    }
    json j_off = j;
    j_off["obstacles"][0]["file"] = "block.OFF";
    const RunSummary s_off = run_scene(parse_scene(write_json(dir + "/block_off.json", j_off)), quiet(dir + "/block_off_out"));
    REQUIRE(s_off.status == "completed");
    const CsvTable markers_off = read_csv(dir + "/block_off_out/markers.csv");
    const auto& x_off = markers_off.column("top_x");
    REQUIRE(x_off.size() == x.size());
    for (std::size_t i = 0; i < x.size(); ++i) CHECK(x_off[i] == Approx(x[i]).margin(1e-9));
  }
  SECTION("stacked: the upper cabinet rests on the lower one, not the other way round") {
    const json j = {{"name", "stacked cabinets at rest"},
                    {"items", {{{"kind", "separated_cabinets"}, {"name", "pair"}, {"fidelity", "coarse"}}}},
                    {"ground_motion", {{"source", "synthetic"}, {"level", 0.0}}},
                    {"duration", 0.3},
                    {"outputs", {{"figures", false}}}};
    const SceneSpec spec = parse_scene(write_json(dir + "/stacked.json", j));
    const RunSummary s = run_scene(spec, quiet(dir + "/stacked_out"));
    REQUIRE(s.status == "completed");
    REQUIRE(s.items.size() == 2);
    CHECK(s.items[0].name == "pair/lower");
    CHECK(s.items[0].resting_on.empty());
    CHECK(s.items[0].state == "standing");
    CHECK(s.items[1].name == "pair/upper");
    CHECK(s.items[1].resting_on == "pair/lower");
    CHECK(s.items[1].state == "standing");
    // contact_forces.csv rows are means over the steps since the previous row: at rest they carry the
    // weights (Table 2: upper 21.3 kg, lower 28.8 kg). Rows of single steps read a phase of the
    // penalty contact's step-to-step alternation instead (a cabinet at rest showed -75 N from the floor).
    // Columns by name: "<item>|<partner>_f?", the force on the item from the partner.
    const CsvTable cf = read_csv(dir + "/stacked_out/contact_forces.csv");
    double on_lower_from_upper = 0, on_lower_from_floor = 0;
    int n_pair = 0, n_floor = 0;
    const auto &t = cf.column("t"), &pair_fz = cf.column("pair/lower|pair/upper_fz"),
               &floor_fz = cf.column("pair/lower|floor_fz");
    CHECK_FALSE(cf.has("pair/upper|pair/lower_fz"));  // each pair once, the first item first
    for (double f : cf.column("pair/upper|floor_fz")) CHECK(f == 0.0);  // the upper one never touches the floor
    for (std::size_t r = 0; r < cf.rows(); ++r) {
      if (t[r] < 0.15) continue;
      on_lower_from_upper += pair_fz[r], ++n_pair;
      on_lower_from_floor += floor_fz[r], ++n_floor;
    }
    REQUIRE(n_pair > 10);
    REQUIRE(n_floor > 10);
    const double g = 9.80665;
    CHECK(on_lower_from_upper / n_pair == Approx(-21.3 * g).epsilon(0.03));
    CHECK(on_lower_from_floor / n_floor == Approx((21.3 + 28.8) * g).epsilon(0.03));
  }
  SECTION("stacked, item pairs as rows: contact_pairs.csv holds the pair columns' non-zero values") {
    // outputs.contact_pairs "rows" (the default above 100 bodies, where n (n - 1) / 2 pairs of columns
    // no longer fit): one row per touching pair and history row, the same means as the columns.
    json j = {{"name", "stacked cabinets at rest"},
              {"items", {{{"kind", "separated_cabinets"}, {"name", "pair"}, {"fidelity", "coarse"}}}},
              {"ground_motion", {{"source", "synthetic"}, {"level", 0.0}}},
              {"duration", 0.3},
              {"outputs", {{"figures", false}}}};
    REQUIRE(run_scene(parse_scene(write_json(dir + "/cols.json", j)), quiet(dir + "/cols_out")).status == "completed");
    j["outputs"]["contact_pairs"] = "rows";
    REQUIRE(run_scene(parse_scene(write_json(dir + "/rows.json", j)), quiet(dir + "/rows_out")).status == "completed");
    const CsvTable cols = read_csv(dir + "/cols_out/contact_forces.csv");
    const CsvTable rows = read_csv(dir + "/rows_out/contact_forces.csv");
    CHECK_FALSE(rows.has("pair/lower|pair/upper_fz"));
    CHECK(rows.column("pair/lower|floor_fz") == cols.column("pair/lower|floor_fz"));
    std::ifstream in(dir + "/rows_out/contact_pairs.csv");
    std::string line;
    std::getline(in, line);
    CHECK(line == "t,item_a,item_b,fx,fy,fz");
    std::map<double, std::array<double, 3>> by_t;
    while (std::getline(in, line)) {
      std::vector<std::string> cell;
      std::stringstream ls(line);
      for (std::string c; std::getline(ls, c, ',');) cell.push_back(c);
      REQUIRE(cell.size() == 6);
      CHECK(cell[1] == "pair/lower");
      CHECK(cell[2] == "pair/upper");
      by_t[std::stod(cell[0])] = {std::stod(cell[3]), std::stod(cell[4]), std::stod(cell[5])};
    }
    const auto& t = cols.column("t");
    int touching = 0;
    for (std::size_t r = 0; r < cols.rows(); ++r) {
      const std::array<double, 3> f{cols.column("pair/lower|pair/upper_fx")[r], cols.column("pair/lower|pair/upper_fy")[r],
                                    cols.column("pair/lower|pair/upper_fz")[r]};
      const bool zero = f[0] == 0 && f[1] == 0 && f[2] == 0;
      CHECK(by_t.count(t[r]) == (zero ? 0u : 1u));
      if (!zero && by_t.count(t[r])) {
        CHECK(by_t[t[r]] == f);
        ++touching;
      }
    }
    CHECK(touching > 10);
    CHECK(touching == static_cast<int>(by_t.size()));
  }
  SECTION("standing") {
    json j = small_scene_json(dir + "/stand_out");
    j["name"] = "no motion";
    j["ground_motion"]["level"] = 0.0;
    j["duration"] = 0.5;
    j["outputs"]["figures"] = false;
    j["outputs"]["vtu_every"] = 0;
    const SceneSpec spec = parse_scene(write_json(dir + "/stand.json", j));
    const RunSummary s = run_scene(spec, quiet(""));
    REQUIRE(s.status == "completed");
    REQUIRE(s.items.size() == 2);
    for (const auto& it : s.items) {
      INFO(it.name << ": slide " << it.slide << " m, tilt " << it.tilt_deg << " deg");
      CHECK(it.state == "standing");
      // Settling on the penalty springs (alpha = the weight, so the feet sink L/n on average, more under
      // the heavier side) tilts the side table by 0.7 deg and moves its centre of gravity by 3.5 mm.
      CHECK(it.slide < 0.01);
      CHECK(it.tilt_deg < 2.0);
    }
  }
}

TEST_CASE("energy created by the contact is judged by its work as applied, not by the trapezoidal estimate",
          "[runner][energy]") {
  // A landing as measured on a rigid block (tests/contact_dynamics/stiff_law.cpp): the trapezoidal
  // estimate of the contact's work shows +30 J of 100 while the work the integrator applied is -5 J
  // (the imbalance, -35 J, holds the difference). Nothing was created: no diagnosis. With +30 J applied
  // the contact did feed the items, and the diagnosis says so with that figure.
  EnergyLedger E;
  E.initial_total = 100;
  E.gravity_potential = 60;
  E.contact_work = 30;
  E.contact_work_applied = -5;
  ContactStepEstimate est;
  est.dt = 1e-3;
  est.item = "tall_cabinet";
  CHECK(energy_creation_diagnosis(E, 1e-3, 0.25, est).empty());
  E.contact_work_applied = 30;
  const std::string why = energy_creation_diagnosis(E, 1e-3, 0.25, est);
  CHECK_THAT(why, Catch::Contains("energy is being created") && Catch::Contains("30 J of net positive work"));
}

TEST_CASE("the explicit contact's stable step is estimated from the scene's law, not the paper's alpha",
          "[runner][energy]") {
  // A floor node of mass m on the law's normal spring k at its resting overlap is stable below
  // 2 sqrt(m / k). `stiff` springs sink 2.5 um under the weight the resting nodes share: k = W / (n 2.5 um).
  // The estimate used the paper's alpha / L for every law and said 3.76 ms for a cabinet under `stiff`
  // with explicit contact, which diverged at dt 1 ms within 0.27 s. Contact inside the implicit step
  // (the default) sets no such limit.
  const auto estimate = [](const std::string& law, const std::string& implicit) {
    const SceneSpec s = parse_scene_json(json{{"name", "estimate"},
                                              {"items", {{{"kind", "locker"}, {"fidelity", "full"}}}},
                                              {"contact", {{"law", law}, {"implicit", implicit}}},
                                              {"duration", 0.1}},
                                         "estimate.json");
    SceneSimulation<DirectLdltSolver> scene(s, 0, 1);
    const ContactStepEstimate est = contact_step_estimate(
        *scene.sim, *scene.model, scene.items, scene_body_contacts(s, *scene.model, scene.items), s.contact.law);
    // The same from the closed forms of the two springs.
    const ItemInfo& it = scene.items.at(0);
    const ContactParams p = scene_body_contacts(s, *scene.model, scene.items).at(it.body).floor;
    const double n = double(it.bottom_nodes.size());
    double expected = std::numeric_limits<double>::infinity();
    for (int node : it.bottom_nodes) {
      double half = std::numeric_limits<double>::infinity();
      for (int e = 0; e < scene.model->num_elements(); ++e)
        if (scene.model->elements()[e].n1 == node || scene.model->elements()[e].n2 == node)
          half = std::min(half, 0.5 * scene.model->section_of(e).contact_width());
      const double k = law == "stiff" ? scene.model->body_mass(it.body) * 9.80665 / (n * 2.5e-6) : p.alpha / half;
      expected = std::min(expected, 2.0 * std::sqrt(scene.sim->nodal_mass(node) / k));
    }
    return std::pair{est, expected};
  };
  const auto [stiff, stiff_expected] = estimate("stiff", "none");
  INFO("stiff: " << stiff.dt << " s, closed form " << stiff_expected << " s");
  CHECK(stiff.dt == Approx(stiff_expected).epsilon(1e-6));
  CHECK(stiff.dt < 1e-3);  // the run that diverged at dt 1 ms is told why
  CHECK(stiff.item == "locker");
  CHECK(stiff.remedy() == "reduce dt");  // `stiff` sets its own spring: nothing else to change
  const auto [paper, paper_expected] = estimate("paper", "none");
  INFO("paper: " << paper.dt << " s, closed form " << paper_expected << " s");
  CHECK(paper.dt == Approx(paper_expected).epsilon(1e-6));
  CHECK(paper.dt > 1e-3);
  CHECK(paper.remedy() == "reduce dt or the penalty alpha_kgf");
  CHECK(std::isinf(estimate("stiff", "all").first.dt));
}

TEST_CASE("a completed run that lost too much energy carries a warning naming the cause", "[runner][energy]") {
  // A ledger that started at 100 J of gravity energy and holds 60 J with no work done: 40 J lost,
  // 40 % of its scale (100 J, the initial total).
  EnergyLedger E;
  E.initial_total = 100;
  E.gravity_potential = 60;
  ContactStepEstimate est;
  est.dt = 1e-3;
  est.item = "desk";
  REQUIRE(E.imbalance() == Approx(-40));
  REQUIRE(E.scale() == Approx(100));
  SECTION("dt beyond the contact's stable step: names the time step and the item") {
    const std::string w = energy_loss_warning(E, 5e-3, 0.15, est);
    CHECK_THAT(w, Catch::Contains("does not close") && Catch::Contains("40 %") &&
                      Catch::Contains("too stiff for the time step") && Catch::Contains("'desk'"));
  }
  SECTION("dt within it: names impacts") {
    CHECK_THAT(energy_loss_warning(E, 5e-4, 0.15, est), Catch::Contains("Impacts"));
  }
  SECTION("a loss under the limit, a gain, or no limit: no warning") {
    CHECK(energy_loss_warning(E, 5e-3, 0.5, est).empty());
    CHECK(energy_loss_warning(E, 5e-3, 0.0, est).empty());
    E.gravity_potential = 140;  // 40 J made: the creation check's business, not this one's
    CHECK(energy_loss_warning(E, 5e-3, 0.15, est).empty());
  }
}

namespace {

// An observer that counts its calls and the history rows, and checks what the runner promises it.
struct CallCounter : RunObserver {
  int begins = 0, ends = 0, rows = 0;
  long steps = 0;
  std::size_t items_at_end = 0;
  void begin(const RunView& run) override {
    ++begins;
    CHECK(run.sim.steps() == 0);
    CHECK(run.row_due());
    ++rows;
  }
  void after_step(const RunView& run, const StepInfo&) override {
    ++steps;
    CHECK(run.sim.steps() == steps);
    rows += run.row_due();
  }
  void end(const RunView&, RunSummary& summary) override {
    ++ends;
    items_at_end = summary.items.size();  // the standard observers before it filled the final states
  }
};

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

// Every number of two summaries equal to the bit (wall time and folder aside).
void check_same_outcome(const RunSummary& a, const RunSummary& b) {
  CHECK(a.status == b.status);
  CHECK(a.diagnosis == b.diagnosis);
  CHECK(bits(a.t_end) == bits(b.t_end));
  CHECK(bits(a.duration) == bits(b.duration));
  CHECK(a.steps == b.steps);
  CHECK(bits(a.energy_imbalance) == bits(b.energy_imbalance));
  CHECK(bits(a.max_energy_imbalance) == bits(b.max_energy_imbalance));
  CHECK(a.factorizations == b.factorizations);
  CHECK((a.elements == b.elements && a.nodes == b.nodes && a.bodies == b.bodies));
  REQUIRE(a.items.size() == b.items.size());
  for (std::size_t i = 0; i < a.items.size(); ++i) {
    const ItemFinalState &x = a.items[i], &y = b.items[i];
    INFO(x.name);
    CHECK((x.name == y.name && x.state == y.state && x.resting_on == y.resting_on));
    const std::pair<double, double> values[] = {
        {x.slide, y.slide}, {x.tilt_deg, y.tilt_deg}, {x.max_tilt_deg, y.max_tilt_deg}, {x.lift, y.lift}};
    for (const auto& [u, v] : values) CHECK(bits(u) == bits(v));
    for (int c = 0; c < 3; ++c) CHECK(bits(x.cog_displacement[c]) == bits(y.cog_displacement[c]));
  }
  REQUIRE(a.section_peaks.size() == b.section_peaks.size());
  for (std::size_t i = 0; i < a.section_peaks.size(); ++i) {
    const SectionForcePeak &p = a.section_peaks[i], &q = b.section_peaks[i];
    CHECK(p.section == q.section);
    for (int c = 0; c < 6; ++c) {
      CHECK(bits(p.min[c]) == bits(q.min[c]));
      CHECK(bits(p.max[c]) == bits(q.max[c]));
      CHECK(bits(p.t_min[c]) == bits(q.t_min[c]));
      CHECK(bits(p.t_max[c]) == bits(q.t_max[c]));
    }
  }
}

}  // namespace

TEST_CASE("a run that writes no files returns the same outcome, to the bit, as one that writes them",
          "[runner][observers]") {
  const std::string folder = fresh_dir("outcome_files");
  const SceneSpec spec = parse_scene_json(small_scene_json(folder), "outcome");
  CallCounter with_files_calls, without_files_calls;
  const RunSummary with_files = run_scene(spec, quiet(""), {&with_files_calls});
  fs::remove_all(folder);
  RunOptions o = quiet("");
  o.write_files = false;
  const RunSummary without_files = run_scene(spec, o, {&without_files_calls});
  CHECK_FALSE(fs::exists(folder));  // not even the folder
  CHECK(without_files.out_dir.empty());
  CHECK(with_files.out_dir == folder);
  REQUIRE(with_files.status == "completed");
  check_same_outcome(with_files, without_files);
  // The final states and peaks are those summary.json holds.
  REQUIRE(without_files.section_peaks.size() == 1);
  CHECK(without_files.section_peaks[0].section == "office_chair:column:0#0");
  for (const CallCounter* c : {&with_files_calls, &without_files_calls}) {
    CHECK(c->begins == 1);
    CHECK(c->ends == 1);
    CHECK(c->steps == 300);
    CHECK(c->rows == 31);  // t = 0, 0.01, ..., 0.3 s
    CHECK(c->items_at_end == 2);
  }
}

TEST_CASE("RunOptions::output_interval is a time, rounded to whole steps", "[runner][observers]") {
  const std::string out = fresh_dir("output_interval");
  json j = small_scene_json(out);
  j["outputs"]["figures"] = false;
  j["outputs"]["vtu_every"] = 0;
  const SceneSpec spec = parse_scene_json(j, "output_interval");
  SECTION("0.05 s at dt = 1 ms: a row every 50 steps") {
    RunOptions o = quiet(out);
    o.output_interval = 0.05;
    CallCounter calls;
    REQUIRE(run_scene(spec, o, {&calls}).status == "completed");
    const CsvTable m = read_csv(out + "/markers.csv");
    REQUIRE(m.rows() == 7);
    CHECK(m.column("t")[1] == Approx(0.05).margin(1e-12));
    CHECK(calls.rows == 7);
  }
  SECTION("zero, negative or not a number: an InputError naming it, before the run") {
    for (double bad : {0.0, -0.01, std::numeric_limits<double>::quiet_NaN()}) {
      RunOptions o = quiet(out + "_bad");
      o.output_interval = bad;
      CHECK_THROWS_WITH(run_scene(spec, o), Catch::Contains("output_interval"));
      CHECK_FALSE(fs::exists(out + "_bad"));
    }
  }
}

TEST_CASE("a run that diverges to NaN ends as 'diverged' with its last finite state and the time it diverged",
          "[runner][errors]") {
  // Issue 13: the final states were taken from the diverged (NaN) state and read "overturned, tilt 90,
  // lift 999999999.975 m" (std::min(1e9, NaN) is 1e9). A floor spring of 1e12 N/m against 5 ms steps,
  // applied explicitly, multiplies a node's penetration by about dt^2 k / m = 1e8 per step: the state
  // overflows within some 40 steps (measured before the fix: "overturned, tilt 135 deg, slide 1e154 m",
  // energy imbalance NaN, after 42 steps). The energy check, which would stop it earlier, is off.
  // At the centre lines: at the surfaces the spring is shared by a node's four resting corners and the
  // state grew only to 1e155 J within the second, without overflowing. Without a refresh on frame drift
  // (the scene default 5e-4 refactorises every step here: the state then stays finite, the table
  // thrown 279 km up at 3e5 m/s, which only the energy check, off here, stops).
  const std::string out = fresh_dir("diverged_nan");
  const SceneSpec s = parse_scene_json(json::parse(R"({
    "name": "diverging",
    "items": [{"kind": "side_table", "fidelity": "full"}],
    "ground_motion": {"source": "synthetic", "seed": 3, "pga": 1.0},
    "contact": {"law": "spring_dashpot", "implicit": "none", "floor": {"stiffness": 1e12},
                "plane_contact_at": "centre_lines"},
    "integrator": {"frame_drift_refresh": 0},
    "duration": 1.0,
    "dt": 0.005,
    "allow_coarse_dt": true
  })"),
                                       "diverging.json");
  RunOptions opt = quiet(out);
  opt.energy_creation_limit = 0;
  opt.figures = true;
  const RunSummary sum = run_scene(s, opt);
  INFO(sum.diagnosis);
  REQUIRE(sum.status == "diverged");
  CHECK_THAT(sum.diagnosis, Catch::Contains("non-finite") || Catch::Contains("not finite"));
  // The run ends at its last finite step; the step after it diverged.
  CHECK(sum.t_end < s.duration);
  CHECK(sum.steps == std::lround(sum.t_end / s.dt));
  REQUIRE(sum.t_diverged);
  CHECK(*sum.t_diverged == Approx(sum.t_end + s.dt).margin(1e-12));
  REQUIRE(sum.items.size() == 1);
  const ItemFinalState& it = sum.items[0];
  CHECK(it.state == "diverged");
  CHECK(std::isfinite(it.slide));
  CHECK(std::isfinite(it.tilt_deg));
  CHECK(std::isfinite(it.max_tilt_deg));
  CHECK(std::isfinite(it.lift));
  CHECK(it.lift != Approx(1e9).epsilon(1e-6));
  CHECK(it.cog_displacement.allFinite());
  CHECK(std::isfinite(sum.energy_imbalance));
  // The files say the same, with numbers (nlohmann::json writes NaN as null).
  const json fin = read_json(out + "/final_state.json");
  CHECK(fin.at(0).at("state") == "diverged");
  for (const char* key : {"slide_m", "tilt_deg", "max_tilt_deg", "lift_m"}) CHECK(fin.at(0).at(key).is_number());
  const json summary = read_json(out + "/summary.json");
  CHECK(summary.at("status") == "diverged");
  CHECK(summary.at("t_end_s").get<double>() == sum.t_end);
  CHECK(summary.at("t_diverged_s").get<double>() == *sum.t_diverged);
  CHECK(summary.at("energy_imbalance_relative").is_number());
  CHECK(fs::exists(out + "/room_final.png"));
  CHECK(read_json(out + "/run.json").at("status") == "diverged");
  CHECK(read_json(out + "/run.json").at("diagnosis") == sum.diagnosis);
}

TEST_CASE("a completed run has no divergence time", "[runner][errors]") {
  const std::string out = fresh_dir("not_diverged");
  SceneSpec s = parse_scene_json(small_scene_json(out), "small.json");
  s.duration = 0.02;
  const RunSummary sum = run_scene(s, quiet(out));
  REQUIRE(sum.status == "completed");
  CHECK_FALSE(sum.t_diverged);
  CHECK(read_json(out + "/summary.json").at("t_diverged_s").is_null());
  for (const auto& it : sum.items) CHECK(it.state != "diverged");
}

namespace {
// A UV sphere of radius r as an OBJ file: rings x segments vertices (two triangles per quad).
void write_sphere_obj(const std::string& path, double r, int rings, int segments) {
  std::ofstream f(path);
  f.precision(17);
  for (int i = 0; i < rings; ++i) {
    const double th = std::numbers::pi * (i + 0.5) / rings;
    for (int j = 0; j < segments; ++j) {
      const double ph = 2 * std::numbers::pi * j / segments;
      f << "v " << r * std::sin(th) * std::cos(ph) << ' ' << r * std::sin(th) * std::sin(ph) << ' '
        << r * (1 + std::cos(th)) << '\n';
    }
  }
  for (int i = 0; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const int a = i * segments + j + 1, b = i * segments + (j + 1) % segments + 1;
      f << "f " << a << ' ' << b << ' ' << b + segments << "\nf " << a << ' ' << b + segments << ' ' << a + segments << '\n';
    }
}
}  // namespace

TEST_CASE("a large mesh obstacle far from every item costs little of the steps", "[runner][obstacles]") {
  // Issue 13: every node of every step searched the closest point of a 20 000-vertex obstacle: 50 steps
  // took 5 to 23 s. Here the side table and the chair (264 nodes) and a 20 022-vertex sphere 1 m from
  // both, 50 steps. Before the fix a closest-point search per node and evaluation (about 17 us each)
  // made the obstacle most of the steps' time; after it, a box test of a few ns per node. Measured:
  // 0.255 s of 0.265 s before (0.015 s without the obstacle), 65 us of 10 ms after (the same as without
  // it). Bound: 10 %, both timed in the same run (a loaded machine slows both).
  const std::string dir = fresh_dir("far_obstacle");
  fs::create_directories(dir);
  write_sphere_obj(dir + "/sphere.obj", 0.25, 141, 142);
  json j = json::parse(R"({
    "name": "far obstacle",
    "items": [{"kind": "side_table", "x": -0.8, "y": -0.8, "fidelity": "full"},
              {"kind": "office_chair", "x": 0.6, "y": -0.9}],
    "ground_motion": {"source": "synthetic", "seed": 3, "pga": 6.0, "dimensions": "3d"},
    "duration": 0.05,
    "dt": 0.001
  })");
  const auto run = [&](const json& scene) {
    SceneSpec s = parse_scene_json(scene, dir + "/scene.json");
    s.base_dir = dir;
    validate(s);
    SceneSimulation<DirectLdltSolver> sim(s, 0, 1);
    for (int k = 0; k < 50; ++k) sim.sim->step();
    std::vector<Vec3> x;
    for (int n = 0; n < sim.model->num_nodes(); ++n) x.push_back(sim.sim->position(n));
    return std::tuple{sim.sim->contact_model().timings(), sim.sim->timings().total, x};
  };
  const auto [none, steps_none, x_none] = run(j);
  j["obstacles"] = json::array({{{"file", "sphere.obj"}, {"position", {1.5, 1.5, 0.0}}}});
  const auto [with, steps_with, x_with] = run(j);
  INFO("50 steps: obstacle " << with.obstacles << " s of " << steps_with << " s (" << steps_none
                             << " s without the obstacle)");
  CHECK(none.obstacles == 0);
  CHECK(with.obstacles < 0.1 * steps_with);
  // Far from every item, the obstacle changes nothing.
  CHECK(x_with == x_none);
}

namespace {

// The small scene, 20 steps, no figures: quick.
SceneSpec quick_scene(const std::string& out) {
  json j = small_scene_json(out);
  j["duration"] = 0.02;
  j["outputs"]["figures"] = false;
  j["outputs"]["vtu_every"] = 10;
  return parse_scene_json(j, "quick.json");
}

void touch(const std::string& path, const std::string& text = "x") {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path) << text;
}

}  // namespace

TEST_CASE("results_file names the files a run writes, and no other", "[runner][results_folder]") {
  for (const char* f : {"run.json", "run.json.tmp", "summary.json", "final_state.json", "markers.csv", "energy.csv",
                        "sectional_forces.csv", "contact_forces.csv", "room.pvd", "room.pvd.tmp", "room_final.png",
                        "marker_desk.top.png", "shear_0.png", "vtu/room_0.vtu", "vtu/room_120.vtu.tmp"}) {
    INFO(f);
    CHECK(results_file(f));
  }
  for (const char* f : {"notes.txt", "scene.json", "markers.csv.bak", "my.png", "vtu/mine.vtu", "vtu/x/room_1.vtu",
                        "sub/marker_a.png", "sub/run.json", "run.json.old", "vtu"}) {
    INFO(f);
    CHECK_FALSE(results_file(f));
  }
  const std::regex iso(R"(\d{4}-\d{2}-\d{2}T\d{2}:\d{2}:\d{2}\.\d{3}Z)");
  CHECK(std::regex_match(iso8601_utc(std::chrono::system_clock::now()), iso));
  CHECK(iso8601_utc(std::chrono::system_clock::time_point{}) == "1970-01-01T00:00:00.000Z");
  CHECK(iso8601_utc(std::chrono::system_clock::time_point{std::chrono::milliseconds(1764117222123)}) ==
        "2025-11-26T00:33:42.123Z");
}

TEST_CASE("a run refuses a non-empty folder it did not write unless overwrite, and removes only its own old results",
          "[runner][results_folder]") {
  const std::string out = fresh_dir("policy");
  const SceneSpec spec = quick_scene(out);
  touch(out + "/notes.txt", "mine");
  touch(out + "/vtu/mine.vtu", "mine");
  touch(out + "/marker_old.png", "stale");
  touch(out + "/vtu/room_99999.vtu", "stale");

  // Refused, with the folder named and the way out; nothing on disk changed.
  CHECK_THROWS_AS(run_scene(spec, quiet(out)), InputError);
  CHECK_THROWS_WITH(run_scene(spec, quiet(out)), Catch::Contains("results folder '" + out + "'") &&
                                                     Catch::Contains("not written by furniture_fem") &&
                                                     Catch::Contains("--overwrite"));
  CHECK(fs::exists(out + "/marker_old.png"));
  CHECK_FALSE(fs::exists(out + "/run.json"));
  CHECK_FALSE(fs::exists(out + "/summary.json"));
  // A run that writes no files does not look at the folder.
  RunOptions none = quiet(out);
  none.write_files = false;
  CHECK(run_scene(spec, none).status == "completed");

  // --overwrite in a folder no run wrote: files named as outputs are the user's too (no run.json says a
  // run wrote them), so it refuses, naming them, and removes nothing (until 2026-11-26 it removed them).
  RunOptions o = quiet(out);
  o.overwrite = true;
  CHECK_THROWS_WITH(run_scene(spec, o), Catch::Contains("results folder '" + out + "'") &&
                                            Catch::Contains("marker_old.png, vtu/room_99999.vtu") &&
                                            Catch::Contains("move those files"));
  CHECK(fs::exists(out + "/marker_old.png"));
  CHECK(fs::exists(out + "/vtu/room_99999.vtu"));
  CHECK_FALSE(fs::exists(out + "/run.json"));
  // Without them, it writes beside the user's other files.
  fs::remove(out + "/marker_old.png");
  fs::remove(out + "/vtu/room_99999.vtu");
  REQUIRE(run_scene(spec, o).status == "completed");
  CHECK(fs::exists(out + "/notes.txt"));
  CHECK(fs::exists(out + "/vtu/mine.vtu"));
  CHECK(read_json(out + "/run.json").at("options").at("overwrite") == true);
  check_outputs(out, spec, false);

  // Now the folder is one a run wrote: the next run needs no overwrite, and clears what the last one left.
  touch(out + "/shear_7.png", "stale");
  touch(out + "/vtu/room_88888.vtu", "stale");
  REQUIRE(run_scene(spec, quiet(out)).status == "completed");
  CHECK_FALSE(fs::exists(out + "/shear_7.png"));
  CHECK_FALSE(fs::exists(out + "/vtu/room_88888.vtu"));
  CHECK(fs::exists(out + "/notes.txt"));
  CHECK(fs::exists(out + "/vtu/mine.vtu"));
  const json record = read_json(out + "/run.json");
  for (const auto& f : record.at("files")) CHECK(results_file(f.get<std::string>()));
  CHECK(record.at("files").back() == "run.json");

  // A run.json saying "running" (a run still writing, or one killed): refused unless overwrite.
  json running = record;
  running["status"] = "running";
  write_json(out + "/run.json", running);
  CHECK_THROWS_WITH(run_scene(spec, quiet(out)), Catch::Contains("still writing") && Catch::Contains("--overwrite"));
  REQUIRE(run_scene(spec, o).status == "completed");
  CHECK(read_json(out + "/run.json").at("status") == "done");

  // A file where the folder should be.
  CHECK_THROWS_WITH(run_scene(spec, quiet(out + "/notes.txt")), Catch::Contains("is not a folder"));
  // An empty folder, and a folder written before run.json existed (its summary.json names the version).
  const std::string empty = fresh_dir("policy_empty");
  fs::create_directories(empty);
  CHECK(run_scene(spec, quiet(empty)).status == "completed");
  const std::string legacy = fresh_dir("policy_legacy");
  touch(legacy + "/summary.json", R"({"furniture_fem_version": "0.1.0"})");
  touch(legacy + "/room_final.png", "stale");
  REQUIRE(run_scene(spec, quiet(legacy)).status == "completed");
  CHECK_FALSE(fs::exists(legacy + "/room_final.png"));
}

TEST_CASE("run.json is written first (running) and last (done, failed), atomically", "[runner][results_folder]") {
  const std::string out = fresh_dir("record");
  const SceneSpec spec = quick_scene(out);
  // What the first observer sees at the start, and after the first step.
  struct Peek : RunObserver {
    json at_begin, at_step;
    void begin(const RunView& run) override { at_begin = read_json(run.out_dir + "/run.json"); }
    void after_step(const RunView& run, const StepInfo&) override {
      if (run.sim.steps() == 1) at_step = read_json(run.out_dir + "/run.json");
    }
  } peek;
  RunOptions o = quiet(out);
  o.git_hash = "0123456789abcdef";
  const auto before = std::chrono::system_clock::now();
  const RunSummary s = run_scene(spec, o, {&peek});
  REQUIRE(s.status == "completed");
  const std::regex iso(R"(\d{4}-\d{2}-\d{2}T\d{2}:\d{2}:\d{2}\.\d{3}Z)");
  for (const json* j : {&peek.at_begin, &peek.at_step}) {
    CHECK(j->at("status") == "running");
    CHECK(j->at("end_utc").is_null());
    CHECK(j->at("wall_seconds").is_null());
    CHECK(std::regex_match(j->at("start_utc").get<std::string>(), iso));
    CHECK(j->at("scene") == to_json(spec));
  }
  const json r = read_json(out + "/run.json");
  CHECK(r.at("program") == "furniture_fem");
  CHECK(r.at("furniture_fem_version") == version_string);
  CHECK(r.at("git_hash") == "0123456789abcdef");
  CHECK(r.at("status") == "done");
  CHECK(r.at("summary_status") == "completed");
  CHECK(r.at("start_utc") == peek.at_begin.at("start_utc"));
  CHECK(r.at("start_utc").get<std::string>() >= iso8601_utc(before - std::chrono::milliseconds(1)));
  CHECK(std::regex_match(r.at("end_utc").get<std::string>(), iso));
  CHECK(r.at("end_utc").get<std::string>() >= r.at("start_utc").get<std::string>());
  CHECK(r.at("wall_seconds").get<double>() >= s.wall_seconds);
  CHECK(r.at("out_dir") == out);
  // The scene as run: the same as summary.json's, and it reads back as the same scene.
  CHECK(r.at("scene") == read_json(out + "/summary.json").at("scene"));
  CHECK(to_json(parse_scene_json(r.at("scene"), "run.json")) == r.at("scene"));
  const std::set<std::string> files = r.at("files").get<std::set<std::string>>();
  for (const char* f : {"run.json", "summary.json", "final_state.json", "markers.csv", "contact_forces.csv", "room.pvd",
                        "vtu/room_0.vtu", "vtu/room_20.vtu"}) {
    INFO(f);
    CHECK(files.count(f) == 1);
  }
  CHECK_FALSE(fs::exists(out + "/run.json.tmp"));

  // An exception leaving the run: run.json says "failed" and why, and the exception reaches the caller.
  struct Thrower : RunObserver {
    void after_step(const RunView& run, const StepInfo&) override {
      if (run.sim.steps() == 5) throw std::runtime_error("observer gave up");
    }
  } thrower;
  CHECK_THROWS_WITH(run_scene(spec, quiet(out), {&thrower}), "observer gave up");
  const json failed = read_json(out + "/run.json");
  CHECK(failed.at("status") == "failed");
  CHECK(failed.at("error") == "observer gave up");
  CHECK(failed.at("end_utc").is_string());
}

TEST_CASE("input_motion.csv: the table's acceleration, and its velocity and displacement integrated from rest",
          "[runner][input_motion]") {
  // X: a triangular pulse, 0 -> 2 m/s^2 at 0.1 s -> 0 at 0.2 s; Y: 1 m/s^2 from 0 to 1 s. Integrated:
  // vx = 10 t^2, dx = 10 t^3 / 3 up to 0.1 s, ... 0.2 m/s and 0.02 m + 0.2 (t - 0.2) after 0.2 s;
  // vy = t, dy = t^2 / 2.
  const std::string out = fresh_dir("input_motion");
  const SceneSpec spec = parse_scene_json(json::parse(R"({
    "name": "known input",
    "items": [{"kind": "side_table"}],
    "ground_motion": {"source": "points", "x": [[0, 0], [0.1, 2.0], [0.2, 0]], "y": [[0, 1.0], [1.0, 1.0]]},
    "duration": 0.3,
    "outputs": {"figures": true, "markers": ["side_table.top_centre"]}
  })"),
                                          "known.json");
  const RunSummary s = run_scene(spec, quiet(out));
  REQUIRE(s.status == "completed");
  const CsvTable m = read_csv(out + "/input_motion.csv");
  REQUIRE(m.rows() == 31);
  const auto exact = [](double t) {
    std::array<double, 6> r{};  // ax, vx, dx, ay, vy, dy
    if (t <= 0.1) r = {20 * t, 10 * t * t, 10 * t * t * t / 3, 0, 0, 0};
    else if (t <= 0.2) {
      const double u = t - 0.1;
      r = {2 - 20 * u, 0.1 + 2 * u - 10 * u * u, 1.0 / 300 + 0.1 * u + u * u - 10 * u * u * u / 3, 0, 0, 0};
    } else r = {0, 0.2, 0.02 + 0.2 * (t - 0.2), 0, 0, 0};
    r[3] = 1, r[4] = t, r[5] = t * t / 2;
    return r;
  };
  for (std::size_t i = 0; i < m.rows(); ++i) {
    const double t = m.column("t")[i];
    const auto e = exact(t);
    INFO("t = " << t);
    CHECK(m.column("ax")[i] == Approx(e[0]).margin(1e-9));
    CHECK(m.column("vx")[i] == Approx(e[1]).margin(1e-9));
    CHECK(m.column("dx")[i] == Approx(e[2]).margin(1e-9));
    if (t > 0) CHECK(m.column("ay")[i] == Approx(e[3]).margin(1e-12));  // at t = 0 the point itself
    CHECK(m.column("vy")[i] == Approx(e[4]).margin(1e-9));
    CHECK(m.column("dy")[i] == Approx(e[5]).margin(1e-9));
    CHECK(m.column("az")[i] == 0.0);
    CHECK(m.column("dz")[i] == 0.0);
  }
  check_png(out + "/input_motion.png", 1000, 900);

  // markers.csv: absolute accelerations beside the displacements, each the mean since the previous row,
  // so that from rest the absolute velocity at a row is the sum of a * (row interval) over the rows
  // before, and integrating that velocity (trapezoids between rows) gives back the absolute
  // displacement, the relative one plus the floor's. Under this pulse the table slides (its top moves
  // 2 cm against the floor by 0.3 s) and rocks as it settles on the penalty springs (its top's absolute
  // Z acceleration swings between -1 and +3.7 m/s^2 in the first 0.06 s).
  const CsvTable mk = read_csv(out + "/markers.csv");
  const std::string top = "side_table.top_centre";
  for (const char* c : {"_x", "_y", "_z", "_ax", "_ay", "_az"}) REQUIRE(mk.has(top + c));
  const auto& t = mk.column("t");
  const char* axis[3] = {"x", "y", "z"};
  for (int c = 0; c < 3; ++c) {
    const auto& a = mk.column(top + "_a" + axis[c]);
    const auto& d = mk.column(top + "_" + axis[c]);
    const auto& floor_d = m.column(std::string("d") + axis[c]);
    double v = 0, D = 0, worst = 0;  // absolute velocity and displacement rebuilt from the accelerations
    for (std::size_t i = 1; i < mk.rows(); ++i) {
      const double h = t[i] - t[i - 1], v_next = v + a[i] * h;
      D += 0.5 * h * (v + v_next);
      v = v_next;
      worst = std::max(worst, std::abs(D - (d[i] + floor_d[i])));
    }
    // Measured: 3e-5, 1.3e-4 and 8.2e-4 m (Z: the settling's chatter within a row interval, which the
    // trapezoids between rows do not follow), against displacements of 20, 18 and 6 mm.
    INFO("axis " << axis[c] << ": absolute displacement rebuilt from the accelerations, worst error " << worst << " m");
    CHECK(worst < (c == 2 ? 1.5e-3 : 3e-4));
  }
  CHECK(std::abs(mk.column(top + "_x").back()) > 0.01);  // it slid: the check above is not the floor's alone
}

TEST_CASE("the energy ledger's verdict: closes within the tolerance, or says by how much and which term moved",
          "[runner][energy]") {
  const std::string out = fresh_dir("verdict");
  SceneSpec spec = quick_scene(out);
  spec.duration = 0.1;
  RunOptions o = quiet(out);
  const RunSummary s = run_scene(spec, o);
  REQUIRE(s.status == "completed");
  const EnergyVerdict& v = s.energy;
  CHECK(v.tolerance == 0.05);
  CHECK(v.relative == Approx(v.imbalance / v.scale));
  CHECK(std::abs(v.relative) == Approx(s.energy_imbalance).epsilon(1e-12));
  CHECK(v.closes == (std::abs(v.relative) <= 0.05));
  CHECK_THAT(v.text, Catch::StartsWith(v.closes ? "the energy ledger closes" : "the energy ledger does not close"));
  const json j = read_json(out + "/summary.json").at("energy_verdict");
  CHECK(j.at("closes") == v.closes);
  CHECK(j.at("text") == v.text);
  CHECK(j.at("imbalance_relative").get<double>() == v.relative);
  // The largest step of the imbalance lies between two history rows, and names the term that moved most.
  CHECK(v.t_to - v.t_from == Approx(0.01).margin(1e-9));
  CHECK(std::set<std::string>{"kinetic", "strain", "gravity_potential", "external_work", "contact_work",
                              "damping_work", "plastic_work"}
            .count(v.term) == 1);
  const CsvTable energy = read_csv(out + "/energy.csv");
  double largest = 0;
  for (std::size_t i = 1; i < energy.rows(); ++i)
    largest = std::max(largest, std::abs(energy.column("imbalance")[i] - energy.column("imbalance")[i - 1]));
  CHECK(std::abs(v.imbalance_step) == Approx(largest).epsilon(1e-6));

  // A tolerance no run meets: the verdict says it does not close, how much, when, and the term.
  o.energy_tolerance = 1e-15;
  const RunSummary strict = run_scene(spec, o);
  CHECK_FALSE(strict.energy.closes);
  CHECK_THAT(strict.energy.text, Catch::StartsWith("the energy ledger does not close") &&
                                     Catch::Contains("changed most between t = ") && Catch::Contains(strict.energy.term));
}


TEST_CASE("a dt beyond twice the explicit contact's stable step is refused unless the scene asks for it",
          "[runner][dt]") {
  // Issue 51: dt = 1 s over a 10 s run took 10 steps and reported a slide, without a word.
  SceneSpec s;
  s.source = "coarse.json";
  s.dt = 0.01;
  ContactStepEstimate est;
  est.dt = 2e-3;
  est.item = "locker";
  est.stiffness_key = "the penalty alpha_kgf";
  try {
    check_contact_step(s, est);
    FAIL("dt = 5 times the estimate was accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "dt");
    CHECK_THAT(std::string(e.what()),
               Catch::StartsWith("coarse.json: dt: 0.01 s is 5 times the explicit contact's stable step, estimated at "
                                 "0.002 s for item 'locker'") &&
                   Catch::Contains("more than 2 times it, the contact cannot resolve the item's rocking or impacts; "
                                   "reduce dt or the penalty alpha_kgf, or set allow_coarse_dt: true"));
  }
  s.dt = contact_step_error_factor * est.dt;  // at the factor: runs (the energy diagnoses name the estimate)
  CHECK_NOTHROW(check_contact_step(s, est));
  s.dt = 0.01;
  s.allow_coarse_dt = true;  // asked for
  CHECK_NOTHROW(check_contact_step(s, est));
  s.allow_coarse_dt = false;
  CHECK_NOTHROW(check_contact_step(s, ContactStepEstimate{}));  // contact inside the implicit step: no limit
  CHECK(contact_step_error_factor == 2.0);
}

TEST_CASE("allow_coarse_dt is read, and written only when set", "[runner][dt]") {
  const json base = {{"name", "coarse"}, {"items", {{{"kind", "block"}, {"fidelity", "rigid"}, {"params", {{"mass_kg", 10.0}}}}}}};
  const SceneSpec unset = parse_scene_json(base, "coarse.json");
  CHECK_FALSE(unset.allow_coarse_dt);
  CHECK_FALSE(to_json(unset).contains("allow_coarse_dt"));  // older scene.json files (and fingerprints) unchanged
  json asked = base;
  asked["allow_coarse_dt"] = true;
  const SceneSpec set = parse_scene_json(asked, "coarse.json");
  CHECK(set.allow_coarse_dt);
  CHECK(to_json(set).at("allow_coarse_dt") == true);
  CHECK(parse_scene_json(to_json(set), "again.json").allow_coarse_dt);
  json wrong = base;
  wrong["allow_coarse_dt"] = "yes";
  CHECK_THROWS_WITH(parse_scene_json(wrong, "coarse.json"), Catch::Contains("allow_coarse_dt"));
}

TEST_CASE("an obstacle passing through an item at t = 0 is refused, naming both", "[runner][obstacles]") {
  // Issue 51: a mesh through an item's members ran, the penalty pushing them apart with energy from
  // nowhere (the ledger 6.7 % off, exit 0). A plate in the plane x = x0 crosses the block's edge tubes
  // (10 mm wide: contact 5 mm from their centre lines) that run along x.
  const std::string dir = fresh_dir("obstacle_through_item");
  fs::create_directories(dir);
  {
    std::ofstream obj(dir + "/plate.obj");
    obj << "v 0 -1 -0.5\nv 0 1 -0.5\nv 0 1 1\nv 0 -1 1\nf 1 2 3\nf 1 3 4\n";
  }
  const auto scene = [&](double plate_x) {
    const json j = {{"name", "plate"},
                    {"items", {{{"kind", "block"}, {"name", "left"}, {"fidelity", "rigid"}, {"x", -1.0}, {"params", {{"mass_kg", 10.0}}}},
                               {{"kind", "block"}, {"name", "crate"}, {"fidelity", "rigid"}, {"x", 0.5}, {"params", {{"mass_kg", 10.0}}}}}},
                    {"obstacles", {{{"file", "plate.obj"}, {"position", {plate_x, 0.0, 0.0}}}}},
                    {"duration", 0.01}};
    return parse_scene(write_json(dir + "/plate.json", j));
  };
  const SceneSpec through = scene(0.55);
  Model model;
  const std::vector<ItemInfo> items = build_scene(through, model);
  const MeshObstacle plate = detail::scene_obstacle(through, 0);
  const detail::ObstacleIntrusion in = detail::obstacle_intrusion(model, items.at(1), plate);
  CHECK(in.depth == Approx(0.005));  // the plate cuts a centre line: the tube's half width
  CHECK(in.point.x() == Approx(0.55));
  CHECK(detail::obstacle_intrusion(model, items.at(0), plate).depth <= 0);
  try {
    check_scene_model(through);
    FAIL("an obstacle through an item was accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "obstacles[0]");
    CHECK_THAT(std::string(e.what()),
               Catch::Contains("obstacles[0]: obstacle \"" + through.resolve("plate.obj") +
                               "\" passes through item 'crate' (items[1]) at t = 0: 0.005 m into its member '") &&
                   Catch::Contains("move the obstacle or the item"));
  }
  CHECK_THROWS_WITH(run_scene(through, quiet(dir + "/out")), Catch::Contains("passes through item 'crate'"));
  // 50 mm clear of the 0.4 m block's side: runs.
  CHECK_NOTHROW(check_scene_model(scene(0.5 + 0.25)));
}

TEST_CASE("a wall time is said in the unit that reads best", "[runner][forecast]") {
  CHECK(detail::wall_time_text(0.4) == "0.4 s");
  CHECK(detail::wall_time_text(45) == "45 s");
  CHECK(detail::wall_time_text(150) == "2.5 min");
  CHECK(detail::wall_time_text(9000) == "2.5 h");
  CHECK(detail::wall_time_text(3 * 86400) == "3.0 days");
}

}  // namespace run_scene_tests
