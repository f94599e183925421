#pragma once
// furniture_fem/furniture/item_kind_registry.hpp: what a kind of item is made of, as one type: its name,
// the parameters it takes (key, unit, range, default, meaning) and its builder. A registry maps names
// to kinds; scene files are read against it (furniture/item_kinds.hpp holds the one in use and the
// built-in kinds). docs/furniture/furniture.md shows how to write and register a kind.
#include <cmath>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "../core/errors.hpp"
#include "../core/model.hpp"
#include "furniture.hpp"

namespace furniture_fem {

// One parameter of a kind, as scene files give it (items[i].params.<key>).
struct ItemParameter {
  std::string_view key;
  std::string_view unit;  // "m", "kg", "-" ...
  double lo = 0, hi = 0;  // accepted range, both ends included unless lo_exclusive
  bool lo_exclusive = false;
  double default_value = 0;  // used when the scene file leaves the key out
  std::string_view meaning;  // one line, for the docs table
  bool integer = false;

  std::string range_text() const {
    return std::string(lo_exclusive ? "(" : "[") + detail::fmt(lo) + ", " + detail::fmt(hi) + "]";
  }
  // Why `value` is not accepted, or nothing when it is.
  std::optional<std::string> violation(double value) const {
    // std::trunc, not a cast to an integer type: a value past its range (1.6e19 shelves) was undefined
    // behaviour (found by fuzzing, docs/fuzzing.md); such a value is an integer, out of the range below.
    if (integer && value != std::trunc(value)) return "must be an integer";
    if (!((lo_exclusive ? value > lo : value >= lo) && value <= hi)) return "must lie in " + range_text();
    return std::nullopt;
  }
};

// The values of a kind's parameters for one item: the given ones, the declared defaults elsewhere.
class ItemValues {
 public:
  ItemValues(std::string_view kind, const std::vector<ItemParameter>& parameters,
             const std::map<std::string, double>& given = {})
      : kind_(kind) {
    for (const auto& p : parameters) values_.emplace(std::string(p.key), p.default_value);
    for (const auto& [key, value] : given) {
      const auto it = values_.find(key);
      if (it == values_.end()) throw ModelError("kind \"" + kind_ + "\" has no parameter \"" + key + "\"");
      it->second = value;
    }
  }
  double operator[](std::string_view key) const {
    const auto it = values_.find(key);
    if (it == values_.end()) throw ModelError("kind \"" + kind_ + "\" declares no parameter \"" + std::string(key) + "\"");
    return it->second;
  }
  int integer(std::string_view key) const { return static_cast<int>((*this)[key]); }

 private:
  std::string kind_;
  std::map<std::string, double, std::less<>> values_;
};

using ItemBuilder = std::function<std::vector<ItemInfo>(Model&, const Placement&, const ItemValues&, const BuildOptions&)>;

// A registered kind. Made from a kind type K by ItemKindEntry::of<K>(), which reads:
//   static constexpr std::string_view name, meaning;
//   static std::vector<ItemParameter> parameters();          // its own parameters (may be empty)
//   static Vec3 size(const ItemValues&);                      // outer W, D, H as built
//   static std::vector<ItemInfo> build(Model&, const Placement&, const ItemValues&, const BuildOptions&);
//   static constexpr bool single_body;                        // false: mass_kg, cog_h, cog_d1 do not apply
//   static constexpr std::string_view note;                   // why a parameter does not apply ("" if none)
// ItemKindDefaults gives the last three (and no parameters) to a kind type that derives from it.
struct ItemKindEntry {
  ItemKind kind{""};
  std::string_view meaning;
  std::string_view note;
  bool single_body = true;
  std::vector<ItemParameter> parameters;
  std::function<Vec3(const ItemValues&)> size;
  ItemBuilder build;

  template <class K>
  static ItemKindEntry of() {
    return {ItemKind(K::name), K::meaning, K::note, K::single_body, K::parameters(), &K::size, &K::build};
  }
  const ItemParameter* parameter(std::string_view key) const {
    for (const auto& p : parameters)
      if (p.key == key) return &p;
    return nullptr;
  }
  ItemValues values(const std::map<std::string, double>& given = {}) const {
    return ItemValues(kind.name(), parameters, given);
  }
};

struct ItemKindDefaults {
  static constexpr bool single_body = true;
  static constexpr std::string_view note = "";
  static std::vector<ItemParameter> parameters() { return {}; }
};

// Kinds by name, in the order they were added. Entries never move once added.
class ItemKindRegistry {
 public:
  template <class K>
  void add() { add(ItemKindEntry::of<K>()); }
  void add(ItemKindEntry entry) {
    if (entry.kind.name().empty()) throw ModelError("an item kind needs a name");
    if (find(entry.kind.name())) throw ModelError("item kind \"" + to_string(entry.kind) + "\" is already registered");
    kinds_.push_back(std::move(entry));
  }
  const ItemKindEntry* find(std::string_view name) const {
    for (const auto& k : kinds_)
      if (k.kind.name() == name) return &k;
    return nullptr;
  }
  const ItemKindEntry& at(ItemKind kind) const {
    if (const auto* k = find(kind.name())) return *k;
    throw ModelError("item kind \"" + to_string(kind) + "\" is not registered; registered kinds: " + names());
  }
  const std::deque<ItemKindEntry>& kinds() const { return kinds_; }
  std::string names() const {
    std::string list;
    for (const auto& k : kinds_) list += (list.empty() ? "" : ", ") + to_string(k.kind);
    return list;
  }

 private:
  std::deque<ItemKindEntry> kinds_;
};

// A list of kind types, added to a registry in order.
template <class... Kinds>
struct ItemKindList {
  static void add_to(ItemKindRegistry& registry) { (registry.add<Kinds>(), ...); }
};

}  // namespace furniture_fem
