#pragma once
// furniture_fem/scene/laws/stiff.hpp: the scene law "stiff", the spring-dashpot law with its stiffness and
// damping from each item's mass, resting nodes and inertia (docs/contact/contact.md, "The stiff rule").
#include <algorithm>
#include <array>
#include <limits>
#include <string_view>

#include "../../contact/stiff_contact.hpp"
#include "law_record.hpp"

namespace furniture_fem {

struct StiffSceneLaw : SceneLawDefaults {
  static constexpr std::string_view name = "stiff";
  using law = SpringDashpotLaw;
  // Its parts' stiffness and damping come from each item (the stiff rule), not from the scene.
  static constexpr std::array<std::string_view, 2> rule_parameters{"stiffness", "damping"};
  static constexpr std::string_view rule_parameters_why =
      "it sets each item's stiffness and damping from its mass and inertia (docs/contact/contact.md, \"The stiff rule\")";
  static constexpr std::array<std::string_view, 3> unused_item_parameters{"alpha_kgf", "dc_kgf", "alpha_scale"};
  static constexpr std::string_view unused_item_parameters_why =
      "it sets each item's stiffness and damping from its mass and inertia; docs/contact/contact.md";

  static void item_base(ContactParams& p, const LawSetup& s, const ItemInfo& item) {
    set_stiff_contact(s.model, item.body, p);
  }
  // One cap for the scene (a pair takes the mean of two items' values), from its lightest node. Kept for
  // rigid groups too: uncapped, the stiff dashpot's clamp makes a rigid stack chatter
  // (docs/contact/implicit_contact.md, "Rigid groups").
  static void item_pair(ContactParams& p, const LawSetup& s) {
    double lightest = std::numeric_limits<double>::infinity();
    for (const auto& it : s.items) lightest = std::min(lightest, lightest_node_mass(s.model, it.body));
    cap_for_explicit_pairs(p, lightest, s.spec.dt);
  }
};

}  // namespace furniture_fem
