#pragma once
// furniture_fem/core/detail/step_kernel.hpp: Simulation::StaticScope (statics for the life of a scope) and
// Simulation::StepKernel (the sweeps a step scheme drives). Included by core/simulation.hpp right after
// the class (member classes defined out of it); not a header of its own.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/step_kernel.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif

namespace furniture_fem {

template <class Element, class Integrator, class LinearSolver, class Contact>
class Simulation<Element, Integrator, LinearSolver, Contact>::StaticScope {
 public:
  enum Exit { keep_dynamics, restart_dynamics };
  StaticScope(Simulation& sim, Exit exit)
      : sim_(sim), saved_(sim.static_), exit_(exit), exceptions_(std::uncaught_exceptions()) {
    sim.place_unplaced_nodes();  // statics reads every node
    sim.static_ = true;
  }
  ~StaticScope() {
    sim_.static_ = saved_;
    if (exit_ == keep_dynamics) return;
    sim_.started_ = false;
    if (std::uncaught_exceptions() > exceptions_)
      for (auto& bs : sim_.systems_) bs.needs_refresh = true;
  }
  StaticScope(const StaticScope&) = delete;
  StaticScope& operator=(const StaticScope&) = delete;

 private:
  Simulation& sim_;
  bool saved_;
  Exit exit_;
  int exceptions_;
};

template <class Element, class Integrator, class LinearSolver, class Contact>
class Simulation<Element, Integrator, LinearSolver, Contact>::StepKernel {
 public:
  StepKernel(Simulation& sim, double t1) : sim_(sim), t1_(t1) {}
  int max_iterations() const { return sim_.opt_.max_iterations; }
  double tolerance() const { return sim_.opt_.tolerance; }
  bool check_finite() const { return sim_.opt_.check_finite; }
  double end_time() const { return t1_; }

  // Each body in one go: its residual, solve, update and commit (carry-over).
  StepInfo solve_and_commit_bodies() {
    sim_.body_sweep([&](int b) { sim_.solve_and_commit_body(b); });
    const BodyStepSums total = sim_.sum_bodies(t1_);
    StepInfo info;
    info.residual = total.residual();
    info.refreshed_bodies = total.refreshed;
    info.shifted_points = total.shifted;
    return info;
  }
  void contact_at_end_of_step() {
    sim_.timed(sim_.timings_.contact, [&] { sim_.contact_at_end_of_step(); });
  }
  void evaluate_residuals() {
    sim_.body_sweep([&](int b) {
      BodyStepSums& s = sim_.sums_[b];
      sim_.residual_body(sim_.systems_[b], sim_.fext1_, s.residual_num, s.residual_den);
    });
  }
  double residual_norm() { return sim_.sum_bodies(t1_).residual(); }
  // Returns the number of bodies whose matrix was refreshed.
  int update_bodies(bool first_solve) {
    sim_.body_sweep([&](int b) { sim_.update_body(b, sim_.sums_[b], first_solve); });
    return sim_.sum_bodies(t1_).refreshed;
  }
  // Contact at the current iterate (its positions and velocities).
  void contact_at_trial() {
    sim_.timed(sim_.timings_.contact, [&] { sim_.contact_forces(t1_, sim_.v_, sim_.fc1_); });
  }
  // Returns the number of ASI integration points moved.
  int commit_bodies() {
    sim_.body_sweep([&](int b) { sim_.commit_body(b, sim_.sums_[b]); });
    return sim_.sum_bodies(t1_).shifted;
  }

 private:
  Simulation& sim_;
  double t1_;
};

}  // namespace furniture_fem
