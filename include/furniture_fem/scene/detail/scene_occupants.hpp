#pragma once
// Internal: the scene's "occupants" (harm/occupant.hpp) and "strike_thresholds" (harm/strike.hpp) read,
// written and checked (docs/harm/occupants.md). Shared by the reader, the writer and validate(). Users include
// furniture_fem/scene/scene.hpp.
#ifndef FURNITURE_FEM_SCENE_INTERNAL
#error "furniture_fem/scene/detail/scene_occupants.hpp is internal: include <furniture_fem/scene/scene.hpp>"
#endif
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "../../core/errors.hpp"
#include "../../harm/strike.hpp"
#include "../json_reader.hpp"
#include "../spec.hpp"

namespace furniture_fem::detail {

// An occupant's numeric keys: where each is kept, and its bounds (a person's sizes; forms from a
// child's head to an adult's body, stiffness from soft padding to bone).
struct OccupantNumber {
  std::string_view key;
  double Occupant::*field;
  double ImpactForm::*form_field;  // with field == nullptr: a field of the head's or body's form
  bool head;
  double lo, hi;
  std::string_view unit;
};
inline const std::array<OccupantNumber, 7>& occupant_numbers() {
  static const std::array<OccupantNumber, 7> list = {{
      {"height", &Occupant::height, nullptr, false, 0.5, 2.5, "m"},
      {"body_radius", &Occupant::body_radius, nullptr, false, 0.05, 1.0, "m"},
      {"head_radius", &Occupant::head_radius, nullptr, false, 0.03, 0.3, "m"},
      {"head_mass", nullptr, &ImpactForm::mass, true, 0.5, 20.0, "kg"},
      {"head_stiffness", nullptr, &ImpactForm::stiffness, true, 1e3, 1e9, "N/m"},
      {"body_mass", nullptr, &ImpactForm::mass, false, 1.0, 200.0, "kg"},
      {"body_stiffness", nullptr, &ImpactForm::stiffness, false, 1e2, 1e9, "N/m"},
  }};
  return list;
}
inline double& occupant_value(Occupant& o, const OccupantNumber& n) {
  if (n.field) return o.*(n.field);
  ImpactForm& form = n.head ? o.head : o.body;
  return form.*(n.form_field);
}
inline double occupant_value(const Occupant& o, const OccupantNumber& n) {
  if (n.field) return o.*(n.field);
  return (n.head ? o.head : o.body).*(n.form_field);
}

// The first problem of an occupant that needs no built model, as (key, message), or none.
inline std::optional<std::pair<std::string, std::string>> occupant_problem(const Occupant& o, const SceneSpec& s) {
  using P = std::pair<std::string, std::string>;
  for (const OccupantNumber& n : occupant_numbers()) {
    const double v = occupant_value(o, n);
    if (!(v >= n.lo && v <= n.hi))
      return P{std::string(n.key), "must be in [" + fmt(n.lo) + ", " + fmt(n.hi) + "] " + std::string(n.unit) + " (got " + fmt(v) + ")"};
  }
  if (!(o.height >= 2 * o.head_radius + 2 * o.body_radius))
    return P{"height", "must leave room for the head and the body: at least 2 head_radius + 2 body_radius = " +
                           fmt(2 * o.head_radius + 2 * o.body_radius) + " m (got " + fmt(o.height) + ")"};
  if (!(std::abs(o.position.x()) <= 0.5 * s.table.size_x && std::abs(o.position.y()) <= 0.5 * s.table.size_y))
    return P{"position", "(" + fmt(o.position.x()) + ", " + fmt(o.position.y()) + ") is off the table (" +
                             fmt(s.table.size_x) + " m x " + fmt(s.table.size_y) + " m, centred on the origin)"};
  return std::nullopt;
}

inline Occupant read_occupant(const nlohmann::json& v, const std::string& path, const std::string& source,
                              std::size_t index, const SceneSpec& s) {
  const ObjectReader o(v, path, source);
  std::vector<std::string_view> allowed = {"name", "position", "posture", "obstacle"};
  for (const OccupantNumber& n : occupant_numbers()) allowed.push_back(n.key);
  o.allow_only(allowed, "key of an occupant");
  Occupant occ;
  occ.name = o.string("name", "occupant_" + std::to_string(index + 1));
  const std::string posture = o.string("posture", "standing");
  if (posture != "standing" && posture != "seated")
    o.fail(o.path("posture"), "expected \"standing\" or \"seated\", got \"" + posture + "\"");
  occ.posture = posture == "standing" ? Posture::standing : Posture::seated;
  const PostureSizes sizes = posture_sizes(occ.posture);
  occ.height = sizes.height, occ.body_radius = sizes.body_radius;
  if (!o.has("position")) o.fail(o.path("position"), "required: [x, y] on the floor (m)");
  const nlohmann::json& p = v.at("position");
  if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number() ||
      !std::isfinite(p[0].get<double>()) || !std::isfinite(p[1].get<double>()))
    o.fail(o.path("position"), "expected [x, y], two finite numbers (m), got " + ObjectReader::describe(p));
  occ.position = Vec2(p[0].get<double>(), p[1].get<double>());
  occ.floor_z = s.table.floor_z;
  for (const OccupantNumber& n : occupant_numbers()) occupant_value(occ, n) = o.number(n.key, occupant_value(occ, n));
  occ.obstacle = o.boolean("obstacle", false);
  return occ;
}

inline nlohmann::json occupant_json(const Occupant& o) {
  nlohmann::json j = {{"name", o.name},
                      {"position", {o.position.x(), o.position.y()}},
                      {"posture", std::string(to_string(o.posture))},
                      {"obstacle", o.obstacle}};
  for (const OccupantNumber& n : occupant_numbers()) j[std::string(n.key)] = occupant_value(o, n);
  return j;
}

// "strike_thresholds": the values a strike is judged against (harm/strike.hpp), each positive.
inline constexpr std::array<std::pair<std::string_view, double StrikeThresholds::*>, 3> strike_threshold_keys = {{
    {"hic15", &StrikeThresholds::hic15}, {"head_force", &StrikeThresholds::head_force}, {"energy", &StrikeThresholds::energy}}};

inline StrikeThresholds read_strike_thresholds(const ObjectReader& o) {
  o.allow_only({"hic15", "head_force", "energy"}, "strike threshold");
  StrikeThresholds t;
  for (const auto& [key, field] : strike_threshold_keys) {
    t.*field = o.number(key, t.*field);
    o.positive(key);
  }
  return t;
}
inline nlohmann::json strike_thresholds_json(const StrikeThresholds& t) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [key, field] : strike_threshold_keys) j[std::string(key)] = t.*field;
  return j;
}

}  // namespace furniture_fem::detail
