// This file must NOT compile. It composes a Simulation with an Integrator policy that gives the
// generalized-alpha coefficients, a mode and a name, but no stepper(dt): the Simulation needs the
// stepper (integrators.hpp, the Stepper concept), and the concept check must stop the compilation with
// a sentence that names it. The ctest test compile_fail_integrator_without_stepper passes only if the
// compilation fails AND the compiler's output contains "the Integrator policy must provide stepper".
#include <furniture_fem/core/simulation.hpp>

#include <string>

struct CoefficientsOnly {
  furniture_fem::EquilibriumMode mode = furniture_fem::EquilibriumMode::iterate;
  furniture_fem::IntegratorCoefficients coefficients() const { return {0, 0, 0.25, 0.5}; }
  std::string name() const { return "coefficients without a stepper"; }
};

int main() {
  furniture_fem::Model model;
  furniture_fem::Simulation<furniture_fem::AsiGaussTimoshenko, CoefficientsOnly> sim(model);
  return 0;
}
