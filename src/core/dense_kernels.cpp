// The compiled core's dense kernels (core/dense_kernels.hpp), defined once: programs linking
// furniture_fem::core_compiled call these instead of instantiating the decompositions in every unit.
// The target compiles its units with FURNITURE_FEM_BUILDING_CORE_LIBRARY: the functions are out of line here
// (the header declares them without inline) and declared only in simulation_instances.cpp.
#define FURNITURE_FEM_CORE_INTERNAL
#include <furniture_fem/core/detail/dense_kernels_impl.hpp>
