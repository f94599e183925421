#pragma once
// furniture_fem/furniture/kinds/desk.hpp: the kind "desk" (build_desk, furniture/furniture.hpp).
#include "paper_kind.hpp"

namespace furniture_fem {

struct DeskKind : PaperKind {
  static constexpr std::string_view name = "desk";
  static constexpr std::string_view meaning = "the paper's steel desk, W1200 D700 H700";
  static Vec3 size(const ItemValues&) { return paper_size(PaperItem::desk); }
  static std::vector<ItemInfo> build(Model& model, const Placement& at, const ItemValues&, const BuildOptions& o) {
    return {build_desk(model, at, o)};
  }
};

}  // namespace furniture_fem
