#pragma once
// furniture_fem/scene/laws/law_list.hpp: the scene contact laws. The built-in laws are one list, one line
// each; they and any law a program adds at run time (register_contact_law<R>()) are held in one registry,
// which the reader, the writer, validation, the per-item set-up and the run read (docs/contact/contact.md,
// "Adding a contact law").
//
//   builtin_contact_laws              the built-in records; the first is a scene's default
//   law_kind<R>                       the ContactLawKind of built-in record R (s.contact.law = law_kind<StiffSceneLaw>)
//   ContactLawRegistry                laws by name: what a record states, as values, and its law's kernel
//   contact_law_registry()            the registry scenes are read and run against
//   register_contact_law<R>()         makes a program's own record nameable in scene files and studies
//   scene_law(kind)                   what the reader, writer, validation and set-up need of a law
//   contact_law_table()               the override keys by law, as the table of docs/scene/scene_file.md,
//                                     generated from the laws' parts' declarations (LawParameter)
#include <algorithm>
#include <array>
#include <cstddef>
#include <deque>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "../../contact/contact_law_kernel.hpp"
#include "../../core/errors.hpp"
#include "hunt_crossley.hpp"
#include "law_record.hpp"
#include "paper.hpp"
#include "paper_anisotropic.hpp"
#include "spring_dashpot.hpp"
#include "stick_slip.hpp"
#include "stiff.hpp"

namespace furniture_fem {

using builtin_contact_laws = LawList<PaperSceneLaw, PaperAnisotropicSceneLaw, SpringDashpotSceneLaw,
                                     HuntCrossleySceneLaw, StickSlipSceneLaw, StiffSceneLaw>;

namespace detail {
template <class R, class... Rs>
consteval std::size_t index_in(LawList<Rs...>) {
  std::size_t i = 0, found = sizeof...(Rs);
  ((std::is_same_v<R, Rs> ? found = i++ : i++), ...);
  return found;
}
}  // namespace detail

// A built-in law's kind: its place in the list, which is its place in every registry (they come first).
template <SceneContactLaw R>
  requires(detail::index_in<R>(builtin_contact_laws{}) < builtin_contact_laws::size)
inline constexpr ContactLawKind law_kind{detail::index_in<R>(builtin_contact_laws{})};

// A record's statements as values, and its law's kernel: what the code that reads a law at run time needs.
struct SceneLawInfo {
  std::string_view name;
  // Its scene keys, in the order they are applied: its parts' declarations (the kernel's, less the rule
  // keys) and then the record's own (in the slots after its parts', in their order). A key may stand more
  // than once (it then sets each field).
  std::vector<LawParameter> parameters;
  std::span<const std::string_view> rule_parameters;  // its parts' keys its item_base sets, and why
  std::string_view rule_parameters_why;
  std::string_view own_stick_spring;
  std::optional<ImplicitContact> default_implicit;
  std::span<const std::string_view> unused_item_parameters;
  std::string_view unused_item_parameters_why;
  void (*item_base)(ContactParams&, const LawSetup&, const ItemInfo&);
  void (*item_pair)(ContactParams&, const LawSetup&);
  std::shared_ptr<const ContactLawKernel> kernel;  // the law's force, one object shared by every run

  template <SceneContactLaw R>
  static SceneLawInfo of() {
    SceneLawInfo info{R::name,           {},
                      R::rule_parameters, R::rule_parameters_why,
                      R::own_stick_spring, R::default_implicit,
                      R::unused_item_parameters, R::unused_item_parameters_why,
                      &R::item_base,     &R::item_pair,
                      make_contact_law_kernel<typename R::law>()};
    std::size_t first_own_slot = 0;  // past the slots its parts declare
    for (const LawParameter& p : info.kernel->parameters()) {
      if (!info.set_by_rule(p.key)) info.parameters.push_back(p);
      if (!p.field) first_own_slot = std::max(first_own_slot, p.slot + 1);
    }
    if (first_own_slot + R::own_parameters.size() > ContactParams::max_law_params)
      throw ModelError("contact law \"" + std::string(R::name) + "\" declares more than " +
                       std::to_string(ContactParams::max_law_params) + " parameters of its own (ContactParams::law_params)");
    for (std::size_t i = 0; i < R::own_parameters.size(); ++i) {
      LawParameter own = R::own_parameters[i];
      own.slot = first_own_slot + i;
      info.parameters.push_back(own);
    }
    return info;
  }
  // The first declaration of scene key `key` (all of a key's agree on its unit, range and place), or null.
  const LawParameter* parameter(std::string_view key) const {
    for (const auto& p : parameters)
      if (p.key == key) return &p;
    return nullptr;
  }
  // Whether the law reads scene key `key`.
  bool reads(std::string_view key) const { return parameter(key) != nullptr; }
  // Whether `key` is one of its parts' that its item_base sets from the item.
  bool set_by_rule(std::string_view key) const {
    for (auto k : rule_parameters)
      if (k == key) return true;
    return false;
  }
  // The given overrides, in declaration order (mu before mu_long before mu_short: each narrows the one
  // before), into an item's parameters.
  void apply(ContactParams& p, const ContactOverrides& given) const {
    for (const auto& d : parameters)
      if (const auto it = given.values.find(std::string(d.key)); it != given.values.end()) p.set(d, it->second);
  }
  // An item's start for the law's own slots: their defaults, and which scale with the node share.
  void set_slot_defaults(ContactParams& p) const {
    for (const auto& d : parameters) {
      if (d.field) continue;
      p.law_params[d.slot] = d.default_value;
      if (d.per_node) p.law_params_per_node |= 1u << d.slot;
    }
  }
};

// Laws by name, in the order they were added (a ContactLawKind is that place). Entries never move once added.
class ContactLawRegistry {
 public:
  template <SceneContactLaw R>
  ContactLawKind add() { return add(SceneLawInfo::of<R>()); }
  ContactLawKind add(SceneLawInfo law) {
    if (law.name.empty()) throw ModelError("a contact law needs a name");
    if (find(law.name)) throw ModelError("contact law \"" + std::string(law.name) + "\" is already registered");
    laws_.push_back(std::move(law));
    return ContactLawKind{laws_.size() - 1};
  }
  const SceneLawInfo* find(std::string_view name) const {
    for (const auto& law : laws_)
      if (law.name == name) return &law;
    return nullptr;
  }
  std::optional<ContactLawKind> kind(std::string_view name) const {
    for (std::size_t i = 0; i < laws_.size(); ++i)
      if (laws_[i].name == name) return ContactLawKind{i};
    return std::nullopt;
  }
  const SceneLawInfo& at(ContactLawKind kind) const {
    if (kind.index >= laws_.size())
      throw ModelError("unknown contact law (index " + std::to_string(kind.index) + " of " +
                       std::to_string(laws_.size()) + "); registered laws: " + names());
    return laws_[kind.index];
  }
  const std::deque<SceneLawInfo>& laws() const { return laws_; }
  std::size_t size() const { return laws_.size(); }
  // The names, as "paper, paper_anisotropic, ..." (the reader's list of choices).
  std::string names() const {
    std::string list;
    for (const auto& law : laws_) list.append(list.empty() ? "" : ", ").append(law.name);
    return list;
  }

