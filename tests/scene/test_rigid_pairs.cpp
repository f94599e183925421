// Two rigid items meeting by their hulls (contact.rigid_pairs = "hulls"; contact/detail/hull_pair.hpp):
// the paper's upper cabinet standing on the lower one, both rigid, checked against closed-form
// mechanics with either contact place (members' centre lines, surfaces) and laws: at rest the
// contact carries the upper cabinet's weight and nothing creeps; under a constant table acceleration
// above mu_item g the upper one slides on the lower with a - mu g, below it holds. The key is read,
// written back, changes the result, and an unknown value is a named error.
#include <catch2/catch.hpp>

#include <furniture_fem/scene/scene_runner.hpp>

#include <cmath>
#include <string>

using namespace furniture_fem;
using nlohmann::json;
using Catch::Matchers::Contains;

namespace rigid_pairs_tests {  // this file's own names (its group compiles files in batches)

namespace {

constexpr double g = 9.80665;

// The two cabinets at rigid fidelity on the table, floor friction 1 (the stack never slides below
// 0.47 g, where it would tip), mu_item between them; a table acceleration along X (a points motion).
json stacked_scene(const json& x_points, double mu_item, const std::string& law, const std::string& place,
                   const std::string& rigid_pairs = "hulls", const std::string& fidelity = "rigid") {
  return {{"name", "stacked cabinets"},
          {"items", {{{"kind", "separated_cabinets"},
                      {"name", "cabinets"},
                      {"fidelity", fidelity},
                      {"params", {{"mu_floor_long", 1.0}, {"mu_floor_short", 1.0}, {"mu_item", mu_item}}}}}},
          {"ground_motion", {{"source", "points"}, {"x", x_points}}},
          {"contact", {{"law", law}, {"plane_contact_at", place}, {"rigid_pairs", rigid_pairs}}},
          {"duration", 1.0},
          {"dt", 0.001},
          {"outputs", {{"figures", false}}}};
}

template <class Law>
struct Stack {
  SceneSpec spec;
  SceneSimulation<DirectLdltSolver> scene;
  int lower, upper;             // bodies
  int lower_top, upper_bottom;  // a node of each at the interface (a rigid body's lean moves it least)
  explicit Stack(const json& j) : spec(parse_scene_json(j, "stack.json")), scene((validate(spec), spec)) {
    lower = scene.items[0].body;
    upper = scene.items[1].body;
    const Model& m = *scene.model;
    const auto extreme = [&](int body, double sign) {
      int best = -1;
      for (int n : m.body(body).nodes)
        if (best < 0 || sign * m.node(n).X.z() > sign * m.node(best).X.z()) best = n;
      return best;
    };
    lower_top = extreme(lower, 1);
    upper_bottom = extreme(upper, -1);
  }
  // The upper cabinet's displacement relative to the lower one's, at the interface.
  Vec3 slide() const { return scene.sim->displacement(upper_bottom) - scene.sim->displacement(lower_top); }
  // The force of the upper cabinet on the lower one (the pair's force on its lower-numbered body).
  Vec3 force_on_lower() const {
    for (const auto& pf : scene.sim->contact_model().pair_forces())
      if (pf.body_a == lower && pf.body_b == upper) return pf.force_on_a;
    return Vec3::Zero();
  }
};

// At rest for 3 s under gravity: the pair carries the upper cabinet's weight, and nothing moves after
// the first 0.5 s by more than `drift` (m).
template <class Law>
void check_rest(const std::string& law, const std::string& place, double drift) {
  INFO(law << " law, contact at " << place);
  Stack<Law> s(stacked_scene({{0.0, 0.0}, {3.0, 0.0}}, 0.3, law, place));
  s.scene.sim->run_until(0.5);
  const Vec3 settled = s.slide();
  s.scene.sim->run_until(3.0);
  const double weight = s.scene.model->body_mass(s.upper) * g;
  const Vec3 F = s.force_on_lower();
  INFO("force on the lower cabinet " << F.transpose() << " N, the upper one's weight " << weight << " N; moved "
                                     << (s.slide() - settled).transpose() << " m after settling");
  CHECK(F.z() == Approx(-weight).epsilon(1e-3));
  CHECK(F.head<2>().norm() < 1e-3 * weight);
  CHECK((s.slide() - settled).norm() < drift);
}

// The upper cabinet's slide on the lower one over 0.5 s after a table acceleration a_over_g g is
// applied (within 1 ms, at 0.2 s), against the closed form 0.5 (a - mu g) t^2 of a block on a fixed
// block (the lower cabinet holds on the floor: friction 1 against at most 0.4 g). Below mu g: the
// first elastic step (the stick springs, 0.2 to 0.3 s) and no creep after it.
template <class Law>
void check_slide(const std::string& law, const std::string& place, double mu, double a_over_g) {
  const double a = a_over_g * g;
  Stack<Law> s(stacked_scene({{0.2, 0.0}, {0.201, a}, {3.0, a}}, mu, law, place));
  s.scene.sim->run_until(0.2);
  const Vec3 before = s.slide();
  s.scene.sim->run_until(0.3);
  const Vec3 step = s.slide();
  s.scene.sim->run_until(0.7);
  const double slid = (s.slide() - before).x(), crept = (s.slide() - step).x();
  const double t = 0.5 - 0.0005;
  const double expected = -0.5 * (a - mu * g) * t * t;
  INFO(law << " law at " << place << ", mu " << mu << ", a " << a_over_g << " g: slid " << slid << " m (closed form "
           << expected << " m), " << crept << " m after the first 0.1 s");
  if (a_over_g > mu) {
    CHECK(slid == Approx(expected).epsilon(0.01));
  } else {
    CHECK(std::abs((step - before).x()) < 1e-3);
    CHECK(std::abs(crept) < 1e-4);  // issue 10: creep at most 0.1 mm beyond the first elastic step
  }
}

}  // namespace

TEST_CASE("rigid pairs by their hulls: the upper cabinet rests on the lower one with its weight, without creep",
          "[scene][hulls][dynamics]") {
  // Bounds: the weight to 0.1 %; with the `stiff` law no motion beyond 0.1 mm (issue 10's drift at
  // rest; measured 0.03 mm, the last of the settling lean), with the paper's carpet-soft law 1 mm
  // (measured 0.5 to 0.6 mm by hulls, 0.4 to 0.5 mm by members: its slow rocking settles).
  check_rest<SpringDashpotLaw>("stiff", "surfaces", 1e-4);
  check_rest<SpringDashpotLaw>("stiff", "centre_lines", 1e-4);
  check_rest<PaperAnisotropicFloorLaw>("paper_anisotropic", "centre_lines", 1e-3);
}

TEST_CASE("rigid pairs by their hulls: the upper cabinet slides on the lower one as Coulomb friction says",
          "[scene][hulls][dynamics]") {
  // Measured (cog displacements, furniture_quake): 0.4 to 0.6 % above the closed form by hulls, 1.6 to
  // 1.9 % by members (bound 1 %). The paper's law is not checked here: its sign damping joins the
  // normal force friction follows, and the stacked pair slides 41 to 70 % short by hulls, 15 to 23 %
  // long by members (docs/contact/contact.md, "Rigid pairs by their hulls").
  for (const auto& [mu, a] : {std::pair{0.1, 0.25}, std::pair{0.2, 0.4}, std::pair{0.3, 0.15}, std::pair{0.15, 0.1}}) {
    check_slide<SpringDashpotLaw>("stiff", "surfaces", mu, a);
    check_slide<SpringDashpotLaw>("stiff", "centre_lines", mu, a);
  }
}

TEST_CASE("contact.rigid_pairs: read, written back, changes the result, named errors", "[scene][hulls][errors]") {
  const json j = stacked_scene({{0.2, 0.0}, {0.201, 3.0}, {3.0, 3.0}}, 0.2, "stiff", "surfaces");
  const SceneSpec s = parse_scene_json(j, "hulls.json");
  CHECK(s.contact.rigid_pairs == RigidPairContact::hulls);
  CHECK(parse_scene_json(to_json(s), "again.json").contact.rigid_pairs == RigidPairContact::hulls);
  json unset = j, members = j;
  unset["contact"].erase("rigid_pairs");
  CHECK(parse_scene_json(unset, "default.json").contact.rigid_pairs == RigidPairContact::hulls);  // issue 52
  members["contact"]["rigid_pairs"] = "members";
  CHECK(parse_scene_json(members, "members.json").contact.rigid_pairs == RigidPairContact::members);
  // The same scene by members and by hulls: other contacts, another slide (both near the closed form).
  Stack<SpringDashpotLaw> by_hulls(j), by_members(stacked_scene({{0.2, 0.0}, {0.201, 3.0}, {3.0, 3.0}}, 0.2, "stiff",
                                                                "surfaces", "members"));
  by_hulls.scene.sim->run_until(0.4);
  by_members.scene.sim->run_until(0.4);
  CHECK(by_hulls.scene.sim->contact_model().rigid_pair_hulls());
  CHECK_FALSE(by_members.scene.sim->contact_model().rigid_pair_hulls());
  CHECK(by_hulls.slide().x() != by_members.slide().x());
  json bad = j;
  bad["contact"]["rigid_pairs"] = "hull";
  try {
    validate(parse_scene_json(bad, "bad.json"));
    FAIL("no error for rigid_pairs \"hull\"");
  } catch (const InputError& e) {
    CHECK_THAT(e.what(), Contains("contact.rigid_pairs") && Contains("members") && Contains("hulls"));
  }
}

// Two finite-element items' pairs inside the step (contact.flexible_pairs "implicit": the two cabinets
// solved together, docs/contact/implicit_contact.md, "Flexible groups") against the explicit pairs, the
// cabinets at `full` on each other at rest under `stiff`.
TEST_CASE("contact.flexible_pairs: read, written back, the full cabinets rest on each other, named errors",
          "[scene][flexible_groups][errors]") {
  json j = stacked_scene({{0.0, 0.0}, {3.0, 0.0}}, 0.3, "stiff", "surfaces", "hulls", "full");
  // Unset: inside the step under `implicit` `all` (the default), the predictor's load under `rigid`.
  const SceneSpec unset = parse_scene_json(j, "default.json");
  CHECK_FALSE(unset.contact.flexible_pairs.has_value());
  CHECK(flexible_pair_contact(unset.contact) == FlexiblePairContact::implicit_step);
  CHECK_FALSE(to_json(unset)["contact"].contains("flexible_pairs"));  // written when set: older scene.json unchanged
  json paper_treatment = j;
  paper_treatment["contact"]["implicit"] = "rigid";
  CHECK(flexible_pair_contact(parse_scene_json(paper_treatment, "rigid.json").contact) == FlexiblePairContact::explicit_load);
  json apart_json = j;
  apart_json["contact"]["flexible_pairs"] = "explicit";
  const SceneSpec apart_spec = parse_scene_json(apart_json, "explicit.json");
  CHECK(parse_scene_json(to_json(apart_spec), "again.json").contact.flexible_pairs == FlexiblePairContact::explicit_load);
  j["contact"]["flexible_pairs"] = "implicit";
  const SceneSpec joint = parse_scene_json(j, "joint.json");
  CHECK(joint.contact.flexible_pairs == FlexiblePairContact::implicit_step);
  CHECK(parse_scene_json(to_json(joint), "again.json").contact.flexible_pairs == FlexiblePairContact::implicit_step);
  // At rest after 0.2 s of settling, 0.3 s more: with explicit pairs the stiff spring between the
  // frames, applied at the predictor, walks the upper cabinet (measured: 4.8 mm); solved together it
  // holds but for the panels' elastic settling (0.73 um; from 0.1 to 0.3 s, 9.7 um and 1.8 mm; the
  // frames of tests/contact_dynamics/stacked.cpp: 1e-17 m). Bounds: 10 um and 1 mm.
  Stack<SpringDashpotLaw> apart(apart_json), together(j), by_default(stacked_scene({{0.0, 0.0}, {3.0, 0.0}}, 0.3, "stiff", "surfaces", "hulls", "full"));
  CHECK_FALSE(apart.scene.sim->contact_model().flexible_pairs_implicit);
  CHECK(together.scene.sim->contact_model().flexible_pairs_implicit);
  CHECK(by_default.scene.sim->contact_model().flexible_pairs_implicit);
  const auto drift = [](Stack<SpringDashpotLaw>& s) {
    s.scene.sim->run_until(0.2);
    const Vec3 settled = s.slide();
    s.scene.sim->run_until(0.5);
    return (s.slide() - settled).norm();
  };
  const double explicit_drift = drift(apart), joint_drift = drift(together);
  INFO("drift 0.2 to 0.5 s: explicit pairs " << explicit_drift << " m, solved together " << joint_drift << " m");
  CHECK(joint_drift < 1e-5);
  CHECK(explicit_drift > 1e-3);
  const auto error_of = [](json bad) {
    try {
      validate(parse_scene_json(bad, "bad.json"));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  json needs_all = j;
  needs_all["contact"]["implicit"] = "rigid";
  CHECK_THAT(error_of(needs_all), Contains("contact.flexible_pairs") && Contains("\"implicit\": \"all\""));
  json unknown = j;
  unknown["contact"]["flexible_pairs"] = "joint";
  CHECK_THAT(error_of(unknown), Contains("contact.flexible_pairs") && Contains("explicit") && Contains("implicit"));
}

}  // namespace rigid_pairs_tests
