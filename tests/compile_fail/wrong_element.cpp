// This file must NOT compile. It composes a Simulation with an Element policy that has no response()
// and no section_forces(); the concept check in simulation.hpp must stop the compilation with a
// sentence that names the mistake. The ctest test compile_fail_wrong_element passes only if the
// compilation fails AND the compiler's output contains "the Element policy must provide".
#include <furniture_fem/core/simulation.hpp>

#include <string_view>

struct ElementWithoutResponse {
  static constexpr std::string_view name = "an element that forgot its response";
  static constexpr bool needs_pairs = false;
  struct State {};
  static State initial_state(const furniture_fem::ElementProps&) { return {}; }
};

int main() {
  furniture_fem::Model model;
  furniture_fem::Simulation<ElementWithoutResponse> sim(model);
  return 0;
}
