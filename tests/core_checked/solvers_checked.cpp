// The core's solvers built without NDEBUG, so that Eigen's own checks (eigen_assert) run: a Release
// build compiles them out, and a call Eigen forbids then passes unnoticed. Found by the sanitized
// (Debug) core group, 2026-11-27: DirectLdltSolver::solve before any factorisation asked Eigen's
// SimplicialLDLT for info(), which asserts "Decomposition is not initialized" and aborted the run.
#include <catch2/catch.hpp>

#include <furniture_fem/core/solvers.hpp>

using namespace furniture_fem;

TEST_CASE("with Eigen's checks on, the direct solver declines to solve until it has factorised", "[solver]") {
  static_assert(
#ifdef NDEBUG
      false,
#else
      true,
#endif
      "this group must be built without NDEBUG (tests/CMakeLists.txt)");
  // A 2 x 2 SPD system: [[4, 1], [1, 3]] x = [1, 2] has x = [1/11, 7/11].
  SparseMatrix K(2, 2);
  K.insert(0, 0) = 4, K.insert(0, 1) = 1, K.insert(1, 0) = 1, K.insert(1, 1) = 3;
  K.makeCompressed();
  const Eigen::Vector2d r(1, 2);
  Eigen::VectorXd x;
  DirectLdltSolver solver;
  CHECK_FALSE(solver.solve(r, x));  // nothing analysed or factorised
  solver.analyse(K);
  CHECK_FALSE(solver.solve(r, x));  // analysed only
  solver.factorize(K);
  REQUIRE(solver.solve(r, x));
  CHECK(std::abs(x[0] - 1.0 / 11) < 1e-15);
  CHECK(std::abs(x[1] - 7.0 / 11) < 1e-15);
}
