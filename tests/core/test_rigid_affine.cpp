// core/detail/rigid_affine.hpp: a rigid body's affine nodal fields and the sums over its nodes from
// its mass moments, against the same sums formed node by node.
#include <catch2/catch.hpp>

#include <furniture_fem/core/simulation.hpp>
#include <furniture_fem/core/integrators.hpp>
#include <furniture_fem/core/rotation.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <random>
#include <vector>

using namespace furniture_fem;
using detail::AffineField;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace rigid_affine_tests {  // this file's own names (its group compiles files in batches)

namespace {

struct RandomBody {
  std::vector<Vector3d> X, J;
  std::vector<double> m;
  std::vector<int> nodes;
};

RandomBody random_body(std::mt19937& rng, int n, double size) {
  std::uniform_real_distribution<double> u(-1, 1), mass(0.01, 3.0);
  RandomBody b;
  const Vector3d offset(5 * u(rng), 5 * u(rng), 5 * u(rng));  // far from the origin, as a placed item
  for (int i = 0; i < n; ++i) {
    b.X.push_back(offset + size * Vector3d(u(rng), u(rng), u(rng)));
    b.m.push_back(mass(rng));
    const double j = 1e-4 * mass(rng);
    b.J.push_back(Vector3d::Constant(j));
    b.nodes.push_back(i);
  }
  return b;
}

AffineField random_field(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  AffineField f;
  f.a = Vector3d(u(rng), u(rng), u(rng));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) f.B(i, j) = u(rng);
  return f;
}

Matrix3d random_rotation(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  return Eigen::AngleAxisd(3 * u(rng), Vector3d(u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
}

}  // namespace

TEST_CASE("a rigid body's sums from its mass moments equal the sums over its nodes", "[core][rigid]") {
  std::mt19937 rng(20261129);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 1 + trial * 7;
    const double size = trial % 3 == 0 ? 0.05 : (trial % 3 == 1 ? 0.8 : 2.0);
    const RandomBody b = random_body(rng, n, size);
    const auto mm = detail::RigidMassMoments::of(std::span<const int>(b.nodes), b.X, b.m, b.J);
    const AffineField f = random_field(rng, 10.0), g = random_field(rng, 0.3);
    const Matrix3d P = random_rotation(rng);

    double total = 0, dot = 0, dot2 = 0;
    Vector3d centre = Vector3d::Zero(), sum = Vector3d::Zero(), moment = Vector3d::Zero();
    for (int i = 0; i < n; ++i) {
      total += b.m[i];
      centre += b.m[i] * b.X[i];
    }
    centre /= total;
    Matrix3d inertia = Matrix3d::Zero();
    for (int i = 0; i < n; ++i) {
      const Vector3d rho = b.X[i] - centre, fi = f.at(rho), gi = g.at(rho), r = P * rho;
      sum += b.m[i] * fi;
      dot += b.m[i] * fi.dot(gi);
      dot2 += b.m[i] * b.m[i] * fi.dot(gi);
      moment += b.m[i] * r.cross(fi);
      inertia += b.m[i] * (r.squaredNorm() * Matrix3d::Identity() - r * r.transpose()) + Matrix3d(b.J[i].asDiagonal());
    }
    INFO("trial " << trial << ": " << n << " nodes, size " << size);
    const double fs = f.a.norm() + size * f.B.norm(), gs = g.a.norm() + size * g.B.norm();
    CHECK((mm.centre - centre).norm() <= 1e-12 * (centre.norm() + size));
    CHECK((mm.mass.sum(f) - sum).norm() <= 1e-12 * total * fs);
    CHECK(std::abs(mm.mass.dot(f, g) - dot) <= 1e-12 * total * fs * gs);
    CHECK(std::abs(mm.mass_squared.dot(f, g) - dot2) <= 1e-12 * mm.mass_squared.w * fs * gs);
    CHECK((mm.mass.moment(P, f) - moment).norm() <= 1e-12 * total * size * fs);
    CHECK((mm.inertia(P) - inertia).norm() <= 1e-12 * (total * size * size + mm.rotary.norm()));
  }
}

TEST_CASE("Newmark's rates of affine fields are the nodes' rates", "[core][rigid]") {
  // The scheme's acceleration and velocity are linear in their inputs: applied to the fields, they give
  // at every arm what the node's own update gives.
  std::mt19937 rng(7);
  const double dt = 1e-3;
  const AlphaStepper stepper = Newmark::paper().stepper(dt);
  const IntegratorCoefficients c = stepper.coefficients();
  const AffineField du = random_field(rng, 1e-3), vn = random_field(rng, 1.0), an = random_field(rng, 10.0);
  const auto fields = stepper.update(du, vn, an);
  const AffineField a1 = fields.acceleration, v1 = fields.velocity;
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 20; ++k) {
    const Vector3d rho(u(rng), u(rng), u(rng));
    const auto node = stepper.update<Vector3d>(du.at(rho), vn.at(rho), an.at(rho));
    const Vector3d a_node = node.acceleration, v_node = node.velocity;
    // The acceleration differences terms of about du / (beta dt^2): rounding relative to those terms.
    const double terms = (du.at(rho).norm() + dt * vn.at(rho).norm() + dt * dt * an.at(rho).norm()) / (c.beta * dt * dt);
    CHECK((a1.at(rho) - a_node).norm() <= 1e-13 * terms);
    CHECK((v1.at(rho) - v_node).norm() <= 1e-13 * (vn.at(rho).norm() + dt * (an.at(rho).norm() + terms)));
  }
}

