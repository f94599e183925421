#pragma once
// furniture_fem/scene/item_parameters.hpp: the parameters an item of a scene file takes
// (items[i].params): those every kind takes (mesh, mass, contact), listed here, and each kind's own,
// declared by the kind (furniture/item_kinds.hpp). item_parameter_tables() writes them as the
// markdown tables of docs/scene/scene_file.md (tests/scene checks that the page matches).
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "../furniture/item_kinds.hpp"
#include "spec.hpp"

namespace furniture_fem {

// A parameter every kind takes, read into a field of ItemParams. Its default is the builder's (or
// ItemContact's) own value, described in words.
struct CommonItemParameter {
  ItemParameter parameter;  // key, unit, range, meaning (default_value unused)
  std::optional<double> ItemParams::*field;
  bool single_body_only;          // not for kinds of two bodies (each body has its own Table 2 row)
  std::string_view default_text;  // for the docs table
};

inline constexpr std::array<CommonItemParameter, 16> common_item_parameters{{
    {{"panel_spacing", "m", 0.02, 5.0, false, 0, "panel grid spacing"}, &ItemParams::panel_spacing, false,
     "the kind's tuned value"},
    {{"grid_scale", "-", 0.1, 20.0, false, 0, "multiplies the panel grid spacing (0.5 finer, 2 coarser)"},
     &ItemParams::grid_scale, false, "1"},
    {{"element_length", "m", 0.005, 1.0, false, 0, "target element length"}, &ItemParams::element_length, false,
     "0.05"},
    {{"mass_kg", "kg", 0.0, 1e4, true, 0, "mass the body is calibrated to"}, &ItemParams::mass_kg, true,
     "Table 2; others: the kind's estimate"},
    {{"cog_h", "m", 0.0, 10.0, true, 0, "centre of gravity above the base; below the height (validate)"},
     &ItemParams::cog_h, true, "Table 2; others: geometric"},
    {{"cog_d1", "m", 0.0, 10.0, true, 0, "centre of gravity from the front; within the depth (validate)"},
     &ItemParams::cog_d1, true, "Table 2; others: geometric"},
    {{"alpha_kgf", "kgf", 0.0, 1e6, true, 0, "contact penalty coefficient"}, &ItemParams::alpha_kgf, false,
     "Table 4; others: the item's weight"},
    {{"dc_kgf", "kgf", 0.0, 1e6, false, 0, "contact damping coefficient"}, &ItemParams::dc_kgf, false,
     "Table 4; others: 1.2 alpha"},
    {{"mu_floor_long", "-", 0.0, 5.0, false, 0, "dynamic floor friction along the longer edge"},
     &ItemParams::mu_floor_long, false, "Table 4; others: 0.8 x static"},
    {{"mu_floor_short", "-", 0.0, 5.0, false, 0, "dynamic floor friction along the shorter edge"},
     &ItemParams::mu_floor_short, false, "Table 4; others: 0.8 x static"},
    {{"mu_wall", "-", 0.0, 5.0, false, 0, "dynamic friction against walls"}, &ItemParams::mu_wall, false,
     "Table 4; others: the longer edge's floor value"},
    {{"mu_item", "-", 0.0, 5.0, false, 0, "dynamic friction against other items"}, &ItemParams::mu_item, false,
     "0.169"},
    {{"mass_scale", "-", 0.01, 100.0, false, 0, "multiplies every mass of the item (centre of gravity kept)"},
     &ItemParams::mass_scale, false, "1"},
    {{"friction_scale", "-", 0.0, 100.0, false, 0, "multiplies every friction coefficient of the item"},
     &ItemParams::friction_scale, false, "1"},
    {{"alpha_scale", "-", 0.001, 1000.0, false, 0, "multiplies the contact penalty coefficient alpha"},
     &ItemParams::alpha_scale, false, "1"},
    {{"stiffness_scale", "-", 0.001, 1000.0, false, 0,
      "multiplies the Young's and shear moduli of the item's members; `full` and `coarse` items only"},
     &ItemParams::stiffness_scale, false, "1"},
}};

// Whether `params` sets the common parameter `key` (false for a key that is not one).
inline bool common_parameter_given(const ItemParams& params, std::string_view key) {
  for (const auto& c : common_item_parameters)
    if (c.parameter.key == key) return (params.*(c.field)).has_value();
  return false;
}

// The keys items of `kind` accept in their params, common ones first.
inline std::vector<std::string_view> accepted_item_parameters(const ItemKindEntry& kind) {
  std::vector<std::string_view> keys;
  for (const auto& c : common_item_parameters)
    if (kind.single_body || !c.single_body_only) keys.push_back(c.parameter.key);
  for (const auto& p : kind.parameters) keys.push_back(p.key);
  return keys;
}

// Why `key` is refused for items of `kind`: names the kind and lists what it takes.
inline std::string not_a_parameter_message(const ItemKindEntry& kind) {
  std::string list;
  for (auto key : accepted_item_parameters(kind)) list += (list.empty() ? "" : ", ") + std::string(key);
  return "not a parameter of kind \"" + to_string(kind.kind) + "\"" +
         (kind.note.empty() ? std::string() : " (" + std::string(kind.note) + ")") + "; its parameters: " + list;
}

namespace detail {
inline std::string parameter_row(const ItemParameter& p, const std::string& kinds, const std::string& default_text) {
  return "| `" + std::string(p.key) + "` | " + std::string(p.unit) + (p.integer ? ", integer" : "") + " | " +
         p.range_text() + " | " + kinds + default_text + " | " + std::string(p.meaning) + " |\n";
}
}  // namespace detail

// The markdown of docs/scene/scene_file.md's item parameter tables: the common parameters, then each
// kind of `registry` with its own. Default: the built-in kinds (what the docs describe).
inline std::string item_parameter_tables(const ItemKindRegistry& registry = builtin_item_kind_registry()) {
  std::string two_body;
  for (const auto& k : registry.kinds())
    if (!k.single_body) two_body += (two_body.empty() ? "" : ", ") + to_string(k.kind);
  std::string md = "Every kind takes these (their defaults are each kind's own values):\n\n"
                   "| key | unit | range | kinds | default | meaning |\n|---|---|---|---|---|---|\n";
  for (const auto& c : common_item_parameters)
    md += detail::parameter_row(c.parameter, c.single_body_only ? "all but " + two_body + " | " : "all | ",
                                std::string(c.default_text));
  for (const auto& k : registry.kinds()) {
    md += "\n`" + to_string(k.kind) + "`: " + std::string(k.meaning);
    if (k.parameters.empty()) {
      md += "; no parameters of its own.\n";
      continue;
    }
    md += ".\n\n| key | unit | range | default | meaning |\n|---|---|---|---|---|\n";
    for (const auto& p : k.parameters) md += detail::parameter_row(p, "", detail::fmt(p.default_value));
  }
  return md;
}

}  // namespace furniture_fem
