// Threads over bodies (SimulationOptions::threads, core/detail/parallel.hpp): which thread steps which
// body must not change a result, so a run on 2 or 3 threads is the one-thread run to the bit, and
// a failure inside a body's work reaches the caller from a helper thread as it does from the caller.
#include <catch2/catch.hpp>

#include <furniture_fem/core/simulation.hpp>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

using namespace furniture_fem;

namespace threads_tests {  // this file's own names (its group compiles files in batches)

namespace {

// Four flexible bodies of different sizes (so that the largest-first order and the helper's share
// both matter): three clamped columns with heads, shaken into yielding, and a free L-frame falling.
Model four_bodies() {
  Model model;
  const int sec = model.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002));
  const int mat = model.add_material(Material::steel());
  MemberOptions o;
  o.pairs = true;
  for (const int elements : {4, 10, 6}) {
    const int body = model.add_body("column_" + std::to_string(elements));
    const double x = 0.5 * elements;
    const int base = model.add_node({x, 0, 0}, body), head = model.add_node({x, 0, 1.0}, body);
    model.fix(base);
    o.elements = elements;
    model.add_member("column", base, head, sec, mat, o);
    model.add_point_mass(head, 30.0);
  }
  const int frame = model.add_body("frame");
  const int a = model.add_node({1, 1, 0.5}, frame), c = model.add_node({1.6, 1, 0.5}, frame);
  const int d = model.add_node({1.6, 1.4, 0.7}, frame);
  o.elements = 4;
  model.add_member("arm", a, c, sec, mat, o);
  model.add_member("leg", c, d, sec, mat, o);
  return model;
}

using Sim = Simulation<AsiGaussTimoshenko, RuntimeIntegrator>;

Sim make(const Model& model, int threads) {
  SimulationOptions opt;
  opt.dt = 1e-3;
  opt.threads = threads;
  opt.refresh_interval_steps = 5;
  Sim sim(model, RuntimeIntegrator::from(Newmark::paper()), opt);
  sim.set_table_acceleration([](double t) { return Vec3(60 * std::sin(2 * std::numbers::pi * 2 * t), 0, 0); });
  return sim;
}

}  // namespace

TEST_CASE("a run on 2 or 3 threads is the one-thread run to the bit", "[threads]") {
  const Model model = four_bodies();
  Sim one = make(model, 1);
  for (int k = 0; k < 300; ++k) one.step();
  for (const int threads : {2, 3}) {
    INFO(threads << " threads");
    Sim many = make(model, threads);
    for (int k = 0; k < 300; ++k) many.step();
    for (int n = 0; n < model.num_nodes(); ++n) {
      INFO("node " << n);
      REQUIRE(many.position(n) == one.position(n));
      REQUIRE(many.rotation(n) == one.rotation(n));
      REQUIRE(many.velocity(n) == one.velocity(n));
    }
    for (int e = 0; e < model.num_elements(); ++e) REQUIRE(many.section_forces(e).My == one.section_forces(e).My);
    REQUIRE(many.energy().imbalance() == one.energy().imbalance());
    REQUIRE(many.factorizations() == one.factorizations());
    // Moved, a simulation keeps its helper threads and goes on as the one-thread run does.
    Sim moved = std::move(many);
    Sim reference = make(model, 1);
    for (int k = 0; k < 350; ++k) reference.step();
    for (int k = 0; k < 50; ++k) moved.step();
    REQUIRE(moved.position(model.num_nodes() - 1) == reference.position(model.num_nodes() - 1));
  }
  // The run is one where the bodies differ: a column yields at its root, the frame falls.
  int hinges = 0;
  for (int e = 0; e < model.num_elements(); ++e) hinges += one.element_state(e).hinge != 0;
  CHECK(hinges > 0);
  CHECK(one.position(model.num_nodes() - 1).z() < 0.7 - 0.3);
}

TEST_CASE("a non-finite state found on a helper thread stops the step as on one thread", "[threads]") {
  const Model model = four_bodies();
  for (const int threads : {1, 2}) {
    INFO(threads << " threads");
    Sim sim = make(model, threads);
    for (int k = 0; k < 10; ++k) sim.step();
    // NaN velocity at the frame's last node (the smallest body: a helper's share when one takes part).
    Vec6 bad = Vec6::Zero();
    bad[0] = std::numeric_limits<double>::quiet_NaN();
    sim.set_velocity(model.num_nodes() - 1, bad);
    CHECK_THROWS_AS(sim.step(), SimulationError);
  }
}

}  // namespace threads_tests
