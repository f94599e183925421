#pragma once
// furniture_fem/scene/laws/law_record.hpp: what a scene contact law states about itself. Each law is one
// record (scene/laws/<law>.hpp) and scene/laws/law_list.hpp lists them; the reader, the writer,
// validation, the per-item set-up and the run dispatch are generated from that list
// (docs/contact/contact.md, "Adding a contact law").
//
//   LawParameter                            a parameter, as a law's part declares it (contact/law_parameter.hpp);
//                                           a record may declare more of its own (ContactParams::law_params)
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

#include "../../contact/contact_law_kernel.hpp"
#include "../../contact/contact_laws.hpp"
#include "../spec.hpp"

namespace furniture_fem {

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
  // Keys its parts declare that its item_base sets from each item instead (the stiff rule), and why:
  // given in a scene, they are an error.
  static constexpr std::array<std::string_view, 0> rule_parameters{};
  static constexpr std::string_view rule_parameters_why{};
  // The law's own parameters beyond its parts' (LawParameter, held in ContactParams::law_params[slot], slot
  // their place here), at most ContactParams::max_law_params.
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
template <class R>
consteval bool part_key(std::string_view key) {
  for (const auto& p : contact_law_parameters<typename R::law>)
    if (p.key == key) return true;
  return false;
}
// Whether a record's own keys fit ContactParams::law_params and are neither its parts' keys nor repeated,
// and its rule keys are its parts'.
template <class R>
consteval bool declares_distinct_own_keys() {
  if (R::own_parameters.size() > ContactParams::max_law_params) return false;
  for (std::size_t i = 0; i < R::own_parameters.size(); ++i) {
    if (part_key<R>(R::own_parameters[i].key) || R::own_parameters[i].field != nullptr) return false;
    for (std::size_t j = 0; j < i; ++j)
      if (R::own_parameters[j].key == R::own_parameters[i].key) return false;
  }
  for (std::string_view key : R::rule_parameters)
    if (!part_key<R>(key)) return false;
  return true;
}
}  // namespace detail

// A scene contact law: a name, a ContactLaw (its parts declare the keys it reads) and its own parameters.
// A hand-kept key list (`parameters`, before issue 48's declarations) is refused: the parts say it.
template <class R>
concept SceneContactLaw = std::derived_from<R, SceneLawDefaults> && ContactLawPolicy<typename R::law> && requires {
  { R::name } -> std::convertible_to<std::string_view>;
} && !requires { R::parameters; } && detail::declares_distinct_own_keys<R>();

}  // namespace furniture_fem
