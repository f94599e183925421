// Checkpoints (core/checkpoint.hpp): a simulation's state saved mid-run and loaded into a simulation
// built the same way takes the steps of the run that was never stopped, to the bit; a checkpoint of
// another model, or a truncated one, is refused with the file named.
#include <catch2/catch.hpp>

#include <furniture_fem/core/simulation.hpp>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

using namespace furniture_fem;

namespace checkpoint_tests {  // this file's own names (its group compiles files in batches)

namespace {

// A clamped steel column (8 ASI-Gauss elements) with a 30 kg head, shaken hard enough for a plastic
// hinge at its root, beside a free L-frame solved as a rigid body: the factorisation reused between
// refreshes, the integration points shifting, a hinge forming, and the rigid path.
struct ColumnAndFrame {
  Model model;
  ColumnAndFrame() {
    const int sec = model.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002));
    const int mat = model.add_material(Material::steel());
    MemberOptions o;
    o.elements = 8;
    o.pairs = true;
    const int column = model.add_body("column");
    const int base = model.add_node({0, 0, 0}, column), head = model.add_node({0, 0, 1.0}, column);
    model.fix(base);
    model.add_member("column", base, head, sec, mat, o);
    model.add_point_mass(head, 30.0);
    const int frame = model.add_body("frame");
    const int a = model.add_node({1, 0, 0.5}, frame), c = model.add_node({1.6, 0, 0.5}, frame);
    const int d = model.add_node({1.6, 0.4, 0.7}, frame);
    o.elements = 4;
    model.add_member("arm", a, c, sec, mat, o);
    model.add_member("leg", c, d, sec, mat, o);
  }
};

using Sim = Simulation<AsiGaussTimoshenko, RuntimeIntegrator>;

std::unique_ptr<Sim> make(const Model& model, EquilibriumMode mode, double stiffness_damping = 0,
                          double frame_drift_refresh = 0) {
  SimulationOptions opt;
  opt.dt = 1e-3;
  opt.stiffness_damping = stiffness_damping;
  opt.frame_drift_refresh = frame_drift_refresh;
  opt.refresh_interval_steps = 7;
  RuntimeIntegrator integrator = RuntimeIntegrator::from(Newmark::paper());
  integrator.mode = mode;
  auto sim = std::make_unique<Sim>(model, integrator, opt);
  if (model.num_bodies() > 1) sim->set_rigid(1);
  sim->set_table_acceleration([](double t) { return Vec3(60 * std::sin(2 * std::numbers::pi * 2 * t), 0, 0); });
  return sim;
}

// Every number the next steps depend on and the outputs read, compared bit for bit.
void require_same_state(const Sim& a, const Sim& b) {
  REQUIRE(a.steps() == b.steps());
  REQUIRE(a.time() == b.time());
  for (int n = 0; n < a.model().num_nodes(); ++n) {
    INFO("node " << n);
    REQUIRE(a.position(n) == b.position(n));
    REQUIRE(a.rotation(n) == b.rotation(n));
    REQUIRE(a.velocity(n) == b.velocity(n));
    REQUIRE(a.acceleration(n) == b.acceleration(n));
  }
  for (int e = 0; e < a.model().num_elements(); ++e) {
    INFO("element " << e);
    REQUIRE(a.element_state(e).s == b.element_state(e).s);
    REQUIRE(a.element_state(e).hinge == b.element_state(e).hinge);
    REQUIRE(a.section_forces(e).My == b.section_forces(e).My);
  }
  const EnergyLedger ea = a.energy(), eb = b.energy();
  REQUIRE(ea.imbalance() == eb.imbalance());
  REQUIRE(ea.external_work == eb.external_work);
  REQUIRE(a.factorizations() == b.factorizations());
}

// A run stopped after `at` steps, its checkpoint loaded into a new simulation and run on to `steps`,
// against the run never stopped; returns the uninterrupted run.
std::unique_ptr<Sim> resume_matches(const Model& model, EquilibriumMode mode, double stiffness_damping, int at, int steps,
                                    double frame_drift_refresh = 0) {
  auto whole = make(model, mode, stiffness_damping, frame_drift_refresh);
  auto first = make(model, mode, stiffness_damping, frame_drift_refresh);
  for (int k = 0; k < at; ++k) first->step();
  StateWriter w;
  first->save_state(w);
  first.reset();  // the stopped run is gone; only its bytes are left
  auto resumed = make(model, mode, stiffness_damping, frame_drift_refresh);
  StateReader r(w.bytes(), "memory");
  resumed->load_state(r);
  r.finish();
  for (int k = 0; k < steps; ++k) whole->step();
  for (int k = at; k < steps; ++k) resumed->step();
  require_same_state(*whole, *resumed);
  return whole;
}

}  // namespace

