#pragma once
// furniture_fem/scene/laws/hunt_crossley.hpp: the scene law "hunt_crossley", a Hertz spring whose damping
// grows with the overlap, with regularised Coulomb friction.
#include <string_view>

#include "law_record.hpp"

namespace furniture_fem {

struct HuntCrossleySceneLaw : SceneLawDefaults {
  static constexpr std::string_view name = "hunt_crossley";
  using law = HuntCrossleyLaw;
};

}  // namespace furniture_fem
