#pragma once
// furniture_fem/core/detail/rigid_body.hpp: Simulation::RigidBody, a rigid body's step: six DOF, Newton on its translation and rotation, the residual reduced
// from the nodal one.
// Included by core/simulation.hpp right after the class (a member class of Simulation, defined out of
// the class so that simulation.hpp stays readable); not a header of its own.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/rigid_body.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif
#include "../dense_kernels.hpp"

namespace furniture_fem {

template <class Element, class Integrator, class LinearSolver, class Contact>
struct Simulation<Element, Integrator, LinearSolver, Contact>::RigidBody {
  // Nothing to assemble: the rigid solve builds its 6 x 6 matrix itself.
  static void evaluate(detail::BodySystem& bs) { bs.assembled = true; }

  static Vec3 mass_centre(const Simulation& sim, const detail::BodySystem& bs) {
    Vec3 c = Vec3::Zero();
    double m = 0;
    for (int n : bs.nodes) {
      c += sim.mass_[6 * n] * sim.x_[n];
      m += sim.mass_[6 * n];
    }
    return c / m;
  }

  // The body's acceleration at the start from the net forces fnet0_ (Newton-Euler about the centre of
  // mass), given to its nodes as the rigid motion's: each node's own f / m is not a rigid motion, and
  // when the contact puts a force on a few support points only it is far off (a block touching the
  // floor at 1 m/s got 100 km/s^2 at its corners, and Newmark carried that into the next steps).
  static void initial_acceleration(Simulation& sim, const detail::BodySystem& bs) {
    if (bs.nodes.empty()) return;
    const Vec3 c = mass_centre(sim, bs);
    Vec3 F = Vec3::Zero(), M = Vec3::Zero();
    Mat3 I = Mat3::Zero();
    double m = 0;
    for (int n : bs.nodes) {
      const Vec3 r = sim.x_[n] - c, f = sim.fnet0_.template segment<3>(6 * n);
      F += f;
      M += r.cross(f) + sim.fnet0_.template segment<3>(6 * n + 3);
      I += sim.mass_[6 * n] * (r.squaredNorm() * Mat3::Identity() - r * r.transpose()) + sim.node_rotary_inertia(n);
      m += sim.mass_[6 * n];
    }
    const Vec3 w = sim.v_.template segment<3>(6 * bs.nodes.front() + 3);  // one angular velocity for all
    const Vec3 ac = F / m, alpha = detail::ldlt_solve(I, M - w.cross(I * w));
    for (int n : bs.nodes) {
      const Vec3 r = sim.x_[n] - c;
      sim.a_.template segment<3>(6 * n) = ac + alpha.cross(r) + w.cross(w.cross(r));
      sim.a_.template segment<3>(6 * n + 3) = alpha;
    }
  }

  // The motion of the step starts at the body's place at t_n.
  static void start_step(const Simulation& sim, detail::BodySystem& bs) {
    bs.rigid_c0 = mass_centre(sim, bs);
    bs.rigid_dc.setZero();
    bs.rigid_Q.setIdentity();
    bs.rigid_at_start = true;
  }

  // Statics has no inertia to hold a rigid body: its solve fails (the caller reports it).
  static void solve(Simulation& sim, detail::BodySystem& bs, BodyStepSums& s) {
    if (sim.static_) {
      s.solve_failed = true;
      return;
    }
    newton_step(sim, bs);
    bs.needs_refresh = false;
    bs.assembled = false;
  }

  // The contact terms reduced like the mass: with T = [I, -S] (dx_n = dc - S dtheta), T^T K T.
  static void add_contact_terms(const Simulation& sim, const detail::BodySystem& bs, const Vec3& c,
                                Eigen::Matrix<double, 6, 6>& A) {
    for (const auto& ct : bs.contact) {
      const int n = bs.nodes[ct.local];
      const Mat3 S = detail::skew(ct.at_node() ? Vec3(sim.x_[n] - c) : Vec3(sim.x_[n] + sim.R_[n] * ct.arm0 - c));
      A.template block<3, 3>(0, 0) += ct.K;
      A.template block<3, 3>(0, 3) -= ct.K * S;
      A.template block<3, 3>(3, 0) += S * ct.K;
      A.template block<3, 3>(3, 3) -= S * ct.K * S;
    }
  }

