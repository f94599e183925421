#pragma once
// furniture_fem/core/detail/rigid_fields.hpp: Simulation::RigidFields, a rigid body stepped on its fields: every translational field affine in the nodes'
// material arms, the step's sums from the body's mass moments.
// Included by core/simulation.hpp right after the class (a member class of Simulation, defined out of
// the class so that simulation.hpp stays readable); not a header of its own.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/rigid_fields.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif

namespace furniture_fem {

template <class Element, class Integrator, class LinearSolver, class Contact>
struct Simulation<Element, Integrator, LinearSolver, Contact>::RigidFields {
  using Fields = detail::RigidFieldState;
  struct Arms {  // the material positions and masses, as detail::RigidMassMoments::of reads them
    const Model& model;
    const Vec3& operator[](int n) const { return model.node(n).X; }
  };
  struct Masses {
    const Eigen::VectorXd& mass;
    double operator[](int n) const { return mass[6 * n]; }
  };
  struct Rotary {
    const Eigen::VectorXd& mass;
    Vec3 operator[](int n) const { return mass.template segment<3>(6 * n + 3); }
  };

  // Whether the body can go on its fields: rigid, free of point inertias, nodal loads and springs,
  // and its nodes placed and moving as one rigid body (fitted, then checked node by node).
  static bool eligible(const Simulation& sim, int b) {
    const auto& bs = sim.systems_[b];
    if (!sim.opt_.rigid_fields || !bs.rigid || bs.nodes.empty() || sim.static_) return false;
    for (int n : bs.nodes)
      if (sim.rotary_index_[n] >= 0 || !sim.nodal_load_.template segment<6>(6 * n).isZero(0.0)) return false;
    for (const auto& sp : sim.springs_)
      if (sim.model_.node(sp.node).body == b) return false;
    return true;
  }
  // A node's material arm, kept per body in its nodes' order (rigid_arms_).
  static const Vec3& arm(const Simulation& sim, int n) {
    return sim.rigid_arms_[sim.model_.node(n).body][sim.local_index_[n]];
  }
  static void set_arms(Simulation& sim, int b) {
    const auto& bs = sim.systems_[b];
    auto& arms = sim.rigid_arms_[b];
    arms.resize(bs.nodes.size());
    for (size_t k = 0; k < bs.nodes.size(); ++k) arms[k] = sim.model_.node(bs.nodes[k]).X - sim.fields_[b].mm.centre;
  }
  // a + B r written out: the passes over the nodes are these and stores (Eigen's product was a call).
  static Vec3 affine(const Vec3& a, const Mat3& B, const Vec3& r) {
    return Vec3(a[0] + B(0, 0) * r[0] + B(0, 1) * r[1] + B(0, 2) * r[2],
                a[1] + B(1, 0) * r[0] + B(1, 1) * r[1] + B(1, 2) * r[2],
                a[2] + B(2, 0) * r[0] + B(2, 1) * r[1] + B(2, 2) * r[2]);
  }
  static Vec3 at(const detail::AffineField& f, const Vec3& r) { return affine(f.a, f.B, r); }
  // A node's six values: its translational part, then its rotational part.
  static void put(double* node, const Vec3& translation, const Vec3& rotation) {
    for (int j = 0; j < 3; ++j) {
      node[j] = translation[j];
      node[3 + j] = rotation[j];
    }
  }
  static bool nonzero6(const double* p) {
    return (p[0] != 0) | (p[1] != 0) | (p[2] != 0) | (p[3] != 0) | (p[4] != 0) | (p[5] != 0);
  }

