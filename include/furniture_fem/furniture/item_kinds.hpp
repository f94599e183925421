#pragma once
// furniture_fem/furniture/item_kinds.hpp: the kinds of item scene files can name. The built-in kinds are
// one header each in furniture/kinds/ and one line of builtin_item_kinds below; a kind of your own is
// added at run time with register_item_kind<K>() (docs/furniture/furniture.md, examples/step-7-custom-item).
#include <optional>
#include <string_view>

#include "item_kind_registry.hpp"
#include "kinds/block.hpp"
#include "kinds/bookshelf.hpp"
#include "kinds/desk.hpp"
#include "kinds/locker.hpp"
#include "kinds/office_chair.hpp"
#include "kinds/separated_cabinets.hpp"
#include "kinds/side_table.hpp"
#include "kinds/table.hpp"
#include "kinds/tall_cabinet.hpp"

namespace furniture_fem {

// In the order the docs list them.
using builtin_item_kinds = ItemKindList<TallCabinetKind, SeparatedCabinetsKind, SideTableKind, DeskKind,
                                        OfficeChairKind, BookshelfKind, LockerKind, TableKind, BlockKind>;

// A registry holding the built-in kinds only (the docs table is made from it).
inline ItemKindRegistry builtin_item_kind_registry() {
  ItemKindRegistry registry;
  builtin_item_kinds::add_to(registry);
  return registry;
}

// The registry scene files are read and built against: the built-in kinds and those registered since.
// Register kinds before reading or building scenes on other threads: it is not locked.
inline ItemKindRegistry& item_kind_registry() {
  static ItemKindRegistry registry = builtin_item_kind_registry();
  return registry;
}

// Makes kind type K (see ItemKindEntry) known to scene files. Throws ModelError if its name is taken.
template <class K>
void register_item_kind() {
  item_kind_registry().add<K>();
}

// The registered kind of that name (its ItemKind refers to the registry's copy of the name).
inline std::optional<ItemKind> item_kind_from_string(std::string_view name) {
  if (const auto* entry = item_kind_registry().find(name)) return entry->kind;
  return std::nullopt;
}

}  // namespace furniture_fem
