#pragma once
// A contact law that a test program registers itself (issue 48; docs/contact/contact.md, "Adding a
// contact law"): a cubic spring k3 (L - l)^3 on the overlap, k3 a parameter of its own, composed with
// the paper's damping and friction. Shared by the scene and study tests.
#include <furniture_fem/scene/laws/law_list.hpp>

#include <array>
#include <cstddef>
#include <string_view>

namespace ffem_test {

struct CubicSpring {
  static constexpr std::size_t k3 = 0;  // its slot in ContactParams::law_params (own_parameters[0])
  double force(const furniture_fem::ContactKinematics& k, const furniture_fem::ContactParams& p, double, double) const {
    const double d = k.L - k.l;
    return p.law_params[k3] * d * d * d;
  }
  double stiffness(const furniture_fem::ContactKinematics& k, const furniture_fem::ContactParams& p, double,
                   double) const {
    const double d = k.L - k.l;
    return 3 * p.law_params[k3] * d * d;
  }
};

struct CubicSceneLaw : furniture_fem::SceneLawDefaults {
  static constexpr std::string_view name = "cubic";
  using law = furniture_fem::ContactLaw<CubicSpring, furniture_fem::PaperSignDamping, furniture_fem::PaperSignFriction>;
  static constexpr std::array<furniture_fem::LawParameter, 1> own_parameters{{
      {.key = "k3", .unit = "N/m^3", .lo = 0, .hi = 1e20, .lo_exclusive = true, .default_value = 1e13,
       .meaning = "the cubic spring: k3 (L - l)^3 per node", .per_node = true},
  }};
};

// The law's kind, registered once per test program.
inline furniture_fem::ContactLawKind cubic_law() {
  static const furniture_fem::ContactLawKind kind = furniture_fem::register_contact_law<CubicSceneLaw>();
  return kind;
}

}  // namespace ffem_test
