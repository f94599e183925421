#pragma once
// furniture_fem/contact/law_parameter.hpp: a parameter a contact law's part reads, as the part declares it.
// The scene keys, their ranges, validation, the overrides, the per-node share scaling, the pair mixing and
// the docs tables of every law, built-in or registered, are generated from these declarations
// (docs/contact/contact.md, "Adding a contact law").
//
//   LawParameter    key, unit, range, default, meaning, share scaling, where the value is kept
#include <cstddef>
#include <string>
#include <string_view>

#include "../core/model.hpp"

namespace furniture_fem {

struct ContactParams;

namespace detail {
// "(lo, hi]" or "[lo, hi]", appended piece by piece: GCC 12 warns on a + chain of strings here
// (-Wrestrict, a false alarm).
inline std::string range_text(double lo, double hi, bool lo_exclusive) {
  std::string text(lo_exclusive ? "(" : "[");
  return text.append(fmt(lo)).append(", ").append(fmt(hi)).append("]");
}
}  // namespace detail

// One parameter: a key of contact.floor / wall / item. Its value is kept in a field of ContactParams (a
// built-in part's: `field`) or in ContactParams::law_params[slot] (a law's own). Two items in contact take
// the mean of their values (ContactParams::pair); a per_node value is scaled with a contact's share of
// nodes (a rigid item's support point standing for n nodes takes n times it). Several parts of one law may
// declare the same key (the paper's penalty and damping both read q): the key then sets each.
struct LawParameter {
  std::string_view key, unit;
  double lo = 0, hi = 0;  // accepted range of the scene value, both ends included unless lo_exclusive
  bool lo_exclusive = false;
  // An item's value unless given: a slot's starts here (the record's item_base may set it from the item);
  // a field's follows from the item's own parameters (scene_body_contacts: the paper's weight rule).
  double default_value = 0;
  std::string_view meaning;  // one line, for the docs table
  bool per_node = false;     // a force coefficient (N, N/m^k, N s/m ...): scaled with the node share
  bool floor_only = false;   // only contact.floor takes it
  double ContactParams::*field = nullptr;  // where a part keeps it; null: law_params[slot]
  std::size_t slot = 0;
  double (*to_si)(double) = nullptr;  // the stored value from the scene's (kgf to N ...); null: as given

  std::string range_text() const { return detail::range_text(lo, hi, lo_exclusive); }
  bool accepts(double v) const { return (lo_exclusive ? v > lo : v >= lo) && v <= hi; }
  double stored(double scene_value) const { return to_si ? to_si(scene_value) : scene_value; }
  // The same key kept elsewhere (a part that reads it from another field).
  constexpr LawParameter with_field(double ContactParams::*other) const {
    LawParameter d = *this;
    d.field = other;
    return d;
  }
  // The same key with the same storage (one declaration read by two parts).
  constexpr bool same_as(const LawParameter& o) const {
    return key == o.key && field == o.field && (field != nullptr || slot == o.slot) && to_si == o.to_si;
  }
  // What the reader and the docs say of a key: two declarations of one key must agree on it.
  constexpr bool same_key_terms(const LawParameter& o) const {
    return unit == o.unit && lo == o.lo && hi == o.hi && lo_exclusive == o.lo_exclusive && floor_only == o.floor_only;
  }
};

}  // namespace furniture_fem
