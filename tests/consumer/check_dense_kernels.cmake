# Units linked to the compiled core that instantiate a Simulation (the scene library's units, the step-4
# tutorial's) take the dense and sparse kernels (core/dense_kernels.hpp, core/solvers.hpp, the GMRES of
# core/detail/matrix_free.hpp) from the library: each object references them (U) and compiles none of
# the decompositions they hold (no weak or text symbol of Eigen's CompleteOrthogonalDecomposition,
# JacobiSVD, LDLT or SelfAdjointEigenSolver of a 3 x 3, 4 x 4 or 6 x 6 matrix, of the self-adjoint
# solver's tridiagonalisation, of SimplicialLDLT's analysis and factorisation, of the incomplete Cholesky,
# or of Eigen's CG and GMRES loops). -DOBJECTS=<object files, comma-separated>.
string(REPLACE "," ";" objects "${OBJECTS}")
set(kernel "furniture_fem::detail::(pseudo_inverse|kabsch_rotation|ldlt_solve|ldlt_solve_if_regular|lu_solve|smallest_eigenvector|symmetric_eigen|solve_near|analyse_ldlt|factorize_ldlt|solve_ldlt|compute_cg|solve_cg)<void>\\(")
set(fixed "Eigen::Matrix<double, [346], [346], 0, [346], [346]>")
set(sparse "SimplicialCholeskyBase<[^\n]*::(factorize_preordered|analyzePattern_preordered)|IncompleteCholesky<[^\n]*::factorize<")
set(loops "internal::(conjugate_gradient|gmres|tridiagonalization_inplace)<")
set(decomposition "Eigen::((CompleteOrthogonalDecomposition|JacobiSVD|LDLT|SelfAdjointEigenSolver)<${fixed}|${sparse}|${loops})")
foreach(object IN LISTS objects)
  execute_process(COMMAND nm -C ${object} OUTPUT_VARIABLE symbols RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "nm failed on ${object}")
  endif()
  string(REGEX MATCHALL " U [^\n]*${kernel}" taken "${symbols}")
  string(REGEX MATCHALL " [TWtw] [^\n]*${decomposition}[^\n]*" compiled "${symbols}")
  list(LENGTH taken n_taken)
  list(LENGTH compiled n_compiled)
  if(n_taken EQUAL 0)
    message(FATAL_ERROR "${object}: no dense kernel taken from furniture_fem::core_compiled")
  endif()
  if(n_compiled GREATER 0)
    list(GET compiled 0 first)
    message(FATAL_ERROR "${object}: ${n_compiled} symbols of the dense kernels' decompositions compiled in the unit, e.g.${first}")
  endif()
  message(STATUS "${object}: ${n_taken} dense kernels taken from the compiled core, none compiled")
endforeach()
