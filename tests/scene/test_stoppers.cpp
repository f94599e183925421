// Stoppers in scenes (issue 49; docs/restraints/restraints.md, "stopper" and "Verification"): a wedge under
// an item's front edge leans the item back by its height; the stoppers then carry the share of the weight
// the moment balance about the back edge gives, and the item tips forward at the acceleration the moment
// balance about the wedge gives, later than a free one. The scene keys' errors name the stopper.
#include <catch2/catch.hpp>

#include <furniture_fem/scene/scene_runner.hpp>

#include "../support/scene_input.hpp"

#include <algorithm>
#include <cmath>
#include <string>

using namespace furniture_fem;
using nlohmann::json;
using Catch::Matchers::Contains;

namespace stopper_scene_tests {  // this file's own names (its group compiles files in batches)

namespace {

constexpr double g = 9.80665;
const double pi = std::acos(-1.0);

struct Block {
  double W, D, H, h, M;
};

// A rigid block (mu 0.9 on the floor: it tips, it does not slide) turned to face +X (yaw 90 deg: its
// front at +X), on two stoppers of wedge height `wedge` under its front corners, the `stiff` law. The
// table's acceleration along X follows `x_points`: a negative one throws the block forward, over the
// wedges.
json block_on_stoppers(const Block& c, double wedge, const json& x_points, double duration) {
  json restraints = json::array();
  for (const char* corner : {"bottom_front_left", "bottom_front_right"})
    restraints.push_back({{"name", std::string("stop_") + corner}, {"kind", "stopper"}, {"item", "crate"},
                          {"point", corner}, {"wedge_height", wedge}});
  return {{"name", "block on stoppers"},
          {"items", {{{"kind", "block"},
                      {"name", "crate"},
                      {"fidelity", "rigid"},
                      {"yaw_deg", 90.0},
                      {"params", {{"width", c.W}, {"depth", c.D}, {"height", c.H}, {"cog_h", c.h}, {"mass_kg", c.M},
                                  {"mu_floor_long", 0.9}, {"mu_floor_short", 0.9}}}}}},
          {"restraints", restraints},
          {"ground_motion", {{"source", "points"}, {"x", x_points}}},
          {"contact", {{"law", "stiff"}}},
          {"duration", duration},
          {"dt", 0.001},
          {"outputs", {{"figures", false}}}};
}

// The block's geometry as built (leaning on its stoppers): its back edge (its lowest nodes, farthest
// toward -X), its front edge (the stoppers' nodes), its centre of gravity.
struct Lean {
  double M, back_x, back_z, front_x, front_z, cog_x, cog_z;
  // The stoppers' vertical force at rest: moments about the back edge.
  double resting_force() const { return M * g * (cog_x - back_x) / (front_x - back_x); }
  // The table acceleration at which the block tips forward about the wedges: moments about the front edge.
  double tipping_acceleration() const { return g * (front_x - cog_x) / (cog_z - front_z); }
};
template <class Scene>
Lean lean_of(const Scene& scene) {
  const Model& m = *scene.model;
  const ItemInfo& it = scene.items[0];
  const RestraintSet& stops = scene.sim->contact_model().restraints();
  Lean l{};
  l.M = m.body_mass(it.body);
  l.back_z = 1e9;
  for (int n : m.body(it.body).nodes) l.back_z = std::min(l.back_z, m.node(n).X.z());
  l.back_x = 1e9;
  for (int n : m.body(it.body).nodes)
    if (m.node(n).X.z() < l.back_z + 1e-9) l.back_x = std::min(l.back_x, m.node(n).X.x());
  l.front_x = stops[0].rest.x();
  l.front_z = stops[0].rest.z();
  const Vec3 cog = m.body_centre_of_gravity(it.body);
  l.cog_x = cog.x();
  l.cog_z = cog.z();
  return l;
}

template <class Scene>
double tilt_deg(const Scene& scene) {
  const int hub = scene.items[0].marker("cog")->node;
  return std::acos(std::clamp(scene.sim->rotation(hub)(2, 2), -1.0, 1.0)) * 180 / pi;
}

SceneSpec read(const json& j) { return ffem_test::validated_scene(j, "stoppers.json"); }

std::string read_error(const json& j) { return ffem_test::scene_error(j, "stoppers.json"); }

const Block blocks[] = {{0.6, 0.4, 1.6, 0.8, 80}, {0.9, 0.45, 1.8, 0.85, 120}};

}  // namespace

TEST_CASE("stoppers lean a block back by their height and carry the moment balance's share of its weight", "[scene][restraints][stopper]") {
  // The build turns the block about its back bottom edge until the stoppers' nodes stand the wedge's
  // height above the back edge's, their distance along the floor then sqrt(L^2 - h^2) for the distance L
  // between its front and back bottom nodes standing free; both exact to round-off. At rest (1.5 s, nothing
  // moving: the drop onto the wedges at the start has died out under their damping) the stoppers carry
  // M g (x_g - x_back) / (x_front - x_back): the horizontal forces are nil but for the wedges' give as
  // the block settles into them (their lateral force times the wedge's height, 1e-4 of the moment).
  // Bound 0.5 %.
  for (const Block& c : blocks) {
    for (const double wedge : {0.01, 0.02}) {
      INFO("block " << c.W << " x " << c.D << " x " << c.H << " m, " << c.M << " kg, wedge " << wedge << " m");
      json j = block_on_stoppers(c, wedge, {{0.0, 0.0}, {2.0, 0.0}}, 1.5);
      const SceneSpec spec = read(j);
      SceneSimulation<DirectLdltSolver> scene(spec);
      const Lean l = lean_of(scene);
      j.erase("restraints");
      Model free;
      double lo = 1e9, hi = -1e9;
      for (int n : free.body(build_scene(read(j), free)[0].body).nodes)
        if (free.node(n).X.z() < 0.006) lo = std::min(lo, free.node(n).X.x()), hi = std::max(hi, free.node(n).X.x());
      CHECK(l.front_z - l.back_z == Approx(wedge).margin(1e-12));
      CHECK(l.front_x - l.back_x == Approx(std::sqrt((hi - lo) * (hi - lo) - wedge * wedge)).epsilon(1e-12));
      scene.sim->run_until(1.5);
      double carried = 0;
      for (const auto& s : scene.sim->contact_model().restraints().states()) {
        CHECK(s.regime == RestraintRegime::elastic);
        carried += s.on_item.z();
      }
      INFO("stoppers carry " << carried << " N, moment balance " << l.resting_force() << " N, weight " << l.M * g << " N");
      CHECK(carried == Approx(l.resting_force()).epsilon(0.005));
      CHECK(tilt_deg(scene) < 0.05);
    }
  }
}

TEST_CASE("a block on stoppers tips forward at the acceleration the moment balance about the wedges gives", "[scene][restraints][stopper][dynamics]") {
  // The table's acceleration (toward -X, throwing the block forward) rises from 0 at 0.3 s to f a* at
  // 2.3 s and holds: a* = g (x_front - x_g) / (z_g - z_front), the block pivoting on the wedges' tops
  // (friction 0.5 on them holds the 0.3 g it takes). At 0.95 a* it stands (tilt below 0.5 deg), at
  // 1.05 a* it overturns (past 60 deg by 5 s). The same block standing free tips at g b / h about its
  // front edge, below a*: that is what a stopper is for.
  for (const Block& c : blocks) {
    for (const double wedge : {0.01, 0.02}) {
      double a_star = 0, free = 0;
      {
        SceneSimulation<DirectLdltSolver> scene(read(block_on_stoppers(c, wedge, {{0.0, 0.0}, {1.0, 0.0}}, 0.1)));
        const Lean l = lean_of(scene);
        a_star = l.tipping_acceleration();
        free = g * (0.5 * c.D - 0.005) / (c.h - 0.005);  // the free block about its front bottom nodes
      }
      CHECK(a_star > free);
      for (const double f : {0.95, 1.05}) {
        INFO("block " << c.D << " x " << c.H << " m, wedge " << wedge << " m: a = " << f << " a*, a* = " << a_star
                      << " m/s^2, free " << free << " m/s^2");
        const double a = -f * a_star;
        SceneSimulation<DirectLdltSolver> scene(read(block_on_stoppers(c, wedge, {{0.3, 0.0}, {2.3, a}, {6.0, a}}, 5.0)));
        double largest = 0;
        while (scene.sim->time() < 5.0 - 1e-9) {
          scene.sim->step();
          largest = std::max(largest, tilt_deg(scene));
          if (largest > 60) break;
        }
        INFO("largest tilt " << largest << " deg");
        if (f < 1) CHECK(largest < 0.5);
        else CHECK(largest > 60);
        for (const auto& s : scene.sim->contact_model().restraints().states()) CHECK_FALSE(s.broken());
      }
    }
  }
}

TEST_CASE("a stopper's bad placement or height is named with the restraint and its key", "[scene][restraints][stopper][json]") {
  const json good = block_on_stoppers(blocks[0], 0.015, {{0.0, 0.0}, {1.0, 0.0}}, 0.1);
  CHECK(read_error(good) == "no error");
  const SceneSpec s = read(good);
  CHECK(s.restraints[0].kind == RestraintKind::stopper);
  const json once = to_json(s);
  CHECK(to_json(parse_scene_json(once, "again")) == once);

  const auto with = [&](int i, const char* key, const json& value) {
    json j = good;
    j["restraints"][i][key] = value;
    return read_error(j);
  };
  CHECK_THAT(with(0, "wedge_height", 0.2), Contains("restraints[0].wedge_height") && Contains("got 0.2"));
  CHECK_THAT(with(1, "wedge_height", 0.02), Contains("restraints[1].wedge_height") && Contains("share one height"));
  CHECK_THAT(with(0, "point", "top_front_left"), Contains("restraints[0].point") && Contains("under the item's front edge"));
  CHECK_THAT(with(0, "point", "bottom_back_left"), Contains("restraints[0].point") && Contains("from the item's back edge"));
  CHECK_THAT(with(0, "wall", "wall_plus_x"), Contains("restraints[0]") && Contains("wall") && Contains("allowed here"));
}

TEST_CASE("an item near a wall leans back on its stoppers until its top touches the wall", "[scene][restraints][stopper]") {
  // The block's back 1 and 3 cm from the -X wall, where the full lean (15 mm over 0.39 m) would take its
  // top back by 6 cm: it leans until its top back nodes stand their contact distance (half their
  // members' 10 mm) from the wall, and its front edge rises less. Far from the wall it leans fully.
  for (const double gap : {0.01, 0.03, 0.5}) {
    json j = block_on_stoppers(blocks[0], 0.015, {{0.0, 0.0}, {1.0, 0.0}}, 0.1);
    j["items"][0]["x"] = -2.0 + 0.5 * blocks[0].D + gap;
    SceneSimulation<DirectLdltSolver> scene(read(j));
    const Model& m = *scene.model;
    double nearest = 1e9;
    for (int n : m.body(scene.items[0].body).nodes) nearest = std::min(nearest, m.node(n).X.x() + 2.0);
    const Lean l = lean_of(scene);
    INFO("gap " << gap << " m: nearest node " << nearest << " m from the wall; front edge raised " << l.front_z - l.back_z << " m");
    if (gap < 0.05) {
      CHECK(nearest == Approx(0.005).margin(1e-9));
      CHECK(l.front_z - l.back_z < 0.015);
      CHECK(l.front_z - l.back_z > 0);
    } else {
      CHECK(l.front_z - l.back_z == Approx(0.015).margin(1e-12));
    }
  }
}

}  // namespace stopper_scene_tests
