// The contact-dynamics group's room simulations, compiled once for the group's units
// (dynamics_scenes.hpp declares them extern: a unit that steps one compiles none of its solver).
#include "dynamics_scenes.hpp"

namespace furniture_fem {
FFEM_DYNAMICS_SIMULATIONS()
}  // namespace furniture_fem
