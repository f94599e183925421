#pragma once
// furniture_fem/odeint/odeint_adapter.hpp: the same model integrated explicitly by Boost.Odeint steppers.
//
// OdeintSystem<Sim> is an odeint system, sys(x, dxdt, t), over the state
//
//     x = [ q_0 .. q_{N-1},  w_0 .. w_{N-1} ],   q_n = (u_n, psi_n),  w_n = (v_n, omega_n)
//
// per node: the displacement u, the total rotation vector psi (R = rotation_exp(psi)), the velocity v
// and the angular velocity omega in world axes (what Simulation::velocity() returns). The second half
// holds the velocities the lumped mass acts on, so the equations of motion are those of the implicit
// solver:
//
//     du/dt = v,   dpsi/dt = T(psi)^-1 omega,   m dv/dt = f_ext - f_int - c m v,
//     J domega/dt = m_ext - m_int - c J omega,
//
// with T the left Jacobian of SO(3) (omega = T(psi) dpsi/dt; T = I for small rotations, so the rotation
// half of dx/dt is qdot). The rotary inertia is isotropic (simulation.hpp), so there is no gyroscopic
// term. Internal forces come from the Simulation itself (set_pose, update_internal_forces,
// internal_force: the element policy, the corotational frames and any support springs), masses from
// nodal_mass / nodal_rotary_inertia, gravity and mass damping from its options; fixed DOFs are held.
// User loads are added through set_load. Contact and base excitation are not included.
//
// Limits: elastic response (every evaluation commits the element history, and the ASI hinge rule is
// not applied between stages, so plastic elements are not supported); |psi| < 2 pi (T is singular at
// 2 pi: fine for vibrations and for rotations up to a turn); an explicit stepper is stable only below
// its limit, e.g. dt < 2.83 / omega_max for runge_kutta4 (see max_frequency).
//
// Style note (odeint passes systems and steppers by value): the system holds a pointer to the
// Simulation and no buffers, so its copies are cheap and all act on the same model.
#include <Eigen/Core>
#include <boost/numeric/odeint/integrate/integrate_const.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta4.hpp>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

#include "../core/dense_kernels.hpp"
#include "../core/simulation.hpp"

namespace furniture_fem {

namespace detail {
// Inverse of the left Jacobian of SO(3): dpsi/dt = T(psi)^-1 omega for R = exp(psi), dR/dt R^T = [omega].
inline Mat3 so3_left_jacobian_inverse(const Vec3& psi) {
  const double th2 = psi.squaredNorm();
  const Mat3 S = skew(psi);
  double c;
  if (th2 < 1e-8) {
    c = 1.0 / 12.0 + th2 / 720.0;  // series of 1/th^2 - (1 + cos th) / (2 th sin th)
  } else {
    const double th = std::sqrt(th2);
    c = 1.0 / th2 - (1.0 + std::cos(th)) / (2.0 * th * std::sin(th));
  }
  return Mat3::Identity() - 0.5 * S + c * S * S;
}
}  // namespace detail

template <class Sim>
class OdeintSystem {
 public:
  using state_type = std::vector<double>;
  // Adds external nodal forces at time t to f (6 per node: forces, then moments; world axes).
  using load_function = std::function<void(double t, Eigen::VectorXd& f)>;

  // Structural damping (SimulationOptions::stiffness_damping) is a rate over the implicit step's
  // deformation increment: an explicit system function has no step to take it over.
  explicit OdeintSystem(Sim& sim) : sim_(&sim), nodes_(sim.model().num_nodes()) {
    if (sim.options().stiffness_damping != 0)
      throw ModelError("odeint: stiffness_damping is not supported by the explicit system (got " +
                       detail::fmt(sim.options().stiffness_damping) + " s); use mass_damping");
  }

  void set_load(load_function load) { load_ = std::move(load); }
  std::size_t size() const { return 12 * static_cast<std::size_t>(nodes_); }

  // The Simulation's current displacements, rotations and velocities as a state.
  state_type state() const {
    state_type x(size());
    const std::size_t h = 6 * static_cast<std::size_t>(nodes_);
    for (int n = 0; n < nodes_; ++n) {
      const Vec3 u = sim_->displacement(n), psi = detail::rotation_log(sim_->rotation(n));
      const Vec6 v = sim_->velocity(n);
      for (int i = 0; i < 3; ++i) {
        x[6 * n + i] = u[i];
        x[6 * n + 3 + i] = psi[i];
      }
      for (int i = 0; i < 6; ++i) x[h + 6 * n + i] = v[i];
    }
    return x;
  }

  // Writes a state into the Simulation (poses, velocities, internal forces), e.g. to read results.
  void write_back(const state_type& x) const {
    pose(x);
    const std::size_t h = 6 * static_cast<std::size_t>(nodes_);
    for (int n = 0; n < nodes_; ++n) sim_->set_velocity(n, Eigen::Map<const Vec6>(&x[h + 6 * n]));
  }

