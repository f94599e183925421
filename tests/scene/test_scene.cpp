// Scenes: the paper's configurations (element and node counts against the paper), JSON round trips,
// and the errors a broken scene file must give (key path and offending value in the message).
#include <catch2/catch.hpp>

#include <furniture_fem/scene/scene.hpp>

#include "../support/input_errors.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>

using namespace furniture_fem;
using nlohmann::json;

namespace scene_tests {  // this file's own names (its group compiles files in batches)

namespace {

const std::filesystem::path source_dir = std::filesystem::path(__FILE__).parent_path();

std::string tmp_file(const std::string& name) {
  std::filesystem::create_directories(FFEM_TEST_TMP);
  return (std::filesystem::path(FFEM_TEST_TMP) / name).string();
}

// No test reads ../shared (a user's machine never has it). The JMA-Kobe files the paper's
// configurations and the docs' example name (and the Hachinohe file of an example) are written here, under the same names, as short valid
// AT2 records: validate() checks that a scene's record files exist, and the readers themselves are
// tested in tests/excitation. Layout: <root>/shared/ground_motions/, so that a scene whose base folder
// is <root>/repo/examples/scenes finds "../../../shared/ground_motions/..." as in the repository.
const std::filesystem::path& records_root() {
  static const std::filesystem::path root = [] {
    const std::filesystem::path r = std::filesystem::path(FFEM_TEST_TMP) / "scene_records";
    const std::filesystem::path dir = r / "shared" / "ground_motions";
    std::filesystem::create_directories(dir);
    for (const char* name : {"jma_kobe_1995_NS_PEER_RSN1106_KJM000.AT2", "jma_kobe_1995_EW_PEER_RSN1106_KJM090.AT2",
                             "jma_kobe_1995_UD_PEER_RSN1106_KJM-UP.AT2"}) {
      std::ofstream f(dir / name);
      f << "PEER NGA STRONG MOTION DATABASE RECORD (stand-in written by tests/scene)\n"
           "KOBE 1/16/95, KJMA, stand-in\n"
           "ACCELERATION TIME SERIES IN UNITS OF G\n"
           "NPTS=    10, DT=   .0100 SEC\n"
           "  .1000000E-01  .2000000E-01  .1000000E-01  .0000000E+00 -.1000000E-01\n"
           " -.2000000E-01 -.1000000E-01  .0000000E+00  .1000000E-01  .0000000E+00\n";
    }
    // Hachinohe 1968 NS (examples/scenes/configuration3_storey20_hachinohe.json): two columns, s and gal.
    std::ofstream(dir / "hachinohe_1968_NS_gal_dt0.01.txt") << "0.01 1.0\n0.02 -2.0\n0.03 1.5\n0.04 0.0\n";
    return r;
  }();
  return root;
}
std::string records_dir() { return (records_root() / "shared" / "ground_motions").string(); }

// A small valid scene as JSON, to be broken one key at a time.
json small_scene() {
  return json::parse(R"({
    "name": "small",
    "items": [
      {"kind": "tall_cabinet", "x": 1.77, "y": -0.5, "yaw_deg": -90},
      {"kind": "desk", "x": 0.6, "y": 0.0, "yaw_deg": -90},
      {"kind": "office_chair", "x": -0.82, "y": 0.0, "yaw_deg": 90}
    ],
    "ground_motion": {"source": "synthetic", "seed": 7, "pga": 2.5, "duration": 5},
    "duration": 5,
    "dt": 0.001,
    "outputs": {"markers": ["desk.top_front_centre"]}
  })");
}

using ffem_test::input_error;  // "no error" when nothing is thrown: the message checks then fail

// Broken scenes go through a file, as a user's would.
std::string write_broken(const json& j) {
  const std::string path = tmp_file("broken.json");
  std::ofstream(path) << j.dump(2);
  return path;
}
std::string parse_error(const json& j) { return input_error([&] { parse_scene(write_broken(j)); }); }
std::string validate_error(const json& j) {
  return input_error([&] { validate(parse_scene(write_broken(j))); });
}

using Catch::Matchers::Contains;

}  // namespace

