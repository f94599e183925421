#pragma once
// furniture_fem/core/detail/simulation_contact_step.hpp: the contact inside the step: a body solved again while its contacts change status, the
// contact terms of its effective matrix.
// Included by core/simulation.hpp right after the class: member functions of Simulation defined out of
// the class (declared, with what they do, in it); not a header of its own.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/simulation_contact_step.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif

namespace furniture_fem {

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::solve_and_commit_body(int b) {
  if (const int g = group_of(b); g >= 0) {
    if (groups_[g].front() == b) solve_and_commit_group(groups_[g]);
    return;
  }
  BodyStepSums& s = sums_[b];
  timed(s.solve, [&] { residual_body(systems_[b], fext1_, s.residual_num, s.residual_den); });
  if (!update_body(b, s, true)) return;
  resolve_changed_contacts(std::span<const int>(&b, 1));
  if (s.solve_failed) return;
  if (opt_.check_finite) {
    s.not_finite = s.not_finite || !increment_finite(b);
    if (s.not_finite) return;
  }
  commit_body(b, s);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::resolve_changed_contacts(std::span<const int> members) {
  if constexpr (BodyPlaneContactPolicy<Contact>) {
    if (opt_.contact_iterations <= 0 || static_) return;
    const ContactView at_end{model_, x_, v_, t_state_, stepper_.dt(), &R_};
    if (std::none_of(members.begin(), members.end(), [&](int b) { return contact_.body_plane_status_changed(at_end, b); }))
      return;  // the usual case, checked without allocating
    const size_t n = members.size();
    std::vector<std::vector<char>> status(n);
    for (size_t i = 0; i < n; ++i) status[i] = contact_.last_status(model_, members[i]);
    std::vector<typename Contact::BodyPlaneContacts> used(n), now(n);
    bool iterated = false;
    for (int it = 0; it < opt_.contact_iterations && !sums_[members.front()].solve_failed; ++it) {
      const ContactView view{model_, x_, v_, t_state_, stepper_.dt(), &R_};
      bool changed = false;
      for (size_t i = 0; i < n; ++i) {
        now[i] = contact_.body_plane_contacts(view, members[i]);
        changed = changed || now[i].status != status[i];
      }
      if (!changed) break;
      for (size_t i = 0; i < n; ++i) {
        status[i] = std::move(now[i].status);
        replace_plane_contacts(members[i], used[i], std::move(now[i]), !iterated);
      }
      iterated = true;
      newton_step_from_current_state(members);
    }
    if (!iterated) return;
    for (const auto& u : used)
      for (const auto& t : u.tangents)  // the last evaluation's forces at the end state
        add_wrench(fc1_, t, plane_contact_shift(t));
  }
}

template <class Element, class Integrator, class LinearSolver, class Contact>
template <class Contacts>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::replace_plane_contacts(int b, Contacts& used, Contacts&& now, bool first) {
  if (first) remove_predictor_plane_forces(b);
  for (size_t k = 0; k < used.forces.size(); ++k) subtract_wrench(fc1_, used.tangents[k], used.forces[k]);
  for (size_t k = 0; k < now.forces.size(); ++k) add_wrench(fc1_, now.tangents[k], now.forces[k]);
  contact_iterated_[b] = 1;
  used = std::move(now);
  set_body_contact_terms(systems_[b], used.tangents);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::newton_step_from_current_state(std::span<const int> members) {
  if (members.size() > 1) carry_group_pairs_to_current_state(members);
  double num = 0, den = 0;
  for (int b : members) residual_body(systems_[b], fext1_, num, den);
  if (const int b = members.front(); !systems_[b].rigid) {
    if (members.size() > 1) update_group(members, false);
    else update_body(b, sums_[b], false);
    return;
  }
  timed(sums_[members.front()].solve, [&] {
    if (members.size() > 1) RigidBody::group_newton_step(*this, members);
    else RigidBody::newton_step(*this, systems_[members.front()]);
  });
  for (int b : members) kinematics_body(b);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::carry_group_pairs_to_current_state(std::span<const int> members) {
  if constexpr (PairTangentPolicy<Contact>) {
    const auto& pairs = contact_.pair_tangents();
    for (int k : group_pairs_[group_of(members.front())]) {
      const Vec3 shift = pair_shift(pairs[k]);
      share_pair_force(pairs[k], shift - pair_predictor_shift_[k], [&](int node, const Vec6& w) { fc1_.segment<6>(6 * node) += w; });
      pair_predictor_shift_[k] = shift;
    }
  }
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::remove_predictor_plane_forces(int b) {
  if constexpr (BodyPlaneContactPolicy<Contact>) {
    for (const auto& [n, w] : contact_.plane_forces())
      if (model_.node(n).body == b) {
        fc1_.segment<3>(6 * n) -= w.template head<3>();
        if (has_moment(w)) fc1_.segment<3>(6 * n + 3) -= w.template tail<3>();
      }
    const auto& tangents = contact_.nodal_tangents();
    for (size_t k = 0; k < tangents.size(); ++k)
      if (model_.node(tangents[k].node).body == b) subtract_wrench(fc1_, tangents[k], predictor_shift_[k]);
  }
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::set_body_contact_terms(detail::BodySystem& bs, const std::vector<NodalContactTangent>& tangents) {
  const double kf = stepper_.stiffness_factor(), cf = stepper_.velocity_factor();
  bs.contact.clear();
  for (const auto& t : tangents) {
    const int local = local_index_[t.node];
    const Mat3 k = kf * (t.K + cf * t.C);
    const auto same = std::find_if(bs.contact.begin(), bs.contact.end(),
                                   [&](const auto& c) { return c.local == local && c.at_node() && t.at_node(); });
    if (same != bs.contact.end()) {
      same->K += k;
      same->status += t.status;
    } else {
      bs.contact.push_back({local, t.status, k, t.arm0});
    }
  }
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline Vec6 Simulation<Element, Integrator, LinearSolver, Contact>::plane_contact_shift(const NodalContactTangent& t) const {
  const int i = 6 * t.node;
  Vec6 w;
  if (t.at_node()) {
    w << -(t.K * (x_[t.node] - t.x) + t.C * (v_.segment<3>(i) - t.v)), Vec3::Zero();
    return w;
  }
  const Vec3 arm = R_[t.node] * t.arm0;
  const Vec3 f = -(t.K * (x_[t.node] + arm - t.x) + t.C * (v_.segment<3>(i) + v_.segment<3>(i + 3).cross(arm) - t.v));
  w << f, arm.cross(f);
  return w;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline bool Simulation<Element, Integrator, LinearSolver, Contact>::has_moment(const Vec6& w) {
  return w[3] != 0 || w[4] != 0 || w[5] != 0;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::add_wrench(Eigen::VectorXd& f, const NodalContactTangent& t, const Vec6& w) {
  f.segment<3>(6 * t.node) += w.template head<3>();
  if (!t.at_node()) f.segment<3>(6 * t.node + 3) += w.template tail<3>();
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::subtract_wrench(Eigen::VectorXd& f, const NodalContactTangent& t, const Vec6& w) {
  f.segment<3>(6 * t.node) -= w.template head<3>();
  if (!t.at_node()) f.segment<3>(6 * t.node + 3) -= w.template tail<3>();
}

}  // namespace furniture_fem
