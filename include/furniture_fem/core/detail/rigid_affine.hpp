#pragma once
// furniture_fem/core/detail/rigid_affine.hpp: a rigid body's nodal fields as affine functions of the
// nodes' material arms, and the sums over its nodes the step needs, from the body's mass moments.
//
// On a rigid body the nodal Newmark scheme moves every node by d_n = dc + (Q - I) r_n (r_n its arm from
// the mass centre at the step's start, itself Q0 rho_n with rho_n = X_n - X_c the material arm), and
// Newmark's acceleration and velocity are linear in the increment and the step's start values. So every
// translational field of the scheme (increment, velocity, acceleration and their start values) is
// f_n = a + B rho_n with one vector a and one 3 x 3 matrix B per body, and every rotational field is one
// vector per body. A sum over the nodes of such fields weighted by the nodes' masses is a sum of the
// body's mass moments (sum m, sum m rho, sum m rho rho^T) and, for squared norms, of the squared
// masses' moments: the cost of a rigid body's step no longer grows with its nodes
// (docs/performance.md section 7; docs/core/theory.md, "Rigid bodies on their fields").
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/rigid_affine.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif
#include <Eigen/Core>
#include <span>
#include <type_traits>

#include "../dense_kernels.hpp"

namespace furniture_fem::detail {

// f(rho) = a + B rho.
struct AffineField {
  static constexpr bool checkpoint_as_bytes = true;  // core/checkpoint.hpp (no padding: 8-byte fields)
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Matrix3d B = Eigen::Matrix3d::Zero();

  static AffineField uniform(const Eigen::Vector3d& a) { return {a, Eigen::Matrix3d::Zero()}; }
  Eigen::Vector3d at(const Eigen::Vector3d& rho) const { return a + B * rho; }

  friend AffineField operator+(const AffineField& f, const AffineField& g) { return {f.a + g.a, f.B + g.B}; }
  friend AffineField operator-(const AffineField& f, const AffineField& g) { return {f.a - g.a, f.B - g.B}; }
  friend AffineField operator*(double s, const AffineField& f) { return {s * f.a, s * f.B}; }
  friend AffineField operator/(const AffineField& f, double s) { return {f.a / s, f.B / s}; }
  AffineField& operator+=(const AffineField& g) {
    a += g.a;
    B += g.B;
    return *this;
  }
};

// Weighted moments of a set of points rho_n: sum w, sum w rho, sum w rho rho^T.
struct Moments {
  static constexpr bool checkpoint_as_bytes = true;  // core/checkpoint.hpp (no padding: 8-byte fields)
  double w = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();

  void add(double weight, const Eigen::Vector3d& rho) {
    w += weight;
    first += weight * rho;
    second += weight * rho * rho.transpose();
  }
  // sum_n w_n f(rho_n) . g(rho_n)
  double dot(const AffineField& f, const AffineField& g) const {
    return w * f.a.dot(g.a) + f.a.dot(g.B * first) + g.a.dot(f.B * first) + (f.B * second * g.B.transpose()).trace();
  }
  // sum_n w_n f(rho_n)
  Eigen::Vector3d sum(const AffineField& f) const { return w * f.a + f.B * first; }
  // sum_n w_n (P rho_n) x f(rho_n), P a linear map of the arms (the body's turn since rho was taken)
  Eigen::Vector3d moment(const Eigen::Matrix3d& P, const AffineField& f) const {
    // (P rho) x (a + B rho) summed: (P first) x a + the axial vector of the skew part of P S B^T.
    const Eigen::Matrix3d M = P * second * f.B.transpose();  // sum w (P rho)(B rho)^T
    return (P * first).cross(f.a) + Eigen::Vector3d(M(1, 2) - M(2, 1), M(2, 0) - M(0, 2), M(0, 1) - M(1, 0));
  }
};

// A rigid body's mass moments about its material mass centre X_c: the masses' (for sums of forces and
// moments, the inertia) and the squared masses' (for the squared norms of the residual's inertia).
struct RigidMassMoments {
  static constexpr bool checkpoint_as_bytes = true;  // core/checkpoint.hpp (no padding: 8-byte fields)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // X_c
  Moments mass, mass_squared;
  Eigen::Vector3d rotary = Eigen::Vector3d::Zero();          // sum J_n per axis (the lumped diagonal)
  Eigen::Vector3d rotary_squared = Eigen::Vector3d::Zero();  // sum J_n^2 per axis

