#pragma once
// furniture_fem/core/detail/simulation_step_nodes.hpp: the step's length, the nodes a step reads and places, finiteness, the ASI shifts.
// Included by core/simulation.hpp right after the class: member functions of Simulation defined out of
// the class (declared, with what they do, in it); not a header of its own.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/simulation_step_nodes.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif

namespace furniture_fem {

template <class Element, class Integrator, class LinearSolver, class Contact>
inline bool Simulation<Element, Integrator, LinearSolver, Contact>::increment_finite(int b) const {
  return fields_[b].on ? RigidFields::finite(fields_[b]) : detail::nodes_finite(Du_, systems_[b].nodes);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline int Simulation<Element, Integrator, LinearSolver, Contact>::substeps_for_impacts() const {
  if (opt_.max_impact_substeps <= 1 || static_) return 1;
  if constexpr (requires(const ContactView& view) { contact_.fastest_closing(view); }) {
    const ContactView view{model_, x_, v_, t_, stepper_.dt(), &R_};
    const double speed = contact_.fastest_closing(view);
    if (!(speed * stepper_.dt() > opt_.impact_travel)) return 1;  // also NaN: the step's own check reports it
    return static_cast<int>(std::min<double>(std::ceil(speed * stepper_.dt() / opt_.impact_travel), opt_.max_impact_substeps));
  } else {
    return 1;
  }
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::set_step_length(double dt) {
  stepper_ = integrator_.stepper(dt);
  for (auto& bs : systems_)
    if (!bs.rigid) {
      bs.needs_refresh = true;
      bs.assembled = false;
    }
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::update_step_nodes() {
  if constexpr (requires(std::vector<int>& out) {
                  contact_.nodes_read(model_, 0, out);
                  contact_.nodes_read_revision();
                }) {
    if (contact_.nodes_read_revision() == step_nodes_revision_) return;
    place_unplaced_nodes();  // left by the old lists
    step_nodes_revision_ = contact_.nodes_read_revision();
    std::vector<int> read;
    for (int b = 0; b < model_.num_bodies(); ++b) {
      auto& local = step_nodes_[b];
      local.clear();
      if (!contact_.nodes_read(model_, b, read)) continue;
      for (int n : read) local.push_back(local_index_[n]);
      std::sort(local.begin(), local.end());
      if (local.size() == systems_[b].nodes.size()) local.clear();
    }
  }
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline const std::vector<int>& Simulation<Element, Integrator, LinearSolver, Contact>::step_nodes(int b) const {
  return step_nodes_[b].empty() ? all_local_[b] : step_nodes_[b];
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::place_unplaced_nodes() const {
  for (int b = 0; b < static_cast<int>(unplaced_.size()); ++b)
    if (unplaced_[b]) RigidFields::place_all(*this, b);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::place_body_nodes(int node) const {
  if (const int b = model_.node(node).body; unplaced_[b]) RigidFields::place_all(*this, b);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::place_node_if_unplaced(int n) const {
  if (const int b = model_.node(n).body; unplaced_[b])
    RigidFields::place(*this, b, std::span<const int>(&local_index_[n], 1));
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline int Simulation<Element, Integrator, LinearSolver, Contact>::first_non_finite_node_by_body() const {
  const auto bad = [&](int n) {
    return !(x_[n].allFinite() && R_[n].allFinite() && v_.segment<6>(6 * n).allFinite());
  };
  int first = -1;
  const auto note = [&](int n) {
    if (bad(n) && (first < 0 || n < first)) first = n;
  };
  for (int b = 0; b < model_.num_bodies(); ++b) {
    const auto& nodes = systems_[b].nodes;
    if (unplaced_[b] && !RigidFields::state_finite(fields_[b])) RigidFields::place_all(*this, b);
    if (unplaced_[b])
      for (int k : step_nodes_[b]) note(nodes[k]);
    else
      for (int n : nodes) note(n);
  }
  return first;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::nodes_set_from_outside(int node) {
  if (!started_) return;
  auto& F = fields_[model_.node(node).body];
  if (F.on) F.refit = true;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline std::string Simulation<Element, Integrator, LinearSolver, Contact>::non_finite_diagnosis() const {
  for (int n = 0; n < model_.num_nodes(); ++n) {
    const bool bad = !x_[n].allFinite() || !v_.segment<6>(6 * n).allFinite() || !Du_.segment<6>(6 * n).allFinite() ||
                     !r_.segment<6>(6 * n).allFinite();
    if (bad)
      return "node " + std::to_string(n) + " of body '" + model_.body(model_.node(n).body).name +
             "' has a non-finite position, velocity or force; the step diverged (try a smaller dt or a softer "
             "penalty)";
  }
  return "a non-finite value appeared; the step diverged (try a smaller dt)";
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline Vec3 Simulation<Element, Integrator, LinearSolver, Contact>::rotary_momentum(int n) const {
  return node_rotary_inertia(n) * v_.segment<3>(6 * n + 3);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline double Simulation<Element, Integrator, LinearSolver, Contact>::dof_value(int n, int dof) const {
  return dof < 3 ? u_[n][dof] : detail::rotation_log(R_[n])[dof - 3];
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline double Simulation<Element, Integrator, LinearSolver, Contact>::spring_scale() const {
  return static_ ? load_factor_ : (load_scale_ ? load_scale_(t_state_) : 1.0);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline Mat3 Simulation<Element, Integrator, LinearSolver, Contact>::body_rotation(const detail::BodySystem& bs) const {
  Vec3 xc = Vec3::Zero();
  for (int n : bs.nodes) xc += x_[n];
  xc /= std::max<size_t>(1, bs.nodes.size());
  return detail::best_rotation(
      static_cast<int>(bs.nodes.size()),
      [&](int i) { return std::pair<Vec3, Vec3>(model_.node(bs.nodes[i]).X, x_[bs.nodes[i]]); }, bs.Xc, xc);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline int Simulation<Element, Integrator, LinearSolver, Contact>::shift_integration_points(int b) {
  int shifted = 0;
  if constexpr (requires(State s) { s.hinge; s.plastic_increment; }) {
    auto& bs = systems_[b];
    int skip = -1;  // a partner whose point was just moved: its d_ and new s are not in equilibrium yet
    for (int e : bs.elements) {
      if (e == skip) continue;  // checked at the next step, from forces at its new point
      const int p = model_.elements()[e].partner;  // pairs are consecutive elements of one member
      State* partner = p >= 0 ? &committed_[p] : nullptr;
      const ElementProps* pp = p >= 0 ? &props_[p] : nullptr;
      if (Element::shift_integration_point(props_[e], committed_[e], d_[e], partner, pp)) {
        ++shifted;
        bs.needs_refresh = true;
        if (p > e) skip = p;
      }
    }
    if (shifted) {
      evaluate_body(b, bs.needs_refresh);
      for (int e : bs.elements) committed_[e] = trial_[e];
    }
  }
  return shifted;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline int Simulation<Element, Integrator, LinearSolver, Contact>::shift_integration_points() {
  int shifted = 0;
  for (int b = 0; b < model_.num_bodies(); ++b) shifted += shift_integration_points(b);
  return shifted;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline double Simulation<Element, Integrator, LinearSolver, Contact>::strain_energy(int e) const {
  if constexpr (requires(State s) { s.eps_p; }) {
    const auto s = Element::section_forces(props_[e], committed_[e], d_[e]).as_vector();
    double w = 0;
    for (int i = 0; i < 6; ++i) w += 0.5 * s[i] * s[i] / props_[e].D[i];
    return w * props_[e].L0;
  } else {
    return 0.5 * d_[e].dot(fl_[e]);
  }
}

}  // namespace furniture_fem
