// Restraints in scenes (issue 49; docs/restraints/restraints.md, "Verification"): a rigid block tied to a
// wall carries the moment balance's force, breaks its ties when the closed form says and then overturns
// as a free block, rocks freely until a slack strap is taken up, and holds on mats below their peel
// strength and slides at the floor's friction above it; the energy ledger closes with ties breaking.
// The scene keys: read, written back, and each bad value named with its restraint and key.
#include <catch2/catch.hpp>

#include <furniture_fem/scene/scene_runner.hpp>

#include "../support/scene_input.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace furniture_fem;
using nlohmann::json;
using Catch::Matchers::Contains;

namespace restraint_scene_tests {  // this file's own names (its group compiles files in batches)

namespace {

constexpr double g = 9.80665;

struct Block {
  double W, D, H, h, M;
};

// A rigid block (mu 0.9 on the floor: it rocks, it does not slide) standing 5 cm from the +X wall, tied
// to it by two restraints of `kind` from its top corners on that side; the table's acceleration along +X
// is `x_points`. Under it the block leans toward -X, away from the wall, and the ties pull it back.
json tied_block(const Block& c, const json& x_points, const json& values, double duration, const std::string& kind = "strap") {
  json restraints = json::array();
  for (const char* corner : {"top_front_right", "top_back_right"}) {
    json r = {{"name", std::string("tie_") + corner}, {"kind", kind}, {"item", "crate"}, {"point", corner}, {"wall", "wall_plus_x"}};
    r.update(values);
    restraints.push_back(r);
  }
  return {{"name", "tied block"},
          {"items", {{{"kind", "block"},
                      {"name", "crate"},
                      {"fidelity", "rigid"},
                      {"x", 2.0 - 0.5 * c.W - 0.05},
                      {"params", {{"width", c.W}, {"depth", c.D}, {"height", c.H}, {"cog_h", c.h}, {"mass_kg", c.M},
                                  {"mu_floor_long", 0.9}, {"mu_floor_short", 0.9}}}}}},
          {"restraints", restraints},
          {"ground_motion", {{"source", "points"}, {"x", x_points}}},
          {"contact", {{"law", "stiff"}}},
          {"duration", duration},
          {"dt", 0.001},
          {"outputs", {{"figures", false}}}};
}

// The block's lever arms from its model: the pivot (its bottom nodes farthest toward -X), its centre of
// gravity and the height of its ties' nodes, all at rest.
struct Levers {
  double M, pivot_x, pivot_z, cog_x, cog_z, tie_z;
  // The ties' total horizontal force that holds the block upright under table acceleration a (moments
  // about the pivot): M (a (z_cog - z_p) - g (x_cog - x_p)) / (z_tie - z_p).
  double holding_force(double a) const { return M * (a * (cog_z - pivot_z) - g * (cog_x - pivot_x)) / (tie_z - pivot_z); }
  // The table acceleration at which the block starts to tip free: g b / h about its pivot.
  double tipping_acceleration() const { return g * (cog_x - pivot_x) / (cog_z - pivot_z); }
};
template <class Scene>
Levers levers_of(const Scene& scene) {
  const Model& m = *scene.model;
  const ItemInfo& it = scene.items[0];
  Levers l{};
  l.M = m.body_mass(it.body);
  l.pivot_x = 1e9;
  for (int n : it.bottom_nodes) l.pivot_x = std::min(l.pivot_x, m.node(n).X.x());
  l.pivot_z = m.node(it.bottom_nodes.front()).X.z();
  const Vec3 cog = m.body_centre_of_gravity(it.body);
  l.cog_x = cog.x();
  l.cog_z = cog.z();
  l.tie_z = scene.sim->contact_model().restraints()[0].rest.z();
  return l;
}

template <class Scene>
double tilt_deg(const Scene& scene) {
  const int hub = scene.items[0].marker("cog")->node;
  return std::acos(std::clamp(scene.sim->rotation(hub)(2, 2), -1.0, 1.0)) * 180 / std::acos(-1.0);
}

template <class Scene>
double ties_force(const Scene& scene) {
  double sum = 0;
  for (const auto& s : scene.sim->contact_model().restraints().states()) sum += s.force;
  return sum;
}

SceneSpec read(const json& j) { return ffem_test::validated_scene(j, "restraints.json"); }

std::string read_error(const json& j) { return ffem_test::scene_error(j, "restraints.json"); }

}  // namespace

TEST_CASE("a block tied to a wall at its top carries the moment balance's force in its ties", "[scene][restraints][dynamics]") {
  // The table's acceleration rises from 0 at 0.3 s to a_over * g b/h at 1.3 s and holds. Leaning on its
  // pivot (its heel lifted), the block is held by its ties alone: their moment about the pivot equals
  // M a (z_g - z_p) - M g (x_g - x_p), taken at the block's pose (it leans by the ties' stretch, about
  // 0.02 deg, which moves the arms by up to 0.2 %), averaged over 2.5-3 s (the block rings on its ties
  // after the ramp). The ties' moment: each one's force as reported, at its node. Bound 0.5 % (issue 49).
  // The ties' own stiffness (defaults): far stiffer ties (2e6 N/m) cannot lean the block enough to lift
  // its heel off the floor's penalty (a few um), and the floor then shares the moment (the ties carried
  // 55 N where the balance says 33).
  for (const Block c : {Block{0.3, 0.4, 0.9, 0.45, 40}, Block{0.4, 0.45, 1.8, 0.9, 80}, Block{0.5, 0.4, 1.2, 0.5, 120}}) {
    for (const std::string kind : {"strap", "l_bracket"}) {
      INFO(kind << " on a block " << c.W << " x " << c.H << " m, cog at " << c.h << " m, " << c.M << " kg");
      const double a_over = kind == "strap" ? 1.5 : 1.3;
      json values = {{"strength", 1e4}};
      if (kind == "l_bracket") values.update({{"shear_stiffness", 1e-3}, {"shear_strength", 1e4}, {"softening", 0.5}});
      const double gbh = g * 0.5 * c.W * (1 - 0.005 / c.h) / (c.h - 0.005);  // about the block's pivot
      const double a = a_over * gbh;
      const SceneSpec spec = read(tied_block(c, {{0.3, 0.0}, {1.3, a}, {5.0, a}}, values, 3.0, kind));
      SceneSimulation<DirectLdltSolver> scene(spec);
      REQUIRE(levers_of(scene).tipping_acceleration() == Approx(gbh).epsilon(1e-3));
      const ItemInfo& it = scene.items[0];
      const Model& m = *scene.model;
      const RestraintSet& ties = scene.sim->contact_model().restraints();
      int toe = it.bottom_nodes.front();
      for (int n : it.bottom_nodes)
        if (m.node(n).X.x() < m.node(toe).X.x()) toe = n;
      double ties_moment = 0, balance = 0;
      int rows = 0;
      while (scene.sim->time() < 3.0 - 1e-9) {
        scene.sim->step();
        if (scene.sim->time() <= 2.5) continue;
        const Vec3 p = scene.sim->position(toe);
        const Vec3 cog = m.body_centre_of_gravity(it.body, [&](int n) -> const Vec3& { return scene.sim->position(n); });
        balance += m.body_mass(it.body) * (a * (cog.z() - p.z()) - g * (cog.x() - p.x()));
        for (std::size_t i = 0; i < ties.size(); ++i) {
          const Vec3 r = scene.sim->position(ties[i].node) - p, f = ties.states()[i].on_item;
          ties_moment += r.z() * f.x() - r.x() * f.z();
        }
        ++rows;
      }
      INFO("ties' moment " << ties_moment / rows << " N m, balance " << balance / rows << " N m; tilt " << tilt_deg(scene) << " deg");
      CHECK(ties_moment / rows == Approx(balance / rows).epsilon(0.005));
      CHECK(tilt_deg(scene) < 0.5);
    }
  }
}

TEST_CASE("a tie weaker than the holding force breaks when the closed form says, and the block then overturns", "[scene][restraints][dynamics]") {
  // The table's acceleration rises at r = 3 m/s^2 per s from 0.3 s: the ties' force follows the moment
  // balance (quasi-static: the block on its ties rings at ~10 Hz, far above the ramp's pace), so each
  // tie of strength S breaks when holding_force(a) = 2 S, at t = 0.3 + a_b / r. Bound: 1 % of that
  // acceleration (0.01 a_b / r in time). Strengths 5 % and 15 % of the block's weight: it breaks them
  // before it could slide (mu 0.9).
  for (const Block c : {Block{0.3, 0.4, 0.9, 0.45, 40}, Block{0.4, 0.45, 1.8, 0.9, 80}}) {
    for (const double share : {0.05, 0.15}) {
      const double S = share * c.M * g;
      INFO("block " << c.W << " x " << c.H << " m, " << c.M << " kg, ties of " << S << " N");
      const double r = 3.0;
      const SceneSpec spec = read(tied_block(c, {{0.3, 0.0}, {10.3, 10.0 * r}}, {{"strength", S}}, 6.0));
      SceneSimulation<DirectLdltSolver> scene(spec);
      const Levers l = levers_of(scene);
      // holding_force(a) = 2 S, solved for a.
      const double a_b = (2 * S * (l.tie_z - l.pivot_z) / l.M + g * (l.cog_x - l.pivot_x)) / (l.cog_z - l.pivot_z);
      const double t_b = 0.3 + a_b / r;
      double largest = 0;
      while (scene.sim->time() < std::min(t_b + 1.5, 6.0) - 1e-9) {
        scene.sim->step();
        largest = std::max(largest, tilt_deg(scene));
      }
      const auto& states = scene.sim->contact_model().restraints().states();
      for (const auto& s : states) {
        INFO("broke at " << s.broke_at << " s, closed form " << t_b << " s");
        CHECK(s.failure == RestraintFailure::tension);
        CHECK(std::abs(s.broke_at - t_b) <= 0.01 * a_b / r);
      }
      CHECK(largest > 60);
    }
  }
}

TEST_CASE("a block on slack straps rocks freely until the slack is taken up, then is held", "[scene][restraints][dynamics]") {
  // Tipping about its toe by theta, a tie's node moves on a circle about the toe: the strap is taut when
  // its distance to the anchor reaches its length at rest plus the slack. Under 1.3 g b/h applied within
  // 10 ms the block tips free. At every step the closed form (the block turned rigidly by its tilt about
  // its toe where the toe is then: the floor's friction lets the toe give by a fraction of a mm) says
  // whether the strap is taut; it must agree with the strap's own state wherever the closed form's
  // stretch is more than 1 % of the slack from zero. The block is caught: its largest tilt passes the
  // take-up tilt and stays below 3 times it (it does not overturn).
  const Block c{0.3, 0.4, 0.9, 0.45, 40};
  for (const double slack : {0.01, 0.03}) {
    INFO("slack " << slack << " m");
    const double gbh = g * 0.5 * c.W * (1 - 0.005 / c.h) / (c.h - 0.005);
    const double a = 1.3 * gbh;
    const SceneSpec spec = read(tied_block(c, {{0.3, 0.0}, {0.31, a}, {5.0, a}}, {{"slack", slack}, {"strength", 1e5}}, 3.0));
    SceneSimulation<DirectLdltSolver> scene(spec);
    const Model& m = *scene.model;
    const RestraintSet& ties = scene.sim->contact_model().restraints();
    const Restraint& tie = ties[0];
    int toe = scene.items[0].bottom_nodes.front();
    for (int n : scene.items[0].bottom_nodes)
      if (m.node(n).X.x() < m.node(toe).X.x() - 1e-9 ||
          (std::abs(m.node(n).X.x() - m.node(toe).X.x()) < 1e-9 && std::abs(m.node(n).X.y() - tie.rest.y()) < std::abs(m.node(toe).X.y() - tie.rest.y())))
        toe = n;
    const Vec3 r0 = tie.rest - m.node(toe).X;
    const double taut = (tie.rest - tie.anchor).norm() + slack;
    // The closed form's stretch of the strap at tilt th (rad) about the toe at `p`.
    const auto stretch_at = [&](double th, const Vec3& p) {
      const Vec3 turned(r0.x() * std::cos(th) - r0.z() * std::sin(th), r0.y(), r0.x() * std::sin(th) + r0.z() * std::cos(th));
      return (p + turned - tie.anchor).norm() - taut;
    };
    double theta_taut = 0;
    {
      double lo = 0, hi = 0.5;
      for (int i = 0; i < 100; ++i) (stretch_at(0.5 * (lo + hi), m.node(toe).X) < 0 ? lo : hi) = 0.5 * (lo + hi);
      theta_taut = 0.5 * (lo + hi) * 180 / std::acos(-1.0);
    }
    double largest = 0;
    int disagreements = 0, judged = 0;
    while (scene.sim->time() < 3.0 - 1e-9) {
      scene.sim->step();
      const double tilt = tilt_deg(scene);
      largest = std::max(largest, tilt);
      const double e = stretch_at(tilt * std::acos(-1.0) / 180, scene.sim->position(toe));
      if (std::abs(e) < 0.01 * slack) continue;
      ++judged;
      if ((e > 0) != (ties.states()[0].force > 0)) ++disagreements;
    }
    INFO("slack taken up at " << theta_taut << " deg (toe at rest); largest tilt " << largest << " deg; "
                              << disagreements << " of " << judged << " steps disagree");
    CHECK(disagreements == 0);
    CHECK(judged > 1000);
    CHECK(largest > theta_taut);
    CHECK(largest < 3 * theta_taut);
  }
}

namespace {
// A low rigid block (0.6 x 0.6 x 0.3 m: it would tip only at 2 g) at x = 1 m on four mats at its bottom
// corners, the table's acceleration rising from 0.3 s to a at 4.3 s and held to 4.8 s.
json block_on_mats(double M, double mu, double peel, double a) {
  json restraints = json::array();
  for (const char* corner : {"bottom_front_left", "bottom_front_right", "bottom_back_left", "bottom_back_right"})
    restraints.push_back({{"name", std::string("mat_") + corner}, {"kind", "mat"}, {"item", "crate"}, {"point", corner},
                          {"strength", peel}, {"tension_strength", 1e4}});
  return {{"name", "block on mats"},
          {"items", {{{"kind", "block"},
                      {"name", "crate"},
                      {"fidelity", "rigid"},
                      {"x", 1.0},
                      {"params", {{"width", 0.6}, {"depth", 0.6}, {"height", 0.3}, {"mass_kg", M},
                                  {"mu_floor_long", mu}, {"mu_floor_short", mu}}}}}},
          {"restraints", restraints},
          {"ground_motion", {{"source", "points"}, {"x", {{0.3, 0.0}, {4.3, a}, {6.0, a}}}}},
          {"duration", 4.8},
          {"dt", 0.001},
          {"outputs", {{"figures", false}}}};
}
}  // namespace

TEST_CASE("a block on mats holds below their peel strength and slides at the floor's friction above it", "[scene][restraints][dynamics]") {
  // Friction sticks up to mu M g, the mats take the rest: each of the four carries (M a - mu M g) / 4,
  // and they peel when that reaches their strength F, at a* = mu g + 4 F / M. The ramp is slow (4 s):
  // sliding on the mats' springs (2.8 Hz for 200 kg) the block overshoots its static place by
  // M a' / (4 k w), 0.2 mm against the 0.9 mm to the peel at 0.9 a*. Below (0.9 a*) the block stands on
  // the mats' shear, displaced (M a - mu M g) / (4 k) (bound 5 %: the friction's own give); above
  // (1.1 a*) they peel and the block slides with a - mu g relative to the table from then on,
  // from its position and velocity when they peeled (bound 5 %: the paper law's friction follows its
  // oscillating normal force, test_points_and_block).
  struct Case {
    double M, mu, F;
  };
  for (const Case c : {Case{200, 0.3, 150}, Case{120, 0.5, 100}}) {
    const double a_star = c.mu * g + 4 * c.F / c.M;
    for (const double f : {0.9, 1.1}) {
      INFO(c.M << " kg, mu " << c.mu << ", mats of " << c.F << " N, a = " << f << " a* (a* = " << a_star << " m/s^2)");
      const double a = f * a_star;
      const SceneSpec spec = read(block_on_mats(c.M, c.mu, c.F, a));
      SceneSimulation<DirectLdltSolver> scene(spec);
      const int hub = scene.items[0].marker("cog")->node;
      const double k = scene.sim->contact_model().restraints()[0].p.stiffness;
      double peeled_at = -1;
      double x_peel = 0, v_peel = 0;
      while (scene.sim->time() < 4.8 - 1e-9) {
        scene.sim->step();
        const auto& states = scene.sim->contact_model().restraints().states();
        if (peeled_at < 0 && std::all_of(states.begin(), states.end(), [](const RestraintState& s) { return s.broken(); })) {
          peeled_at = scene.sim->time();
          x_peel = scene.sim->displacement(hub).x();
          v_peel = scene.sim->velocity(hub).x();
        }
      }
      const double x = scene.sim->displacement(hub).x();
      if (f < 1) {
        CHECK(peeled_at < 0);
        const double expected = -(c.M * a - c.mu * c.M * g) / (4 * k);
        INFO("displaced " << x << " m, closed form " << expected << " m");
        CHECK(x == Approx(expected).epsilon(0.05));
      } else {
        REQUIRE(peeled_at > 0);
        for (const auto& s : scene.sim->contact_model().restraints().states()) CHECK(s.failure == RestraintFailure::peel);
        // Peeled while the acceleration still rose (before 4.3 s): a(t) from the ramp; after 4.3 s, a.
        const auto a_at = [&](double t) { return t < 4.3 ? a * (t - 0.3) / 4.0 : a; };
        // Relative to the table: x'' = -(a(t) - mu g) from the state at the peel, integrated over 1 ms
        // steps (exact for the piecewise-linear a(t)).
        double v = v_peel, xs = 0;
        for (double t = peeled_at; t < 4.8 - 1e-9; t += 1e-3) {
          const double acc0 = -(a_at(t) - c.mu * g), acc1 = -(a_at(t + 1e-3) - c.mu * g);
          xs += 1e-3 * v + 1e-6 * (2 * acc0 + acc1) / 6;
          v += 0.5e-3 * (acc0 + acc1);
        }
        INFO("peeled at " << peeled_at << " s; slid " << x - x_peel << " m after, closed form " << xs << " m");
        CHECK(x - x_peel == Approx(xs).epsilon(0.05));
      }
    }
  }
}

namespace {
// A low rigid block (0.6 x 0.6 x 0.4 m, 30 kg, mu 0.3 on the floor) under a ceiling 0.6 m up, held by two
// poles on its diagonal top corners, the table's acceleration rising from 0.3 s to a at 3.3 s and held
// to 4 s. The `stiff` law: a pole's preload is set against the item's place at the start, and the paper
// law's soft floor gives way under it (this block sank 0.3 mm under the poles' 200 N and their force
// fell to 66 and 73 N; docs/restraints/restraints.md).
json block_under_poles(double preload, double pad_mu, double a) {
  json restraints = json::array();
  for (const char* corner : {"top_front_left", "top_back_right"})
    restraints.push_back({{"name", std::string("pole_") + corner}, {"kind", "pole"}, {"item", "crate"}, {"point", corner},
                          {"preload", preload}, {"friction", pad_mu}});
  return {{"name", "block under poles"},
          {"ceiling", {{"height", 0.6}}},
          {"items", {{{"kind", "block"},
                      {"name", "crate"},
                      {"fidelity", "rigid"},
                      {"params", {{"width", 0.6}, {"depth", 0.6}, {"height", 0.4}, {"mass_kg", 30.0},
                                  {"mu_floor_long", 0.3}, {"mu_floor_short", 0.3}}}}}},
          {"restraints", restraints},
          {"ground_motion", {{"source", "points"}, {"x", {{0.3, 0.0}, {3.3, a}, {5.0, a}}}}},
          {"contact", {{"law", "stiff"}}},
          {"duration", 4.0},
          {"dt", 0.001},
          {"outputs", {{"figures", false}}}};
}
}  // namespace

TEST_CASE("a pole's preload raises what friction holds by the floor's and the pad's mu times the preload", "[scene][restraints][dynamics]") {
  // Two poles press the block down with P each: the floor's friction holds mu_f (M g + 2 P) and the
  // poles' pads mu_c 2 P, so the block slides above a* = (mu_f (M g + 2 P) + 2 mu_c P) / M, against
  // mu_f g without poles. At 0.95 a* it stands (it moves by the pads' give, 2 mu_c P / k_l at most,
  // 1.2 mm, plus the floor friction's: bound 3 mm); at 1.05 a* it slides (more than 5 cm by 4 s).
  for (const double pad_mu : {0.3, 0.6}) {
    const double P = 100, M = 30;
    const double a_star = (0.3 * (M * g + 2 * P) + 2 * pad_mu * P) / M;
    for (const double f : {0.95, 1.05}) {
      INFO("pad mu " << pad_mu << ", a = " << f << " a* (a* = " << a_star << " m/s^2, without poles " << 0.3 * g << ")");
      const SceneSpec spec = read(block_under_poles(P, pad_mu, f * a_star));
      SceneSimulation<DirectLdltSolver> scene(spec);
      const int hub = scene.items[0].marker("cog")->node;
      scene.sim->run_until(0.3);
      const double x0 = scene.sim->displacement(hub).x();
      scene.sim->run_until(4.0);
      const double moved = scene.sim->displacement(hub).x() - x0;
      const auto& states = scene.sim->contact_model().restraints().states();
      INFO("moved " << moved << " m; pole forces " << states[0].force << ", " << states[1].force << " N");
      for (const auto& st : states) CHECK(st.force == Approx(P).epsilon(0.02));  // the block neither rises nor sinks
      if (f < 1) CHECK(std::abs(moved) < 3e-3);
      else CHECK(moved < -0.05);
    }
  }
}

TEST_CASE("a run whose brackets yield and whose strap breaks writes its outputs, and its energy ledger closes", "[scene][restraints][dynamics]") {
  // A block held by two weak brackets (15 N, a long plateau) and a stiff, weaker strap (15 N) at its top:
  // the table's acceleration rises to 1.52 g b/h and back to zero. The strap takes 80 % of the holding
  // force (its stiffness against the brackets') and breaks near 1.3 g b/h; the brackets then yield on
  // their plateau while the demand exceeds their 30 N, and hold; the block comes back upright. What each
  // dissipated: a bracket its strength times its plastic pull (the plateau's area), the strap what it
  // stored when it broke, S^2 / (2 k) (bound 5 %: the trapezoidal work of the step it broke in adds half
  // its force times that step's travel, 0.35 um against the 15 um it had stretched: 2.3 % measured). The
  // run's energy ledger (its contact work holds the restraints') closes within its 5 % tolerance. The
  // brackets' shear is nearly free here: a bracket's default shear stiffness carries most of the moment
  // by the corner's rise (60 % for this block) and its pull would not reach its strength.
  const Block c{0.3, 0.4, 0.9, 0.45, 40};
  const double gbh = g * 0.5 * c.W * (1 - 0.005 / c.h) / (c.h - 0.005);
  json j = tied_block(c, {{0.3, 0.0}, {2.3, 1.52 * gbh}, {3.3, 0.0}}, {{"strength", 15}, {"plateau", 0.05}, {"softening", 0.05}, {"shear_stiffness", 1e-3}},
                      5.0, "l_bracket");
  j["restraints"].push_back({{"name", "strap"}, {"kind", "strap"}, {"item", "crate"}, {"point", "top_front_right"},
                             {"wall", "wall_plus_x"}, {"stiffness", 1e6}, {"strength", 15}});
  const SceneSpec spec = read(j);
  const std::string out = std::string(FFEM_TEST_TMP) + "/restraints_run";
  std::filesystem::remove_all(out);
  RunOptions o;
  o.out_dir = out;
  o.progress = false;
  o.forecast = false;
  o.threads = 1;
  const RunSummary sum = run_scene(spec, o);
  REQUIRE(sum.status == "completed");
  INFO(sum.energy.text);
  CHECK(sum.energy.closes);
  REQUIRE(sum.restraints.size() == 3);
  for (int i = 0; i < 2; ++i) {
    const RestraintOutcome& b = sum.restraints[i];
    INFO(b.name << ": peak " << b.peak_force << " N, dissipated " << b.dissipated << " J");
    CHECK_FALSE(b.broke);
    CHECK(b.peak_ratio == Approx(1.0));
    CHECK(b.dissipated > 0);
  }
  const RestraintOutcome& strap = sum.restraints[2];
  CHECK(strap.broke);
  CHECK(strap.failure == "tension");
  CHECK(strap.dissipated == Approx(15.0 * 15.0 / (2 * 1e6)).epsilon(0.05));
  // restraints.csv's last row: each bracket's plastic pull from its state gives its dissipated energy.
  std::ifstream csv(out + "/restraints.csv");
  std::string header, line, last;
  std::getline(csv, header);
  CHECK(header == "t,tie_top_front_right_force,tie_top_front_right_extension,tie_top_front_right_regime,"
                  "tie_top_back_right_force,tie_top_back_right_extension,tie_top_back_right_regime,"
                  "strap_force,strap_extension,strap_regime");
  while (std::getline(csv, line)) last = line;
  CHECK(last.substr(last.rfind(',') + 1) == "5");  // the strap: broken
  const json summary = json::parse(std::ifstream(out + "/summary.json"));
  REQUIRE(summary.at("restraints").size() == 3);
  CHECK(summary.at("restraints")[2].at("failure") == "tension");
  CHECK(summary.at("restraints")[0].at("broke_at_s").is_null());
}

TEST_CASE("a bracket's dissipated energy is its strength times its plastic pull", "[scene][restraints][dynamics]") {
  // The same run stepped here, the brackets' states read: D = F_u p for a bracket that yielded on its
  // plateau and unloaded elastically (the area inside its force-pull path), bound 2 %.
  const Block c{0.3, 0.4, 0.9, 0.45, 40};
  const double gbh = g * 0.5 * c.W * (1 - 0.005 / c.h) / (c.h - 0.005);
  const SceneSpec spec = read(tied_block(c, {{0.3, 0.0}, {2.3, 1.52 * gbh}, {3.3, 0.0}},
                                         {{"strength", 15}, {"plateau", 0.05}, {"softening", 0.05}, {"shear_stiffness", 1e-3}}, 5.0, "l_bracket"));
  SceneSimulation<DirectLdltSolver> scene(spec);
  scene.sim->run_until(5.0);
  const RestraintSet& set = scene.sim->contact_model().restraints();
  for (std::size_t i = 0; i < set.size(); ++i) {
    const RestraintState& s = set.states()[i];
    INFO(set[i].name << ": plastic pull " << s.plastic << " m, dissipated " << set.dissipated_energy(i) << " J");
    REQUIRE(s.plastic > 1e-4);
    CHECK(set.dissipated_energy(i) == Approx(15.0 * s.plastic).epsilon(0.02));
  }
}

TEST_CASE("a flexible locker breaks its straps where the rigid one does, about the edge it pivots on", "[scene][restraints][dynamics]") {
  // Issue 49's `full` against `rigid` in one scene: a locker (0.9 x 0.515 x 1.79 m, 45.2 kg, mu 0.9) with its
  // back 3 cm from the +X wall, tied by two 30 N straps at its top back corners, the table's acceleration
  // rising at 2 m/s^2 per s from 0.3 s: the straps break at a_b = 2 (t_b - 0.3), where the moments about
  // its pivot balance: a_b = (2 S (z_tie - z_p) / M + g (x_g - x_p)) / (z_g - z_p). The pivot: its front
  // bottom nodes with contact at the members' centre lines; their tubes' outer edge, 25 mm out and down, at
  // the surfaces. Bounds: rigid 0.5 % of the closed form (the block tests' bound); `full` 2 % (issue 49).
  // At the surfaces the flexible locker, barely tilted (0.3 mrad: its straps hold it), still bears on the
  // back corners of each node's cube too, so it pivots at its centre lines, 3.7 % below the rigid locker
  // (docs/restraints/restraints.md, "`full` against `rigid`"); not its frame's give: ten times its members'
  // stiffness moves a_b by under 0.1 %.
  struct Break {
    double a_b, about_nodes, about_edge;  // measured; the closed form about the nodes, about the outer edge
  };
  const auto strap_break = [](const std::string& fidelity, const std::string& contact_at, double stiffness = 1) {
    json params = {{"mu_floor_long", 0.9}, {"mu_floor_short", 0.9}};
    if (stiffness != 1) params["stiffness_scale"] = stiffness;
    json straps = json::array();
    for (const char* corner : {"top_back_left", "top_back_right"})
      straps.push_back({{"name", corner}, {"kind", "strap"}, {"item", "locker"}, {"point", corner}, {"wall", "wall_plus_x"}, {"strength", 30.0}});
    const json j = {{"name", "strapped locker"},
                    {"items", {{{"kind", "locker"}, {"name", "locker"}, {"fidelity", fidelity}, {"yaw_deg", -90.0}, {"x", 1.7125}, {"params", params}}}},
                    {"restraints", straps},
                    {"ground_motion", {{"source", "points"}, {"x", {{0.3, 0.0}, {6.3, 12.0}}}}},
                    {"contact", {{"law", "stiff"}, {"plane_contact_at", contact_at}}},
                    {"duration", 3.3},
                    {"dt", 0.001},
                    {"outputs", {{"figures", false}}}};
    SceneSimulation<DirectLdltSolver> scene(read(j));
    const Model& m = *scene.model;
    const ItemInfo& it = scene.items[0];
    double x_p = 1e9;
    for (int n : it.bottom_nodes) x_p = std::min(x_p, m.node(n).X.x());
    const double z_p = m.node(it.bottom_nodes.front()).X.z(), half = 0.025;  // the 50 x 30 tubes' half width
    const Vec3 cog = m.body_centre_of_gravity(it.body);
    const double M = m.body_mass(it.body), z_tie = scene.sim->contact_model().restraints()[0].rest.z();
    const auto closed_form = [&](double xp, double zp) { return (2 * 30.0 * (z_tie - zp) / M + g * (cog.x() - xp)) / (cog.z() - zp); };
    const auto& states = scene.sim->contact_model().restraints().states();
    while (scene.sim->time() < 3.3 - 1e-9 && !(states[0].broken() && states[1].broken())) scene.sim->step();
    REQUIRE(states[0].broken());
    REQUIRE(states[1].broken());
    return Break{2.0 * (std::max(states[0].broke_at, states[1].broke_at) - 0.3), closed_form(x_p, z_p), closed_form(x_p - half, z_p - half)};
  };
  const Break rigid_lines = strap_break("rigid", "centre_lines"), full_lines = strap_break("full", "centre_lines");
  const Break rigid_surface = strap_break("rigid", "surfaces"), full_surface = strap_break("full", "surfaces");
  const Break full_stiffer = strap_break("full", "surfaces", 10);
  INFO("closed form about the nodes " << rigid_lines.about_nodes << ", about the edge " << rigid_lines.about_edge << " m/s^2; a_b at the centre lines: rigid "
       << rigid_lines.a_b << ", full " << full_lines.a_b << "; at the surfaces: rigid " << rigid_surface.a_b << ", full " << full_surface.a_b
       << ", ten times stiffer " << full_stiffer.a_b);
  CHECK(rigid_lines.a_b == Approx(rigid_lines.about_nodes).epsilon(0.005));
  CHECK(rigid_surface.a_b == Approx(rigid_surface.about_edge).epsilon(0.005));
  CHECK(full_lines.a_b == Approx(rigid_lines.a_b).epsilon(0.02));
  CHECK(full_lines.a_b == Approx(full_lines.about_nodes).epsilon(0.02));
  CHECK(full_surface.a_b == Approx(full_surface.about_nodes).epsilon(0.02));
  CHECK(full_stiffer.a_b == Approx(full_surface.a_b).epsilon(1e-3));
}

TEST_CASE("a finite-element item's stiff restraints outside the implicit step are refused where they would ring", "[scene][restraints][dynamics]") {
  // A `full` tall cabinet bracketed to the wall behind it at its top back corners (1.7e6 N/m across the
  // pull on nodes of about 21 g: stable to about 0.22 ms as a load), its contact outside the step
  // (implicit "rigid"), nudged along the wall by 0.2 m/s^2 for 0.1 s. At dt 1 ms the run is refused;
  // run anyway, the brackets ring and shear off (what the refusal guards against; stop 75's fastening
  // study at full fidelity lost every bracket so); inside the step, or at dt 0.4 ms, they hold.
  json j = {{"name", "bracketed full cabinet"},
            {"dt", 1e-3},
            {"duration", 0.4},
            {"items", {{{"kind", "tall_cabinet"}, {"name", "cab"}, {"fidelity", "full"}, {"x", 2.0 - 0.03 - 0.2}, {"yaw_deg", -90.0}}}},
            {"walls", {{{"name", "wall_plus_x"}, {"point", {2.0, 0.0, 0.0}}, {"normal", {-1.0, 0.0, 0.0}}, {"width", 4.0}, {"height", 2.5}}}},
            {"restraints", {{{"name", "left"}, {"kind", "l_bracket"}, {"item", "cab"}, {"point", "top_back_left"}, {"wall", "wall_plus_x"}},
                            {{"name", "right"}, {"kind", "l_bracket"}, {"item", "cab"}, {"point", "top_back_right"}, {"wall", "wall_plus_x"}}}},
            {"ground_motion", {{"source", "points"}, {"x", {{0.0, 0.0}, {10.0, 0.0}}}, {"y", {{0.0, 0.0}, {0.05, 0.2}, {0.1, 0.0}, {10.0, 0.0}}}}},
            {"contact", {{"implicit", "rigid"}}},
            {"outputs", {{"figures", false}}}};
  RunOptions o;
  o.write_files = false;
  o.progress = false;
  o.forecast = false;
  o.threads = 1;
  const auto run = [&](const json& scene) { return run_scene(read(scene), o); };
  const std::string refused = ffem_test::input_error([&] { (void)run(j); });
  CHECK_THAT(refused, Contains("restraints[0]") && Contains("'left'") && Contains("1.7e+06 N/m") && Contains("dt 0.001 s") &&
                          Contains("contact.implicit \"all\""));
  json coarse = j;
  coarse["allow_coarse_dt"] = true;
  for (const RestraintOutcome& b : run(coarse).restraints) {
    CAPTURE(b.name);
    CHECK(b.broke);
    CHECK(b.failure == "shear");
  }
  json inside = j;
  inside["contact"]["implicit"] = "all";
  json finer = j;
  finer["dt"] = 4e-4;
  for (const json& held : {inside, finer}) {
    const RunSummary sum = run(held);
    CHECK(sum.status == "completed");
    for (const RestraintOutcome& b : sum.restraints) {
      CAPTURE(b.name, held["dt"].get<double>());
      CHECK_FALSE(b.broke);
      CHECK(b.peak_force < 40.0);  // its share of the cabinet's lean on the wall, not a ringing node
    }
  }
}

TEST_CASE("restraints are read, written back, and each bad value is named with its restraint and key", "[scene][restraints][json]") {
  const Block c{0.3, 0.4, 0.9, 0.45, 40};
  const json good = tied_block(c, {{0.3, 0.0}, {1.3, 1.0}}, {{"stiffness", 8e4}}, 1.0, "l_bracket");
  const SceneSpec s = read(good);
  REQUIRE(s.restraints.size() == 2);
  CHECK(s.restraints[0].kind == RestraintKind::l_bracket);
  CHECK(s.restraints[0].values.at("stiffness") == 8e4);
  const json once = to_json(s);
  CHECK(to_json(parse_scene_json(once, "again")) == once);
  CHECK(once.at("restraints")[0].at("screws") == "stud");

  const auto with = [&](const char* key, const json& value) {
    json j = good;
    j["restraints"][0][key] = value;
    return read_error(j);
  };
  CHECK_THAT(with("strength", -5), Contains("restraints[0].strength") && Contains("got -5"));
  CHECK_THAT(with("preload", 10), Contains("restraints[0]") && Contains("preload") && Contains("allowed here"));
  CHECK_THAT(with("point", "top_middle_nowhere"), Contains("restraints[0].point") && Contains("top_back_left"));
  CHECK_THAT(with("item", "sofa"), Contains("restraints[0].item") && Contains("no item named \"sofa\""));
  CHECK_THAT(with("wall", "wall_minus_x"), Contains("restraints[0].wall") && Contains("reaches 0.15 m"));
  CHECK_THAT(with("wall", "north"), Contains("restraints[0].wall") && Contains("no wall named \"north\""));
  CHECK_THAT(with("kind", "glue"), Contains("restraints[0].kind") && Contains("l_bracket, strap, mat, pole"));
  CHECK_THAT(with("screws", "concrete"), Contains("restraints[0].screws") && Contains("\"stud\" or \"board\""));
  CHECK_THAT(with("softening", 0.001), Contains("tie_top_front_right") && Contains("softening"));
  json mat = good;
  mat["restraints"][0] = {{"kind", "mat"}, {"item", "crate"}, {"point", "top_front_left"}};
  CHECK_THAT(read_error(mat), Contains("restraints[0].point") && Contains("under the item's base"));
  json pole = good;
  pole["restraints"][0] = {{"kind", "pole"}, {"item", "crate"}, {"point", "top_front_left"}};
  CHECK_THAT(with("point", "top_centre"), Contains("restraints[0].point") && Contains("no node of \"crate\" within 0.1 m"));
  CHECK_THAT(read_error(pole), Contains("restraints[0]") && Contains("ceiling"));
  json twice = good;
  twice["restraints"][1]["name"] = twice["restraints"][0]["name"];
  CHECK_THAT(read_error(twice), Contains("restraints[1].name") && Contains("duplicate"));
}

}  // namespace restraint_scene_tests

