#pragma once
// furniture_fem/core/detail/lu_kernels.hpp: the partial-pivoting LU of a dense matrix kept across calls (a
// flexible group's joint system, a body's Woodbury system), factorised and solved through kernels
// (core/dense_kernels.hpp): templates of a defaulted parameter, instantiated where a simulation uses them
// header-only, and once in the compiled core for its users (the extern declarations below).
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/lu_kernels.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif
#include <Eigen/Core>
#include <Eigen/LU>

#include "../dense_kernels.hpp"

namespace furniture_fem::detail {

using DenseLu = Eigen::PartialPivLU<Eigen::MatrixXd>;

FFEM_DENSE_KERNEL void factorize_lu(DenseLu& lu, const Eigen::MatrixXd& A) { lu.compute(A); }

// A^-1 b, and A^-1 B column by column, with A's factorisation.
FFEM_DENSE_KERNEL Eigen::VectorXd solve_lu(const DenseLu& lu, const Eigen::VectorXd& b) { return lu.solve(b); }
FFEM_DENSE_KERNEL Eigen::MatrixXd solve_lu(const DenseLu& lu, const Eigen::MatrixXd& B) { return lu.solve(B); }

#ifdef FFEM_DENSE_KERNELS_DECLARED_ONLY
extern template void factorize_lu<void>(DenseLu&, const Eigen::MatrixXd&);
extern template Eigen::VectorXd solve_lu<void>(const DenseLu&, const Eigen::VectorXd&);
extern template Eigen::MatrixXd solve_lu<void>(const DenseLu&, const Eigen::MatrixXd&);
#endif

}  // namespace furniture_fem::detail
