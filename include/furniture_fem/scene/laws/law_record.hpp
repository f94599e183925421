#pragma once
// furniture_fem/scene/laws/law_record.hpp: what a scene contact law states about itself. Each law is one
// record (scene/laws/<law>.hpp) and scene/laws/law_list.hpp lists them; the reader, the writer,
// validation, the per-item set-up and the run dispatch are generated from that list
// (docs/contact/contact.md, "Adding a contact law").
//
//   ContactParameter, contact_parameters   the override keys the built-in laws share
//   LawParameter                            a parameter a law declares of its own (ContactParams::law_params)
//   SceneLawDefaults                        what a record inherits unless it says otherwise
//   LawList<R...>                           a list of records
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "../../contact/contact_laws.hpp"
#include "../spec.hpp"

namespace furniture_fem {

// An override key of contact.floor / wall / item: its range, where it may stand, the ContactOverrides
// field that holds it and what it sets in ContactParams. A law reads the keys it declares.
struct ContactParameter {
  std::string_view key, unit;
  double lo, hi;
  bool lo_exclusive;
  bool floor_only;
  std::optional<double> ContactOverrides::*field;
  void (*apply)(ContactParams&, double);
  std::string_view meaning;
};

// In the order they are applied: mu before mu_long before mu_short (each narrows the one before).
inline constexpr std::array<ContactParameter, 8> contact_parameters{{
    {"alpha_kgf", "kgf", 0.0, 1e6, true, false, &ContactOverrides::alpha_kgf,
     [](ContactParams& p, double v) { p.alpha = v * ContactParams::newtons_per_kgf; }, "penalty coefficient"},
    {"dc_kgf", "kgf", 0.0, 1e6, false, false, &ContactOverrides::dc_kgf,
     [](ContactParams& p, double v) { p.Dc = v * ContactParams::newtons_per_kgf; }, "damping coefficient"},
    {"q", "-", 0.0, 10.0, true, false, &ContactOverrides::q, [](ContactParams& p, double v) { p.q = v; },
     "penalty index"},
    {"mu", "-", 0.0, 5.0, false, false, &ContactOverrides::mu,
     [](ContactParams& p, double v) { p.mu = p.mu_long = p.mu_short = v; }, "dynamic friction"},
    {"mu_long", "-", 0.0, 5.0, false, true, &ContactOverrides::mu_long,
     [](ContactParams& p, double v) { p.mu = p.mu_long = v; },
     "`floor` only: along the longer edge (the isotropic laws' floor mu)"},
    {"mu_short", "-", 0.0, 5.0, false, true, &ContactOverrides::mu_short,
     [](ContactParams& p, double v) { p.mu_short = v; }, "`floor` only: along the shorter edge"},
    // One key for every spring: Hunt-Crossley's at the linear spring's stiffness at 25 mm of overlap.
    {"stiffness", "N/m", 0.0, 1e12, true, false, &ContactOverrides::stiffness,
     [](ContactParams& p, double v) {
       p.k_lin = p.k_t = v;
       p.k_hc = v / std::sqrt(0.025);
     },
     "the linear spring; stick_slip's tangential spring k_t; hunt_crossley's k_hc = stiffness / sqrt(0.025 m) "
     "(the same onset stiffness)"},
    {"damping", "N s/m", 0.0, 1e12, false, false, &ContactOverrides::damping,
     [](ContactParams& p, double v) { p.c_lin = p.c_t = v; }, "the normal dashpot; stick_slip's tangential dashpot c_t"},
}};

inline const ContactParameter* find_contact_parameter(std::string_view key) {
  for (const auto& p : contact_parameters)
    if (p.key == key) return &p;
  return nullptr;
}

namespace detail {
// "(lo, hi]" or "[lo, hi]", appended piece by piece: GCC 12 warns on a + chain of strings here
// (-Wrestrict, a false alarm).
inline std::string range_text(double lo, double hi, bool lo_exclusive) {
  std::string text(lo_exclusive ? "(" : "[");
  return text.append(fmt(lo)).append(", ").append(fmt(hi)).append("]");
}
}  // namespace detail

// A parameter a law declares of its own, beyond the shared keys above: a key of contact.floor / wall /
// item, read by the law's force from ContactParams::law_params[slot], slot its place in the record's
// own_parameters. Every item starts from default_value (the record's item_base may set it from the item);
// two items in contact take the mean of their values (ContactParams::pair); a per_node value is scaled
// with a contact's share of nodes (a rigid item's support point standing for n nodes takes n times it).
struct LawParameter {
  std::string_view key, unit;
  double lo = 0, hi = 0;  // accepted range, both ends included unless lo_exclusive
  bool lo_exclusive = false;
  double default_value = 0;
  std::string_view meaning;  // one line, for the docs table
  bool per_node = false;     // a force coefficient (N, N/m^k, N s/m ...): scaled with the node share
  bool floor_only = false;   // only contact.floor takes it