TEST_CASE("configurations 1-3 come within 15 % of the paper's element and node counts", "[scene][counts]") {
  struct Paper {
    int k, elements, nodes;
  };
  for (const Paper p : {Paper{1, 5056, 3804}, Paper{2, 1005, 788}, Paper{3, 6041, 4574}}) {
    const SceneSpec scene = configuration(p.k, records_dir());
    Model model;
    const auto items = build_scene(scene, model);
    REQUIRE_NOTHROW(model.validate());
    const double de = double(model.num_elements()) / p.elements - 1, dn = double(model.num_nodes()) / p.nodes - 1;
    INFO("configuration " << p.k << ": " << model.num_elements() << " elements (paper " << p.elements << ", "
                          << 100 * de << " %), " << model.num_nodes() << " nodes (paper " << p.nodes << ", "
                          << 100 * dn << " %)");
    CHECK(std::abs(de) <= 0.15);
    CHECK(std::abs(dn) <= 0.15);
    CHECK(static_cast<int>(items.size()) == model.num_bodies());
  }
}

TEST_CASE("the paper's configurations are valid and placed as documented", "[scene][configuration]") {
  for (int k = 1; k <= 3; ++k) REQUIRE_NOTHROW(validate(configuration(k, records_dir())));
  const SceneSpec scene = configuration(3, records_dir());
  Model model;
  const auto items = build_scene(scene, model);
  REQUIRE(items.size() == 6);
  CHECK(items[0].name == "tall_cabinet");
  CHECK(items[1].name == "separated_cabinets/lower");
  CHECK(items[2].name == "separated_cabinets/upper");
  // Cabinet backs 30 mm from the wall at x = +2: outer back face at 1.97 m.
  double back = -1e9;
  for (int n : model.body(items[0].body).nodes) back = std::max(back, model.node(n).X.x());
  CHECK(back + 0.025 == Approx(1.97).margin(1e-9));
  // Every body stays on the table.
  for (int n = 0; n < model.num_nodes(); ++n) {
    CHECK(std::abs(model.node(n).X.x()) < 2.0);
    CHECK(std::abs(model.node(n).X.y()) < 2.0);
  }
  // The requested outputs exist on the built items.
  CHECK(scene.outputs.markers.size() == 3);
  REQUIRE(scene.outputs.sectional_forces.size() == 1);
  CHECK(scene.outputs.sectional_forces[0].item == "desk");
  CHECK(scene.ground_motion.file_x.find("KJM000.AT2") != std::string::npos);
  CHECK_THROWS_AS(configuration(4), InputError);
}

