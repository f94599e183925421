// A rigid group's pair terms summed per body pair (core/detail/rigid_pair_terms.hpp) against the
// products T_a^T k T_b formed pair by pair, and against the mechanics they stand for: a common rigid
// motion of two touching bodies moves no contact point relative to the other body (no force), a
// relative translation d of body a gives it the force k d at the point and the moment (p - c_a) x k d.
#include <catch2/catch.hpp>
#include <furniture_fem/core/simulation.hpp>

#include <cmath>
#include <random>
#include <vector>

namespace rigid_pair_terms_tests {  // this file's own names (its group compiles files in batches)

namespace {
using furniture_fem::Mat3;
using furniture_fem::Vec3;

struct Pair {
  int a, b;
  Mat3 k;
  Vec3 p;
};

Mat3 random_matrix(std::mt19937& g, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mat3 m;
  for (int i = 0; i < 9; ++i) m(i) = scale * u(g);
  return m;
}
Vec3 random_point(std::mt19937& g, double half) {
  std::uniform_real_distribution<double> u(-half, half);
  return {u(g), u(g), u(g)};
}

Eigen::MatrixXd summed(int bodies, const std::vector<Pair>& pairs, const std::vector<Vec3>& centre) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6 * bodies, 6 * bodies);
  furniture_fem::detail::RigidPairTerms terms(bodies);
  for (const auto& q : pairs) terms.add(q.a, q.b, q.k, q.p - centre[q.a]);
  terms.add_to(centre, A);
  return A;
}

// Pair by pair: T = [I, -[p - c]x], the four 6 x 6 products.
Eigen::MatrixXd by_products(int bodies, const std::vector<Pair>& pairs, const std::vector<Vec3>& centre) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6 * bodies, 6 * bodies);
  for (const auto& q : pairs) {
    Eigen::Matrix<double, 3, 6> Ta, Tb;
    Ta << Mat3::Identity(), -furniture_fem::detail::skew(q.p - centre[q.a]);
    Tb << Mat3::Identity(), -furniture_fem::detail::skew(q.p - centre[q.b]);
    A.block<6, 6>(6 * q.a, 6 * q.a) += Ta.transpose() * q.k * Ta;
    A.block<6, 6>(6 * q.b, 6 * q.b) += Tb.transpose() * q.k * Tb;
    A.block<6, 6>(6 * q.a, 6 * q.b) -= Ta.transpose() * q.k * Tb;
    A.block<6, 6>(6 * q.b, 6 * q.a) -= Tb.transpose() * q.k * Ta;
  }
  return A;
}
}  // namespace

TEST_CASE("a rigid group's pair terms summed per body pair equal the products pair by pair", "[rigid][pairs]") {
  std::mt19937 g(20261129);
  // Several groups: 2 to 5 bodies, 1 to 40 pairs in either orientation, stiffnesses 1e3 to 1e8 N/m
  // (not symmetric: friction's slope), centres and points up to 2 m from the origin.
  for (int trial = 0; trial < 60; ++trial) {
    const int bodies = 2 + trial % 4;
    const double k = std::pow(10.0, 3 + trial % 6);
    std::vector<Vec3> centre;
    for (int i = 0; i < bodies; ++i) centre.push_back(random_point(g, 2.0));
    std::vector<Pair> pairs;
    const int n = 1 + (7 * trial) % 40;
    std::uniform_int_distribution<int> body(0, bodies - 1);
    for (int i = 0; i < n; ++i) {
      int a = body(g), b = body(g);
      if (a == b) b = (a + 1) % bodies;
      pairs.push_back({a, b, random_matrix(g, k), random_point(g, 2.0)});
    }
    const Eigen::MatrixXd S = summed(bodies, pairs, centre), P = by_products(bodies, pairs, centre);
    // Arms up to 4 m, so entries up to about 16 k per pair and n pairs: the sums' rounding is about
    // 1e-15 of that; 1e-12 leaves room and still catches any wrong block (of the order of the entries).
    INFO("trial " << trial << ", " << bodies << " bodies, " << n << " pairs");
    REQUIRE((S - P).cwiseAbs().maxCoeff() <= 1e-12 * P.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("a rigid group's pair terms: no force under a common rigid motion, k d under a relative one",
          "[rigid][pairs]") {
  const std::vector<Vec3> centre{{0.1, -0.2, 0.5}, {0.3, 0.1, 1.4}};
  Mat3 k;
  k << 2e6, 1e4, 0, -3e4, 1.5e6, 2e3, 0, 0, 8e6;
  const std::vector<Pair> pairs{{0, 1, k, {0.4, 0.0, 1.0}}, {1, 0, 0.5 * k, {-0.2, 0.3, 1.0}}, {0, 1, k, {0.2, -0.3, 1.0}}};
  const Eigen::MatrixXd A = summed(2, pairs, centre);

  // Both bodies translate by v and turn by w about a point o: every point moves by v + w x (x - o).
  const Vec3 v(0.01, -0.02, 0.005), w(0.003, 0.001, -0.004), o(1.0, 2.0, -0.5);
  Eigen::VectorXd q(12);
  for (int i = 0; i < 2; ++i) q.segment<6>(6 * i) << v + w.cross(centre[i] - o), w;
  const Eigen::VectorXd f = A * q;
  CHECK(f.cwiseAbs().maxCoeff() <= 1e-9 * (A.cwiseAbs().maxCoeff() * q.cwiseAbs().maxCoeff()));

  // Body a (0) moves by d alone: each pair's stretch is d, so body a gets sum k_i d and the moments
  // (p_i - c_a) x k_i d, body b the opposite forces and (p_i - c_b) x (-k_i d).
  const Vec3 d(1e-4, -2e-4, 3e-5);
  q.setZero();
  q.head<3>() = d;
  const Eigen::VectorXd g = A * q;
  Vec3 Fa = Vec3::Zero(), Ma = Vec3::Zero(), Mb = Vec3::Zero();
  for (const auto& p : pairs) {
    // A pair listed as (b, a) stretches the other way round, with the same force on body 0.
    const Vec3 fa = p.k * d;
    Fa += fa;
    Ma += (p.p - centre[0]).cross(fa);
    Mb += (p.p - centre[1]).cross(-fa);
  }
  const double tol = 1e-12 * A.cwiseAbs().maxCoeff() * d.norm();
  CHECK((g.segment<3>(0) - Fa).norm() <= tol);
  CHECK((g.segment<3>(3) - Ma).norm() <= tol);
  CHECK((g.segment<3>(6) + Fa).norm() <= tol);
  CHECK((g.segment<3>(9) - Mb).norm() <= tol);
}

}  // namespace rigid_pair_terms_tests