TEST_CASE("a rigid motion's increments are an affine field of the material arms", "[core][rigid]") {
  // d_n = dc + (Q - I) r_n with r_n = Q0 rho_n: a = dc, B = (Q - I) Q0.
  std::mt19937 rng(11);
  const RandomBody b = random_body(rng, 40, 1.0);
  const auto mm = detail::RigidMassMoments::of(std::span<const int>(b.nodes), b.X, b.m, b.J);
  const Matrix3d Q0 = random_rotation(rng), Q = random_rotation(rng);
  const Vector3d c0(0.3, -0.2, 0.9), dc(0.01, 0.02, -0.03);
  const AffineField d{dc, (Q - Matrix3d::Identity()) * Q0};
  for (int i = 0; i < 40; ++i) {
    const Vector3d rho = b.X[i] - mm.centre;
    const Vector3d x0 = c0 + Q0 * rho, x1 = c0 + dc + Q * (x0 - c0);
    CHECK((d.at(rho) - (x1 - x0)).norm() <= 1e-14);
  }
}

TEST_CASE("the affine field through a rigid body's nodal values is the field they came from", "[core][rigid]") {
  std::mt19937 rng(3);
  for (int shape = 0; shape < 3; ++shape) {  // a solid body, a plane of nodes, a line of nodes
    RandomBody b = random_body(rng, 30, 0.7);
    for (auto& x : b.X) {
      if (shape >= 1) x.z() = 1.0;
      if (shape == 2) x.y() = 2.0;
    }
    const auto mm = detail::RigidMassMoments::of(std::span<const int>(b.nodes), b.X, b.m, b.J);
    const AffineField f = random_field(rng, 2.0);
    const auto values = [&](int n) { return Vector3d(f.at(b.X[n] - mm.centre)); };
    const AffineField g = detail::fit_affine_field(std::span<const int>(b.nodes), mm, values, b.X, b.m);
    INFO("shape " << shape);
    for (int n : b.nodes) CHECK((g.at(b.X[n] - mm.centre) - values(n)).norm() <= 1e-12 * (f.a.norm() + f.B.norm()));
    if (shape == 0) CHECK((g.B - f.B).norm() <= 1e-10 * f.B.norm());
  }
}