TEST_CASE("a scene file round-trips exactly", "[scene][json]") {
  SECTION("configuration 3") {
    const SceneSpec scene = configuration(3, records_dir());
    const std::string path = tmp_file("configuration3.json");
    write_scene(scene, path);
    const SceneSpec back = parse_scene(path);
    CHECK(to_json(back) == to_json(scene));
    CHECK(back.base_dir == std::filesystem::path(path).parent_path().string());
  }
  SECTION("every optional part set") {
    json j = small_scene();
    j["table"] = {{"size_x", 5.0}, {"size_y", 4.5}, {"floor_z", 0.1}};
    j["walls"] = json::array({{{"name", "north"}, {"point", {0, 2.25, 0.1}}, {"normal", {0, -2, 0}}, {"height", 2.7},
                               {"width", 5}}});
    j["obstacles"] = json::array({{{"name", "pillar"}, {"file", "pillar.stl"}, {"position", {-2, -2, 0}},
                                   {"yaw_deg", 15}, {"scale", 0.001}}});
    j["items"].push_back({{"kind", "bookshelf"}, {"name", "shelf"}, {"x", -1.8}, {"y", 1.5}, {"yaw_deg", 0},
                          {"fidelity", "coarse"},
                          {"params", {{"width", 0.8}, {"depth", 0.3}, {"height", 1.8}, {"shelves", 3},
                                      {"mass_kg", 28}, {"cog_h", 0.8}, {"mu_static_long", 0.3}, {"alpha_kgf", 30}}}});
    j["items"].push_back({{"kind", "table"}, {"x", -1.0}, {"y", -1.5}, {"fidelity", "auto"}});
    j["contact"] = {{"law", "stick_slip"},
                    {"velocity_regularisation", 0.002},
                    {"floor", {{"mu_long", 0.3}, {"stiffness", 2e5}, {"damping", 40}}},
                    {"item", {{"alpha_kgf", 20}, {"q", 1.5}}}};
    j["integrator"] = {{"scheme", "generalized_alpha"}, {"rho_inf", 0.8}, {"iterate_to_equilibrium", true}};
    j["solver"] = "direct";
    j["refresh_every"] = 0.02;
    j["outputs"] = {{"folder", "results/x"},
                    {"markers", {"desk.top_front_centre", {{"name", "corner"}, {"item", "shelf"}, {"point", {0.4, -0.15, 1.8}}},
                                 {{"name", "seat"}, {"item", "office_chair"}, {"marker", "seat_centre"}}}},
                    {"sectional_forces", {{{"item", "desk"}, {"member", "top/x0:5"}, {"element", 1}}}},
                    {"vtu_every", 50},
                    {"figures", false}};
    const SceneSpec scene = parse_scene_json(j, "full.json");
    CHECK(scene.walls[0].normal == Vec3(0, -2, 0));  // kept as written (normalised where used)
    CHECK(scene.items[4].name == "table");           // unnamed items take their kind's name
    CHECK(scene.refresh_interval_steps() == 20);  // 0.02 s at the default dt of 1 ms
    SceneSpec coarse_steps;
    coarse_steps.dt = 0.005;
    CHECK(coarse_steps.refresh_interval_steps() == 20);  // the default 0.1 s
    coarse_steps.refresh_every = 1e-4;
    CHECK(coarse_steps.refresh_interval_steps() == 1);   // never fewer than every step
    const json once = to_json(scene);
    const std::string path = tmp_file("full.json");
    write_scene(scene, path);
    CHECK(to_json(parse_scene(path)) == once);
    CHECK(to_json(parse_scene_json(once, "again")) == once);
  }
  SECTION("file-based 3-D ground motion with units and dt") {
    json j = small_scene();
    j["ground_motion"] = {{"source", "file"}, {"format", "columns"}, {"files", {{"x", "x.txt"}, {"y", "y.txt"}, {"z", "z.txt"}}},
                          {"units", "gal"}, {"dt", 0.01}, {"level", 0.5}, {"dimensions", "3d"}, {"lowpass_hz", 0},
                          {"window", {{"start", 2.0}, {"end", 12.0}}}};
    const SceneSpec scene = parse_scene_json(j, "gm.json");
    CHECK(scene.ground_motion.units == AccelerationUnits::gal);
    CHECK(*scene.ground_motion.window_end == 12.0);
    CHECK(to_json(parse_scene_json(to_json(scene), "again")) == to_json(scene));
  }
}

TEST_CASE("unnamed items of one kind are numbered", "[scene][json]") {
  json j = small_scene();
  j["items"].push_back({{"kind", "desk"}, {"x", -1.0}, {"y", 1.2}});
  const SceneSpec scene = parse_scene_json(j, "two_desks.json");
  CHECK(scene.items[1].name == "desk");
  CHECK(scene.items[3].name == "desk_2");
  CHECK_NOTHROW(validate(scene));
}

