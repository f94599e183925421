#pragma once
// furniture_fem/core/detail/simulation_entry_points.hpp: Simulation's constructor, step and static solves.
// Included by core/simulation.hpp right after the class; not a header of its own.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/simulation_entry_points.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif

namespace furniture_fem {

// ---- the entry points, defined outside the class ----
// Defined here rather than in the class body, they are not implicitly inline: a translation unit that
// declares an instantiation `extern` (below) compiles none of the solver behind them, and the compiled
// core (furniture_fem::core_compiled) provides them once (docs/performance.md section 6).

template <class Element, class Integrator, class LinearSolver, class Contact>
Simulation<Element, Integrator, LinearSolver, Contact>::Simulation(const Model& model, Integrator integrator,
                                                                  SimulationOptions options, Contact contact)
    : model_(model), integrator_(integrator), opt_(options), stepper_(integrator.stepper(options.dt)),
      contact_(std::move(contact)) {
  model_.validate();
  if (opt_.max_impact_substeps < 1)
    throw ModelError("simulation: max_impact_substeps must be at least 1 (got " +
                     std::to_string(opt_.max_impact_substeps) + ")");
  if (!(opt_.impact_travel > 0) || !std::isfinite(opt_.impact_travel))
    throw ModelError("simulation: impact_travel must be positive and finite (got " + detail::fmt(opt_.impact_travel) +
                     " m)");
  if (!(opt_.frame_drift_refresh >= 0) || !std::isfinite(opt_.frame_drift_refresh))
    throw ModelError("simulation: frame_drift_refresh must be finite and at least 0 rad (got " +
                     detail::fmt(opt_.frame_drift_refresh) + ")");
  if (!(opt_.stiffness_damping >= 0) || !std::isfinite(opt_.stiffness_damping))
    throw ModelError("simulation: stiffness_damping must be finite and at least 0 s (got " +
                     detail::fmt(opt_.stiffness_damping) + ")");
  if constexpr (Element::needs_pairs) {
    for (int e = 0; e < model_.num_elements(); ++e)
      if (model_.elements()[e].slot == PairSlot::none)
        throw ModelError(model_.describe_element(e) + ": the " + std::string(Element::name) +
                         " element needs members split into pairs (MemberOptions::pairs)");
  }
  setup();
}

template <class Element, class Integrator, class LinearSolver, class Contact>
StepInfo Simulation<Element, Integrator, LinearSolver, Contact>::step() {
  if (!started_) start();
  update_step_nodes();
  const int n = substeps_for_impacts();
  divided_ = false;
  if (n <= 1) {
    const StepInfo info = step_to(t_ + stepper_.dt());
    ++steps_;
    return info;
  }
  // An impact: n equal sub-steps ending where the step would have (the observer sees one step). Its
  // start state is kept whole, for a run that diverges within it (step_start_time()).
  divided_ = true;
  division_start_t_ = t_;
  division_start_.x = positions();
  division_start_.u = displacements();
  division_start_.R = rotations();
  division_start_.v = velocities();
  division_start_.a = accelerations();
  const double dt = stepper_.dt(), t_end = t_ + dt;
  StepInfo info;
  set_step_length(dt / n);
  try {
    for (int i = 1; i <= n; ++i) {
      const StepInfo sub = step_to(i == n ? t_end : t_ + stepper_.dt());
      info.iterations += sub.iterations;
      info.residual = std::max(info.residual, sub.residual);
      info.converged = info.converged && sub.converged;
      info.refreshed_bodies += sub.refreshed_bodies;
      info.shifted_points += sub.shifted_points;
    }
  } catch (...) {
    set_step_length(dt);
    throw;
  }
  set_step_length(dt);
  ++steps_;
  ++impact_steps_;
  impact_substeps_ += n;
  return info;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
StepInfo Simulation<Element, Integrator, LinearSolver, Contact>::step_to(double t1) {
  const auto step_start = std::chrono::steady_clock::now();
  struct AddTotal {
    StepTimings& t;
    std::chrono::steady_clock::time_point s;
    ~AddTotal() { t.total += std::chrono::duration<double>(std::chrono::steady_clock::now() - s).count(); }
  } add_total{timings_, step_start};
  step_start_t_ = std::numeric_limits<double>::quiet_NaN();
  t_state_ = t1;
  // Predictor "no motion" (Du = 0) and the loads at t_{n+1}. Its element forces are the last step's.
  const Loads loads = loads_at(t1);
  body_sweep([&](int b) { predict_body(b, loads); });
  step_start_t_ = t_;
  // The predictor's Newmark velocity, (1 - gamma / beta) v_n, has the wrong sign, and friction or the
  // paper's damping evaluated there would pump energy: contact sees v_n + dt a_n (v_contact_) instead.
  timed(timings_.contact, [&] {
    contact_forces(t1, v_contact_, fc1_);
    linearised_contact_at_current_state();
  });
  if (opt_.check_finite && !(detail::all_finite(fc1_) && detail::all_finite(fext1_))) {
    residual();  // for the diagnosis
    throw SimulationError(t_, "the residual is not finite (NaN or infinity) at the start of the step: " +
                                  non_finite_diagnosis());
  }
  StepKernel kernel{*this, t1};
  const StepInfo info = stepper_.do_step(kernel);
  if constexpr (requires { contact_.commit(); }) contact_.commit();
  t_ = t1;
  return info;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
StaticResult Simulation<Element, Integrator, LinearSolver, Contact>::solve_static(int increments, int max_iterations,
                                                                                  double tolerance) {
  const StaticScope statics(*this, StaticScope::restart_dynamics);
  return detail::StaticSolver<Simulation>(*this).load_control(increments, max_iterations, tolerance);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
StaticPath Simulation<Element, Integrator, LinearSolver, Contact>::solve_static_displacement(
    int node, int dof, double target, int increments, int max_iterations, double tolerance, double start_load_factor) {
  const StaticScope statics(*this, StaticScope::restart_dynamics);
  return detail::StaticSolver<Simulation>(*this).displacement_control(node, dof, target, increments, max_iterations,
                                                                      tolerance, start_load_factor);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
StaticPath Simulation<Element, Integrator, LinearSolver, Contact>::solve_static_arc_length(
    const ArcLengthOptions& options) {
  const StaticScope statics(*this, StaticScope::restart_dynamics);
  return detail::StaticSolver<Simulation>(*this).arc_length(options);
}

}  // namespace furniture_fem
