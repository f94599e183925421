#pragma once
// furniture_fem/furniture/kinds/locker.hpp: the kind "locker" (build_locker, furniture/furniture.hpp).
#include "generic_box.hpp"

namespace furniture_fem {

struct LockerKind : ItemKindDefaults {
  static constexpr std::string_view name = "locker";
  static constexpr std::string_view meaning = "closed steel locker of any size, a hat shelf at 5/6 of its height";
  static std::vector<ItemParameter> parameters() {
    const auto& tall = paper_item(PaperItem::tall_cabinet);
    return generic_box_parameters({0.9, 0.515, 1.79}, tall.mu_static_long, tall.mu_static_short);
  }
  static Vec3 size(const ItemValues& v) { return generic_box_size(v); }
  static std::vector<ItemInfo> build(Model& model, const Placement& at, const ItemValues& v, const BuildOptions& o) {
    return {build_locker(model, at, v["width"], v["depth"], v["height"], with_static_friction(o, v))};
  }
};

}  // namespace furniture_fem