TEST_CASE("broken scene files name the key path and the value", "[scene][errors]") {
  json j = small_scene();
  REQUIRE_NOTHROW(validate(parse_scene_json(j, "small.json")));

  SECTION("unknown key at the top level") {
    j["dtt"] = 0.001;
    const std::string msg = parse_error(j);
    CHECK_THAT(msg, Contains("broken.json") && Contains("dtt") && Contains("unknown key"));
  }
  SECTION("unknown key inside an item") {
    j["items"][1]["colour"] = "grey";
    CHECK_THAT(parse_error(j), Contains("items[1].colour"));
  }
  SECTION("wrong type") {
    j["items"][2]["yaw_deg"] = "ninety";
    const std::string msg = parse_error(j);
    CHECK_THAT(msg, Contains("items[2].yaw_deg") && Contains("\"ninety\"") && Contains("expected a number"));
  }
  SECTION("negative dt") {
    j["dt"] = -0.001;
    const std::string msg = parse_error(j);
    CHECK_THAT(msg, Contains("dt") && Contains("-0.001") && Contains("positive"));
  }
  SECTION("refresh interval not positive") {
    j["refresh_every"] = 0;
    CHECK_THAT(parse_error(j), Contains("refresh_every") && Contains("got 0") && Contains("positive"));
    j["refresh_every"] = "often";
    CHECK_THAT(parse_error(j), Contains("refresh_every") && Contains("expected a number"));
  }
  SECTION("dt below the scene's minimum: the reader and validate() give the step length's one message") {
    // step_length_problem (core/step_length.hpp) with the scene's bound, 1e-6 s, under the key dt.
    j["dt"] = 5e-7;
    CHECK_THAT(parse_error(j), Contains("broken.json: dt: must be at least 1e-06 s (got 5e-07)"));
    SceneSpec spec = parse_scene_json(small_scene(), "small.json");
    spec.dt = 5e-7;
    CHECK_THAT(input_error([&] { validate(spec); }), Contains("small.json: dt: must be at least 1e-06 s (got 5e-07)"));
    spec.dt = std::numeric_limits<double>::infinity();
    CHECK_THAT(input_error([&] { validate(spec); }), Contains("small.json: dt: must be finite (got inf)"));
    spec.dt = SceneSpec::min_dt;
    CHECK_NOTHROW(validate(spec));
  }
  SECTION("dt longer than the run") {
    j["dt"] = 10.0;
    CHECK_THAT(parse_error(j), Contains("dt") && Contains("duration"));
  }
  SECTION("negative level") {
    j["ground_motion"]["level"] = -0.5;
    CHECK_THAT(parse_error(j), Contains("ground_motion.level") && Contains("-0.5"));
  }
  SECTION("unknown item kind") {
    j["items"][0]["kind"] = "sofa";
    CHECK_THAT(parse_error(j), Contains("items[0].kind") && Contains("\"sofa\"") && Contains("tall_cabinet"));
  }
  SECTION("unknown contact law") {
    j["contact"] = {{"law", "coulomb"}};
    CHECK_THAT(parse_error(j), Contains("contact.law") && Contains("\"coulomb\""));
  }
  SECTION("a parameter the law does not use") {
    j["contact"] = {{"law", "paper"}, {"wall", {{"stiffness", 5e5}}}};
    CHECK_THAT(parse_error(j), Contains("contact.wall.stiffness") && Contains("paper"));
    j["contact"] = {{"law", "spring_dashpot"}, {"floor", {{"mu_short", 0.2}}}};
    CHECK_THAT(parse_error(j), Contains("contact.floor.mu_short") && Contains("spring_dashpot"));
    j["contact"] = {{"law", "stiff"}, {"floor", {{"stiffness", 5e5}}}};
    CHECK_THAT(parse_error(j), Contains("contact.floor.stiffness") && Contains("stiff"));
    j["contact"] = {{"law", "stick_slip"}, {"stick_length", 1e-4}};
    CHECK_THAT(parse_error(j), Contains("contact.stick_length") && Contains("stick_slip"));
  }
  SECTION("keys no law reads are unknown") {  // they were once read and ignored
    for (const char* key : {"restitution", "mu_static", "stick_velocity"}) {
      j["contact"] = {{"law", "hunt_crossley"}, {"floor", {{key, 0.5}}}};
      CHECK_THAT(parse_error(j), Contains(std::string("contact.floor.") + key));
    }
    j["contact"] = {{"law", "hunt_crossley"}, {"item", {{"q", 1.5}}}};
    CHECK_THAT(parse_error(j), Contains("contact.item.q") && Contains("hunt_crossley"));
  }
  SECTION("stick_length out of range") {
    j["contact"] = {{"law", "paper"}, {"stick_length", -1e-5}};
    CHECK_THAT(parse_error(j), Contains("contact.stick_length") && Contains("[0, 0.01]"));
  }
  SECTION("a parameter the item kind does not take") {
    j["items"][1]["params"] = {{"width", 1.4}};
    CHECK_THAT(parse_error(j), Contains("items[1].params.width") && Contains("desk"));
  }
  SECTION("out-of-range item parameter") {
    j["items"][0]["params"] = {{"grid_scale", -2}};
    CHECK_THAT(parse_error(j), Contains("items[0].params.grid_scale") && Contains("-2"));
  }
  SECTION("keys of the other ground-motion source") {
    j["ground_motion"]["format"] = "at2";
    CHECK_THAT(parse_error(j), Contains("ground_motion.format") && Contains("\"file\""));
  }
  SECTION("a 3-D motion without its y record") {
    j["ground_motion"] = {{"source", "file"}, {"dimensions", "3d"}, {"files", {{"x", "x.at2"}, {"z", "z.at2"}}}};
    CHECK_THAT(parse_error(j), Contains("ground_motion.files.y"));
  }
  SECTION("overlapping items") {
    j["items"][2]["x"] = 0.3;  // the chair into the desk
    const std::string msg = validate_error(j);
    CHECK_THAT(msg, Contains("items[2]") && Contains("office_chair") && Contains("desk") && Contains("overlap"));
  }
  SECTION("item outside the table") {
    j["items"][1]["y"] = 1.8;
    const std::string msg = validate_error(j);
    CHECK_THAT(msg, Contains("items[1]") && Contains("desk") && Contains("outside"));
  }
  SECTION("item through a wall") {
    j["walls"] = json::array({{{"name", "partition"}, {"point", {0, 0.5, 0}}, {"normal", {0, -1, 0}}}});
    const std::string msg = validate_error(j);
    CHECK_THAT(msg, Contains("items[1]") && Contains("partition"));
  }
  SECTION("marker on no item") {
    j["outputs"]["markers"] = {"sofa.top"};
    const std::string msg = validate_error(j);
    CHECK_THAT(msg, Contains("outputs.markers[0]") && Contains("sofa"));
  }
  SECTION("marker name an item does not have") {
    j["outputs"]["markers"] = {"desk.armrest"};
    CHECK_THAT(validate_error(j), Contains("outputs.markers[0]") && Contains("armrest") && Contains("top_front_centre"));
  }
  SECTION("sectional force on a member that does not exist") {
    j["outputs"]["sectional_forces"] = {{{"item", "desk"}, {"member", "leg:0"}, {"element", 0}}};
    CHECK_THAT(validate_error(j), Contains("outputs.sectional_forces[0].member") && Contains("leg:0"));
  }
  SECTION("missing record file") {
    j["ground_motion"] = {{"source", "file"}, {"format", "at2"}, {"files", {{"x", "no_such_record.AT2"}}}};
    const std::string msg = validate_error(j);
    CHECK_THAT(msg, Contains("ground_motion.files.x") && Contains("no_such_record.AT2") && Contains("not found"));
  }
  SECTION("unreachable centre of gravity") {
    j["items"][1]["params"] = {{"cog_h", 0.69}, {"cog_d1", 0.01}};
    CHECK_THAT(validate_error(j), Contains("items[1]") && Contains("cannot be built"));
  }
  SECTION("duplicate names") {
    j["items"][2]["name"] = "desk";
    CHECK_THAT(validate_error(j), Contains("items[2].name") && Contains("duplicate"));
  }
}