namespace restraint_scene_tests {

TEST_CASE("a marker may name a point of its item's box, as a restraint does", "[scene][restraints][markers]") {
  // "crate.top_front_left": no builder marker of a block has that name; the box's point (-W/2, -D/2, H)
  // in the item frame, its nearest node the block's top front left corner. A name neither a marker nor a
  // box point is an error listing both.
  const Block c{0.3, 0.4, 0.9, 0.45, 40};
  json j = tied_block(c, {{0.3, 0.0}, {1.3, 1.0}}, json::object(), 1.0);
  j["outputs"]["markers"] = {"crate.top_front_left", "crate.cog"};
  const SceneSpec spec = read(j);
  Model model;
  const auto items = build_scene(spec, model);
  const ResolvedOutputs out = resolve_output_requests(spec, model, items);
  REQUIRE(out.markers.size() == 2);
  const Vec3 corner = items[0].to_world(Vec3(-0.5 * c.W, -0.5 * c.D, c.H));
  CHECK(out.markers[0].node == nearest_node(model, items[0].body, corner));
  CHECK((model.node(out.markers[0].node).X - corner).norm() < 0.01);  // the corner node, 5 mm inside each face
  CHECK(out.markers[1].node == items[0].marker("cog")->node);
  j["outputs"]["markers"] = {"crate.top_middle"};
  CHECK_THAT(read_error(j), Contains("outputs.markers[0]") && Contains("has no marker \"top_middle\"") &&
                               Contains("cog") && Contains("bottom_back_right"));
}

}  // namespace restraint_scene_tests