  // The nodal residual's rotary inertia is the diagonal D_n in world axes (exact for isotropic D_n).
  // For a node with a point inertia on a rigid body, the moment it should have: the turned tensor
  // I_n = R_n T_n R_n^T (T_n the initial tensor) on the (generalized-alpha) angular acceleration, and
  // the gyroscopic w x I_n w. Returns the correction D alpha - I_n alpha - w x I_n w over the body.
  static Vec3 anisotropic_inertia_moment(const Simulation& sim, const detail::BodySystem& bs) {
    Vec3 M = Vec3::Zero();
    for (int n : bs.nodes) {
      if (sim.rotary_index_[n] < 0) continue;  // isotropic: the diagonal is exact, w x J w = 0
      const Vec3 D = sim.mass_.template segment<3>(6 * n + 3);
      const Vec3 alpha = sim.stepper_.template at_inertia_point<Vec3>(sim.a_.template segment<3>(6 * n + 3),
                                                                      sim.an_.template segment<3>(6 * n + 3));
      const Vec3 w = sim.v_.template segment<3>(6 * n + 3);
      const Mat3 In = sim.node_rotary_inertia(n);
      M += D.cwiseProduct(alpha) - In * alpha - w.cross(In * w);
    }
    return M;
  }

  // Nodal increments dx_n = dc + dtheta x r_n, rotations dtheta; the nodal residual and effective
  // mass reduced to 6 x 6 (T^T r, T^T M* T) and solved.
  static void newton_step(Simulation& sim, detail::BodySystem& bs) {
    const ReducedSystem sys = reduced_system(sim, bs);
    apply_increment(sim, bs, detail::ldlt_solve(sys.A, sys.R));
  }

  // A group of rigid bodies joined by pairs (gather_pair_groups): the members' 6 x 6 systems on the
  // diagonal, and each pair's terms k = (1 - af) (K + gamma / (beta dt) C) through the motion of its
  // contact point on each body, T = [I, -[point - c]x]: T_a^T k T_a, T_b^T k T_b, -T_a^T k T_b, -T_b^T k T_a.
  static void group_newton_step(Simulation& sim, std::span<const int> members) {
    const int n = static_cast<int>(members.size());
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6 * n, 6 * n);
    Eigen::VectorXd R(6 * n);
    std::vector<Vec3> centre(n);
    for (int i = 0; i < n; ++i) {
      const ReducedSystem sys = reduced_system(sim, sim.systems_[members[i]]);
      A.template block<6, 6>(6 * i, 6 * i) = sys.A;
      R.template segment<6>(6 * i) = sys.R;
      centre[i] = sys.c;
    }
    if constexpr (PairTangentPolicy<Contact>) add_pair_terms(sim, members, centre, A);
    const Eigen::VectorXd dq = detail::lu_solve(A, R);
    for (int i = 0; i < n; ++i) apply_increment(sim, sim.systems_[members[i]], dq.template segment<6>(6 * i));
  }

  // A member template, though called only under `if constexpr`: an explicit instantiation (the compiled
  // core) instantiates every ordinary member of the class, and this one needs a contact with pair tangents
  // (a requires-clause is enough for GCC 12, not for clang 14).
  template <class = void>
  static void add_pair_terms(const Simulation& sim, std::span<const int> members, const std::vector<Vec3>& centre,
                             Eigen::MatrixXd& A) {
    const auto index = [&](int body) {
      return static_cast<int>(std::find(members.begin(), members.end(), body) - members.begin());
    };
    const double kf = sim.stepper_.stiffness_factor(), cf = sim.stepper_.velocity_factor();
    const auto& pairs = sim.contact_.pair_tangents();
    // Summed per body pair (detail/rigid_pair_terms.hpp): the group's matrix gets each body pair's
    // blocks once. (Added pair by pair, the 6 x 6 products T^T k T were 9.8 % of configuration 3
    // rigid's instructions, callgrind.)
    detail::RigidPairTerms terms(static_cast<int>(members.size()));
    for (int k : sim.group_pairs_[sim.group_of(members.front())]) {
      const auto& p = pairs[k];
      const int ia = index(p.body_a);
      terms.add(ia, index(p.body_b), kf * (p.K + cf * p.C), p.point - centre[ia]);
    }
    terms.add_to(centre, A);
  }

