#pragma once
// furniture_fem/furniture/kinds/tall_cabinet.hpp: the kind "tall_cabinet" (build_tall_cabinet, furniture/furniture.hpp).
#include "paper_kind.hpp"

namespace furniture_fem {

struct TallCabinetKind : PaperKind {
  static constexpr std::string_view name = "tall_cabinet";
  static constexpr std::string_view meaning = "the paper's double-door steel cabinet, W900 D400 H1850, four shelves";
  static Vec3 size(const ItemValues&) { return paper_size(PaperItem::tall_cabinet); }
  static std::vector<ItemInfo> build(Model& model, const Placement& at, const ItemValues&, const BuildOptions& o) {
    return {build_tall_cabinet(model, at, o)};
  }
};

}  // namespace furniture_fem