TEST_CASE("a rigid body's reduced residual and its norms from fields and moments equal the nodal sums",
          "[core][rigid]") {
  // The reference is Simulation::residual_body's formula node by node (six DOFs, masses m and J, the
  // node's external force m g1 + l1 at t_{n+1} and m g0 + l0 at t_n, contact fc1 and fc0, no internal
  // force), reduced with T^T as RigidBody::reduced_system does.
  using V6 = Eigen::Matrix<double, 6, 1>;
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 5 + 9 * trial;
    const RandomBody b = random_body(rng, n, 0.6);
    const auto mm = detail::RigidMassMoments::of(std::span<const int>(b.nodes), b.X, b.m, b.J);
    const Matrix3d P = random_rotation(rng);
    detail::RigidStepFields f{random_field(rng, 1.0), random_field(rng, 20.0), random_field(rng, 1.0),
                              random_field(rng, 20.0)};
    f.w = Vector3d(u(rng), u(rng), u(rng));
    f.alpha = 10 * Vector3d(u(rng), u(rng), u(rng));
    f.wn = Vector3d(u(rng), u(rng), u(rng));
    f.alphan = 10 * Vector3d(u(rng), u(rng), u(rng));
    const double am = trial % 2 ? 0.0 : 1.0 / 3, af = trial % 2 ? 0.0 : 1.0 / 3, c = trial % 3 == 0 ? 0.5 : 0.0;
    const Vector3d g1(u(rng), u(rng), -9.81 + u(rng)), g0(u(rng), u(rng), -9.81 + u(rng));
    // Contact forces and nodal loads on a few nodes (one node twice: two contacts on it).
    std::vector<V6> fc1(n, V6::Zero()), fc0(n, V6::Zero()), l1(n, V6::Zero()), l0(n, V6::Zero());
    std::vector<detail::RigidNodeExtra> extra;
    for (int k = 0; k < 1 + trial % 5; ++k) {
      const int node = static_cast<int>(rng() % n);
      V6 c1, c0, L1, L0;
      for (int i = 0; i < 6; ++i) {
        c1[i] = 100 * u(rng);
        c0[i] = 100 * u(rng);
        L1[i] = k == 0 ? 5 * u(rng) : 0.0;
        L0[i] = k == 0 ? 5 * u(rng) : 0.0;
      }
      fc1[node] += c1, fc0[node] += c0, l1[node] += L1, l0[node] += L0;
      extra.push_back({b.X[node] - mm.centre, b.m[node], b.J[node], (1 - af) * (c1 + L1) + af * (c0 + L0), L1, c1});
    }
    // The nodal reference. With two contacts on one node the norms' sums need the node's total, so the
    // extras of one node are merged for the reference's comparison below.
    V6 R = V6::Zero();
    double num = 0, den = 0;
    for (int i = 0; i < n; ++i) {
      const Vector3d rho = b.X[i] - mm.centre, r = P * rho;
      V6 m6, a, an, v, vn;
      m6 << Vector3d::Constant(b.m[i]), b.J[i];
      a << f.a.at(rho), f.alpha;
      an << f.an.at(rho), f.alphan;
      v << f.v.at(rho), f.w;
      vn << f.vn.at(rho), f.wn;
      V6 fx, fx0;
      fx << b.m[i] * g1, Vector3d::Zero();
      fx0 << b.m[i] * g0, Vector3d::Zero();
      fx += l1[i];
      fx0 += l0[i];
      const V6 inertia = m6.cwiseProduct((1 - am) * a + am * an);
      const V6 damping = (c * m6).cwiseProduct((1 - af) * v + af * vn);
      const V6 ri = (1 - af) * (fx + fc1[i]) + af * (fx0 + fc0[i]) - inertia - damping;
      num += ri.squaredNorm();
      den += fx.squaredNorm() + inertia.squaredNorm() + fc1[i].squaredNorm();
      R.head<3>() += ri.head<3>();
      R.tail<3>() += r.cross(Vector3d(ri.head<3>())) + ri.tail<3>();
    }
    // Merge extras of one node (the function's norms treat each entry as the node's whole extra).
    std::vector<detail::RigidNodeExtra> merged;
    for (const auto& e : extra) {
      auto it = std::find_if(merged.begin(), merged.end(), [&](const auto& x) { return x.rho == e.rho; });
      if (it == merged.end()) merged.push_back(e);
      else it->s += e.s, it->l1 += e.l1, it->fc1 += e.fc1;
    }
    const AlphaStepper stepper({am, af, 0.25, 0.5}, EquilibriumMode::iterate, 1e-3);  // only am, af enter
    const auto got = detail::rigid_reduced_residual(mm, P, f, stepper, c, g1, g0, merged);
    INFO("trial " << trial << ", " << n << " nodes, " << merged.size() << " nodes with extras");
    const double scale = R.norm() + mm.mass.w * 30;
    CHECK((got.R - R).norm() <= 1e-11 * scale);
    CHECK(std::abs(got.num - num) <= 1e-11 * (num + den));
    CHECK(std::abs(got.den - den) <= 1e-11 * den);
  }
}