  Vec3 displacement(const state_type& x, int n) const { return Eigen::Map<const Vec3>(&x[6 * n]); }
  Vec3 position(const state_type& x, int n) const { return sim_->model().node(n).X + displacement(x, n); }

  // The odeint system function.
  void operator()(const state_type& x, state_type& dxdt, double t) const {
    pose(x);
    const std::size_t h = 6 * static_cast<std::size_t>(nodes_);
    const Vec3 g = sim_->options().gravity;
    const double c = sim_->options().mass_damping;
    Eigen::VectorXd fext;
    if (load_) {
      fext.setZero(6 * nodes_);
      load_(t, fext);
    }
    for (int n = 0; n < nodes_; ++n) {
      const double m = sim_->nodal_mass(n), J = sim_->nodal_rotary_inertia(n);
      const Vec6 fint = sim_->internal_force(n);
      const Eigen::Map<const Vec3> v(&x[h + 6 * n]), w(&x[h + 6 * n + 3]), psi(&x[6 * n + 3]);
      Vec6 f = -fint;
      f.head<3>() += m * g - c * m * v;
      f.tail<3>() -= c * J * w;
      if (load_) f += fext.segment<6>(6 * n);
      const Vec3 dpsi = detail::so3_left_jacobian_inverse(psi) * w;
      for (int i = 0; i < 3; ++i) {
        const bool fu = sim_->dof_fixed(n, i), fr = sim_->dof_fixed(n, 3 + i);
        dxdt[6 * n + i] = fu ? 0.0 : v[i];
        dxdt[6 * n + 3 + i] = fr ? 0.0 : dpsi[i];
        dxdt[h + 6 * n + i] = fu || !(m > 0) ? 0.0 : f[i] / m;
        dxdt[h + 6 * n + 3 + i] = fr || !(J > 0) ? 0.0 : f[3 + i] / J;
      }
    }
  }

  // Highest natural frequency (rad/s) of the model at its current state, over all bodies (dense
  // eigenvalues of M^-1/2 K M^-1/2 on the free DOFs: for the small models explicit runs suit).
  double max_frequency() const {
    double wmax = 0;
    for (int b = 0; b < sim_->model().num_bodies(); ++b) {
      const Eigen::MatrixXd K = sim_->stiffness_matrix(b);
      const Eigen::VectorXd m = sim_->mass_diagonal(b);
      const auto& nodes = sim_->body_nodes(b);
      std::vector<int> free;
      for (int i = 0; i < K.rows(); ++i)
        if (!sim_->dof_fixed(nodes[i / 6], i % 6) && m[i] > 0) free.push_back(i);
      const int k = static_cast<int>(free.size());
      Eigen::MatrixXd A(k, k);
      for (int a = 0; a < k; ++a)
        for (int c = 0; c < k; ++c)
          A(a, c) = 0.5 * (K(free[a], free[c]) + K(free[c], free[a])) / std::sqrt(m[free[a]] * m[free[c]]);
      if (k == 0) continue;
      const double largest = detail::symmetric_eigen(A, false).values.maxCoeff();
      wmax = std::max(wmax, std::sqrt(std::max(0.0, largest)));
    }
    return wmax;
  }

  Sim& simulation() const { return *sim_; }

 private:
  void pose(const state_type& x) const {
    for (int n = 0; n < nodes_; ++n) {
      const Eigen::Map<const Vec3> u(&x[6 * n]), psi(&x[6 * n + 3]);
      sim_->set_pose(n, sim_->model().node(n).X + u, detail::rotation_exp(psi));
    }
    sim_->update_internal_forces();
  }

  Sim* sim_;  // not owned; odeint copies the system, every copy acts on the same Simulation
  int nodes_;
  load_function load_;
};

// Integrates the Simulation's model from t0 to t1 with a fixed step dt using an odeint stepper (e.g.
// boost::numeric::odeint::runge_kutta4<std::vector<double>>), starting from the Simulation's current
// state and writing the final state back into it. observer(x, t) is called at every step (odeint's
// convention; OdeintSystem::position(x, node) reads a node from x). Returns the number of steps.
template <class Stepper, class Sim, class Observer>
std::size_t integrate_explicit(Stepper stepper, OdeintSystem<Sim>& system, double t0, double t1, double dt,
                               Observer observer) {
  auto x = system.state();
  const std::size_t steps = boost::numeric::odeint::integrate_const(stepper, system, x, t0, t1, dt, observer);
  system.write_back(x);
  return steps;
}

template <class Stepper, class Sim>
std::size_t integrate_explicit(Stepper stepper, OdeintSystem<Sim>& system, double t0, double t1, double dt) {
  return integrate_explicit(stepper, system, t0, t1, dt, [](const std::vector<double>&, double) {});
}

}  // namespace furniture_fem
