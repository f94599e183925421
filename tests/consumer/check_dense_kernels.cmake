# Units linked to the compiled core that instantiate a Simulation (the scene library's units, the step-4
# tutorial's) take the dense kernels (core/dense_kernels.hpp) from the library:
# each object references them (U) and compiles none of the small decompositions they hold (no weak or
# text symbol of Eigen's CompleteOrthogonalDecomposition, JacobiSVD, LDLT or SelfAdjointEigenSolver of a
# 3 x 3 or 6 x 6 matrix). -DOBJECTS=<object files, comma-separated>.
string(REPLACE "," ";" objects "${OBJECTS}")
set(kernel "furniture_fem::detail::(pseudo_inverse|kabsch_rotation|ldlt_solve|ldlt_solve_if_regular|lu_solve|smallest_eigenvector)<void>\\(")
set(fixed "Eigen::Matrix<double, [36], [36], 0, [36], [36]>")
set(decomposition "Eigen::(CompleteOrthogonalDecomposition|JacobiSVD|LDLT|SelfAdjointEigenSolver)<${fixed}")
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
