#pragma once
// furniture_fem/scene/laws/paper.hpp: the scene law "paper", the paper's law (eqs. 1-4) as published.
#include <array>
#include <string_view>

#include "law_record.hpp"

namespace furniture_fem {

struct PaperSceneLaw : SceneLawDefaults {
  static constexpr std::string_view name = "paper";
  using law = PaperLaw;
  static constexpr std::array<std::string_view, 5> parameters{"alpha_kgf", "dc_kgf", "q", "mu", "mu_long"};
};

}  // namespace furniture_fem