TEST_CASE("JSON syntax errors report the line", "[scene][errors]") {
  const std::string path = tmp_file("syntax.json");
  {
    std::ofstream out(path);
    out << "{\n  \"name\": \"x\",\n  \"dt\": 0.001,,\n}\n";
  }
  try {
    parse_scene(path);
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(e.line() == 3);
    CHECK_THAT(std::string(e.what()), Contains("syntax.json:3"));
  }
  CHECK_THROWS_AS(parse_scene(tmp_file("does_not_exist.json")), InputError);
}

TEST_CASE("overlapping footprints among many items: the same first pair as comparing every pair",
          "[scene][errors]") {
  // validate() places items in a grid of cells and compares neighbours only (every pair took minutes
  // for 90 000 items, issue 13). Checked against the pairwise definition on random rooms of 400 side
  // tables, 1 m apart, jittered by up to +-0.3 m and turned at random: the first overlapping pair
  // (lowest index, then lowest partner) and its depth must be the same.
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3), yaw(0.0, 360.0);
  int rooms_with_overlap = 0;
  for (int trial = 0; trial < 12; ++trial) {
    json j = small_scene();
    j["table"] = {{"size_x", 40.0}, {"size_y", 40.0}};
    j["walls"] = json::array();
    j["items"] = json::array();
    for (int a = 0; a < 20; ++a)
      for (int b = 0; b < 20; ++b)
        j["items"].push_back({{"kind", "side_table"}, {"x", -10.0 + a + jitter(rng)}, {"y", -10.0 + b + jitter(rng)},
                              {"yaw_deg", yaw(rng)}});
    const SceneSpec spec = parse_scene_json(j, "many.json");
    long first_i = -1, first_k = -1;
    for (size_t i = 0; i < spec.items.size() && first_i < 0; ++i)
      for (size_t k = 0; k < i; ++k)
        if (furniture_fem::detail::overlap_depth(furniture_fem::detail::footprint(spec.items[k]),
                                                 furniture_fem::detail::footprint(spec.items[i])) > 1e-6) {
          first_i = long(i), first_k = long(k);
          break;
        }
    if (first_i < 0) continue;  // validate() would then build 400 items: not needed here
    ++rooms_with_overlap;
    const std::string msg = input_error([&] { validate(spec); });
    INFO("trial " << trial << ": " << msg);
    CHECK_THAT(msg, Contains("items[" + std::to_string(first_i) + "]") &&
                        Contains("(items[" + std::to_string(first_k) + "]) overlap"));
  }
  CHECK(rooms_with_overlap >= 6);  // the rooms do test something
}