TEST_CASE("a rigid body's mass matrix and step works from its moments equal the nodal sums", "[core][rigid]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 30; ++trial) {
    const int n = 3 + 11 * trial;
    const RandomBody b = random_body(rng, n, 0.9);
    const auto mm = detail::RigidMassMoments::of(std::span<const int>(b.nodes), b.X, b.m, b.J);
    const Matrix3d P = random_rotation(rng);
    const double mf = 4e5 * (1 + u(rng)), c = trial % 2 ? 0.3 : 0.0;
    detail::RigidStepFields f{random_field(rng, 1.0), random_field(rng, 20.0), random_field(rng, 1.0),
                              random_field(rng, 20.0)};
    f.w = Vector3d(u(rng), u(rng), u(rng));
    f.wn = Vector3d(u(rng), u(rng), u(rng));
    const AffineField du = random_field(rng, 1e-3);
    const Vector3d dtheta = 1e-3 * Vector3d(u(rng), u(rng), u(rng));
    const Vector3d atab0(u(rng), u(rng), u(rng)), atab1(u(rng), u(rng), u(rng));
    // RigidBody::reduced_system's mass part and commit_body's sums, node by node.
    Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
    double external = 0, damping = 0;
    Vector3d centre = Vector3d::Zero();
    for (int i = 0; i < n; ++i) centre += b.m[i] * b.X[i];
    centre /= mm.mass.w;
    for (int i = 0; i < n; ++i) {
      const Vector3d rho = b.X[i] - centre, r = P * rho;
      Matrix3d S;
      S << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
      const double m = mf * b.m[i];
      A.block<3, 3>(0, 0) += m * Matrix3d::Identity();
      A.block<3, 3>(0, 3) -= m * S;
      A.block<3, 3>(3, 0) += m * S;
      A.block<3, 3>(3, 3) += mf * (b.m[i] * (r.squaredNorm() * Matrix3d::Identity() - r * r.transpose()) +
                                   Matrix3d(b.J[i].asDiagonal()));
      external += 0.5 * du.at(rho).dot(-b.m[i] * (atab0 + atab1));
      damping -= 0.5 * c * (du.at(rho).dot(b.m[i] * (f.vn.at(rho) + f.v.at(rho))) +
                            dtheta.dot(b.J[i].cwiseProduct(f.wn + f.w)));
    }
    INFO("trial " << trial);
    CHECK((detail::rigid_mass_matrix(mm, P, mf) - A).norm() <= 1e-12 * A.norm());
    const auto w = detail::rigid_step_work(mm, du, dtheta, f, atab0, atab1, c);
    CHECK(std::abs(w.external - external) <= 1e-12 * mm.mass.w * 2e-3 * (2 + 0.9 * du.B.norm() / 1e-3));
    CHECK(std::abs(w.damping - damping) <= 1e-12 * mm.mass.w * 1e-2 + 1e-300);
  }
}

