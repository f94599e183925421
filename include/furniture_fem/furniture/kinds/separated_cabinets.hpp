#pragma once
// furniture_fem/furniture/kinds/separated_cabinets.hpp: the kind "separated_cabinets"
// (build_separated_cabinets, furniture/furniture.hpp): two bodies, "<name>/lower" then "<name>/upper".
#include "paper_kind.hpp"

namespace furniture_fem {

struct SeparatedCabinetsKind : PaperKind {
  static constexpr std::string_view name = "separated_cabinets";
  static constexpr std::string_view meaning =
      "the paper's upper cabinet (H730) standing on the lower one (H1120), W900 D400: two bodies";
  static constexpr bool single_body = false;
  static constexpr std::string_view note = "two bodies: each cabinet follows Table 2";
  // Stacked: H = 1120 + 730 mm.
  static Vec3 size(const ItemValues&) {
    return paper_size(PaperItem::lower_separated_cabinet) + Vec3(0, 0, paper_item(PaperItem::upper_separated_cabinet).H);
  }
  static std::vector<ItemInfo> build(Model& model, const Placement& at, const ItemValues&, const BuildOptions& o) {
    auto pair = build_separated_cabinets(model, at, o);
    std::vector<ItemInfo> out;
    out.push_back(std::move(pair.lower));
    out.push_back(std::move(pair.upper));
    return out;
  }
};

}  // namespace furniture_fem
