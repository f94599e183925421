// The compiled core's dense kernels (core/dense_kernels.hpp), instantiated once: programs linking
// furniture_fem::core_compiled call these instead of instantiating the decompositions in every unit.
// The target compiles its units with FURNITURE_FEM_BUILDING_CORE_LIBRARY: the header declares the
// kernels only (as in simulation_instances.cpp); their definitions are included here.
#define FURNITURE_FEM_CORE_INTERNAL
#include <furniture_fem/core/detail/dense_kernels_impl.hpp>
#include <furniture_fem/core/detail/lu_kernels.hpp>
#include <furniture_fem/core/detail/matrix_free.hpp>
#include <furniture_fem/core/solvers.hpp>

namespace furniture_fem::detail {

template Eigen::Matrix3d pseudo_inverse<void>(const Eigen::Matrix3d&);
template Eigen::Matrix3d kabsch_rotation<void>(const Eigen::Matrix3d&);
template Eigen::Vector3d ldlt_solve<void>(const Eigen::Matrix3d&, const Eigen::Vector3d&);
template Eigen::Vector4d ldlt_solve<void>(const Eigen::Matrix4d&, const Eigen::Vector4d&);
template Eigen::Matrix<double, 6, 1> ldlt_solve<void>(const Eigen::Matrix<double, 6, 6>&, const Eigen::Matrix<double, 6, 1>&);
template bool ldlt_solve_if_regular<void>(const Eigen::Matrix3d&, const Eigen::Vector3d&, double, Eigen::Vector3d&);
template Eigen::VectorXd lu_solve<void>(const Eigen::MatrixXd&, const Eigen::VectorXd&);
template Eigen::Vector3d smallest_eigenvector<void>(const Eigen::Matrix3d&);
template SymmetricEigen symmetric_eigen<void>(const Eigen::MatrixXd&, bool);
template bool solve_near<void>(Eigen::Index, ProductOperator::Apply, const DenseLu&,
                               const Eigen::VectorXd&, Eigen::VectorXd&, int, double);
template void factorize_lu<void>(DenseLu&, const Eigen::MatrixXd&);
template Eigen::VectorXd solve_lu<void>(const DenseLu&, const Eigen::VectorXd&);
template Eigen::MatrixXd solve_lu<void>(const DenseLu&, const Eigen::MatrixXd&);
template void analyse_ldlt<void>(SimplicialLdlt&, const SparseMatrix&);
template bool factorize_ldlt<void>(SimplicialLdlt&, SupernodalFactor&, const SparseMatrix&);
template void solve_ldlt<void>(const SimplicialLdlt&, const SupernodalFactor&, const Eigen::VectorXd&, Eigen::VectorXd&,
                               Eigen::VectorXd&);
template bool compute_cg<void>(IncompleteCholeskyCg&, const SparseMatrix&);
template long solve_cg<void>(const IncompleteCholeskyCg&, const Eigen::VectorXd&, Eigen::VectorXd&);

}  // namespace furniture_fem::detail
