#pragma once
// furniture_fem/furniture/kinds/office_chair.hpp: the kind "office_chair" (build_office_chair, furniture/furniture.hpp).
#include "paper_kind.hpp"

namespace furniture_fem {

struct OfficeChairKind : PaperKind {
  static constexpr std::string_view name = "office_chair";
  static constexpr std::string_view meaning = "the paper's office chair on five casters, W520 D520 H810";
  static Vec3 size(const ItemValues&) { return paper_size(PaperItem::office_chair); }
  static std::vector<ItemInfo> build(Model& model, const Placement& at, const ItemValues&, const BuildOptions& o) {
    return {build_office_chair(model, at, o)};
  }
};

}  // namespace furniture_fem
