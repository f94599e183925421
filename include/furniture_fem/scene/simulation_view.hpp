#pragma once
// furniture_fem/scene/simulation_view.hpp: the observers' view (observer.hpp, SimulationView) of one
// composed Simulation: the only observer-facing code instantiated per contact law and linear solver
// (runner.hpp). Observers include observer.hpp and never this header, so they compile no solver.
#include <string>
#include <string_view>
#include <vector>

#include "../core/simulation.hpp"
#include "observer.hpp"

namespace furniture_fem {

namespace detail {
template <class Sim>
struct policies_of;
template <class Element, class Integrator, class Solver, class Contact>
struct policies_of<Simulation<Element, Integrator, Solver, Contact>> {
  using element = Element;
  using solver = Solver;
};
}  // namespace detail

// The view of one composed Simulation (the only observer-facing code instantiated per law and solver).
template <class Sim>
class SimulationViewOf final : public SteppedSimulation {
 public:
  explicit SimulationViewOf(Sim& sim) : sim_(sim) {}
  StepInfo step() override { return sim_.step(); }
  void save_state(StateWriter& w) const override { sim_.save_state(w); }
  void load_state(StateReader& r) override { sim_.load_state(r); }
  bool copy_node_states_at(double t, NodeStates& into) const override {
    // A step that stopped after its predictor is at the start time still: its start state is the one.
    if (t == sim_.step_start_time()) {
      sim_.copy_step_start_states(into);
      return true;
    }
    if (t != sim_.time()) return false;
    into.x = sim_.positions();
    into.u = sim_.displacements();
    into.R = sim_.rotations();
    into.v = sim_.velocities();
    into.a = sim_.accelerations();
    return true;
  }
  int first_non_finite_node() const override { return sim_.first_non_finite_node(); }
  double time() const override { return sim_.time(); }
  long steps() const override { return sim_.steps(); }
  const Vec3& position(int n) const override { return sim_.position(n); }
  const Vec3& displacement(int n) const override { return sim_.displacement(n); }
  const Mat3& rotation(int n) const override { return sim_.rotation(n); }
  Vec6 velocity(int n) const override { return sim_.velocity(n); }
  Vec6 acceleration(int n) const override { return sim_.acceleration(n); }
  double nodal_mass(int n) const override { return sim_.nodal_mass(n); }
  double kinetic_energy(int n) const override { return sim_.kinetic_energy(n); }
  SectionForces section_forces(int e) const override { return sim_.section_forces(e); }
  EnergyLedger energy() const override { return sim_.energy(); }
  const std::vector<PairForce>& pair_forces() const override { return sim_.contact_model().pair_forces(); }
  const RestraintSet& restraints() const override { return sim_.contact_model().restraints(); }
  long factorizations() const override { return sim_.factorizations(); }
  double factor_reuse_error() const override { return sim_.factor_reuse_error(); }
  long drift_refreshes() const override { return sim_.drift_refreshes(); }
  double max_frame_drift() const override { return sim_.max_frame_drift(); }
  long impact_steps() const override { return sim_.impact_steps(); }
  long impact_substeps() const override { return sim_.impact_substeps(); }
  const StepTimings& timings() const override { return sim_.timings(); }
  std::string integrator_name() const override { return sim_.integrator().name(); }
  std::string_view solver_name() const override { return detail::policies_of<Sim>::solver::name; }
  std::string_view element_name() const override { return detail::policies_of<Sim>::element::name; }

 private:
  Sim& sim_;
};

}  // namespace furniture_fem