  // The fields through the nodes' state (at the start of a run, or after nodes were set from outside);
  // false, and the body stays node by node, when the nodes are not one rigid body's.
  static bool fit(Simulation& sim, int b, Fields& F) {
    const auto& bs = sim.systems_[b];
    const Arms X{sim.model_};
    const Masses m{sim.mass_};
    F.mm = detail::RigidMassMoments::of(bs.nodes, X, m, Rotary{sim.mass_});
    set_arms(sim, b);
    const int n0 = bs.nodes.front();
    F.Q = sim.R_[n0];
    F.c = Vec3::Zero();
    for (int n : bs.nodes) F.c += m[n] * sim.x_[n];
    F.c /= F.mm.mass.w;
    const auto trans = [&](const Eigen::VectorXd& v) {
      return detail::fit_affine_field(bs.nodes, F.mm, [&](int n) -> Vec3 { return v.template segment<3>(6 * n); }, X, m);
    };
    F.f.v = trans(sim.v_);
    F.f.a = trans(sim.a_);
    F.f.w = sim.v_.template segment<3>(6 * n0 + 3);
    F.f.alpha = sim.a_.template segment<3>(6 * n0 + 3);
    // Rounding of the fit is ~1e-15 of the values; anything near 1e-9 is a motion that is not rigid.
    const double size = std::sqrt(F.mm.mass.second.trace() / F.mm.mass.w) + 1.0;
    double vmax = 1, amax = 1;
    for (int n : bs.nodes) {
      vmax = std::max(vmax, sim.v_.template segment<6>(6 * n).cwiseAbs().maxCoeff());
      amax = std::max(amax, sim.a_.template segment<6>(6 * n).cwiseAbs().maxCoeff());
    }
    for (int n : bs.nodes) {
      const Vec3& rho = arm(sim, n);
      const int i = 6 * n;
      if ((sim.x_[n] - (F.c + F.Q * rho)).norm() > 1e-9 * size || (sim.R_[n] - F.Q).norm() > 1e-9 ||
          (sim.v_.template segment<3>(i) - F.f.v.at(rho)).norm() > 1e-9 * vmax ||
          (sim.v_.template segment<3>(i + 3) - F.f.w).norm() > 1e-9 * vmax ||
          (sim.a_.template segment<3>(i) - F.f.a.at(rho)).norm() > 1e-9 * amax ||
          (sim.a_.template segment<3>(i + 3) - F.f.alpha).norm() > 1e-9 * amax)
        return false;
    }
    return true;
  }

  // At the start of a run (start()): the fields from the nodes' state; the nodes' net forces become
  // their contact forces alone (a rigid body has no internal force; its uniform load is g0).
  static void begin(Simulation& sim, int b) {
    Fields& F = sim.fields_[b];
    F = {};
    if (!eligible(sim, b) || !fit(sim, b, F)) return;
    const Loads loads = sim.loads_at(sim.t_);
    F.g0 = sim.opt_.gravity * loads.gravity_factor - loads.table_acc;
    for (int n : sim.systems_[b].nodes)
      sim.fnet0_.template segment<6>(6 * n) = sim.fc0_.template segment<6>(6 * n);
    F.on = true;
  }
  // Nodes set from outside between steps: fitted again, or back to node by node (the nodal arrays
  // the node-by-node step starts from: its external forces at t_n in fext0_ and fnet0_).
  static void refit(Simulation& sim, int b) {
    Fields& F = sim.fields_[b];
    F.refit = false;
    const Vec3 g0 = F.g0;
    if (eligible(sim, b) && fit(sim, b, F)) return;
    F.on = false;
    for (int n : sim.systems_[b].nodes) {
      const int i = 6 * n;
      sim.fext0_.template segment<3>(i) = sim.mass_[i] * g0;
      sim.fext0_.template segment<3>(i + 3).setZero();
      sim.fnet0_.template segment<6>(i) = sim.fext0_.template segment<6>(i) + sim.fc0_.template segment<6>(i);
    }
  }

