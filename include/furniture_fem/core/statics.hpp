#pragma once
// furniture_fem/core/statics.hpp: what the static solves of a Simulation return, and the options of the
// path-following ones (docs/core/theory.md section 7).
//
//   solve_static(increments, iterations, tolerance)          load control      -> StaticResult
//   solve_static_displacement(node, dof, target, increments) displacement control -> StaticPath
//   solve_static_arc_length(ArcLengthOptions)                 arc-length         -> StaticPath
//
// The reference load is everything statics scales by the load factor: nodal loads, gravity and the
// targets of support springs. None of them throws when the structure cannot carry the load: the result
// says why it stopped, and the simulation is left in the last converged state.
#include <algorithm>
#include <limits>
#include <string>
#include <vector>

namespace furniture_fem {

// Load control: the load factor ramped from 1/increments to 1.
struct StaticResult {
  int increments = 0;         // converged increments
  int iterations = 0;         // Newton iterations, all increments together
  bool converged = true;      // every increment converged (the load factor reached 1)
  double residual = 0;        // relative residual of the last iteration
  double load_factor = 0;     // load factor of the state left (the last converged increment)
  std::string reason;         // empty when converged; otherwise why the solve stopped
};

// One converged point of a path: the load factor and the displacement of the followed DOF (metres, or
// the rotation vector's component in radians for DOFs 3-5).
struct StaticPathPoint {
  double load_factor = 0, displacement = 0;
  int iterations = 0;
};

// A load-displacement path; points[0] is the state the solve started from.
struct StaticPath {
  std::vector<StaticPathPoint> points;
  bool converged = true;   // stopped at the target or at a limit of the options, not by a failure
  std::string reason;      // why it stopped (always set)
  int iterations = 0;
  double load_factor() const { return points.empty() ? 0.0 : points.back().load_factor; }
  double peak_load_factor() const {
    double p = -std::numeric_limits<double>::infinity();
    for (const auto& q : points) p = std::max(p, q.load_factor);
    return p;
  }
};

// Crisfield's cylindrical arc-length method: each increment has the length arc_length in the space of
// the translational DOFs (metres; rotations are left out so that the units agree). The path is reported
// at (node, dof). It stops at max_increments, when the load factor exceeds max_load_factor, when the
// reported DOF has moved by max_displacement (in absolute value) from its start, or when a failed
// increment (no convergence, a failed solve) has been cut below min_arc_length.
struct ArcLengthOptions {
  int node = 0, dof = 0;
  double arc_length = 0;         // first increment's length (m); <= 0: 1/20 of the linear response to
                                 // the reference load (about 20 increments to load factor 1 if elastic)
  double max_arc_length = 0;     // the length grows after easy increments up to this; <= 0: 4 arc_length
  double min_arc_length = 0;     // <= 0: arc_length / 1024
  int max_increments = 100;
  double max_load_factor = std::numeric_limits<double>::infinity();
  double max_displacement = std::numeric_limits<double>::infinity();
  double start_load_factor = 0;  // the load factor of the current state
  int max_iterations = 30;
  double tolerance = 1e-9;       // relative residual, as for solve_static
};

}  // namespace furniture_fem
