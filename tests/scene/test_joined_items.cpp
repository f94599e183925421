// Restraints between two items (issue 49; docs/restraints/restraints.md, "Between items"): the upper of
// the separated cabinets joined to the lower by brackets at its bottom corners is held down with the force
// a falling table asks, and the lower one takes their reaction; straps between them break in tension, and
// the energy ledger closes with joints that hold; the keys' errors are named.
#include <catch2/catch.hpp>

#include <furniture_fem/scene/scene_runner.hpp>

#include "../support/scene_input.hpp"

#include <algorithm>
#include <cmath>
#include <string>

using namespace furniture_fem;
using nlohmann::json;
using Catch::Matchers::Contains;

namespace joined_items_tests {  // this file's own names (its group compiles files in batches)

namespace {

constexpr double g = 9.80665;

// The separated cabinets, rigid, with their backs 5 cm from the +X wall (yaw -90 deg: they face -X); the
// lower one held to the wall at its top back corners by brackets far stronger than anything here, the
// upper one joined to the lower by two brackets of `kind` from its bottom back corners to the lower's top
// back corners. The table's acceleration along +X follows `x_points`: it throws the stack away from the
// wall, and the upper cabinet tips forward on the lower one's top.
json joined_stack(const json& x_points, double duration, const json& joint = json::object(), const std::string& kind = "l_bracket") {
  json restraints = json::array();
  for (const char* side : {"left", "right"}) {
    restraints.push_back({{"name", std::string("wall_") + side}, {"kind", "l_bracket"}, {"item", "pair/lower"},
                          {"point", std::string("top_back_") + side}, {"wall", "wall_plus_x"}, {"strength", 1e5}, {"stiffness", 1e6},
                          {"shear_strength", 1e5}, {"softening", 0.5}});
    json j = {{"name", std::string("joint_") + side}, {"kind", kind}, {"item", "pair/upper"}, {"point", std::string("bottom_back_") + side},
              {"anchor_item", "pair/lower"}, {"anchor_point", std::string("top_back_") + side}};
    j.update(joint);
    restraints.push_back(j);
  }
  return {{"name", "joined stack"},
          {"items", {{{"kind", "separated_cabinets"}, {"name", "pair"}, {"fidelity", "rigid"}, {"yaw_deg", -90.0},
                      {"x", 2.0 - 0.05 - 0.5 * 0.4}, {"params", {{"mu_floor_long", 0.9}, {"mu_floor_short", 0.9}}}}}},
          {"restraints", restraints},
          {"ground_motion", {{"source", "points"}, {"x", x_points}}},
          {"contact", {{"law", "stiff"}}},
          {"duration", duration},
          {"dt", 0.001},
          {"outputs", {{"figures", false}}}};
}

SceneSpec read(const json& j) { return ffem_test::validated_scene(j, "joined.json"); }

std::string read_error(const json& j) { return ffem_test::scene_error(j, "joined.json"); }

template <class Scene>
const ItemInfo& body_named(const Scene& scene, const std::string& name) {
  return *std::find_if(scene.items.begin(), scene.items.end(), [&](const ItemInfo& it) { return it.name == name; });
}

}  // namespace

TEST_CASE("an upper cabinet joined to the lower one is held down by its joints with the force the table's fall asks", "[scene][restraints][joined]") {
  // The table accelerates downward at a_z > g (from 0.3 s to 1.3 s, then held): both cabinets would float
  // up from it at a_z - g relative to the table. The lower one is held by its wall brackets (their shear),
  // the upper one by four brackets joining its bottom corners to the lower's top corners (pull: up).
  // Their pulls add up to M_u (a_z - g); the wall brackets' vertical forces less the floor's push on the
  // lower cabinet (its back bottom edge stays on the floor: the joints' and its own lift, in front of the
  // brackets, turn it about that edge) add up to (M_u + M_l) (a_z - g): the joints' reaction reaches the
  // lower cabinet. Averaged over the last 0.3 s; bound 0.5 %.
  // Rigid (the joints two rigid items' pair, solved with both) and finite-element (the two frames solved
  // together); the frames' run is shorter (2 s, averaged over its last 0.3 s) for the test's time.
  struct Case {
    const char* fidelity;
    double over, duration;
  };
  for (const Case c : {Case{"rigid", 1.2, 3.0}, Case{"rigid", 1.5, 3.0}, Case{"full", 1.5, 2.0}}) {
    const double az = c.over * g, over = c.over;
    json j = joined_stack({{0.0, 0.0}, {5.0, 0.0}}, c.duration);
    j["items"][0]["fidelity"] = c.fidelity;
    j["ground_motion"]["z"] = {{0.3, 0.0}, {1.3, -az}, {5.0, -az}};
    for (const char* side : {"left", "right"})
      j["restraints"].push_back({{"name", std::string("joint_front_") + side}, {"kind", "l_bracket"}, {"item", "pair/upper"},
                                 {"point", std::string("bottom_front_") + side}, {"anchor_item", "pair/lower"},
                                 {"anchor_point", std::string("top_front_") + side}});
    SceneSimulation<DirectLdltSolver> scene(read(j));
    const Model& m = *scene.model;
    const double Mu = m.body_mass(body_named(scene, "pair/upper").body), Ml = m.body_mass(body_named(scene, "pair/lower").body);
    const auto& contact = scene.sim->contact_model();
    const RestraintSet& set = contact.restraints();
    const int lower = body_named(scene, "pair/lower").body;
    double joints = 0, walls = 0, floor = 0;
    int rows = 0;
    while (scene.sim->time() < c.duration - 1e-9) {
      scene.sim->step();
      if (scene.sim->time() <= c.duration - 0.3 - 1e-9) continue;
      for (std::size_t i = 0; i < set.size(); ++i) (set[i].between_items() ? joints : walls) -= set.states()[i].on_item.z();
      for (const PairForce& pf : contact.pair_forces())
        if (pf.body_a == lower && pf.body_b == PairForce::floor_id) floor += pf.force_on_a.z();
      ++rows;
    }
    INFO(c.fidelity << ", a_z = " << over << " g; upper " << Mu << " kg, lower " << Ml << " kg: joints hold " << joints / rows << " N, walls "
                  << walls / rows << " N, the floor pushes " << floor / rows << " N");
    CHECK(joints / rows == Approx(Mu * (az - g)).epsilon(0.005));
    CHECK((walls - floor) / rows == Approx((Mu + Ml) * (az - g)).epsilon(0.005));
    for (const auto& st : set.states()) CHECK_FALSE(st.broken());
  }
}

TEST_CASE("joints that break let the upper cabinet tip; joints that hold keep the energy ledger closed", "[scene][restraints][joined]") {
  // The same stack thrown away from the wall (8 m/s^2 from 2.3 s): straps of 40 N between the cabinets
  // carry their strength and break in tension, and the upper cabinet falls. The same at 3 m/s^2 with
  // straps that hold: the run's energy ledger, whose contact work holds the joints' work on both items,
  // closes within its 5 % tolerance (the fall's impacts lose energy with the penalty contact at this dt,
  // with or without joints: 97 J of 469 J without them, so the ledger is checked where nothing falls).
  for (const double strength : {40.0, 1e4}) {
    const double a = strength < 100 ? 8.0 : 3.0;
    SceneSimulation<DirectLdltSolver> scene(read(joined_stack({{0.3, 0.0}, {2.3, a}, {5.0, a}}, 3.0, {{"strength", strength}}, "strap")));
    const RestraintSet& set = scene.sim->contact_model().restraints();
    double largest_pull = 0;
    while (scene.sim->time() < 3.0 - 1e-9) {
      scene.sim->step();
      for (std::size_t i = 0; i < set.size(); ++i)
        if (set[i].between_items()) largest_pull = std::max(largest_pull, set.states()[i].force);
    }
    const EnergyLedger e = scene.sim->energy();
    INFO("joints of " << strength << " N: largest tension " << largest_pull << " N; energy imbalance " << e.imbalance() << " J of "
                      << e.scale() << " J");
    for (std::size_t i = 0; i < set.size(); ++i)
      if (set[i].between_items()) CHECK(set.states()[i].broken() == (strength < 100));
    if (strength < 100) {
      CHECK(largest_pull == Approx(strength).epsilon(0.01));
    } else {
      CHECK(largest_pull > 10);
      CHECK(std::abs(e.imbalance()) < 0.05 * e.scale());
    }
  }
}

TEST_CASE("a joint between items is read, written back, and its bad keys are named", "[scene][restraints][joined][json]") {
  const json good = joined_stack({{0.3, 0.0}, {1.3, 1.0}}, 0.1);
  const SceneSpec s = read(good);
  CHECK(s.restraints[1].anchor_item == "pair/lower");
  const json once = to_json(s);
  CHECK(to_json(parse_scene_json(once, "again")) == once);
  CHECK_FALSE(once.at("restraints")[1].contains("wall"));

  const auto with = [&](const char* key, const json& value) {
    json j = good;
    j["restraints"][1][key] = value;
    return read_error(j);
  };
  CHECK_THAT(with("wall", "wall_plus_x"), Contains("restraints[1].anchor_item") && Contains("not both"));
  CHECK_THAT(with("anchor_item", "sofa"), Contains("restraints[1].anchor_item") && Contains("no item named \"sofa\""));
  CHECK_THAT(with("anchor_item", "pair/upper"), Contains("restraints[1].anchor_item") && Contains("another"));
  CHECK_THAT(with("anchor_point", "top_front_left"), Contains("restraints[1].anchor_point") && Contains("reaches 0.15 m"));
  CHECK_THAT(with("anchor_point", "nowhere"), Contains("restraints[1].anchor_point") && Contains("no point named"));
  // A joint needs both items inside the implicit step: with contact.implicit "rigid", finite-element
  // cabinets' contact is not.
  json outside = good;
  outside["items"][0]["fidelity"] = "full";
  outside["contact"]["implicit"] = "rigid";
  CHECK_THAT(read_error(outside), Contains("restraints[1].anchor_item") && Contains("\"pair/upper\" (finite-element, its contact outside") &&
                                      Contains("implicit step"));
  outside["contact"]["implicit"] = "all";
  CHECK(read_error(outside) == "no error");
  json mat = good;
  mat["restraints"][1] = {{"kind", "mat"}, {"item", "pair/lower"}, {"point", "bottom_front_left"}, {"anchor_item", "pair/upper"}};
  CHECK_THAT(read_error(mat), Contains("restraints[1]") && Contains("anchor_item") && Contains("allowed here"));
}

}  // namespace joined_items_tests