  struct ReducedSystem {
    Eigen::Matrix<double, 6, 6> A;
    Vec6 R;
    Vec3 c;  // the mass centre the rotations are about
  };
  static ReducedSystem reduced_system(const Simulation& sim, const detail::BodySystem& bs) {
    const double mf = sim.stepper_.mass_factor(sim.opt_.mass_damping);
    if (const auto& F = sim.fields_[&bs - sim.systems_.data()]; F.on) {
      Eigen::Matrix<double, 6, 6> A = detail::rigid_mass_matrix(F.mm, F.Q, mf);
      if (!sim.static_) add_contact_terms(sim, bs, F.c, A);
      return {A, F.R, F.c};
    }
    const auto& mass = sim.mass_;
    const auto& r_nodal = sim.r_;
    // Nodes not moved since start_step: their mass centre is rigid_c0, to the bit.
    const Vec3 c = bs.rigid_at_start ? bs.rigid_c0 : mass_centre(sim, bs);
    Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
    Vec6 R6 = Vec6::Zero();
    // The body's inertia tensor about c (world axes), in the same pass: sum over nodes of
    // m (|r|^2 I - r r^T) + R_n T_n R_n^T, T_n the node's initial rotary inertia (node_rotary_inertia).
    Mat3 I = Mat3::Zero();
    for (int n : bs.nodes) {
      const Vec3 r = sim.x_[n] - c;
      const Mat3 S = detail::skew(r);  // dtheta x r = -S dtheta
      const double m = mf * mass[6 * n];
      // m I on the diagonal only: the off-diagonal terms added +0 to +0 (m >= 0), the same bits.
      for (int j = 0; j < 3; ++j) A(j, j) += m;
      A.template block<3, 3>(0, 3) -= m * S;
      A.template block<3, 3>(3, 0) += m * S;
      const Vec3 rf = r_nodal.template segment<3>(6 * n), rm = r_nodal.template segment<3>(6 * n + 3);
      R6.template head<3>() += rf;
      R6.template tail<3>() += S * rf + rm;
      I += mass[6 * n] * (r.squaredNorm() * Mat3::Identity() - r * r.transpose()) + sim.rigid_node_rotary_inertia(n);
    }
    if (!sim.static_) add_contact_terms(sim, bs, c, A);
    A.template block<3, 3>(3, 3) += mf * I;
    R6.template tail<3>() += anisotropic_inertia_moment(sim, bs);
    return {A, R6, c};
  }
  // The body moved by dq (its centre's translation, then its rotation) on top of the step's motion so far.
  static void apply_increment(Simulation& sim, detail::BodySystem& bs, const Vec6& dq) {
    bs.rigid_dc += dq.template head<3>();
    bs.rigid_Q = detail::rotation_exp(dq.template tail<3>()) * bs.rigid_Q;
    const Vec3 rot = detail::rotation_log(bs.rigid_Q);
    if (auto& F = sim.fields_[&bs - sim.systems_.data()]; F.on) {
      // d_n = dc + (Q_step - I) r_n with r_n = Q_start rho_n the arm at the step's start.
      F.du = {bs.rigid_dc, (bs.rigid_Q - Mat3::Identity()) * F.Q_start};
      F.dtheta = rot;
      F.c = F.c_start + bs.rigid_dc;
      F.Q = bs.rigid_Q * F.Q_start;
      return;
    }
    for (int n : bs.nodes) {
      const Vec3 x0 = sim.model_.node(n).X + sim.u0_[n];
      sim.Du_.template segment<3>(6 * n) = bs.rigid_c0 + bs.rigid_dc + bs.rigid_Q * (x0 - bs.rigid_c0) - x0;
      sim.Du_.template segment<3>(6 * n + 3) = rot;
    }
  }
};

}  // namespace furniture_fem
