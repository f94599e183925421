#pragma once
// Where tests of the scene contact laws probe a law's floor force: a node `overlap` into the floor of a
// 25 mm contact, approaching while sliding slowly (sticking) and fast (slipping), at an angle to the
// item's long axis (x).
#include <furniture_fem/contact/contact_laws.hpp>

#include <array>

namespace ffem_test {

inline std::array<furniture_fem::ContactKinematics, 2> floor_probes(double overlap) {
  std::array<furniture_fem::ContactKinematics, 2> probes;
  const std::array<furniture_fem::Vec3, 2> velocities{furniture_fem::Vec3(3e-5, 4e-5, -2e-3),
                                                      furniture_fem::Vec3(0.3, 0.4, -0.01)};
  for (std::size_t i = 0; i < probes.size(); ++i) {
    probes[i].L = 0.025;
    probes[i].l = 0.025 - overlap;
    probes[i].v = velocities[i];
    probes[i].long_axis = furniture_fem::Vec3::UnitX();
    probes[i].dt = 1e-3;
  }
  return probes;
}

}  // namespace ffem_test
