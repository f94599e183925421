// The compiled core (CMake target furniture_fem::core_compiled): the Simulation combinations that
// core/simulation.hpp declares `extern` under FURNITURE_FEM_COMPILED_CORE, instantiated once here, so a
// program linking the target compiles none of their solver code (docs/performance.md section 6).
// The headers stay usable alone: furniture_fem::core instantiates whatever a program uses.
#include <furniture_fem/core/simulation.hpp>

namespace furniture_fem {

template class Simulation<AsiGaussTimoshenko, Newmark, DirectLdltSolver>;
template class Simulation<ConventionalTimoshenko, Newmark, DirectLdltSolver>;
template class Simulation<CubicEulerBernoulli, Newmark, DirectLdltSolver>;

}  // namespace furniture_fem
