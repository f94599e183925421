#pragma once
// furniture_fem/core/detail/matrix_free.hpp: a square matrix known only by its product with a vector,
// for Eigen's iterative solvers (Eigen's "matrix-free solvers" pattern), and a preconditioner that
// solves with a factorisation of a nearby matrix. A flexible group's joint system (I + D G) y = b is
// solved so, by GMRES preconditioned with the LU of an earlier step's system
// (Simulation::solve_flexible_group).
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/matrix_free.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <functional>
#include <unsupported/Eigen/IterativeSolvers>
#include <utility>

#include "lu_kernels.hpp"

namespace furniture_fem::detail {
class ProductOperator;
}

template <>
struct Eigen::internal::traits<furniture_fem::detail::ProductOperator>
    : public Eigen::internal::traits<Eigen::SparseMatrix<double>> {};

namespace furniture_fem::detail {

// y = A x by a function; the solvers only multiply.
class ProductOperator : public Eigen::EigenBase<ProductOperator> {
 public:
  using Scalar = double;
  using RealScalar = double;
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic, IsRowMajor = false };
  using Apply = std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>;

  ProductOperator(Eigen::Index n, Apply apply) : n_(n), apply_(std::move(apply)) {}
  Eigen::Index rows() const { return n_; }
  Eigen::Index cols() const { return n_; }
  template <class Rhs>
  Eigen::Product<ProductOperator, Rhs, Eigen::AliasFreeProduct> operator*(const Eigen::MatrixBase<Rhs>& x) const {
    return Eigen::Product<ProductOperator, Rhs, Eigen::AliasFreeProduct>(*this, x.derived());
  }
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const { apply_(x, y); }

 private:
  Eigen::Index n_;
  Apply apply_;
};

// M^-1 x by a given LU (of a matrix near the operator); set() before the solve.
class LuPreconditioner {
 public:
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic };
  void set(const DenseLu* lu) { lu_ = lu; }
  template <class M>
  LuPreconditioner& analyzePattern(const M&) { return *this; }
  template <class M>
  LuPreconditioner& factorize(const M&) { return *this; }
  template <class M>
  LuPreconditioner& compute(const M&) { return *this; }
  template <class Rhs>
  Eigen::VectorXd solve(const Eigen::MatrixBase<Rhs>& b) const { return lu_->solve(b.derived()); }
  Eigen::ComputationInfo info() const { return Eigen::Success; }

 private:
  const DenseLu* lu_ = nullptr;
};

}  // namespace furniture_fem::detail

template <class Rhs>
struct Eigen::internal::generic_product_impl<furniture_fem::detail::ProductOperator, Rhs, Eigen::SparseShape,
                                             Eigen::DenseShape, Eigen::GemvProduct>
    : Eigen::internal::generic_product_impl_base<
          furniture_fem::detail::ProductOperator, Rhs,
          generic_product_impl<furniture_fem::detail::ProductOperator, Rhs>> {
  template <class Dest>
  static void scaleAndAddTo(Dest& dst, const furniture_fem::detail::ProductOperator& lhs, const Rhs& rhs,
                            const double& alpha) {
    const Eigen::VectorXd x = rhs;
    Eigen::VectorXd y(x.size());
    lhs.apply(x, y);
    dst.noalias() += alpha * y;
  }
};

namespace furniture_fem::detail {

// Solves A y = b (A by its product) by GMRES preconditioned with lu, the LU of a matrix near A: a
// low-rank change of that matrix takes about its rank in iterations. False when the relative
// preconditioned residual has not reached tolerance within max_iterations (y is then not the solution).
// A kernel (core/dense_kernels.hpp): instantiated only where a simulation calls it, and once in the
// compiled core for its users.
FFEM_DENSE_KERNEL bool solve_near(Eigen::Index n, ProductOperator::Apply times_A, const DenseLu& lu,
                                  const Eigen::VectorXd& b, Eigen::VectorXd& y, int max_iterations, double tolerance) {
  const ProductOperator A(n, std::move(times_A));
  Eigen::GMRES<ProductOperator, LuPreconditioner> gmres;
  gmres.preconditioner().set(&lu);
  gmres.set_restart(max_iterations);
  gmres.setMaxIterations(max_iterations);
  gmres.setTolerance(tolerance);
  gmres.compute(A);
  y = gmres.solve(b);
  return gmres.info() == Eigen::Success && y.allFinite();
}
#ifdef FFEM_DENSE_KERNELS_DECLARED_ONLY
extern template bool solve_near<void>(Eigen::Index, ProductOperator::Apply, const DenseLu&,
                                      const Eigen::VectorXd&, Eigen::VectorXd&, int, double);
#endif

}  // namespace furniture_fem::detail