 private:
  std::deque<SceneLawInfo> laws_;
};

// A registry holding the built-in laws only (the docs table is made from it).
inline ContactLawRegistry builtin_contact_law_registry() {
  ContactLawRegistry registry;
  [&]<class... R>(LawList<R...>) { (registry.add<R>(), ...); }(builtin_contact_laws{});
  return registry;
}

// The registry scene files are read, checked and run against: the built-in laws and those registered
// since. Register laws before reading or running scenes on other threads: it is not locked.
inline ContactLawRegistry& contact_law_registry() {
  static ContactLawRegistry registry = builtin_contact_law_registry();
  return registry;
}

// Makes record R (law_record.hpp says what it states) nameable in scene files and study variants, under
// R::name; returns its kind (SceneSpec::contact.law). A name already registered, a built-in's included, is
// a ModelError naming the law.
template <SceneContactLaw R>
ContactLawKind register_contact_law() {
  if (builtin_contact_law_registry().find(R::name))
    throw ModelError("contact law \"" + std::string(R::name) +
                     "\" is a built-in law: register your law under a name of its own");
  return contact_law_registry().add<R>();
}

// The registered law of that name, if any.
inline std::optional<ContactLawKind> contact_law_kind(std::string_view name) { return contact_law_registry().kind(name); }

inline const SceneLawInfo& scene_law(ContactLawKind kind) { return contact_law_registry().at(kind); }

// Which items' floor and wall contact is inside the implicit step: the spec's choice, else its law's
// default, else every item's (issue 52: explicit, a flexible item's contact creeps at rest; the paper's
// reproductions, configuration(k), name `rigid`, the paper's explicit treatment of its FE items).
inline ImplicitContact implicit_contact(const ContactSpec& c) {
  if (c.implicit) return *c.implicit;
  return scene_law(c.law).default_implicit.value_or(ImplicitContact::all);
}

// The names joined as `"a", "b" and "c"`, of the registered laws that pass `keep`.
template <class Keep>
std::string law_name_list(Keep&& keep) {
  std::vector<std::string_view> names;
  for (const auto& law : contact_law_registry().laws())
    if (keep(law)) names.push_back(law.name);
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    out += i == 0 ? "" : i + 1 == names.size() ? " and " : ", ";
    out.append("\"").append(names[i]).append("\"");
  }
  return out;
}

// The override keys and the laws that read them, as markdown, one row per key in the order the laws
// declare them, its meanings those of its declarations (docs/scene/scene_file.md holds the built-in laws'
// table; tests/scene checks that the page holds it).
inline std::string contact_law_table(const ContactLawRegistry& registry = builtin_contact_law_registry()) {
  // Appended piece by piece: GCC 12 warns on + chains of strings here (-Wrestrict, a false alarm).
  std::string head = "| key | unit | range |", rule = "|---|---|---|";
  for (const auto& law : registry.laws()) {
    head.append(" ").append(law.name).append(" |");
    rule.append("---|");
  }
  std::string md = head;
  md.append(" meaning |\n").append(rule).append("---|\n");
  std::vector<std::string_view> keys;
  for (const auto& law : registry.laws())
    for (const auto& p : law.parameters)
      if (std::find(keys.begin(), keys.end(), p.key) == keys.end()) keys.push_back(p.key);
  for (std::string_view key : keys) {
    const LawParameter* first = nullptr;
    std::vector<std::string_view> meanings;
    std::string marks;
    for (const auto& law : registry.laws()) {
      marks.append(law.reads(key) ? " yes |" : " |");
      for (const auto& p : law.parameters) {
        if (p.key != key) continue;
        if (!first) first = &p;
        if (std::find(meanings.begin(), meanings.end(), p.meaning) == meanings.end()) meanings.push_back(p.meaning);
      }
    }
    md.append("| `").append(key).append("` | ").append(first->unit).append(" | ").append(first->range_text());
    md.append(" |").append(marks).append(" ");
    for (std::size_t i = 0; i < meanings.size(); ++i) md.append(i ? "; " : "").append(meanings[i]);
    md.append(" |\n");
  }
  return md;
}

}  // namespace furniture_fem
