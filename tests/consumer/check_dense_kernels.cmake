# Units linked to the compiled core that instantiate a Simulation (the scene library's units, the step-4
# tutorial's) take the dense and sparse kernels (core/dense_kernels.hpp, core/solvers.hpp, the GMRES of
# core/detail/matrix_free.hpp) from the library: each object references them (U) and compiles none of
# the decompositions they hold (no weak or text symbol of Eigen's CompleteOrthogonalDecomposition,
# JacobiSVD, LDLT or SelfAdjointEigenSolver of a 3 x 3, 4 x 4 or 6 x 6 matrix, of the self-adjoint
# solver's tridiagonalisation, of SimplicialLDLT's analysis and factorisation, of the incomplete Cholesky,
# or of Eigen's CG and GMRES loops). -DOBJECTS=<object files, comma-separated>.
include(${CMAKE_CURRENT_LIST_DIR}/symbol_checks.cmake)
string(REPLACE "," ";" objects "${OBJECTS}")
set(kernel "furniture_fem::detail::(pseudo_inverse|kabsch_rotation|ldlt_solve|ldlt_solve_if_regular|lu_solve|smallest_eigenvector|symmetric_eigen|solve_near|analyse_ldlt|factorize_ldlt|solve_ldlt|compute_cg|solve_cg)<void>\\(")
set(fixed "Eigen::Matrix<double, [346], [346], 0, [346], [346]>")
set(sparse "SimplicialCholeskyBase<[^\n]*::(factorize_preordered|analyzePattern_preordered)|IncompleteCholesky<[^\n]*::factorize<")
set(loops "internal::(conjugate_gradient|gmres|tridiagonalization_inplace)<")
set(decomposition "Eigen::((CompleteOrthogonalDecomposition|JacobiSVD|LDLT|SelfAdjointEigenSolver)<${fixed}|${sparse}|${loops})")
foreach(object IN LISTS objects)
  ffem_symbols(symbols ${object})
  set(problems "")
  ffem_require_taken("${symbols}" "${kernel}" "a dense kernel" problems n_taken)
  ffem_forbid_compiled("${symbols}" "${decomposition}" "TWtw" "symbols of the kernels' decompositions" problems)
  ffem_report_problems("${problems}" "${object}" "${object}: ${n_taken} kernels taken from the compiled core, none compiled")
endforeach()
