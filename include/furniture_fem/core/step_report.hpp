#pragma once
// furniture_fem/core/step_report.hpp: what a simulation reports about its steps, apart from the
// simulation (observers read these through scene/observer.hpp without compiling the solver).
//
//   StepTimings   where the time of the steps went
//   EnergyLedger  what the structure holds, and the work done on it
#include <algorithm>
#include <cmath>

namespace furniture_fem {

// Where the time of the steps went (seconds, accumulated since the start). Wall clock: `contact`
// (every node and element pair, the whole scene at once), `bodies` (the sweep over the bodies that
// does everything else a body needs: residual, solve, updates, element forces, energy, ASI shifts)
// and `total`. Inside the sweep, the time of each body's parts is summed over the bodies, so with
// several threads these are thread seconds and can exceed `bodies`: `solve` (residual, assembly,
// factorisation, substitution, finite-rotation update), `factorize` (the factorisations alone, part
// of `solve`) and `elements` (kinematic update and element forces).
struct StepTimings {
  static constexpr bool checkpoint_as_bytes = true;  // core/checkpoint.hpp
  double elements = 0, contact = 0, solve = 0, factorize = 0, bodies = 0, total = 0;
  double other() const { return total - contact - bodies; }  // predictor, loads, checks (wall)
};

// The energy ledger (J): what the structure holds, and the work done on it.
struct EnergyLedger {
  static constexpr bool checkpoint_as_bytes = true;  // core/checkpoint.hpp
  double kinetic = 0, strain = 0, gravity_potential = 0;
  double external_work = 0;   // base excitation inertial forces and nodal loads
  double contact_work = 0;    // work of contact forces (negative: friction and damping dissipate)
  // The contact forces' work as the integrator applied it (Simulation::StepWork): what the contact gave
  // the items (positive) or took from them. contact_work is the trapezoidal rule on the increment, an
  // estimate of the law's own work; where the contact comes on or lets go within a step the two differ by
  // what the scheme adds or takes there, which the imbalance then shows. Not in the imbalance.
  double contact_work_applied = 0;
  double damping_work = 0;    // work of viscous damping (negative)
  double plastic_work = 0;    // dissipated in plastic hinges (positive)
  double initial_total = 0;
  double total() const { return kinetic + strain + gravity_potential; }
  // What the integrator lost or made: zero for an exact energy balance.
  double imbalance() const {
    return total() - initial_total - external_work - contact_work - damping_work + plastic_work;
  }
  double scale() const {
    return std::max({std::abs(kinetic), std::abs(strain), std::abs(external_work), std::abs(contact_work),
                     std::abs(plastic_work), std::abs(initial_total), 1e-12});
  }
};

}  // namespace furniture_fem