TEST_CASE("hostile scene files: deep nesting, huge numbers, large values give a named error", "[scene][errors]") {
  // Each failed before (issue 13): 100 000 nested brackets overflowed the stack in the message's
  // dump; 1e400 gave the JSON library's own message without the file; a 1 MB value was serialised
  // whole to be cut to 60 characters.
  const auto message_of = [](const std::string& name, const std::string& text) {
    const std::string path = tmp_file(name);
    std::ofstream(path, std::ios::binary) << text;
    return input_error([&] { parse_scene(path); });
  };
  const std::string deep = message_of("deep.json", "{\n\"name\": " + std::string(100000, '[') + std::string(100000, ']') + "}\n");
  CHECK_THAT(deep, Contains("deep.json:2") && Contains("nested more than 64 levels"));
  // 64 levels are fine for the parser (the reader then names the key that is wrong).
  const std::string ok_depth =
      message_of("depth64.json", "{\"name\": " + std::string(63, '[') + std::string(63, ']') + "}\n");
  CHECK_THAT(ok_depth, Contains("name") && !Contains("nested more than"));
  const std::string huge = message_of("huge_number.json", "{\"name\": \"x\", \"dt\": 1e400}\n");
  CHECK_THAT(huge, Contains("huge_number.json:1: dt: number out of range (got 1e400)"));
  // The key path where the library stopped (from its SAX events), in an array too.
  const std::string in_point =
      message_of("point_1e400.json", "{\"walls\": [{\"point\": [0,\n 1e400, 0]}]}\n");
  CHECK_THAT(in_point, Contains("point_1e400.json:2: walls[0].point[1]: number out of range (got 1e400)"));
  const std::string comma = message_of("missing_comma.json", "{\"items\": [{\"kind\": \"block\"\n \"x\": 1}]}\n");
  CHECK_THAT(comma, Contains("missing_comma.json:2: items[0].kind: not valid JSON after its value"));
  // The library stops at a NUL byte: what follows would be read as nothing.
  const std::string nul = message_of("nul_after.json", std::string("{\"name\": \"x\"}\n\0junk", 19));
  CHECK_THAT(nul, Contains("nul_after.json:2: not valid JSON after the top-level value: a NUL byte (byte 15 of 19)"));
  std::string big = "{\"name\": [";
  for (int i = 0; i < 200000; ++i) big += "12345,";
  big += "1]}\n";
  const std::string large = message_of("large_value.json", big);
  CHECK_THAT(large, Contains("large_value.json") && Contains("name"));
  CHECK(large.size() < 400);
}

