#pragma once
// furniture_fem/scene/laws/stick_slip.hpp: the scene law "stick_slip", the paper's normal response with
// Coulomb friction on a tangential spring k_t and dashpot c_t (return mapping).
#include <string_view>

#include "law_record.hpp"

namespace furniture_fem {

struct StickSlipSceneLaw : SceneLawDefaults {
  static constexpr std::string_view name = "stick_slip";
  using law = StickSlipLaw;
  static constexpr std::string_view own_stick_spring = "its tangential spring is k_t";
};

}  // namespace furniture_fem
