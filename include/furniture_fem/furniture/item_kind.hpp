#pragma once
// furniture_fem/furniture/item_kind.hpp: the name of a kind of item ("desk", "bookshelf", or a kind a
// user registers, furniture/item_kinds.hpp). A value type: ItemInfo and scene items carry it.
#include <optional>
#include <string>
#include <string_view>

namespace furniture_fem {

// A kind of item, identified by its name in scene files. The name must outlive the ItemKind: use a
// string literal, a kind type's `name`, or item_kind_from_string(), which returns the registered name.
class ItemKind {
 public:
  constexpr explicit ItemKind(std::string_view name) : name_(name) {}
  constexpr std::string_view name() const { return name_; }
  friend constexpr bool operator==(ItemKind a, ItemKind b) { return a.name_ == b.name_; }

  // The built-in kinds (furniture/kinds/), named for code that picks one.
  static const ItemKind tall_cabinet, separated_cabinets, side_table, desk, office_chair, bookshelf, locker, table,
      block;

 private:
  std::string_view name_;
};

inline constexpr ItemKind ItemKind::tall_cabinet{"tall_cabinet"};
inline constexpr ItemKind ItemKind::separated_cabinets{"separated_cabinets"};
inline constexpr ItemKind ItemKind::side_table{"side_table"};
inline constexpr ItemKind ItemKind::desk{"desk"};
inline constexpr ItemKind ItemKind::office_chair{"office_chair"};
inline constexpr ItemKind ItemKind::bookshelf{"bookshelf"};
inline constexpr ItemKind ItemKind::locker{"locker"};
inline constexpr ItemKind ItemKind::table{"table"};
inline constexpr ItemKind ItemKind::block{"block"};

inline std::string to_string(ItemKind k) { return std::string(k.name()); }

}  // namespace furniture_fem