TEST_CASE("example scene files parse, validate and round-trip", "[scene][examples]") {
  const auto dir = source_dir / "../../examples/scenes";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    ++files;
    INFO(entry.path().string());
    SceneSpec scene = parse_scene(entry.path().string());
    const SceneSpec as_read = scene;
    scene.base_dir = (records_root() / "repo" / "examples" / "scenes").string();  // their records: stand-ins
    CHECK_NOTHROW(validate(scene));
    scene = as_read;
    std::ifstream in(entry.path());
    const json original = json::parse(in);
    CHECK(to_json(scene) == original);  // the examples are written in the full form
  }
  CHECK(files >= 4);
}

TEST_CASE("item-level contact overrides reach ItemContact", "[scene][contact]") {
  json j = small_scene();
  j["items"][0]["params"] = {{"alpha_kgf", 50.0}, {"mu_floor_short", 0.3}, {"mu_item", 0.2}};
  const SceneSpec scene = parse_scene_json(j, "c.json");
  Model model;
  const auto items = build_scene(scene, model);
  CHECK(items[0].contact.alpha == Approx(50.0 * 9.80665));
  CHECK(items[0].contact.mu_floor_short == 0.3);
  CHECK(items[0].contact.mu_floor_long == 0.278);  // Table 4 where not overridden
  CHECK(items[0].contact.mu_item == 0.2);
  CHECK(items[1].contact.mu_item == 0.169);
}

TEST_CASE("the minimal scene of docs/scene/scene_file.md parses and validates", "[scene][examples]") {
  // Copied from the documentation; relative record paths resolve from examples/scenes/ (here from
  // its stand-in, records_root()).
  SceneSpec scene = parse_scene_json(json::parse(R"json({
  "name": "desk and chair, 50 % JMA-Kobe 3-D",
  "items": [
    {"kind": "desk", "x": 0.6, "y": 0.0, "yaw_deg": -90},
    {"kind": "office_chair", "x": -0.82, "y": 0.0, "yaw_deg": 90},
    {"kind": "bookshelf", "name": "shelf", "x": 1.8, "y": 1.0, "yaw_deg": -90,
     "params": {"width": 0.8, "depth": 0.3, "height": 1.8, "shelves": 5, "mass_kg": 35}}
  ],
  "ground_motion": {
    "source": "file", "format": "at2", "level": 0.5, "dimensions": "3d",
    "files": {"x": "../../../shared/ground_motions/jma_kobe_1995_NS_PEER_RSN1106_KJM000.AT2",
              "y": "../../../shared/ground_motions/jma_kobe_1995_EW_PEER_RSN1106_KJM090.AT2",
              "z": "../../../shared/ground_motions/jma_kobe_1995_UD_PEER_RSN1106_KJM-UP.AT2"},
    "window": {"start": 4.0, "end": 16.0}
  },
  "contact": {"law": "paper_anisotropic"},
  "duration": 12.0,
  "outputs": {
    "folder": "out/desk_and_chair",
    "markers": ["desk.top_back_centre", "office_chair.seat_centre",
                {"name": "shelf_top", "item": "shelf", "point": [0, -0.15, 1.8]}],
    "sectional_forces": [{"item": "desk", "member": "top/x6:5", "element": 1}],
    "vtu_every": 100
  }
}
)json"), "docs/scene/scene_file.md");
  scene.base_dir = (records_root() / "repo" / "examples" / "scenes").string();
  REQUIRE_NOTHROW(validate(scene));
  CHECK(scene.walls.size() == 2);  // the default walls
  CHECK(scene.ground_motion.dimensions == MotionDimensions::three_d);
  CHECK(scene.outputs.markers[2].point.has_value());
  Model model;
  const auto items = build_scene(scene, model);
  REQUIRE(items.size() == 3);
  CHECK(items[2].calibration.mass == Approx(35.0));
}

}  // namespace scene_tests
