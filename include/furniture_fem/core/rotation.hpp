#pragma once
// furniture_fem/core/rotation.hpp: rotation helpers without the simulation: the exponential and
// logarithm maps of SO(3), and the rigid rotation that best maps one point cloud onto another
// (detail::best_rotation, Kabsch). Nodal rotations are matrices updated by R <- exp(dtheta) R.
#ifdef FURNITURE_FEM_CORE_INTERNAL
#include "detail/rotation.hpp"
#else
#define FURNITURE_FEM_CORE_INTERNAL
#include "detail/rotation.hpp"
#undef FURNITURE_FEM_CORE_INTERNAL
#endif
