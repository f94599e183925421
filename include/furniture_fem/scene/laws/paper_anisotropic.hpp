#pragma once
// furniture_fem/scene/laws/paper_anisotropic.hpp: the scene law "paper_anisotropic", the paper's law with
// floor friction depending on the sliding direction (mu_long along the item's longer edge, mu_short across).
#include <array>
#include <string_view>

#include "law_record.hpp"

namespace furniture_fem {

struct PaperAnisotropicSceneLaw : SceneLawDefaults {
  static constexpr std::string_view name = "paper_anisotropic";
  using law = PaperAnisotropicFloorLaw;
  static constexpr std::array<std::string_view, 6> parameters{"alpha_kgf", "dc_kgf", "q", "mu", "mu_long", "mu_short"};
};

}  // namespace furniture_fem
