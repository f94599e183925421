#pragma once
// furniture_fem/core/step_length.hpp: what a valid time step is, defined and checked in one place.
//
// The integrator's stepper checks its step length here when it is made (so does every Simulation, at
// construction and for an impact's sub-steps), and the scene reader and scene validation check a
// scene's `dt` with the same function, naming their file and key.
#include <cmath>
#include <string>
#include <string_view>

#include "errors.hpp"
#include "model.hpp"

namespace furniture_fem {

// The shortest step the core accepts. Below it the integrator's mass term m / (beta dt^2) swamps the
// stiffness in double precision (a 0.1 kg node at 1e-9 s: 4e17 N/m against members' 1e6 N/m), and it
// overflows below 1e-154 s: dt = 1e-300 ran and then "diverged; try a smaller dt" (issue 13). A scene
// asks for more, SceneSpec::min_dt (1e-6 s); the core's bound is lower so that an impact's sub-steps
// (SimulationOptions::max_impact_substeps) of a scene's shortest step, and unit tests of the scheme at
// very small omega dt, stay valid.
inline constexpr double min_step_length = 1e-9;

// Why dt (s) is not a valid step length of at least min_dt seconds, naming the value; empty if it is.
inline std::string step_length_problem(double dt, double min_dt = min_step_length) {
  if (!std::isfinite(dt)) return "must be finite (got " + detail::fmt(dt) + ")";
  if (!(dt > 0)) return "must be positive (got " + detail::fmt(dt) + ")";
  if (dt < min_dt) return "must be at least " + detail::fmt(min_dt) + " s (got " + detail::fmt(dt) + ")";
  return {};
}

// dt if it is a valid step length; otherwise a ModelError "<context>: dt <why>".
inline double checked_step_length(double dt, std::string_view context, double min_dt = min_step_length) {
  if (const std::string why = step_length_problem(dt, min_dt); !why.empty())
    throw ModelError(std::string(context) + ": dt " + why);
  return dt;
}

}  // namespace furniture_fem
