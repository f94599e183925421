// The compiled scene runner's scene simulation with the cg solver: its constructor and step, once for
// every contact law (the law is a run-time kernel: contact/contact_law_kernel.hpp). The header declares
// them extern for the runner (run_scene.cpp) and the library's users (scene/scene_simulation.hpp, end).
#define FURNITURE_FEM_BUILDING_SCENE_SIMULATIONS
#include <furniture_fem/scene/scene_simulation.hpp>

namespace furniture_fem {
FFEM_SCENE_RUN_MEMBERS(, ConjugateGradientSolver)
}  // namespace furniture_fem