  // Nodes at material positions X[n], lumped translational masses m[n] and rotary diagonals J[n].
  template <class Positions, class Masses, class Rotary>
  static RigidMassMoments of(std::span<const int> nodes, const Positions& X, const Masses& m, const Rotary& J) {
    RigidMassMoments out;
    double total = 0;
    for (int n : nodes) {
      out.centre += m[n] * X[n];
      total += m[n];
    }
    out.centre /= total;
    for (int n : nodes) {
      const Eigen::Vector3d rho = X[n] - out.centre;
      out.mass.add(m[n], rho);
      out.mass_squared.add(m[n] * m[n], rho);
      out.rotary += J[n];
      out.rotary_squared += J[n].cwiseProduct(J[n]);
    }
    return out;
  }
  // The inertia tensor about the mass centre, arms turned by P (world = P rho): the members' lumped
  // masses and their isotropic rotary terms (point inertias that turn are added by the caller).
  Eigen::Matrix3d inertia(const Eigen::Matrix3d& P) const {
    const Eigen::Matrix3d S = P * mass.second * P.transpose();
    return S.trace() * Eigen::Matrix3d::Identity() - S + Eigen::Matrix3d(rotary.asDiagonal());
  }
};

// The affine field through the values f[n] a rigid body's nodes hold (their state at the start of a
// run, set node by node): a = the mass-weighted mean, B from the first moments of f about it against
// the arms' second moment. Exact for values that are an affine field (up to rounding); a body whose
// nodes lie on a line or in a plane leaves B's action off it undetermined, and the least-norm B (the
// pseudo-inverse) is zero there, where no node reads it.
template <class Values, class Positions, class Masses>
AffineField fit_affine_field(std::span<const int> nodes, const RigidMassMoments& mm, const Values& f, const Positions& X,
                             const Masses& m) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int n : nodes) mean += m[n] * f(n);
  mean /= mm.mass.w;
  Eigen::Matrix3d cross = Eigen::Matrix3d::Zero();  // sum m (f - mean) rho^T
  for (int n : nodes) cross += m[n] * (f(n) - mean) * (X[n] - mm.centre).transpose();
  const Eigen::Matrix3d B = cross * pseudo_inverse(mm.mass.second);
  // The mean is the field's value at the mean arm (zero up to rounding): a = mean - B mean_arm.
  return {mean - B * (mm.mass.first / mm.mass.w), B};
}

// A rigid body's motion over a step as fields: translational (affine in the material arm) and
// rotational (one vector for every node), each at t_{n+1} (v, a; w, alpha) and at t_n (vn, an; wn, alphan).
struct RigidStepFields {
  static constexpr bool checkpoint_as_bytes = true;  // core/checkpoint.hpp (no padding: 8-byte fields)
  AffineField v, a, vn, an;
  Eigen::Vector3d w = Eigen::Vector3d::Zero(), alpha = Eigen::Vector3d::Zero();
  Eigen::Vector3d wn = Eigen::Vector3d::Zero(), alphan = Eigen::Vector3d::Zero();
};

// What a node carries besides its share of the body's uniform loads: its part of the residual that is
// not proportional to its mass, s = (1 - af)(fc1 + l1) + af (fc0 + l0) (contact forces and nodal loads
// at the step's end and start, six components), and the parts the force scale counts apart: the
// external load l1 (nodal loads at t_{n+1}) and the contact force fc1.
struct RigidNodeExtra {
  Eigen::Vector3d rho;                      // material arm
  double m = 0;                             // lumped translational mass
  Eigen::Vector3d J = Eigen::Vector3d::Zero();  // lumped rotary diagonal
  Eigen::Matrix<double, 6, 1> s, l1, fc1;
};

// The generalized-alpha residual of a rigid body's nodes, reduced to the body (T^T r with T = [I, -[r]x]
// about the mass centre, arms r = P rho), with its squared norm and squared force scale as
// Simulation::residual_body sums them node by node (every node's six DOFs; a rigid body has no fixed
// DOF and no internal force). Uniform loads per unit mass: g1 at t_{n+1}, g0 at t_n (gravity less the
// table's acceleration); `extra` lists the nodes with anything else, each node once (its contacts summed).
// The stepper (integrators.hpp) says where the balance is enforced.
struct RigidReducedResidual {
  Eigen::Matrix<double, 6, 1> R = Eigen::Matrix<double, 6, 1>::Zero();
  double num = 0, den = 0;
};
template <class Stepper>
RigidReducedResidual rigid_reduced_residual(const RigidMassMoments& mm, const Eigen::Matrix3d& P,
                                            const RigidStepFields& f, const Stepper& stepper, double c,
                                            const Eigen::Vector3d& g1, const Eigen::Vector3d& g0,
                                            std::span<const RigidNodeExtra> extra) {
  using V3 = Eigen::Vector3d;
  // Translational residual per unit mass: F = (1 - af) g1 + af g0 - I - c D.
  const AffineField inertia = stepper.at_inertia_point(f.a, f.an), damping = stepper.at_force_point(f.v, f.vn);
  AffineField F = AffineField::uniform(stepper.at_force_point(g1, g0)) - inertia - c * damping;
  // Rotational residual per unit rotary mass (per axis): G = -(alpha's) - c (w's).
  const V3 Irot = stepper.at_inertia_point(f.alpha, f.alphan), Drot = stepper.at_force_point(f.w, f.wn);
  const V3 G = -Irot - c * Drot;
  RigidReducedResidual out;
  out.R.head<3>() = mm.mass.sum(F);
  out.R.tail<3>() = mm.mass.moment(P, F) + mm.rotary.cwiseProduct(G);
  out.num = mm.mass_squared.dot(F, F) + mm.rotary_squared.dot(G.cwiseProduct(G));
  const AffineField fx = AffineField::uniform(g1);
  out.den = mm.mass_squared.dot(fx, fx) + mm.mass_squared.dot(inertia, inertia) +
            mm.rotary_squared.dot(Irot.cwiseProduct(Irot));
  for (const auto& e : extra) {
    const V3 Fn = e.m * F.at(e.rho), Gn = e.J.cwiseProduct(G);
    const V3 st = e.s.head<3>(), sr = e.s.tail<3>();
    out.R.head<3>() += st;
    out.R.tail<3>() += (P * e.rho).cross(st) + sr;
    out.num += 2 * Fn.dot(st) + st.squaredNorm() + 2 * Gn.dot(sr) + sr.squaredNorm();
    const V3 fxn = e.m * g1;  // the node's uniform external force; its load adds to it
    out.den += 2 * fxn.dot(e.l1.head<3>()) + e.l1.squaredNorm() + e.fc1.squaredNorm();
  }
  return out;
}