// The step of RigidBody (simulation.hpp) on a free body, node by node, against the same step on its
// fields: predictor, residual reduced to 6 DOFs, one Newton solve, the finite rotation, Newmark's rates,
// the commit; gravity and a table acceleration that changes each step, the body spinning. The fields
// must stay the nodal state's: the same node positions, velocities and accelerations after 2000 steps.
TEST_CASE("a rigid body stepped on its affine fields follows the nodal scheme", "[core][rigid]") {
  using V6 = Eigen::Matrix<double, 6, 1>;
  std::mt19937 rng(17);
  const RandomBody b = random_body(rng, 60, 0.5);
  const int n = 60;
  const auto mm = detail::RigidMassMoments::of(std::span<const int>(b.nodes), b.X, b.m, b.J);
  const Newmark scheme = Newmark::paper();
  const IntegratorCoefficients k = scheme.coefficients();
  const double dt = 1e-3, am = k.alpha_m, af = k.alpha_f, c = 0.0;
  const AlphaStepper stepper = scheme.stepper(dt);
  const double mf = stepper.mass_factor(c);
  const auto table = [](double t) { return Vector3d(3 * std::sin(7 * t), 2 * std::cos(5 * t), 0.5 * std::sin(11 * t)); };
  const Vector3d gravity(0, 0, -9.81);
  // Start: spinning and moving, accelerations of the rigid motion under gravity and the table (no moment).
  const Vector3d v0(0.3, -0.1, 0.2), w0(2.0, -1.0, 4.0), a0 = gravity - table(0.0);
  // Nodal state.
  std::vector<Vector3d> x(n), x0(n);
  std::vector<V6> v(n), a(n), vn(n), an(n), Du(n), fnet0(n);
  for (int i = 0; i < n; ++i) {
    x[i] = b.X[i];
    const Vector3d r = x[i] - mm.centre;
    v[i] << v0 + w0.cross(r), w0;
    a[i] << a0 + w0.cross(w0.cross(r)), Vector3d::Zero();
    fnet0[i] << b.m[i] * (gravity - table(0.0)), Vector3d::Zero();
  }
  // Fields: the same start.
  detail::RigidStepFields f;
  f.v = AffineField{v0, detail::skew(w0)};
  f.a = AffineField{a0, detail::skew(w0) * detail::skew(w0)};
  f.w = w0;
  Vector3d c_body = mm.centre, g0 = gravity - table(0.0);
  Matrix3d Qtot = Matrix3d::Identity();
  for (int step = 1; step <= 2000; ++step) {
    const Vector3d g1 = gravity - table(step * dt);
    // -- nodal --
    Vector3d c0 = Vector3d::Zero();
    for (int i = 0; i < n; ++i) {
      vn[i] = v[i], an[i] = a[i], Du[i].setZero();
      const auto rates = stepper.update<V6>(Du[i], vn[i], an[i]);
      a[i] = rates.acceleration;
      v[i] = rates.velocity;
      x0[i] = x[i];
      c0 += b.m[i] * x[i];
    }
    c0 /= mm.mass.w;
    Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
    V6 R = V6::Zero();
    Matrix3d I = Matrix3d::Zero();
    for (int i = 0; i < n; ++i) {
      V6 m6, fx;
      m6 << Vector3d::Constant(b.m[i]), b.J[i];
      fx << b.m[i] * g1, Vector3d::Zero();
      const V6 r = (1 - af) * fx + af * fnet0[i] - m6.cwiseProduct((1 - am) * a[i] + am * an[i]);
      const Vector3d arm = x[i] - c0;
      const Matrix3d S = detail::skew(arm);
      A.block<3, 3>(0, 0) += mf * b.m[i] * Matrix3d::Identity();
      A.block<3, 3>(0, 3) -= mf * b.m[i] * S;
      A.block<3, 3>(3, 0) += mf * b.m[i] * S;
      R.head<3>() += r.head<3>();
      R.tail<3>() += S * r.head<3>() + r.tail<3>();
      I += b.m[i] * (arm.squaredNorm() * Matrix3d::Identity() - arm * arm.transpose()) + Matrix3d(b.J[i].asDiagonal());
    }
    A.block<3, 3>(3, 3) += mf * I;
    const V6 dq = A.ldlt().solve(R);
    const Matrix3d Q = detail::rotation_exp(dq.tail<3>());
    const Vector3d rot = detail::rotation_log(Q);
    for (int i = 0; i < n; ++i) {
      Du[i] << c0 + dq.head<3>() + Q * (x0[i] - c0) - x0[i], rot;
      const auto rates = stepper.update<V6>(Du[i], vn[i], an[i]);
      a[i] = rates.acceleration;
      v[i] = rates.velocity;
      x[i] = x0[i] + Du[i].head<3>();
      fnet0[i] << b.m[i] * g1, Vector3d::Zero();
    }
    // -- fields --
    detail::RigidStepFields p = f;
    p.vn = f.v, p.an = f.a, p.wn = f.w, p.alphan = f.alpha;
    const auto predicted = stepper.update(AffineField{}, p.vn, p.an);
    const auto predicted_turn = stepper.update<Vector3d>(Vector3d::Zero(), p.wn, p.alphan);
    p.a = predicted.acceleration;
    p.v = predicted.velocity;
    p.alpha = predicted_turn.acceleration;
    p.w = predicted_turn.velocity;
    const auto res = detail::rigid_reduced_residual(mm, Qtot, p, stepper, c, g1, g0, {});
    Eigen::Matrix<double, 6, 6> Af = detail::rigid_mass_matrix(mm, Qtot, mf);
    const V6 dqf = Af.ldlt().solve(res.R);
    const Matrix3d Qf = detail::rotation_exp(dqf.tail<3>());
    const Vector3d rotf = detail::rotation_log(Qf);
    const AffineField du{dqf.head<3>(), (Qf - Matrix3d::Identity()) * Qtot};
    const auto translation = stepper.update(du, p.vn, p.an);
    const auto rotation = stepper.update<Vector3d>(rotf, p.wn, p.alphan);
    p.a = translation.acceleration;
    p.v = translation.velocity;
    p.alpha = rotation.acceleration;
    p.w = rotation.velocity;
    c_body += dqf.head<3>();
    Qtot = Qf * Qtot;
    f = p;
    g0 = g1;
  }
  double dx = 0, dv = 0, da = 0, vmax = 0, amax = 0;
  for (int i = 0; i < n; ++i) {
    const Vector3d rho = b.X[i] - mm.centre;
    dx = std::max(dx, (c_body + Qtot * rho - x[i]).norm());
    dv = std::max(dv, (f.v.at(rho) - v[i].head<3>()).norm() + (f.w - v[i].tail<3>()).norm());
    da = std::max(da, (f.a.at(rho) - a[i].head<3>()).norm() + (f.alpha - a[i].tail<3>()).norm());
    vmax = std::max(vmax, v[i].norm());
    amax = std::max(amax, a[i].norm());
  }
  INFO("after 2000 steps: position " << dx << " m, velocity " << dv << " m/s (of " << vmax << "), acceleration " << da
                                     << " m/s^2 (of " << amax << ")");
  CHECK(dx <= 1e-9);
  CHECK(dv <= 1e-9 * vmax);
  CHECK(da <= 1e-7 * amax);
}

}  // namespace rigid_affine_tests