  // The predictor (Du = 0): Newmark's rates on the fields; the nodes' velocity (the contact's
  // linearisation reads it) and the velocity the contact is evaluated at, vn + dt an.
  static void predict(Simulation& sim, int b, const Loads& loads) {
    auto& bs = sim.systems_[b];
    Fields& F = sim.fields_[b];
    F.c_start = F.c;
    F.Q_start = F.Q;
    F.f.vn = F.f.v;
    F.f.an = F.f.a;
    F.f.wn = F.f.w;
    F.f.alphan = F.f.alpha;
    F.du = {};
    F.dtheta.setZero();
    rates(sim, F);
    F.g1 = sim.opt_.gravity * loads.gravity_factor - loads.table_acc;
    bs.rigid_c0 = F.c;
    bs.rigid_dc.setZero();
    bs.rigid_Q.setIdentity();
    bs.rigid_at_start = true;
    place_start_rates(sim, b, sim.step_nodes(b));
    sim.unplaced_[b] = !sim.step_nodes_[b].empty();
  }
  // The stepper's acceleration and velocity from the increment, on the fields.
  static void rates(const Simulation& sim, Fields& F) {
    auto translation = sim.stepper_.update(F.du, F.f.vn, F.f.an);
    F.f.a = std::move(translation.acceleration);
    F.f.v = std::move(translation.velocity);
    auto rotation = sim.stepper_.update(F.dtheta, F.f.wn, F.f.alphan);
    F.f.alpha = rotation.acceleration;
    F.f.w = rotation.velocity;
  }
  // The increment's rates and the nodes the step reads placed on the body's motion.
  static void kinematics(Simulation& sim, int b) {
    rates(sim, sim.fields_[b]);
    sim.systems_[b].rigid_at_start = false;
    place_motion(sim, b, sim.step_nodes(b));
    sim.unplaced_[b] = !sim.step_nodes_[b].empty();
  }
  // Nodes ks (local indices) of body b on the body's motion: position, displacement, rotation,
  // velocity, acceleration and increment.
  static void place_motion(const Simulation& sim, int b, std::span<const int> ks) {
    const Fields& F = sim.fields_[b];
    const Vec3 shift = F.c - F.mm.centre;  // u_n = (c - X_c) + (Q - I) rho_n: small u stays precise
    const Mat3 turn = F.Q - Mat3::Identity();
    const auto& arms = sim.rigid_arms_[b];
    const auto& nodes = sim.systems_[b].nodes;
    double* v = sim.v_.data();
    double* a = sim.a_.data();
    double* du = sim.Du_.data();
    for (int k : ks) {
      const int n = nodes[k], i = 6 * n;
      const Vec3& rho = arms[k];
      sim.u_[n] = affine(shift, turn, rho);
      sim.x_[n] = affine(F.c, F.Q, rho);
      sim.R_[n] = F.Q;
      put(v + i, at(F.f.v, rho), F.f.w);
      put(a + i, at(F.f.a, rho), F.f.alpha);
      put(du + i, at(F.du, rho), F.dtheta);
    }
  }
  // Nodes ks's velocities: now, at the step's start, and the one the contact is evaluated at.
  static void place_start_rates(const Simulation& sim, int b, std::span<const int> ks) {
    const Fields& F = sim.fields_[b];
    const detail::AffineField vc = sim.stepper_.contact_velocity(F.f.vn, F.f.an);
    const Vec3 wc = sim.stepper_.contact_velocity(F.f.wn, F.f.alphan);
    const auto& arms = sim.rigid_arms_[b];
    const auto& nodes = sim.systems_[b].nodes;
    double* v = sim.v_.data();
    double* vn = sim.vn_.data();
    double* vcon = sim.v_contact_.data();
    for (int k : ks) {
      const int i = 6 * nodes[k];
      put(v + i, at(F.f.v, arms[k]), F.f.w);
      put(vn + i, at(F.f.vn, arms[k]), F.f.wn);
      put(vcon + i, at(vc, arms[k]), wc);
    }
  }
  // Nodes ks placed whole: what a reader from outside sees of them (place_unplaced_nodes).
  static void place(const Simulation& sim, int b, std::span<const int> ks) {
    place_motion(sim, b, ks);
    place_start_rates(sim, b, ks);
  }
  static void place_all(const Simulation& sim, int b) {
    place(sim, b, sim.all_local_[b]);
    sim.unplaced_[b] = 0;
  }
  // A body's state at the start of the step on its fields (step_start_states).
  static void start_states(const Simulation& sim, int b, NodeStates& out) {
    const Fields& F = sim.fields_[b];
    const auto& nodes = sim.systems_[b].nodes;
    const Vec3 shift = F.c_start - F.mm.centre;
    const Mat3 turn = F.Q_start - Mat3::Identity();
    for (size_t k = 0; k < nodes.size(); ++k) {
      const int n = nodes[k], i = 6 * n;
      const Vec3& rho = sim.rigid_arms_[b][k];
      out.u[n] = affine(shift, turn, rho);
      out.x[n] = affine(F.c_start, F.Q_start, rho);
      out.R[n] = F.Q_start;
      put(out.v.data() + i, at(F.f.vn, rho), F.f.wn);
      put(out.a.data() + i, at(F.f.an, rho), F.f.alphan);
    }
  }

