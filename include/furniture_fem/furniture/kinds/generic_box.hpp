#pragma once
// furniture_fem/furniture/kinds/generic_box.hpp: the parameters shared by kinds of any size (bookshelf,
// locker, table, and kinds of your own): outer size and the static friction of the paper's 0.8 rule.
#include "../item_kind_registry.hpp"

namespace furniture_fem {

// Width, depth and height with the kind's defaults, and static floor friction along the longer and
// shorter edge (defaults: a kind's nearest paper item on the carpet of the tests).
inline std::vector<ItemParameter> generic_box_parameters(Vec3 default_size, double mu_static_long, double mu_static_short) {
  return {
      {"width", "m", 0.15, 10.0, false, default_size.x(), "outer width W (item x, along the front)"},
      {"depth", "m", 0.15, 10.0, false, default_size.y(), "outer depth D (item y, front to back)"},
      {"height", "m", 0.15, 10.0, false, default_size.z(), "outer height H"},
      {"mu_static_long", "-", 0.0, 5.0, false, mu_static_long, "static floor friction along the longer edge (0.8 rule)"},
      {"mu_static_short", "-", 0.0, 5.0, false, mu_static_short, "static floor friction along the shorter edge (0.8 rule)"},
  };
}
inline Vec3 generic_box_size(const ItemValues& v) { return {v["width"], v["depth"], v["height"]}; }

// The build options with the kind's static friction filled in.
inline BuildOptions with_static_friction(BuildOptions o, const ItemValues& v) {
  o.mu_static_long = v["mu_static_long"];
  o.mu_static_short = v["mu_static_short"];
  return o;
}

}  // namespace furniture_fem
