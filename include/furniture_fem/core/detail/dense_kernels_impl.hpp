#pragma once
// furniture_fem/core/detail/dense_kernels_impl.hpp: the definitions of core/dense_kernels.hpp's
// function templates: included by it when the library is used header-only, and instantiated once in
// src/core/dense_kernels.cpp for the compiled core.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/dense_kernels_impl.hpp is internal: include <furniture_fem/core/dense_kernels.hpp>"
#endif
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

#include "../dense_kernels.hpp"

namespace furniture_fem::detail {

template <class Unused>
Eigen::Matrix3d pseudo_inverse(const Eigen::Matrix3d& A) {
  return A.completeOrthogonalDecomposition().pseudoInverse();
}

template <class Unused>
Eigen::Matrix3d kabsch_rotation(const Eigen::Matrix3d& H) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0) D(2, 2) = -1;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

template <class Unused>
Eigen::Vector3d ldlt_solve(const Eigen::Matrix3d& A, const Eigen::Vector3d& b) {
  return A.ldlt().solve(b);
}

template <class Unused>
Eigen::Vector4d ldlt_solve(const Eigen::Matrix4d& A, const Eigen::Vector4d& b) {
  return A.ldlt().solve(b);
}

template <class Unused>
Eigen::Matrix<double, 6, 1> ldlt_solve(const Eigen::Matrix<double, 6, 6>& A, const Eigen::Matrix<double, 6, 1>& b) {
  return A.ldlt().solve(b);
}

template <class Unused>
bool ldlt_solve_if_regular(const Eigen::Matrix3d& A, const Eigen::Vector3d& b, double rcond_min, Eigen::Vector3d& x) {
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(A);
  if (ldlt.info() != Eigen::Success || ldlt.rcond() < rcond_min) return false;
  x = ldlt.solve(b);
  return true;
}

template <class Unused>
Eigen::VectorXd lu_solve(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  return A.partialPivLu().solve(b);
}

template <class Unused>
Eigen::Vector3d smallest_eigenvector(const Eigen::Matrix3d& symmetric) {
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(symmetric).eigenvectors().col(0);
}

template <class Unused>
SymmetricEigen symmetric_eigen(const Eigen::MatrixXd& symmetric, bool with_vectors) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(symmetric, with_vectors ? Eigen::ComputeEigenvectors
                                                                                  : Eigen::EigenvaluesOnly);
  SymmetricEigen result{es.eigenvalues(), {}};
  if (with_vectors) result.vectors = es.eigenvectors();
  return result;
}

}  // namespace furniture_fem::detail
