#pragma once
// furniture_fem/core/detail/simulation_pairs.hpp: the contact's forces and tangents, and the item-item pairs inside the step (rigid groups).
// Included by core/simulation.hpp right after the class: member functions of Simulation defined out of
// the class (declared, with what they do, in it); not a header of its own.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/simulation_pairs.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif

namespace furniture_fem {

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::contact_forces(double t, const Eigen::VectorXd& v, Eigen::VectorXd& f) {
  f.setZero();
  if constexpr (!std::is_same_v<Contact, NoContact>) {
    const ContactView view{model_, x_, v, t, stepper_.dt(), &R_};
    contact_.add_forces(view, f);
  }
  gather_contact_tangents();
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::gather_contact_tangents() {
  if constexpr (ImplicitContactPolicy<Contact>) {
    for (auto& bs : systems_) bs.contact.clear();
    if (static_) return;
    const double kf = stepper_.stiffness_factor(), cf = stepper_.velocity_factor();
    for (const auto& t : contact_.nodal_tangents()) {
      auto& bs = systems_[model_.node(t.node).body];
      const Mat3 k = kf * (t.K + cf * t.C);
      const int local = local_index_[t.node];
      if (!bs.contact.empty() && bs.contact.back().local == local && bs.contact.back().at_node() && t.at_node()) {
        bs.contact.back().K += k;
        bs.contact.back().status += t.status;
      } else {
        bs.contact.push_back({local, t.status, k, t.arm0});
      }
    }
  }
  gather_pair_groups();
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline int Simulation<Element, Integrator, LinearSolver, Contact>::group_of(int b) const {
  return group_of_.empty() ? -1 : group_of_[b];
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::gather_pair_groups() {
  groups_.clear();
  group_pairs_.clear();
  group_of_.clear();
  pair_active_.clear();
  if constexpr (PairTangentPolicy<Contact>) {
    const auto& pairs = contact_.pair_tangents();
    if (static_ || pairs.empty()) return;
    const int nb = model_.num_bodies();
    std::vector<int> root(nb);
    for (int b = 0; b < nb; ++b) root[b] = b;
    const auto find = [&](int b) {
      while (root[b] != b) b = root[b] = root[root[b]];
      return b;
    };
    pair_active_.assign(pairs.size(), 0);
    for (size_t k = 0; k < pairs.size(); ++k) {
      const auto& p = pairs[k];
      // Two rigid bodies or two flexible ones; a pair between a rigid and a flexible body stays a load.
      if (p.body_a == p.body_b || systems_[p.body_a].rigid != systems_[p.body_b].rigid) continue;
      pair_active_[k] = 1;
      const int ra = find(p.body_a), rb = find(p.body_b);
      if (ra != rb) root[std::max(ra, rb)] = std::min(ra, rb);
    }
    std::vector<int> group_of_root(nb, -1);
    group_of_.assign(nb, -1);
    for (size_t k = 0; k < pairs.size(); ++k) {
      if (!pair_active_[k]) continue;
      const int r = find(pairs[k].body_a);
      if (group_of_root[r] < 0) {
        group_of_root[r] = static_cast<int>(groups_.size());
        groups_.emplace_back();
        group_pairs_.emplace_back();
      }
      group_pairs_[group_of_root[r]].push_back(static_cast<int>(k));
    }
    for (int b = 0; b < nb; ++b)  // ascending: the lowest body of a group leads it
      if (const int g = group_of_root[find(b)]; g >= 0) {
        group_of_[b] = g;
        groups_[g].push_back(b);
      }
  }
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline Vec3 Simulation<Element, Integrator, LinearSolver, Contact>::pair_relative_position(const PairContactTangent& p) const {
  if (p.has_arms()) return x_[p.a0] + R_[p.a0] * p.arm_a0 - (x_[p.b0] + R_[p.b0] * p.arm_b0);
  return (1 - p.s) * x_[p.a0] + p.s * x_[p.a1] - ((1 - p.t) * x_[p.b0] + p.t * x_[p.b1]);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline Vec3 Simulation<Element, Integrator, LinearSolver, Contact>::pair_relative_velocity(const PairContactTangent& p) const {
  const auto v = [&](int n) { return Vec3(v_.segment<3>(6 * n)); };
  if (p.has_arms()) {
    const auto w = [&](int n) { return Vec3(v_.segment<3>(6 * n + 3)); };
    return v(p.a0) + w(p.a0).cross(R_[p.a0] * p.arm_a0) - (v(p.b0) + w(p.b0).cross(R_[p.b0] * p.arm_b0));
  }
  return (1 - p.s) * v(p.a0) + p.s * v(p.a1) - ((1 - p.t) * v(p.b0) + p.t * v(p.b1));
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline Vec3 Simulation<Element, Integrator, LinearSolver, Contact>::pair_shift(const PairContactTangent& p) const {
  return -(p.K * (pair_relative_position(p) - p.x) + p.C * (pair_relative_velocity(p) - p.v));
}

template <class Element, class Integrator, class LinearSolver, class Contact>
template <class Add>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::share_pair_force(const PairContactTangent& p, const Vec3& F, Add&& add) const {
  const Vec3 pa = (1 - p.s) * x_[p.a0] + p.s * x_[p.a1], pb = (1 - p.t) * x_[p.b0] + p.t * x_[p.b1];
  const Vec3 ma = (p.point - pa).cross(F), mb = (p.point - pb).cross(-F);
  Vec6 w;
  const auto put = [&](int n, double share, const Vec3& f, const Vec3& m) {
    w << share * f, share * m;
    add(n, w);
  };
  put(p.a0, 1 - p.s, F, ma);
  put(p.a1, p.s, F, ma);
  put(p.b0, 1 - p.t, -F, mb);
  put(p.b1, p.t, -F, mb);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::solve_and_commit_group(const std::vector<int>& members) {
  for (int m : members) {
    BodyStepSums& s = sums_[m];
    timed(s.solve, [&] { residual_body(systems_[m], fext1_, s.residual_num, s.residual_den); });
  }
  if (!update_group(members, true)) return;
  resolve_changed_contacts(members);
  for (int m : members) {
    BodyStepSums& s = sums_[m];
    if (s.solve_failed) return;
    if (opt_.check_finite) {
      s.not_finite = s.not_finite || !increment_finite(m);
      if (s.not_finite) return;
    }
  }
  for (int m : members) commit_body(m, sums_[m]);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline bool Simulation<Element, Integrator, LinearSolver, Contact>::update_group(std::span<const int> members, bool first_solve) {
  if (!systems_[members.front()].rigid) {
    if (!solve_flexible_group(members, first_solve)) return false;
  } else {
    timed(sums_[members.front()].solve, [&] { RigidBody::group_newton_step(*this, members); });
  }
  for (int m : members) {
    auto& bs = systems_[m];
    if (bs.rigid) bs.needs_refresh = bs.assembled = false;
    timed(sums_[m].elements, [&] {
      kinematics_body(m);
      evaluate_body(m, bs.needs_refresh);
    });
  }
  return true;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline const std::vector<PairContactTangent>& Simulation<Element, Integrator, LinearSolver, Contact>::pair_tangents() const {
  static const std::vector<PairContactTangent> none;
  if constexpr (PairTangentPolicy<Contact>) return contact_.pair_tangents();
  else return none;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
template <class F>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::for_pair_sides(const PairContactTangent& p, F&& f) {
  f(p.a0, 1 - p.s);
  f(p.a1, p.s);
  f(p.b0, -(1 - p.t));
  f(p.b1, -p.t);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline auto Simulation<Element, Integrator, LinearSolver, Contact>::group_pair_nodes(std::span<const int> members,
                                                                                      const std::vector<int>& ks) const
    -> GroupPairNodes {
  const auto& pairs = pair_tangents();
  GroupPairNodes g;
  g.members.assign(members.begin(), members.end());
  g.locals.resize(members.size());
  std::unordered_map<int, int> at_of;  // node: its place among its member's locals
  for (int k : ks)
    for_pair_sides(pairs[k], [&](int node, double) {
      const int i = static_cast<int>(std::find(members.begin(), members.end(), model_.node(node).body) - members.begin());
      if (at_of.emplace(node, static_cast<int>(g.locals[i].size())).second) g.locals[i].push_back(local_index_[node]);
    });
  // Slots member by member, so that a member's nodes are consecutive (G is block-diagonal by member).
  g.first.assign(members.size() + 1, 0);
  for (std::size_t i = 0; i < members.size(); ++i) g.first[i + 1] = g.first[i] + static_cast<int>(g.locals[i].size());
  g.nodes.resize(g.first.back());
  std::unordered_map<int, int> slot_of;
  for (int k : ks)
    for_pair_sides(pairs[k], [&](int node, double) {
      const int i = static_cast<int>(std::find(members.begin(), members.end(), model_.node(node).body) - members.begin());
      const int slot = g.first[i] + at_of[node];
      g.nodes[slot] = node;
      slot_of[node] = slot;
    });
  // The pairs' terms on the nodes' translations, sum over pairs of w_i w_j Kc, as 3 x 3 blocks.
  const double kf = stepper_.stiffness_factor(), cf = stepper_.velocity_factor();
  std::unordered_map<std::int64_t, int> block_of;
  for (int k : ks) {
    const auto& p = pairs[k];
    const Mat3 Kc = kf * (p.K + cf * p.C);
    for_pair_sides(p, [&](int ni, double wi) {
      for_pair_sides(p, [&](int nj, double wj) {
        const int a = slot_of[ni], c = slot_of[nj];
        const auto [it, fresh] = block_of.emplace(std::int64_t{a} * g.nodes.size() + c, static_cast<int>(g.terms.size()));
        if (fresh) g.terms.push_back({a, c, Mat3::Zero()});
        g.terms[it->second].k += wi * wj * Kc;
      });
    });
  }
  return g;
}

// I + D G formed: D's blocks times G's rows of their column node, within that node's member (G is
// block-diagonal by member; the dense product would cost the cube of the nodes).
template <class Element, class Integrator, class LinearSolver, class Contact>
inline Eigen::MatrixXd Simulation<Element, Integrator, LinearSolver, Contact>::group_matrix(const GroupPairNodes& g,
                                                                                            const std::vector<Eigen::MatrixXd>& G) {
  const auto n = static_cast<Eigen::Index>(g.nodes.size());
  std::vector<int> member_of(n);
  for (std::size_t i = 0; i + 1 < g.first.size(); ++i)
    std::fill(member_of.begin() + g.first[i], member_of.begin() + g.first[i + 1], static_cast<int>(i));
  Eigen::MatrixXd A = Eigen::MatrixXd::Identity(3 * n, 3 * n);
  for (const auto& t : g.terms) {
    const int i = member_of[t.col];
    A.block(3 * t.row, 3 * g.first[i], 3, G[i].cols()).noalias() += t.k * G[i].middleRows(3 * (t.col - g.first[i]), 3);
  }
  return A;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline bool Simulation<Element, Integrator, LinearSolver, Contact>::group_flexibility(const detail::GroupLayout& layout,
                                                                                      std::vector<Eigen::MatrixXd>& G) {
  G.resize(layout.members.size());  // block-diagonal by member
  for (std::size_t i = 0; i < layout.members.size(); ++i)
    if (!FlexibleBody::pair_flexibility(*this, layout.members[i], layout.locals[i], G[i])) return false;
  return true;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline bool Simulation<Element, Integrator, LinearSolver, Contact>::solve_flexible_group(std::span<const int> members, bool first_solve) {
  GroupPairNodes g = group_pair_nodes(members, group_pairs_[group_of(members.front())]);
  detail::GroupFactor& kept = systems_[members.front()].group_factor;
  // The last factorised system preconditions GMRES while the pair nodes are the same (their terms and
  // the members' flexibility change by little from step to step); else, or when GMRES does not
  // converge, this step's system is formed and factorised. (Tried, 2026-12-06: the system kept on the
  // nodes of both steps, a node out of contact with identity rows, so that nodes leaving contact would
  // not force a factorisation; configuration 3 under the default job's motion was no faster.)
  const bool near_kept = !kept.empty() && kept.layout.members == g.members && kept.layout.nodes == g.nodes;
  const auto n = static_cast<Eigen::Index>(g.nodes.size());
  Eigen::VectorXd x0(3 * n);  // this solve's increment at the layout's nodes
  for (Eigen::Index i = 0; i < n; ++i) x0.segment<3>(3 * i) = -Du_.segment<3>(6 * g.nodes[i]);
  for (int m : members) {
    timed(sums_[m].solve, [&] { solve_body(m, sums_[m]); });
    if (sums_[m].solve_failed) return false;
  }
  for (Eigen::Index i = 0; i < n; ++i) x0.segment<3>(3 * i) += Du_.segment<3>(6 * g.nodes[i]);
  bool ok = false;
  timed(sums_[members.front()].solve, [&] {
    std::vector<Eigen::MatrixXd> G;
    if (!group_flexibility(g, G)) return;
    const auto times_D = [&](const Eigen::VectorXd& x, Eigen::VectorXd& out) {
      for (const auto& t : g.terms) out.segment<3>(3 * t.row) += t.k * x.segment<3>(3 * t.col);
    };
    const auto times_A = [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {  // (I + D G) v
      Eigen::VectorXd Gv(3 * n);
      for (std::size_t i = 0; i < G.size(); ++i)
        Gv.segment(3 * g.first[i], G[i].rows()).noalias() = G[i] * v.segment(3 * g.first[i], G[i].rows());
      out = v;
      times_D(Gv, out);
    };
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(3 * n), y;
    times_D(x0, rhs);
    if (!near_kept || !detail::solve_near(3 * n, times_A, kept.lu, rhs, y, 20, 1e-12)) {
      kept.layout = g;
      kept.matrix = group_matrix(g, G);
      detail::factorize_lu(kept.lu, kept.matrix);
      y = detail::solve_lu(kept.lu, rhs);
    }
    if (!y.allFinite()) return;
    for (std::size_t i = 0; i < members.size(); ++i)
      if (!FlexibleBody::subtract_pair_response(*this, members[i], g.locals[i], y.segment(3 * g.first[i], G[i].rows())))
        return;
    ok = true;
  });
  if (!ok) {
    sums_[members.front()].solve_failed = true;
    return false;
  }
  if (first_solve && opt_.finite_rotation_update)
    for (int m : members) FlexibleBody::finite_rotation(*this, m);
  return true;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::linearised_contact_at_current_state() {
  if constexpr (ImplicitContactPolicy<Contact>) {
    const auto& tangents = contact_.nodal_tangents();
    predictor_shift_.resize(tangents.size());
    for (size_t k = 0; k < tangents.size(); ++k) {
      predictor_shift_[k] = plane_contact_shift(tangents[k]);
      add_wrench(fc1_, tangents[k], predictor_shift_[k]);
    }
  }
  if constexpr (PairTangentPolicy<Contact>) {
    const auto& pairs = contact_.pair_tangents();
    pair_predictor_shift_.assign(pairs.size(), Vec3::Zero());
    for (size_t k = 0; k < pair_active_.size(); ++k) {
      if (!pair_active_[k]) continue;
      pair_predictor_shift_[k] = pair_shift(pairs[k]);
      share_pair_force(pairs[k], pair_predictor_shift_[k], [&](int n, const Vec6& w) { fc1_.segment<6>(6 * n) += w; });
    }
  }
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::contact_at_end_of_step() {
  if constexpr (ImplicitContactPolicy<Contact>) {
    const StepWork applied = step_work();
    const auto& tangents = contact_.nodal_tangents();
    for (size_t k = 0; k < tangents.size(); ++k) {
      const auto& t = tangents[k];
      if (contact_iterated_[model_.node(t.node).body]) continue;  // its fc1_ holds its end forces already
      const int i = 6 * t.node;
      const Vec6 delta6 = plane_contact_shift(t) - predictor_shift_[k];
      const Vec3 delta = delta6.template head<3>();
      add_wrench(fc0_, t, delta6);
      add_wrench(fnet0_, t, delta6);
      if (t.at_node()) {
        ledger_.contact_work += 0.5 * Du_.segment<3>(i).dot(delta);
        ledger_.contact_work_applied +=
            applied.of_end_change(applied.path(Du_.segment<3>(i), vn_.segment<3>(i), v_.segment<3>(i)), delta);
      } else {
        ledger_.contact_work += 0.5 * Du_.segment<6>(i).dot(delta6);
        ledger_.contact_work_applied +=
            applied.of_end_change(applied.path(Du_.segment<6>(i), vn_.segment<6>(i), v_.segment<6>(i)), delta6);
      }
    }
    if constexpr (PairTangentPolicy<Contact>) {
      const auto& pairs = contact_.pair_tangents();
      for (size_t k = 0; k < pair_active_.size(); ++k) {
        if (!pair_active_[k]) continue;
        share_pair_force(pairs[k], pair_shift(pairs[k]) - pair_predictor_shift_[k], [&](int n, const Vec6& w) {
          fc0_.segment<6>(6 * n) += w;
          fnet0_.segment<6>(6 * n) += w;
          ledger_.contact_work += 0.5 * Du_.segment<6>(6 * n).dot(w);
          ledger_.contact_work_applied += applied.of_end_change(
              applied.path(Du_.segment<6>(6 * n), vn_.segment<6>(6 * n), v_.segment<6>(6 * n)), w);
        });
      }
    }
    contact_delta_.setZero();
    const ContactView view{model_, x_, v_, t_state_, stepper_.dt(), &R_};
    contact_.end_of_step(view, contact_delta_);
  }
}

}  // namespace furniture_fem
