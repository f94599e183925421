#pragma once
// furniture_fem/core/node_states.hpp: every node's state at one time, in the simulation's layout
// (Simulation::copy_step_start_states; the scene runner keeps the last good one of a run that diverged).
#include <vector>

#include <Eigen/Core>

#include "model.hpp"  // Vec3, Mat3

namespace furniture_fem {

struct NodeStates {
  std::vector<Vec3> x, u;  // positions, displacements
  std::vector<Mat3> R;     // rotations
  Eigen::VectorXd v, a;    // velocities and accelerations, six per node
};

}  // namespace furniture_fem
