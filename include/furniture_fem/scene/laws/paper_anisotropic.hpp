#pragma once
// furniture_fem/scene/laws/paper_anisotropic.hpp: the scene law "paper_anisotropic", the paper's law with
// floor friction depending on the sliding direction (mu_long along the item's longer edge, mu_short across).
#include <string_view>

#include "law_record.hpp"

namespace furniture_fem {

struct PaperAnisotropicSceneLaw : SceneLawDefaults {
  static constexpr std::string_view name = "paper_anisotropic";
  using law = PaperAnisotropicFloorLaw;
};

}  // namespace furniture_fem
