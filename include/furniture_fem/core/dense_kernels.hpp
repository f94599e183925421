#pragma once
// furniture_fem/core/dense_kernels.hpp: the small dense decompositions the solver needs (a 3 x 3
// pseudo-inverse, the Kabsch rotation, 3 x 3, 4 x 4 and 6 x 6 LDLT solves, a partial-pivoting LU solve,
// a symmetric 3 x 3 eigenvector, a symmetric matrix's eigen-decomposition), as functions of concrete types.
//
// Why functions of their own: under GCC 12 these Eigen decompositions, instantiated inside a Simulation,
// are about a third of a unit's front-end time and 0.6 GB of its peak (docs/performance.md section 6,
// "the dense kernels compiled once"). Header-only
// they are defined here (detail/dense_kernels_impl.hpp); a program linking the compiled core
// (furniture_fem::core_compiled, which defines FURNITURE_FEM_COMPILED_CORE for its users) gets them
// declared only and compiled once in src/core/dense_kernels.cpp. The results are the same to the bit
// either way: the same Eigen calls.
#include <Eigen/Core>

// Each is a function template of a defaulted parameter (`template <class = void>`), called without template
// arguments: header-only, a unit then instantiates a kernel only where a Simulation calls it, as it did
// the decompositions before (an inline function would instantiate them in every unit that includes this).
#if defined(FURNITURE_FEM_COMPILED_CORE) || defined(FURNITURE_FEM_BUILDING_CORE_LIBRARY)
#define FFEM_DENSE_KERNELS_DECLARED_ONLY 1
#endif
#define FFEM_DENSE_KERNEL template <class = void>

namespace furniture_fem::detail {

// The Moore-Penrose pseudo-inverse of A (complete orthogonal decomposition): the least-norm inverse,
// zero on A's null space.
FFEM_DENSE_KERNEL Eigen::Matrix3d pseudo_inverse(const Eigen::Matrix3d& A);

// The rotation Q nearest to H = sum (x - xc)(X - Xc)^T: U diag(1, 1, det(U V^T)) V^T from H's SVD.
FFEM_DENSE_KERNEL Eigen::Matrix3d kabsch_rotation(const Eigen::Matrix3d& H);

// x with A x = b, A symmetric (LDLT with symmetric pivoting).
FFEM_DENSE_KERNEL Eigen::Vector3d ldlt_solve(const Eigen::Matrix3d& A, const Eigen::Vector3d& b);
FFEM_DENSE_KERNEL Eigen::Vector4d ldlt_solve(const Eigen::Matrix4d& A, const Eigen::Vector4d& b);
FFEM_DENSE_KERNEL Eigen::Matrix<double, 6, 1> ldlt_solve(const Eigen::Matrix<double, 6, 6>& A,
                                                         const Eigen::Matrix<double, 6, 1>& b);
// The same, false (x untouched) when the factorisation fails or its reciprocal condition estimate is
// below rcond_min.
FFEM_DENSE_KERNEL bool ldlt_solve_if_regular(const Eigen::Matrix3d& A, const Eigen::Vector3d& b, double rcond_min,
                                             Eigen::Vector3d& x);

// x with A x = b, A square (LU with partial pivoting).
FFEM_DENSE_KERNEL Eigen::VectorXd lu_solve(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

// The unit eigenvector of a symmetric 3 x 3 matrix for its smallest eigenvalue (self-adjoint solver).
FFEM_DENSE_KERNEL Eigen::Vector3d smallest_eigenvector(const Eigen::Matrix3d& symmetric);

// A symmetric matrix's eigenvalues, ascending, and (when asked) its orthonormal eigenvectors, column j
// for value j (Eigen's self-adjoint solver: tridiagonal QR). Its lower triangle is read.
struct SymmetricEigen {
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;  // empty when not asked for
};
FFEM_DENSE_KERNEL SymmetricEigen symmetric_eigen(const Eigen::MatrixXd& symmetric, bool with_vectors = true);

}  // namespace furniture_fem::detail

// The definitions: here when used header-only; the compiled core's users link them instead.
#ifndef FFEM_DENSE_KERNELS_DECLARED_ONLY
#ifdef FURNITURE_FEM_CORE_INTERNAL  // included from the module's own internals: leave it defined
#include "detail/dense_kernels_impl.hpp"
#else
#define FURNITURE_FEM_CORE_INTERNAL
#include "detail/dense_kernels_impl.hpp"
#undef FURNITURE_FEM_CORE_INTERNAL
#endif
#endif
