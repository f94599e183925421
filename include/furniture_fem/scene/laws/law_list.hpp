#pragma once
// furniture_fem/scene/laws/law_list.hpp: the scene contact laws, one line each, and what is generated from
// the list. Adding a law: its record (scene/laws/<law>.hpp; law_record.hpp says what it states), its
// include and its line below (docs/contact/contact.md, "Adding a contact law").
//
//   scene_contact_laws                the list; its first law is a scene's default
//   law_kind<R>                       the ContactLawKind of record R (s.contact.law = law_kind<StiffSceneLaw>)
//   scene_law(kind)                   what the reader, writer, validation and set-up need of a law
//   visit_scene_law(kind, f)          f.template operator()<R>() for the law's record (the run dispatch)
//   contact_law_table()               the override keys by law, as the table of docs/scene/scene_file.md
#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "../../core/errors.hpp"
#include "hunt_crossley.hpp"
#include "law_record.hpp"
#include "paper.hpp"
#include "paper_anisotropic.hpp"
#include "spring_dashpot.hpp"
#include "stick_slip.hpp"
#include "stiff.hpp"

namespace furniture_fem {

using scene_contact_laws = LawList<PaperSceneLaw, PaperAnisotropicSceneLaw, SpringDashpotSceneLaw,
                                   HuntCrossleySceneLaw, StickSlipSceneLaw, StiffSceneLaw>;

// ---------------------------------------------------------------------------------------------
// Generated from the list.

namespace detail {
template <class R, class... Rs>
consteval std::size_t index_in(LawList<Rs...>) {
  std::size_t i = 0, found = sizeof...(Rs);
  ((std::is_same_v<R, Rs> ? found = i++ : i++), ...);
  return found;
}
}  // namespace detail

template <SceneContactLaw R>
  requires(detail::index_in<R>(scene_contact_laws{}) < scene_contact_laws::size)
inline constexpr ContactLawKind law_kind{detail::index_in<R>(scene_contact_laws{})};

// A record's statements as values, for the code that reads a law at run time.
struct SceneLawInfo {
  std::string_view name;
  std::span<const std::string_view> parameters;
  std::string_view own_stick_spring;
  std::optional<ImplicitContact> default_implicit;
  std::span<const std::string_view> unused_item_parameters;
  std::string_view unused_item_parameters_why;
  void (*item_base)(ContactParams&, const LawSetup&, const ItemInfo&);
  void (*item_pair)(ContactParams&, const LawSetup&);

  bool reads(std::string_view key) const {
    for (auto k : parameters)
      if (k == key) return true;
    return false;
  }
};

namespace detail {
template <SceneContactLaw R>
constexpr SceneLawInfo info_of() {
  return {R::name,           R::parameters,
          R::own_stick_spring, R::default_implicit,   R::unused_item_parameters,
          R::unused_item_parameters_why, &R::item_base, &R::item_pair};
}
template <class... R>
constexpr std::array<SceneLawInfo, sizeof...(R)> infos_of(LawList<R...>) {
  return {info_of<R>()...};
}
}  // namespace detail

inline constexpr auto scene_law_infos = detail::infos_of(scene_contact_laws{});

inline const SceneLawInfo& scene_law(ContactLawKind kind) {
  if (kind.index >= scene_law_infos.size())
    throw ModelError("unknown contact law (index " + std::to_string(kind.index) + " of " +
                     std::to_string(scene_law_infos.size()) + ")");
  return scene_law_infos[kind.index];
}

// Which items' floor and wall contact is inside the implicit step: the spec's choice, else its law's
// default, else every item's (issue 52: explicit, a flexible item's contact creeps at rest; the paper's
// reproductions, configuration(k), name `rigid`, the paper's explicit treatment of its FE items).
inline ImplicitContact implicit_contact(const ContactSpec& c) {
  if (c.implicit) return *c.implicit;
  return scene_law(c.law).default_implicit.value_or(ImplicitContact::all);
}

// Calls f.template operator()<R>() with the record of `kind`; false when the list has no such law.
template <class F>
bool visit_scene_law(ContactLawKind kind, F&& f) {
  return [&]<class... R>(LawList<R...>) {
    return ((kind == law_kind<R> && (f.template operator()<R>(), true)) || ...);
  }(scene_contact_laws{});
}

// The names joined as `"a", "b" and "c"`, of the laws that pass `keep`.
template <class Keep>
std::string law_name_list(Keep&& keep) {
  std::vector<std::string_view> names;
  for (const auto& law : scene_law_infos)
    if (keep(law)) names.push_back(law.name);
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    out += i == 0 ? "" : i + 1 == names.size() ? " and " : ", ";
    out.append("\"").append(names[i]).append("\"");
  }
  return out;
}

// The override keys and the laws that read them, as markdown (docs/scene/scene_file.md; tests/scene
// checks that the page holds this table).
inline std::string contact_law_table() {
  std::string head = "| key | unit | range |", rule = "|---|---|---|";
  for (const auto& law : scene_law_infos) {
    head += " " + std::string(law.name) + " |";
    rule += "---|";
  }
  std::string md = head + " meaning |\n" + rule + "---|\n";
  for (const auto& p : contact_parameters) {
    md += "| `" + std::string(p.key) + "` | " + std::string(p.unit) + " | " + (p.lo_exclusive ? "(" : "[") +
          detail::fmt(p.lo) + ", " + detail::fmt(p.hi) + "] |";
    for (const auto& law : scene_law_infos) md += law.reads(p.key) ? " yes |" : " |";
    md += " " + std::string(p.meaning) + " |\n";
  }
  return md;
}

}  // namespace furniture_fem