  // The nodes carrying forces besides their share of the uniform load: those with contact forces at
  // either end of the step.
  static std::vector<detail::RigidNodeExtra> loaded_nodes(const Simulation& sim, int b) {
    std::vector<detail::RigidNodeExtra> out;
    for (int k : sim.step_nodes(b)) {
      const int n = sim.systems_[b].nodes[k], i = 6 * n;
      if (!(nonzero6(sim.fc1_.data() + i) | nonzero6(sim.fnet0_.data() + i))) continue;
      const auto fc1 = sim.fc1_.template segment<6>(i), f0 = sim.fnet0_.template segment<6>(i);
      detail::RigidNodeExtra e;
      e.rho = arm(sim, n);
      e.m = sim.mass_[i];
      e.J = sim.mass_.template segment<3>(i + 3);
      e.s = sim.stepper_.template at_force_point<Vec6>(fc1, f0);
      e.l1.setZero();
      e.fc1 = fc1;
      out.push_back(e);
    }
    return out;
  }
  // The residual reduced to the body (kept for its 6 x 6 solve), its squared norm and force scale.
  static void residual(Simulation& sim, int b, double& num, double& den) {
    Fields& F = sim.fields_[b];
    const auto extra = loaded_nodes(sim, b);
    const auto r = detail::rigid_reduced_residual(F.mm, F.Q, F.f, sim.stepper_,
                                                  sim.opt_.mass_damping, F.g1, F.g0, extra);
    F.R = r.R;
    num += r.num;
    den += r.den;
  }

  // The step's works (the uniform load's and the damping's from the moments, the contact's at its
  // nodes) and the contact forces the next step starts from.
  static void commit(Simulation& sim, int b, BodyStepSums& s) {
    auto& bs = sim.systems_[b];
    Fields& F = sim.fields_[b];
    const StepWork applied = sim.step_work();
    const Vec3 g = sim.opt_.gravity;
    const auto w = detail::rigid_step_work(F.mm, F.du, F.dtheta, F.f, g - F.g0, g - F.g1, sim.opt_.mass_damping);
    s.external_work += w.external;
    s.damping_work += w.damping;
    for (int k : sim.step_nodes(b)) {
      const int i = 6 * bs.nodes[k];
      if (!(nonzero6(sim.fc0_.data() + i) | nonzero6(sim.fc1_.data() + i))) continue;
      const auto fc0 = sim.fc0_.template segment<6>(i), fc1 = sim.fc1_.template segment<6>(i);
      const auto du = sim.Du_.template segment<6>(i);
      s.contact_work += 0.5 * du.dot(fc0 + fc1);
      s.contact_work_applied +=
          applied.of(applied.path(du, sim.vn_.template segment<6>(i), sim.v_.template segment<6>(i)), fc0, fc1);
      sim.fc0_.template segment<6>(i) = fc1;
      sim.fnet0_.template segment<6>(i) = fc1;
    }
    F.g0 = F.g1;
    ++bs.steps_since_refresh;
  }

  static bool finite(const Fields& F) {
    return F.du.a.allFinite() && F.du.B.allFinite() && F.dtheta.allFinite() && F.c.allFinite() && F.Q.allFinite();
  }
  // The increment, the placement and the velocity (what first_non_finite_node checks of the nodes).
  static bool state_finite(const Fields& F) {
    return finite(F) && F.f.v.a.allFinite() && F.f.v.B.allFinite() && F.f.w.allFinite();
  }
};

}  // namespace furniture_fem