// The effective matrix's mass part of a rigid body, T^T (mf M) T about its mass centre with arms
// P rho: mf [M I, -[P m1]x; [P m1]x, inertia(P)] (m1 = sum m rho, zero up to rounding).
inline Eigen::Matrix<double, 6, 6> rigid_mass_matrix(const RigidMassMoments& mm, const Eigen::Matrix3d& P, double mf) {
  const Eigen::Vector3d f = P * mm.mass.first;
  Eigen::Matrix3d S;
  S << 0, -f.z(), f.y(), f.z(), 0, -f.x(), -f.y(), f.x(), 0;
  Eigen::Matrix<double, 6, 6> A;
  A << mf * mm.mass.w * Eigen::Matrix3d::Identity(), -mf * S, mf * S, mf * mm.inertia(P);
  return A;
}

// The uniform parts of a rigid body's step works (Simulation::commit_body's sums over its nodes): the
// external work of the table's inertia force, 0.5 sum du . m (-(atab0 + atab1)) (gravity's own work is
// the potential energy's), and the mass damping's, -0.5 c sum du . m (vn + v) over the six DOFs. The
// nodes with loads or contact add theirs (their du, vn, v from the fields).
struct RigidStepWork {
  double external = 0, damping = 0;
};
inline RigidStepWork rigid_step_work(const RigidMassMoments& mm, const AffineField& du, const Eigen::Vector3d& dtheta,
                                     const RigidStepFields& f, const Eigen::Vector3d& atab0,
                                     const Eigen::Vector3d& atab1, double c) {
  RigidStepWork w;
  w.external = -0.5 * mm.mass.sum(du).dot(atab0 + atab1);
  if (c > 0)
    w.damping = -0.5 * c * (mm.mass.dot(du, f.vn + f.v) + mm.rotary.dot(dtheta.cwiseProduct(f.wn + f.w)));
  return w;
}

// A rigid body stepped on its fields (Simulation, SimulationOptions::rigid_fields): its placement
// x_n = c + Q rho_n, the fields of its motion, the step's increment and its uniform load per unit mass at
// the step's start. Plain data, saved whole in checkpoints.
struct RigidFieldState {
  bool on = false;
  RigidMassMoments mm;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();        // mass centre now
  Eigen::Matrix3d Q = Eigen::Matrix3d::Identity();    // turn from the material arms: x_n = c + Q rho_n
  Eigen::Vector3d c_start = Eigen::Vector3d::Zero();  // the same at the step's start
  Eigen::Matrix3d Q_start = Eigen::Matrix3d::Identity();
  RigidStepFields f;
  AffineField du;                                     // the step's increment, translations
  Eigen::Vector3d dtheta = Eigen::Vector3d::Zero();   // and rotations (every node alike)
  Eigen::Vector3d g0 = Eigen::Vector3d::Zero();       // gravity less the table's acceleration at t_n
  Eigen::Vector3d g1 = Eigen::Vector3d::Zero();       // and at t_{n+1}
  bool refit = false;                                 // its nodes were set from outside: fit again
  Eigen::Matrix<double, 6, 1> R = Eigen::Matrix<double, 6, 1>::Zero();  // the last reduced residual
  // Member by member in checkpoints (core/checkpoint.hpp): its two bools are followed by padding bytes.
  template <class Self, class Archive>
    requires std::is_same_v<std::remove_const_t<Self>, RigidFieldState>
  friend void transfer_state(Self& s, Archive& ar) {
    ar(s.on, s.mm, s.c, s.Q, s.c_start, s.Q_start, s.f, s.du, s.dtheta, s.g0, s.g1, s.refit, s.R);
  }
};

}  // namespace furniture_fem::detail
