#pragma once
// furniture_fem/furniture/kinds/side_table.hpp: the kind "side_table" (build_side_table, furniture/furniture.hpp).
#include "paper_kind.hpp"

namespace furniture_fem {

struct SideTableKind : PaperKind {
  static constexpr std::string_view name = "side_table";
  static constexpr std::string_view meaning = "the paper's side table on four casters, W550 D340 H617";
  static Vec3 size(const ItemValues&) { return paper_size(PaperItem::side_table); }
  static std::vector<ItemInfo> build(Model& model, const Placement& at, const ItemValues&, const BuildOptions& o) {
    return {build_side_table(model, at, o)};
  }
};

}  // namespace furniture_fem
