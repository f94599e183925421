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

#include "dense_kernels.hpp"
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

namespace detail {

using SimplicialLdlt = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower>;
using IncompleteCholeskyCg =
    Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, Eigen::IncompleteCholesky<double>>;

// The solvers' Eigen work as kernels (core/dense_kernels.hpp): templates of a defaulted parameter, so a
// program linking the compiled core takes them from it (the extern declarations below) and a header-only
// one instantiates them where a solver is used. Under GCC 12 these sparse classes were 7 of the 41 s
// that including the scene runner took, syntax only (docs/performance.md section 6).

// The symbolic analysis of K's pattern.
FFEM_DENSE_KERNEL void analyse_ldlt(SimplicialLdlt& ldlt, const SparseMatrix& K) { ldlt.analyzePattern(K); }

// The numeric factorisation, its factor repacked into supernodes; false when K is not positive definite.
FFEM_DENSE_KERNEL bool factorize_ldlt(SimplicialLdlt& ldlt, SupernodalFactor& factor, const SparseMatrix& K) {
  ldlt.factorize(K);
  if (ldlt.info() != Eigen::Success) return false;
  factor.assign(ldlt.matrixL().nestedExpression());
  return true;
}

// x = P^T L^-T D^-1 L^-1 P r, what Eigen's solve computes, with the repacked factor (work: scratch).
FFEM_DENSE_KERNEL void solve_ldlt(const SimplicialLdlt& ldlt, const SupernodalFactor& factor, const Eigen::VectorXd& r,
                                  Eigen::VectorXd& work, Eigen::VectorXd& x) {
  work = ldlt.permutationP() * r;
  factor.solve_lower(work);
  work.array() /= ldlt.vectorD().array();
  factor.solve_upper(work);
  x = ldlt.permutationPinv() * work;
}

// The incomplete-Cholesky preconditioner of K (kept by reference: K must outlive the solves); false when
// it fails.
FFEM_DENSE_KERNEL bool compute_cg(IncompleteCholeskyCg& cg, const SparseMatrix& K) {
  cg.compute(K);
  return cg.info() == Eigen::Success;
}

// x = K^-1 r by CG warm-started from x; the iterations it took.
FFEM_DENSE_KERNEL long solve_cg(const IncompleteCholeskyCg& cg, const Eigen::VectorXd& r, Eigen::VectorXd& x) {
  x = cg.solveWithGuess(r, x);
  return cg.iterations();
}

#ifdef FFEM_DENSE_KERNELS_DECLARED_ONLY
extern template void analyse_ldlt<void>(SimplicialLdlt&, const SparseMatrix&);
extern template bool factorize_ldlt<void>(SimplicialLdlt&, SupernodalFactor&, const SparseMatrix&);
extern template void solve_ldlt<void>(const SimplicialLdlt&, const SupernodalFactor&, const Eigen::VectorXd&,
                                      Eigen::VectorXd&, Eigen::VectorXd&);
extern template bool compute_cg<void>(IncompleteCholeskyCg&, const SparseMatrix&);
extern template long solve_cg<void>(const IncompleteCholeskyCg&, const Eigen::VectorXd&, Eigen::VectorXd&);
#endif

}  // namespace detail

// Sparse direct LDL^T (Eigen's simplicial, AMD ordering). The symbolic analysis is done once per
// pattern; the numeric factorisation is redone only when the simulation refreshes the matrix, and its
// factor is then repacked into dense supernodes (detail/supernodal_factor.hpp) for the many
// substitutions that reuse it.
class DirectLdltSolver {
 public:
  static constexpr std::string_view name = "sparse direct LDL^T (reused)";
  void analyse(const SparseMatrix& K) { detail::analyse_ldlt(ldlt_, K); }
  void factorize(const SparseMatrix& K) {
    if (!detail::factorize_ldlt(ldlt_, factor_, K))
      throw SimulationError(0, "sparse LDL^T factorisation failed: the effective matrix is not positive definite "
                               "(a free body without mass, or an unconstrained static model?)");
    ++factorizations_;
  }
  // x = K^-1 r by the repacked factor (detail::solve_ldlt). False before the first factorisation: Eigen's info() may not be asked then (an assertion in builds
  // without NDEBUG: the sanitized core group aborted here, 2026-11-27).
  bool solve(const Eigen::VectorXd& r, Eigen::VectorXd& x) {
    if (factorizations_ == 0 || ldlt_.info() != Eigen::Success || ldlt_.vectorD().size() != r.size()) return false;
    detail::solve_ldlt(ldlt_, factor_, r, work_, x);
    return x.allFinite();
  }
  long factorizations() const { return factorizations_; }
  const detail::SupernodalFactor& factor() const { return factor_; }

 private:
  detail::SimplicialLdlt ldlt_;
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
    if (!detail::compute_cg(cg_, K_))
      throw SimulationError(0, "incomplete Cholesky preconditioner failed: the effective matrix is not positive definite");
    ++factorizations_;
  }
  bool solve(const Eigen::VectorXd& r, Eigen::VectorXd& x) {
    if (x.size() != r.size()) x.setZero(r.size());
    iterations_ += detail::solve_cg(cg_, r, x);
    return x.allFinite();
  }
  long factorizations() const { return factorizations_; }
  long iterations() const { return iterations_; }

 private:
  SparseMatrix K_;
  detail::IncompleteCholeskyCg cg_;
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
