#pragma once
// furniture_fem/core/detail/simulation_sweep.hpp: the sweep over the bodies: each body's elements, residual, predictor, update and commit.
// Included by core/simulation.hpp right after the class: member functions of Simulation defined out of
// the class (declared, with what they do, in it); not a header of its own.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/simulation_sweep.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif

namespace furniture_fem {

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::evaluate_elements(bool assemble_all) {
  pool_.parallel_for(body_order_, opt_.threads,
                       [&](int b) { evaluate_body(b, assemble_all || systems_[b].needs_refresh); });
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::evaluate_body(int b, bool assemble) {
  auto& bs = systems_[b];
  // A flexible body's matrix is made at its first assembly (before start() too: update_internal_forces);
  // only this body's own members are touched, so the parallel sweep may do it.
  if (assemble && !bs.rigid) prepare_matrix(b);
  double* Kv = bs.K.valuePtr();
  if (assemble) std::fill(Kv, Kv + bs.K.nonZeros(), 0.0);
  // A rigid body's internal forces are zero from the start and never written: no pass to clear them.
  if (bs.rigid) return RigidBody::evaluate(bs);
  for (int n : bs.nodes) fint_.segment<6>(6 * n).setZero();
  const double kf = static_ ? 1.0 : stepper_.stiffness_factor();
  // Structural damping: c k_e (d - d_n) / dt on the element's deformations; its tangent c / dt k_e.
  const double cd = static_ ? 0.0 : opt_.stiffness_damping / stepper_.dt();
  Vec12 f, fg;
  Mat12 k, kg;
  for (size_t idx = 0; idx < bs.elements.size(); ++idx) {
    const int e = bs.elements[idx];
    const auto& el = model_.elements()[e];
    const auto cr = detail::corotate(model_.node(el.n1).X, model_.node(el.n2).X, u_[el.n1], u_[el.n2], R_[el.n1],
                                     R_[el.n2], E0_[e], props_[e].L0);
    frames_[e] = cr.E;
    d_[e] = cr.d;
    if constexpr (requires { Element::internal_force(props_[e], committed_[e], cr.d, f, trial_[e]); }) {
      if (assemble || cd > 0) Element::response(props_[e], committed_[e], cr.d, f, k, trial_[e]);
      else Element::internal_force(props_[e], committed_[e], cr.d, f, trial_[e]);
    } else {
      Element::response(props_[e], committed_[e], cr.d, f, k, trial_[e]);
    }
    fl_[e] = f;  // the members' own forces (sections, strain energy): without the damping
    if (cd > 0) {
      fd_[e] = cd * (k * (cr.d - dn_[e]));
      f += fd_[e];
      k *= 1 + cd;
    }
    for (int blk = 0; blk < 4; ++blk) fg.segment<3>(3 * blk) = cr.E * f.segment<3>(3 * blk);
    fint_.segment<6>(6 * el.n1) += fg.head<6>();
    fint_.segment<6>(6 * el.n2) += fg.tail<6>();
    if (assemble) {
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
          kg.block<3, 3>(3 * i, 3 * j) = cr.E * k.block<3, 3>(3 * i, 3 * j) * cr.E.transpose();
      if (opt_.geometric_stiffness) {
        // String stiffness of the axial force: N / l (I - e1 e1^T) on the translations.
        const Mat3 G = fl_[e][6] / cr.l * (Mat3::Identity() - cr.E.col(0) * cr.E.col(0).transpose());
        kg.block<3, 3>(0, 0) += G;
        kg.block<3, 3>(6, 6) += G;
        kg.block<3, 3>(0, 6) -= G;
        kg.block<3, 3>(6, 0) -= G;
      }
      const auto& slots = bs.element_slots[idx];
      for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 12; ++j) Kv[slots[i * 12 + j]] += kf * kg(i, j);
    }
  }
  for (const auto& sp : springs_) {
    if (model_.node(sp.node).body != b) continue;
    const int i = 6 * sp.node + sp.dof;
    fint_[i] += sp.k * dof_value(sp.node, sp.dof);  // its target is a load (external_forces)
    if (assemble) Kv[bs.diag_slot[6 * local_index_[sp.node] + sp.dof]] += kf * sp.k;
  }
  if (assemble) {
    const double mf = static_ ? 0.0 : stepper_.mass_factor(opt_.mass_damping);
    for (size_t k2 = 0; k2 < bs.nodes.size(); ++k2)
      for (int i = 0; i < 6; ++i) {
        const int ld = 6 * static_cast<int>(k2) + i;
        Kv[bs.diag_slot[ld]] += mf * mass_[6 * bs.nodes[k2] + i];
      }
    // Fixed DOFs: identity rows and columns, so the pattern (and the symbolic analysis) stays.
    for (int col = 0; col < bs.ndof(); ++col)
      for (SparseMatrix::InnerIterator it(bs.K, col); it; ++it)
        if (bs.fixed[it.row()] || bs.fixed[col]) it.valueRef() = (it.row() == col) ? 1.0 : 0.0;
    bs.assembled = true;
  }
}

template <class Element, class Integrator, class LinearSolver, class Contact>
template <class F>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::body_sweep(F&& f) {
  timed(timings_.bodies, [&] { pool_.parallel_for(body_order_, sweep_threads(), f); });
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline int Simulation<Element, Integrator, LinearSolver, Contact>::sweep_threads() const {
  const bool any_flexible = std::any_of(systems_.begin(), systems_.end(), [](const auto& bs) { return !bs.rigid; });
  return any_flexible ? opt_.threads : 1;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline auto Simulation<Element, Integrator, LinearSolver, Contact>::sum_bodies(double t) -> BodyStepSums {
  BodyStepSums total;
  for (auto& s : sums_) {
    total += s;
    s = {};
  }
  timings_.solve += total.solve;
  timings_.factorize += total.factorize;
  timings_.elements += total.elements;
  ledger_.external_work += total.external_work;
  ledger_.contact_work += total.contact_work;
  ledger_.contact_work_applied += total.contact_work_applied;
  ledger_.damping_work += total.damping_work;
  if (total.solve_failed)
    throw SimulationError(t_, "the linear solver failed: the effective matrix is not positive definite or the "
                              "solution is not finite (an unsupported static model, or a diverging step)");
  if (total.not_finite)
    throw SimulationError(t, "the displacement increment is not finite: " + non_finite_diagnosis());
  return total;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::residual_body(const detail::BodySystem& bs, const Eigen::VectorXd& fext1, double& num, double& den) {
  const double c = opt_.mass_damping;
  if (const int b = static_cast<int>(&bs - systems_.data()); fields_[b].on) return RigidFields::residual(*this, b, num, den);
  // A node's six DOFs at once (each value by the same operations in the same order as DOF by DOF,
  // so the same bits; the sums below stay in DOF order).
  for (size_t k = 0; k < bs.nodes.size(); ++k) {
    const int i = 6 * bs.nodes[k];
    const Vec6 fx = fext1.segment<6>(i), fc = fc1_.segment<6>(i), fi = fint_.segment<6>(i), m = mass_.segment<6>(i);
    const Vec6 inertia = m.cwiseProduct(stepper_.template at_inertia_point<Vec6>(a_.segment<6>(i), an_.segment<6>(i)));
    const Vec6 damping = (c * m).cwiseProduct(stepper_.template at_force_point<Vec6>(v_.segment<6>(i), vn_.segment<6>(i)));
    Vec6 ri = stepper_.template at_force_point<Vec6>(fx + fc - fi, fnet0_.segment<6>(i)) - inertia - damping;
    const Vec6 scale = fx.cwiseProduct(fx) + fi.cwiseProduct(fi) + inertia.cwiseProduct(inertia) + fc.cwiseProduct(fc);
    for (int j = 0; j < 6; ++j) {
      if (bs.fixed[6 * k + j]) ri[j] = 0.0;
      num += ri[j] * ri[j];
      den += scale[j];
    }
    r_.segment<6>(i) = ri;
  }
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline double Simulation<Element, Integrator, LinearSolver, Contact>::residual() {
  BodyStepSums s;
  for (const auto& bs : systems_) residual_body(bs, fext1_, s.residual_num, s.residual_den);
  return s.residual();
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::predict_body(int b, const Loads& loads) {
  auto& bs = systems_[b];
  if (fields_[b].refit) RigidFields::refit(*this, b);
  if (fields_[b].on) {
    RigidFields::predict(*this, b, loads);
    contact_iterated_[b] = 0;
    return;
  }
  for (int n : bs.nodes) {
    const int i = 6 * n;
    u0_[n] = u_[n];
    R0_[n] = R_[n];
    vn_.segment<6>(i) = v_.segment<6>(i);
    an_.segment<6>(i) = a_.segment<6>(i);
    Du_.segment<6>(i).setZero();
    v_contact_.segment<6>(i) = stepper_.template contact_velocity<Vec6>(vn_.segment<6>(i), an_.segment<6>(i));
    newmark_rates(i);
  }
  if (bs.rigid) RigidBody::start_step(*this, bs);
  contact_iterated_[b] = 0;
  external_forces_body(b, loads, fext1_);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::kinematics_body(int b) {
  auto& bs = systems_[b];
  if (fields_[b].on) return RigidFields::kinematics(*this, b);
  // Every node of a rigid body turns by the same increment: one exponential for all of them.
  const bool same_turn = bs.rigid && !bs.nodes.empty();
  const Mat3 turn = same_turn ? detail::rotation_exp(Du_.segment<3>(6 * bs.nodes.front() + 3)) : Mat3::Identity();
  bs.rigid_at_start = false;
  for (int n : bs.nodes) {
    const int i = 6 * n;
    newmark_rates(i);
    u_[n] = u0_[n] + Du_.segment<3>(i);
    x_[n] = model_.node(n).X + u_[n];
    R_[n] = (same_turn ? turn : detail::rotation_exp(Du_.segment<3>(i + 3))) * R0_[n];
  }
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::newmark_rates(int i) {
  const auto rates = stepper_.template update<Vec6>(Du_.segment<6>(i), vn_.segment<6>(i), an_.segment<6>(i));
  a_.segment<6>(i) = rates.acceleration;
  v_.segment<6>(i) = rates.velocity;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline auto Simulation<Element, Integrator, LinearSolver, Contact>::step_work() const -> StepWork {
  return {static_, stepper_.dt(), stepper_.end_force_share()};
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::commit_body(int b, BodyStepSums& s) {
  auto& bs = systems_[b];
  const StepWork applied = step_work();
  if (fields_[b].on) return RigidFields::commit(*this, b, s);
  for (int n : bs.nodes) {
    const int i = 6 * n;
    const auto du = Du_.segment<6>(i);
    s.external_work += 0.5 * du.dot(fext0_.segment<6>(i) + fext1_.segment<6>(i) - fgrav_.segment<6>(i) * 2.0);
    s.contact_work += 0.5 * du.dot(fc0_.segment<6>(i) + fc1_.segment<6>(i));
    s.contact_work_applied +=
        applied.of(applied.path(du, vn_.segment<6>(i), v_.segment<6>(i)), fc0_.segment<6>(i), fc1_.segment<6>(i));
    if (opt_.mass_damping > 0)
      s.damping_work -= 0.5 * opt_.mass_damping *
                        du.dot((mass_.segment<6>(i).array() * (vn_.segment<6>(i) + v_.segment<6>(i)).array()).matrix());
  }
  // A rigid body's elements are never evaluated (no forces, no history): nothing to commit or shift.
  // (Carrying a rigid body's forces in the loop above, one pass less, took more instructions than it
  // saved: 221 -> 294 M instructions over 1000 steps of configuration 3, callgrind.)
  if (!bs.rigid) {
    for (int e : bs.elements) std::swap(committed_[e], trial_[e]);
    s.shifted += shift_integration_points(b);
    if (opt_.stiffness_damping > 0 && !static_)
      for (int e : bs.elements) {  // its force at the step's start and end over the step's deformation
        s.damping_work -= 0.5 * (fdn_[e] + fd_[e]).dot(d_[e] - dn_[e]);
        dn_[e] = d_[e];
        fdn_[e] = fd_[e];
      }
  }
  for (int n : bs.nodes) {
    const int i = 6 * n;
    fext0_.segment<6>(i) = fext1_.segment<6>(i);
    fc0_.segment<6>(i) = fc1_.segment<6>(i);
    fnet0_.segment<6>(i) = fext1_.segment<6>(i) + fc1_.segment<6>(i) - fint_.segment<6>(i);
  }
  ++bs.steps_since_refresh;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline double Simulation<Element, Integrator, LinearSolver, Contact>::static_residual() {
  double num = 0, den = 0;
  for (int i = 0; i < r_.size(); ++i) {
    const double ri = is_fixed(i) ? 0.0 : fext1_[i] - fint_[i];
    r_[i] = ri;
    num += ri * ri;
    den += fext1_[i] * fext1_[i] + fint_[i] * fint_[i];
  }
  return std::sqrt(num / std::max(den, 1e-300));
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline int Simulation<Element, Integrator, LinearSolver, Contact>::solve_bodies() {
  body_sweep([&](int b) { solve_body(b, sums_[b]); });
  return sum_bodies(t_).refreshed;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline bool Simulation<Element, Integrator, LinearSolver, Contact>::update_body(int b, BodyStepSums& s, bool first_solve) {
  if (const int g = group_of(b); g >= 0) return groups_[g].front() != b || update_group(groups_[g], first_solve);
  timed(s.solve, [&] {
    solve_body(b, s);
    if (first_solve && opt_.finite_rotation_update && !s.solve_failed && !systems_[b].rigid)
      FlexibleBody::finite_rotation(*this, b);
  });
  if (s.solve_failed) return false;
  timed(s.elements, [&] {
    kinematics_body(b);
    evaluate_body(b, systems_[b].needs_refresh);
  });
  return true;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::solve_body(int b, BodyStepSums& s) {
  auto& bs = systems_[b];
  if (bs.steps_since_refresh >= opt_.refresh_interval_steps) bs.needs_refresh = true;
  if (bs.needs_refresh && !bs.assembled) evaluate_body(b, true);
  if (bs.rigid) RigidBody::solve(*this, bs, s);
  else FlexibleBody::solve(*this, b, s);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline auto Simulation<Element, Integrator, LinearSolver, Contact>::loads_at(double t) const -> Loads {
  Loads l;
  if (static_) {
    l.scale = l.gravity_factor = load_factor_;
    return l;
  }
  if (table_acc_) l.table_acc = table_acc_(t);
  if (load_scale_) l.scale = load_scale_(t);
  return l;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::external_forces(double t, Eigen::VectorXd& f) {
  const Loads loads = loads_at(t);
  for (int b = 0; b < model_.num_bodies(); ++b) external_forces_body(b, loads, f);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::external_forces_body(int b, const Loads& loads, Eigen::VectorXd& f) {
  for (int n : systems_[b].nodes) {
    const double m = mass_[6 * n];
    fgrav_.segment<3>(6 * n) = m * opt_.gravity * loads.gravity_factor;
    f.segment<3>(6 * n) = fgrav_.segment<3>(6 * n) - Vec3(m * loads.table_acc);
    f.segment<3>(6 * n + 3).setZero();
    f.segment<6>(6 * n) += loads.scale * nodal_load_.segment<6>(6 * n);
  }
  // A support spring's force k (scale target - u) is split: k scale target is a load (so that a step
  // sees its target at t_{n+1} from its first residual on, in carry-over mode too), k u is internal.
  for (const auto& sp : springs_)
    if (model_.node(sp.node).body == b) f[6 * sp.node + sp.dof] += loads.scale * sp.k * sp.target;
}

}  // namespace furniture_fem
