#pragma once
// furniture_fem/furniture/kinds/paper_kind.hpp: what the paper's items (Table 2) have in common as
// kinds: no parameters of their own, their size from Table 2.
#include "../item_kind_registry.hpp"

namespace furniture_fem {

struct PaperKind : ItemKindDefaults {
  static constexpr std::string_view note = "Table 2 fixes the paper items";
  static Vec3 paper_size(PaperItem item) {
    const auto& row = paper_item(item);
    return {row.W, row.D, row.H};
  }
};

}  // namespace furniture_fem