  std::string range_text() const { return detail::range_text(lo, hi, lo_exclusive); }
  bool accepts(double v) const { return (lo_exclusive ? v > lo : v >= lo) && v <= hi; }
};

// What the per-item set-up of a law may read (scene_body_contacts).
struct LawSetup {
  const SceneSpec& spec;
  const Model& model;
  const std::vector<ItemInfo>& items;
};

// A record derives from this and overrides what differs.
struct SceneLawDefaults {
  // Non-empty: the law has a tangential spring of its own and does not read contact.stick_length (the
  // reason, for the error naming the key).
  static constexpr std::string_view own_stick_spring{};
  // The `implicit` a scene gets when it names the law and no `implicit` (unset: `all`).
  static constexpr std::optional<ImplicitContact> default_implicit{};
  // Item parameters (items[i].params) the law sets itself, and why: given, they are an error.
  static constexpr std::array<std::string_view, 0> unused_item_parameters{};
  static constexpr std::string_view unused_item_parameters_why{};
  // The law's own parameters (LawParameter), at most ContactParams::max_law_params.
  static constexpr std::array<LawParameter, 0> own_parameters{};
  // An item's parameters before the pair kinds get their friction, and its item-item parameters.
  static void item_base(ContactParams&, const LawSetup&, const ItemInfo&) {}
  static void item_pair(ContactParams&, const LawSetup&) {}
};

template <class... Records>
struct LawList {
  static constexpr std::size_t size = sizeof...(Records);
  template <std::size_t I>
  using at = std::tuple_element_t<I, std::tuple<Records...>>;
};

namespace detail {
// Whether every key a record declares is an override key (a misspelt key fails SceneContactLaw).
template <class R>
consteval bool declares_known_keys() {
  for (std::string_view key : R::parameters) {
    bool found = false;
    for (const auto& p : contact_parameters) found = found || p.key == key;
    if (!found) return false;
  }
  return true;
}
// Whether a record's own keys fit ContactParams::law_params and are neither shared keys nor repeated.
template <class R>
consteval bool declares_distinct_own_keys() {
  if (R::own_parameters.size() > ContactParams::max_law_params) return false;
  for (std::size_t i = 0; i < R::own_parameters.size(); ++i) {
    for (const auto& p : contact_parameters)
      if (p.key == R::own_parameters[i].key) return false;
    for (std::size_t j = 0; j < i; ++j)
      if (R::own_parameters[j].key == R::own_parameters[i].key) return false;
  }
  return true;
}
}  // namespace detail

// A scene contact law: a name, a ContactLaw, the shared keys it reads and its own parameters.
template <class R>
concept SceneContactLaw = std::derived_from<R, SceneLawDefaults> && ContactLawPolicy<typename R::law> && requires {
  { R::name } -> std::convertible_to<std::string_view>;
  { R::parameters.size() } -> std::convertible_to<std::size_t>;
} && detail::declares_known_keys<R>() && detail::declares_distinct_own_keys<R>();

}  // namespace furniture_fem
