// The scene's ceiling ("ceiling": {"height"}): read, written back and refused with named errors; a block
// thrown up stops at it; a ceiling not touched changes nothing; an item pushed up against it by a table
// acceleration above g presses on it with M (a - g), rigid and at full fidelity, reported as
// "<item>|ceiling_f?" in contact_forces.csv.
#include <catch2/catch.hpp>

#include <furniture_fem/io/csv.hpp>
#include <furniture_fem/scene/scene_runner.hpp>

#include "../support/scene_input.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

using namespace furniture_fem;
using nlohmann::json;
using Catch::Matchers::Contains;

namespace ceiling_tests {  // this file's own names (its group compiles files in batches)

namespace {

constexpr double g = 9.80665;
constexpr double block_mass = 20.0, block_height = 0.4;

// A 0.4 m cube of 20 kg (rigid: the block kind) on the floor, the paper's law, the table's vertical
// acceleration `z` (a points motion; none along X) and, unless nullopt, a ceiling at `ceiling` m.
json block_scene(const json& z, std::optional<double> ceiling, double duration) {
  json j = {{"name", "block under a ceiling"},
            {"items", {{{"kind", "block"},
                        {"name", "crate"},
                        {"fidelity", "rigid"},
                        {"params", {{"width", 0.4}, {"depth", 0.4}, {"height", block_height}, {"mass_kg", block_mass},
                                    {"mu_floor_long", 0.3}, {"mu_floor_short", 0.3}}}}}},
            {"ground_motion", {{"source", "points"}, {"x", {{0.0, 0.0}, {10.0, 0.0}}}, {"z", z}}},
            {"duration", duration},
            {"dt", 0.001},
            {"outputs", {{"figures", false}}}};
  if (ceiling) j["ceiling"] = {{"height", *ceiling}};
  return j;
}

std::string read_error(const json& j) { return ffem_test::scene_error(j, "ceiling.json"); }

std::string build_error(const json& j) {
  return ffem_test::input_error([&] { const SceneSimulation<DirectLdltSolver> scene(ffem_test::validated_scene(j, "ceiling.json")); });
}

// A point mass on a rigid floor in the table's frame under the same table motion: its highest rise
// (m) and its speed when it last passed `at` going up (m/s), integrated at 1 us (the reference, free of
// the contact law and of the element code).
struct FreeFlight {
  double apex = 0, speed_at = 0;
};
FreeFlight point_mass_flight(const TableMotion& motion, double t_end, double at) {
  const double h = 1e-6;
  double z = 0, v = 0;
  FreeFlight out;
  for (double t = 0; t < t_end; t += h) {
    double acc = -(g + motion.at(t).z());
    if (z <= 0 && acc < 0) acc = 0, v = std::max(v, 0.0), z = 0;  // on the floor: held
    const double z_before = z;
    v += acc * h;
    z += v * h;
    if (z_before < at && z >= at) out.speed_at = v;
    out.apex = std::max(out.apex, z);
  }
  return out;
}

// The block's highest rise (m) above where it stood settled at t0, over the run to t_end.
double block_rise(const json& j, double t0, double t_end, double* top_rest_gap = nullptr) {
  const SceneSpec spec = parse_scene_json(j, "throw.json");
  validate(spec);
  SceneSimulation<DirectLdltSolver> scene(spec);
  REQUIRE(scene.rigid_bodies.size() == 1);
  const int hub = scene.items[0].marker("cog")->node;
  scene.sim->run_until(t0);
  const double settled = scene.sim->displacement(hub).z();
  if (top_rest_gap) *top_rest_gap = -settled;  // how far the weight pressed it into the floor
  double rise = 0;
  while (scene.sim->time() < t_end - 1e-9) {
    scene.sim->step();
    rise = std::max(rise, scene.sim->displacement(hub).z() - settled);
  }
  return rise;
}

// The number of a body's nodes on its top face (the rigid contact's support face against the ceiling).
int top_face_nodes(const Model& model) {
  double top = -1e9;
  for (int n = 0; n < model.num_nodes(); ++n) top = std::max(top, model.node(n).X.z());
  int count = 0;
  for (int n = 0; n < model.num_nodes(); ++n) count += model.node(n).X.z() > top - 1e-9;
  return count;
}

}  // namespace

TEST_CASE("ceiling: read, written back, absent by default; bad values and keys name the key",
          "[scene][ceiling][errors]") {
  const json pulse = {{0.0, 0.0}, {1.0, 0.0}};
  const SceneSpec none = parse_scene_json(block_scene(pulse, std::nullopt, 0.5), "none.json");
  CHECK_FALSE(none.ceiling);
  CHECK_FALSE(to_json(none).contains("ceiling"));  // a scene without one is written as before
  const SceneSpec s = parse_scene_json(block_scene(pulse, 2.0, 0.5), "c.json");
  REQUIRE(s.ceiling);
  CHECK(s.ceiling->height == 2.0);
  const json written = to_json(s);
  CHECK(written["ceiling"] == json{{"height", 2.0}});
  const SceneSpec again = parse_scene_json(written, "again.json");
  REQUIRE(again.ceiling);
  CHECK(again.ceiling->height == 2.0);
  CHECK(to_json(again) == written);

  const json base = block_scene(pulse, 2.0, 0.5);
  for (const auto& [ceiling, expect] :
       {std::pair{json{{"height", 0.0}}, "ceiling.height: must be positive (got 0"},
        std::pair{json{{"height", -1.5}}, "ceiling.height: must be positive (got -1.5)"},
        std::pair{json{{"height", 2e4}}, "ceiling.height: must lie in [0, 10000] (got 20000"},
        std::pair{json{{"height", "2"}}, "ceiling.height: expected a number, got a string"},
        std::pair{json::object(), "ceiling.height: required: the ceiling's height above the table's floor (m)"},
        std::pair{json{{"height", 2.0}, {"z", 2.0}}, "ceiling.z: unknown key; allowed here: height"},
        std::pair{json(2.0), "ceiling: expected an object, got a number"}}) {
    json bad = base;
    bad["ceiling"] = ceiling;
    const std::string message = read_error(bad);
    INFO(ceiling.dump() << " -> " << message);
    CHECK_THAT(message, Contains(expect));
  }
  // JSON holds no NaN or infinity: a SceneSpec made in code is checked by validate().
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (const double h : {std::numeric_limits<double>::quiet_NaN(), inf, -inf, 0.0, 1e5}) {
    SceneSpec code = s;
    code.ceiling->height = h;
    std::string message = "no error";
    try {
      validate(code);
    } catch (const InputError& e) {
      message = e.what();
    }
    INFO(h << " -> " << message);
    CHECK_THAT(message, Contains("ceiling.height: must be positive, finite and at most 10000 m (got "));
  }
  // An item reaching above it at t = 0 (the block's top is its height: its top nodes' centre lines sit
  // half an edge width, 5 mm, below it); touching is allowed.
  CHECK_THAT(build_error(block_scene(pulse, 0.35, 0.5)),
             Contains("ceiling.height: item 'crate' (items[0]) reaches 0.4 m, above the ceiling at 0.35 m (heights "
                      "above the table's floor); raise the ceiling or lower the item"));
  CHECK(build_error(block_scene(pulse, block_height, 0.5)) == "no error");
  json lifted_floor = block_scene(pulse, 0.39, 0.5);
  lifted_floor["table"] = {{"floor_z", 3.0}};  // heights count from the floor
  CHECK_THAT(build_error(lifted_floor), Contains("reaches 0.4 m, above the ceiling at 0.39 m"));
  lifted_floor["ceiling"]["height"] = 0.41;
  CHECK(build_error(lifted_floor) == "no error");
}

TEST_CASE("a block thrown up reaches its ballistic apex without a ceiling and stops at the ceiling with one",
          "[scene][ceiling][dynamics]") {
  // The table accelerates downwards at 2 g for 0.1 s (10 ms ramps, after 0.2 s of settling): in its
  // frame the block rises at g, then flies freely. Closed form without the ramps: v = g T at the pulse's
  // end, 0.049 m up, then v^2 / (2 g) = 0.049 m more: apex (a - g) a T^2 / (2 g) = 0.0981 m. The
  // reference integrates a point mass on a rigid floor under the same motion (the ramps included).
  // The `stiff` law, the law for impacts (docs/contact/contact.md): the paper's law, inside the step,
  // holds the block on the floor about 4 ms longer as it lifts off (its damping pulls while a contact
  // opens) and it rose 7 % less, a matter of the floor's law that the ceiling's test does not need.
  const double a = 2 * g, T = 0.1, t0 = 0.2, t_end = 0.75;
  const json pulse = {{0.0, 0.0}, {t0, 0.0}, {t0 + 0.01, -a}, {t0 + T, -a}, {t0 + T + 0.01, 0.0}, {10.0, 0.0}};
  const auto scene = [&](std::optional<double> ceiling) {
    json j = block_scene(pulse, ceiling, 1.0);
    j["contact"] = {{"law", "stiff"}};
    return j;
  };
  const TableMotion motion = scene_table_motion(parse_scene_json(scene(std::nullopt), "throw.json"));
  const FreeFlight free = point_mass_flight(motion, t_end, 0.0);
  CHECK(free.apex == Approx((a - g) * a * T * T / (2 * g)).epsilon(0.06));  // the ramps: 5 % lower

  // Without a ceiling: the block's rise is the free flight's apex plus what its weight pressed it into
  // the floor (2.5 um: the stiff law's spring, given back on leaving). Measured 0.10 mm above it (0.1 %,
  // the 1 ms steps across the ramps); bound 0.3 mm.
  double pressed = 0;
  const double rise = block_rise(scene(std::nullopt), t0, t_end, &pressed);
  INFO("no ceiling: rise " << rise << " m, point mass " << free.apex << " m, resting overlap " << pressed << " m");
  CHECK(std::abs(rise - free.apex - pressed) < 3e-4);

  // A ceiling 80 mm above the block's top: it reaches it at v_hit = sqrt(2 g (apex - 0.08)) = 0.51 m/s
  // and the ceiling stops it within its spring's overlap. Bound on that overlap: the block's kinetic
  // energy M v_hit^2 / 2 stored in the top face's N nodes' springs k (the face's corners stand for them,
  // docs/contact/contact.md "Rigid bodies"), v_hit sqrt(M / (N k)) (gravity and the dashpot only take
  // energy), plus the travel of the step in which the contact starts, v_hit dt. It must reach the
  // ceiling: at least the gap. Measured: 0.065 mm into it.
  const double gap = 0.08;
  const json with = scene(block_height + gap);
  const SceneSpec spec = parse_scene_json(with, "ceiling.json");
  const SceneSimulation<DirectLdltSolver> built(spec);
  const double k = scene_body_contacts(spec, *built.model, built.items).at(0).wall.k_lin;
  const int N = top_face_nodes(*built.model);
  const double v_hit = point_mass_flight(motion, t_end, gap).speed_at;
  const double overlap_bound = v_hit * std::sqrt(block_mass / (N * k)) + v_hit * spec.dt;
  const double stopped = block_rise(with, t0, t_end);
  INFO("ceiling " << gap << " m above: rise " << stopped << " m, hit at " << v_hit << " m/s, " << N
                  << " top nodes of " << k << " N/m, overlap bound " << overlap_bound << " m");
  CHECK(v_hit == Approx(std::sqrt(2 * g * (free.apex - gap))).epsilon(1e-3));
  CHECK(stopped > gap + pressed);
  CHECK(stopped < gap + pressed + overlap_bound);
}

TEST_CASE("a ceiling the block does not touch changes nothing, to the bit", "[scene][ceiling]") {
  // The block slides under a table acceleration of 0.6 g along X (mu 0.3) with a ceiling 1 mm above
  // its top and without one: every node at every 50th step is where it is without the ceiling.
  json j = block_scene({{0.0, 0.0}, {1.0, 0.0}}, std::nullopt, 0.6);
  j["ground_motion"]["x"] = {{0.2, 0.0}, {0.201, 0.6 * g}, {5.0, 0.6 * g}};
  json with = j;
  with["ceiling"] = {{"height", block_height + 0.001}};
  SceneSimulation<DirectLdltSolver> a(parse_scene_json(j, "a.json")), b(parse_scene_json(with, "b.json"));
  const int hub = a.items[0].marker("cog")->node;
  int compared = 0;
  while (a.sim->time() < 0.6 - 1e-9) {
    a.sim->step();
    b.sim->step();
    if (a.sim->steps() % 50) continue;
    for (int n = 0; n < a.model->num_nodes(); ++n) REQUIRE(a.sim->position(n) == b.sim->position(n));
    ++compared;
  }
  CHECK(compared == 12);
  CHECK(a.sim->displacement(hub).x() < -0.1);  // it did slide (closed form -(0.6 - 0.3) g t^2 / 2 = -0.24 m)
}

namespace {

// Run `j` (with files) pushed up against a ceiling at its top by a table acceleration of -a_table
// (downwards, ramped over 0.2 s from 0.1 s): the mean over the rows from t_from of the ceiling's and
// the floor's force on item `item` (N, z), from contact_forces.csv.
std::pair<double, double> pressed_forces(json j, const std::string& name, const std::string& item, double t_from) {
  const std::string out = (std::filesystem::path(FFEM_TEST_TMP) / "ceiling" / name).string();
  std::filesystem::remove_all(out);
  RunOptions o;
  o.out_dir = out;
  o.progress = false;
  const RunSummary s = run_scene(parse_scene_json(j, name + ".json"), o);
  REQUIRE(s.status == "completed");
  const CsvTable cf = read_csv(out + "/contact_forces.csv");
  const auto &t = cf.column("t"), &ceiling = cf.column(item + "|ceiling_fz"), &floor = cf.column(item + "|floor_fz");
  CHECK(cf.has(item + "|ceiling_fx"));
  CHECK(cf.has(item + "|ceiling_fy"));
  double on_ceiling = 0, on_floor = 0;
  int rows = 0;
  for (std::size_t r = 0; r < cf.rows(); ++r)
    if (t[r] >= t_from) on_ceiling += ceiling[r], on_floor += floor[r], ++rows;
  REQUIRE(rows > 10);
  return {on_ceiling / rows, on_floor / rows};
}

json pushed_up(double a_table) { return {{0.0, 0.0}, {0.1, 0.0}, {0.3, -a_table}, {10.0, -a_table}}; }

}  // namespace

TEST_CASE("an item pushed up against the ceiling presses on it with M (a - g), rigid and at full fidelity",
          "[scene][ceiling][dynamics]") {
  // The table accelerates downwards at a = 1.5 g: in its frame the item is pushed up at a - g = 0.5 g
  // against the ceiling at its top (touching at t = 0, but its weight pressed it into the floor: it
  // lifts at 0.23 s and strikes the ceiling gently), which holds it with M (a - g), pushing down; the
  // floor then carries nothing. The paper's law. Rows' means over the last 0.3 s: the table rang on the
  // ceiling, +-30 N at 10 Hz at 0.45 s, settled to 5e-6 by 1.2 s (measured). Bound 1 % of M (a - g).
  const double a = 1.5 * g;
  SECTION("a rigid block") {
    const json j = block_scene(pushed_up(a), block_height, 1.5);
    const auto [on_ceiling, on_floor] = pressed_forces(j, "block", "crate", 1.2);
    const double expected = -block_mass * (a - g);
    INFO("ceiling on the block " << on_ceiling << " N, expected " << expected << " N; floor " << on_floor << " N");
    CHECK(on_ceiling == Approx(expected).epsilon(0.01));
    CHECK(std::abs(on_floor) < 1e-3 * std::abs(expected));
  }
  // A table (Table 2's rule for its mass, from the built model; its top board's outer face at its
  // height): at full fidelity by its members' surfaces (each node's cube) and centre lines (its nodes),
  // and rigid (the hull of its cubes: the top face's corners stand for its nodes).
  for (const auto& [fidelity, at] : {std::pair{"full", "surfaces"}, std::pair{"full", "centre_lines"},
                                     std::pair{"rigid", "surfaces"}}) {
    DYNAMIC_SECTION("a table, " << fidelity << ", contact at its " << at) {
      json j = {{"name", "table under a ceiling"},
                {"items", {{{"kind", "table"}, {"name", "it"}, {"fidelity", fidelity}}}},
                {"ground_motion", {{"source", "points"}, {"x", {{0.0, 0.0}, {10.0, 0.0}}}, {"z", pushed_up(a)}}},
                {"contact", {{"plane_contact_at", at}}},
                {"duration", 1.5},
                {"dt", 0.001},
                {"integrator", {{"stiffness_damping", 1e-3}}},
                {"outputs", {{"figures", false}}}};
      const SceneSpec spec = parse_scene_json(j, "table.json");
      double mass = 0, top = 0;
      {
        const SceneSimulation<DirectLdltSolver> scene(spec);
        mass = scene.model->body_mass(0);
        top = detail::item_tops(spec, *scene.model, scene.items).at(0);
      }
      j["ceiling"] = {{"height", top}};
      const auto [on_ceiling, on_floor] = pressed_forces(j, std::string("table_") + fidelity + "_" + at, "it", 1.2);
      const double expected = -mass * (a - g);
      INFO("ceiling on the table (" << mass << " kg, top " << top << " m) " << on_ceiling << " N, expected "
                                    << expected << " N; floor " << on_floor << " N");
      CHECK(on_ceiling == Approx(expected).epsilon(0.01));
      CHECK(std::abs(on_floor) < 1e-3 * std::abs(expected));
    }
  }
}

}  // namespace ceiling_tests