TEST_CASE("a simulation loaded from a checkpoint takes the uninterrupted run's steps, to the bit", "[checkpoint]") {
  ColumnAndFrame f;
  for (const EquilibriumMode mode : {EquilibriumMode::carry_over, EquilibriumMode::iterate}) {
    // Saved at steps that fall before, on and after a refresh of the reused factorisation (every 7).
    for (const int at : {1, 23, 28, 150}) {
      INFO("mode " << (mode == EquilibriumMode::iterate ? "iterate" : "carry-over") << ", saved after step " << at);
      resume_matches(f.model, mode, 0.0, at, 400);
    }
  }
  // The run is one where the state matters: the column yields at its root and the frame falls freely.
  auto sim = make(f.model, EquilibriumMode::carry_over);
  for (int k = 0; k < 400; ++k) sim->step();
  int hinges = 0;
  for (int e = 0; e < 8; ++e) hinges += sim->element_state(e).hinge != 0;
  CHECK(hinges > 0);
  CHECK(sim->position(f.model.num_nodes() - 1).z() < 0.7 - 0.5 * 9.80665 * 0.16 + 0.01);  // fell 0.78 m
}

TEST_CASE("with structural damping a checkpoint also resumes to the bit", "[checkpoint][damping]") {
  // The members' dashpots read each element's deformations and damping force at the step's start
  // (SimulationOptions::stiffness_damping): a checkpoint that lost them would resume with a jolt.
  ColumnAndFrame f;
  for (const int at : {23, 150}) {
    INFO("saved after step " << at);
    const auto whole = resume_matches(f.model, EquilibriumMode::carry_over, 5e-4, at, 300);
    CHECK(whole->energy().damping_work < 0);
  }
}

TEST_CASE("with refreshes on frame drift a checkpoint also resumes to the bit", "[checkpoint][factor_reuse]") {
  // A refresh on drift compares each member's frame with its frame at the factorisation
  // (SimulationOptions::frame_drift_refresh): a checkpoint without those frames would resume with no
  // drift to see, and refactorise at other steps. The yielding column's members turn away from its
  // rotation by more than 1e-4 rad within the 7 steps between scheduled refreshes.
  ColumnAndFrame f;
  for (const int at : {23, 150}) {
    INFO("saved after step " << at);
    const auto whole = resume_matches(f.model, EquilibriumMode::carry_over, 0.0, at, 300, 1e-4);
    CHECK(whole->drift_refreshes() > 0);
    CHECK(whole->max_frame_drift() <= 1e-4);
  }
  SimulationOptions opt;
  for (const double a : {-1e-4, std::nan(""), std::numeric_limits<double>::infinity()}) {
    opt.frame_drift_refresh = a;
    INFO("frame_drift_refresh = " << a);
    REQUIRE_THROWS_WITH((Sim(f.model, RuntimeIntegrator::from(Newmark::paper()), opt)),
                        Catch::Contains("frame_drift_refresh must be finite and at least 0 rad (got " + detail::fmt(a) + ")"));
  }
}

TEST_CASE("a checkpoint of another model or a truncated one is refused, naming the file", "[checkpoint][input]") {
  ColumnAndFrame f;
  auto sim = make(f.model, EquilibriumMode::carry_over);
  for (int k = 0; k < 5; ++k) sim->step();
  StateWriter w;
  sim->save_state(w);

  SECTION("truncated") {
    const std::string cut = w.bytes().substr(0, w.bytes().size() / 2);
    auto other = make(f.model, EquilibriumMode::carry_over);
    StateReader r(cut, "run/checkpoint.bin");
    REQUIRE_THROWS_WITH(other->load_state(r), Catch::Contains("run/checkpoint.bin") && Catch::Contains("truncated"));
  }
  SECTION("another model") {
    Model small;
    const int body = small.add_body("bar");
    const int a = small.add_node({0, 0, 0}, body), b = small.add_node({1, 0, 0}, body);
    MemberOptions o;
    o.elements = 2;
    o.pairs = true;
    small.add_member("bar", a, b, small.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002)),
                     small.add_material(Material::steel()), o);
    auto other = make(small, EquilibriumMode::carry_over);
    StateReader r(w.bytes(), "run/checkpoint.bin");
    REQUIRE_THROWS_WITH(other->load_state(r), Catch::Contains("run/checkpoint.bin") && Catch::Contains("nodes") &&
                                                  Catch::Contains("another scene"));
  }
  SECTION("longer than the state") {
    auto other = make(f.model, EquilibriumMode::carry_over);
    const std::string longer = w.bytes() + "extra";  // alive while r reads it (r does not own its bytes)
    StateReader r(longer, "run/checkpoint.bin");
    other->load_state(r);
    REQUIRE_THROWS_WITH(r.finish(), Catch::Contains("run/checkpoint.bin") && Catch::Contains("5 bytes left over"));
  }
}

}  // namespace checkpoint_tests
