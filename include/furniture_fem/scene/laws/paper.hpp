#pragma once
// furniture_fem/scene/laws/paper.hpp: the scene law "paper", the paper's law (eqs. 1-4) as published.
#include <string_view>

#include "law_record.hpp"

namespace furniture_fem {

struct PaperSceneLaw : SceneLawDefaults {
  static constexpr std::string_view name = "paper";
  using law = PaperLaw;
};

}  // namespace furniture_fem
