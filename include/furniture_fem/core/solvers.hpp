#pragma once
// furniture_fem/core/solvers.hpp: linear-solver policies for the effective matrix of one body.
//
// The effective matrix K* = K + M/(beta dt^2) (+ damping) of a body is symmetric positive definite.
// A policy sees one body's sparse matrix at a time: analyse(K) once per pattern, factorize(K) when
// the simulation refreshes the matrix, solve(r, x) for every right-hand side. The simulation decides
// when to refresh (see SimulationOptions::refresh_interval_steps); between refreshes it reuses the
// factorisation with the body's rigid rotation taken out (docs/core/theory.md section 8), which keeps
// it valid for a tumbling item. See docs/core/concept_linear_solver.md.
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <concepts>
#include <string_view>

#include "errors.hpp"
#define FURNITURE_FEM_CORE_INTERNAL
#include "detail/supernodal_factor.hpp"
#undef FURNITURE_FEM_CORE_INTERNAL

namespace furniture_fem {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

template <class S>
concept LinearSolverPolicy = std::default_initializable<S> &&
    requires(S s, const SparseMatrix& K, const Eigen::VectorXd& r, Eigen::VectorXd& x) {
  { S::name } -> std::convertible_to<std::string_view>;
  s.analyse(K);
  s.factorize(K);
  { s.solve(r, x) } -> std::same_as<bool>;
};

// Sparse direct LDL^T (Eigen's simplicial, AMD ordering). The symbolic analysis is done once per
// pattern; the numeric factorisation is redone only when the simulation refreshes the matrix, and its
// factor is then repacked into dense supernodes (detail/supernodal_factor.hpp) for the many
// substitutions that reuse it.
class DirectLdltSolver {
 public:
  static constexpr std::string_view name = "sparse direct LDL^T (reused)";
  void analyse(const SparseMatrix& K) { ldlt_.analyzePattern(K); }
  void factorize(const SparseMatrix& K) {
    ldlt_.factorize(K);
    if (ldlt_.info() != Eigen::Success)
      throw SimulationError(0, "sparse LDL^T factorisation failed: the effective matrix is not positive definite "
                               "(a free body without mass, or an unconstrained static model?)");
    factor_.assign(ldlt_.matrixL().nestedExpression());
    ++factorizations_;
  }
  // x = P^T L^-T D^-1 L^-1 P r, what Eigen's solve computes, with the repacked factor.
  // False before the first factorisation: Eigen's info() may not be asked then (an assertion in builds
  // without NDEBUG: the sanitized core group aborted here, 2026-11-27).
  bool solve(const Eigen::VectorXd& r, Eigen::VectorXd& x) {
    if (factorizations_ == 0 || ldlt_.info() != Eigen::Success || ldlt_.vectorD().size() != r.size()) return false;
    work_ = ldlt_.permutationP() * r;
    factor_.solve_lower(work_);
    work_.array() /= ldlt_.vectorD().array();
    factor_.solve_upper(work_);
    x = ldlt_.permutationPinv() * work_;
    return x.allFinite();
  }
  long factorizations() const { return factorizations_; }
  const detail::SupernodalFactor& factor() const { return factor_; }

 private:
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt_;
  detail::SupernodalFactor factor_;
  Eigen::VectorXd work_;
  long factorizations_ = 0;
};

// Preconditioned conjugate gradients (the paper's solver), incomplete-Cholesky preconditioner
// rebuilt at each refresh, warm-started from the previous solution.
class ConjugateGradientSolver {
 public:
  static constexpr std::string_view name = "preconditioned CG (incomplete Cholesky)";
  double tolerance = 1e-10;
  int max_iterations = 2000;
  void analyse(const SparseMatrix&) {}
  void factorize(const SparseMatrix& K) {
    K_ = K;
    cg_.setTolerance(tolerance);
    cg_.setMaxIterations(max_iterations);
    cg_.compute(K_);
    if (cg_.info() != Eigen::Success)
      throw SimulationError(0, "incomplete Cholesky preconditioner failed: the effective matrix is not positive definite");
    ++factorizations_;
  }
  bool solve(const Eigen::VectorXd& r, Eigen::VectorXd& x) {
    if (x.size() != r.size()) x.setZero(r.size());
    x = cg_.solveWithGuess(r, x);
    iterations_ += cg_.iterations();
    return x.allFinite();
  }
  long factorizations() const { return factorizations_; }
  long iterations() const { return iterations_; }

 private:
  SparseMatrix K_;
  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, Eigen::IncompleteCholesky<double>> cg_;
  long factorizations_ = 0, iterations_ = 0;
};

template <class S>
constexpr bool check_linear_solver_policy() {
  static_assert(LinearSolverPolicy<S>,
                "furniture_fem: the LinearSolver policy must be default-constructible and provide name, "
                "analyse(K), factorize(K) and bool solve(r, x); see docs/core/concept_linear_solver.md");
  return true;
}

}  // namespace furniture_fem
