#pragma once
// furniture_fem/scene/laws/spring_dashpot.hpp: the scene law "spring_dashpot", a linear spring and dashpot
// with regularised Coulomb friction.
#include <string_view>

#include "law_record.hpp"

namespace furniture_fem {

struct SpringDashpotSceneLaw : SceneLawDefaults {
  static constexpr std::string_view name = "spring_dashpot";
  using law = SpringDashpotLaw;
};

}  // namespace furniture_fem
