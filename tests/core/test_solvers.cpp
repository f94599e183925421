// The direct solver's supernodal substitutions (detail/supernodal_factor.hpp) against Eigen's own
// triangular solves and against a dense LDL^T: the repacking changes only the order of the
// floating-point operations, so the results agree to rounding (1e-12 relative, for matrices whose
// condition number is below about 1e3).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <furniture_fem/core/solvers.hpp>
#include <random>

using namespace furniture_fem;

namespace solvers_tests {  // this file's own names (its group compiles files in batches)

namespace {

// Unit lower triangular L with a random pattern: column j has entries in a random subset of the rows
// below it (probability p), and blocks of `block` columns share their pattern below the block (the
// structure of a beam node's six DOFs), so supernodes of several widths occur.
SparseMatrix random_unit_lower(int n, double p, int block, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5), coin(0, 1);
  std::vector<Eigen::Triplet<double>> t;
  for (int b0 = 0; b0 < n; b0 += block) {
    const int b1 = std::min(n, b0 + block);
    std::vector<int> rows;
    for (int i = b1; i < n; ++i)
      if (coin(rng) < p) rows.push_back(i);
    for (int j = b0; j < b1; ++j) {
      t.emplace_back(j, j, 1.0);  // stored diagonal: ignored (unit diagonal)
      for (int i = j + 1; i < b1; ++i) t.emplace_back(i, j, u(rng));
      for (int i : rows) t.emplace_back(i, j, u(rng));
    }
  }
  SparseMatrix L(n, n);
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

// A symmetric positive definite matrix with 6 x 6 blocks on the pattern of a chain of nodes with
// random extra links (a beam frame's pattern), diagonally dominant.
SparseMatrix block_spd(int nodes, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> pick(0, nodes - 1);
  std::vector<std::pair<int, int>> links;
  for (int k = 0; k < nodes; ++k) links.emplace_back(k, k);  // a node's DOFs are coupled
  for (int k = 0; k + 1 < nodes; ++k) links.emplace_back(k, k + 1);
  for (int k = 0; k < nodes / 3; ++k) {
    const int a = pick(rng), b = pick(rng);
    if (a != b) links.emplace_back(a, b);
  }
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6 * nodes, 6 * nodes);
  for (auto [a, b] : links) {
    const Eigen::Matrix<double, 6, 6> B = Eigen::Matrix<double, 6, 6>::NullaryExpr([&] { return u(rng); });
    A.block<6, 6>(6 * a, 6 * b) += B;
    A.block<6, 6>(6 * b, 6 * a) += B.transpose();
  }
  for (int i = 0; i < A.rows(); ++i) A(i, i) = A.row(i).cwiseAbs().sum() + 1.0;
  return A.sparseView();
}

}  // namespace

TEST_CASE("supernodal substitutions match Eigen's triangular solves", "[solver]") {
  for (const int block : {1, 3, 6}) {
    for (const double p : {0.0, 0.05, 0.5, 1.0}) {
      const SparseMatrix L = random_unit_lower(90, p, block, 7u + block);
      detail::SupernodalFactor f;
      f.assign(L);
      const long strictly_lower = L.nonZeros() - L.rows();
      INFO("block " << block << ", p " << p);
      CHECK(static_cast<long>(f.stored_values()) == strictly_lower);  // every stored value is an entry of L
      CHECK(f.supernodes() <= (90 + block - 1) / block);                // shared patterns were found
      if (p == 1.0) CHECK(f.supernodes() == 1);                          // a dense L is one supernode
      const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(90, -1, 2).array().sin();
      Eigen::VectorXd y = b, z = b;
      f.solve_lower(y);
      f.solve_upper(z);
      const Eigen::VectorXd y_ref = L.triangularView<Eigen::UnitLower>().solve(b);
      const Eigen::VectorXd z_ref = L.transpose().triangularView<Eigen::UnitUpper>().solve(b);
      CHECK((y - y_ref).norm() <= 1e-12 * y_ref.norm());
      CHECK((z - z_ref).norm() <= 1e-12 * z_ref.norm());
    }
  }
}

TEST_CASE("the direct solver solves block SPD systems like a dense LDL^T, across refactorisations",
          "[solver]") {
  DirectLdltSolver solver;
  SparseMatrix K = block_spd(40, 3);
  Eigen::VectorXd x;
  CHECK_FALSE(solver.solve(Eigen::VectorXd::Ones(K.rows()), x));  // nothing factorised yet
  solver.analyse(K);
  for (int refresh = 0; refresh < 3; ++refresh) {
    solver.factorize(K);
    const Eigen::VectorXd r = Eigen::VectorXd::LinSpaced(K.rows(), 0, 1).array().cos() * (1 + refresh);
    REQUIRE(solver.solve(r, x));
    const Eigen::VectorXd x_ref = Eigen::MatrixXd(K).ldlt().solve(r);
    INFO("refresh " << refresh);
    CHECK((x - x_ref).norm() <= 1e-12 * x_ref.norm());
    CHECK((K * x - r).norm() <= 1e-12 * r.norm());
    // Six DOFs per node share their pattern: supernodes are at least a node wide on average.
    CHECK(solver.factor().supernodes() <= K.rows() / 6);
    K = K * 1.5;  // same pattern, new values: the repacked factor follows
    K.diagonal().array() += 0.3 * (refresh + 1);
  }
}

}  // namespace solvers_tests
