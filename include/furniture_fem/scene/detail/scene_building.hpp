#pragma once
// Internal: ground_motion.building (BuildingSpec) read, written, checked and applied: the table's
// motion as the floor of a storey of a shear building (excitation/building.hpp). Shared by the reader,
// the writer, validate() and scene_table_motion. Users include furniture_fem/scene/scene.hpp.
#ifndef FURNITURE_FEM_SCENE_INTERNAL
#error "furniture_fem/scene/detail/scene_building.hpp is internal: include <furniture_fem/scene/scene.hpp>"
#endif
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "../../core/errors.hpp"
#include "../../excitation/building.hpp"
#include "../spec.hpp"
#include "scene_json.hpp"

namespace furniture_fem::detail {

// Enough for the tallest buildings (163 floors) with room; the modes' dense solve stays below a second.
inline constexpr int building_max_floors = 1000;

inline ShearBuilding shear_building_of(const BuildingSpec& b) {
  ShearBuilding sb;
  if (b.uniform()) {
    sb = ShearBuilding::uniform(b.storeys, b.period_s, b.damping_ratio);
  } else {
    sb.floor_mass = b.floor_mass;
    sb.storey_stiffness = b.storey_stiffness;
    sb.damping_ratio = b.damping_ratio;
  }
  sb.rayleigh_modes = b.rayleigh_modes;
  return sb;
}

// The first problem of a building, as (key under ground_motion.building, message with the value), or
// none. Read files and SceneSpecs made in code get the same checks (reader and validate()).
inline std::optional<std::pair<std::string, std::string>> building_problem(const BuildingSpec& b) {
  using P = std::pair<std::string, std::string>;
  const auto got = [](double v) { return " (got " + fmt(v) + ")"; };
  if (b.uniform()) {
    if (b.storeys < 1 || b.storeys > building_max_floors)
      return P{"storeys", "must be a whole number of storeys from 1 to " + std::to_string(building_max_floors) +
                              " (got " + std::to_string(b.storeys) + ")"};
    if (!(b.period_s > 0) || !std::isfinite(b.period_s))
      return P{"period_s", "must be a positive finite period in s" + got(b.period_s)};
  } else {
    if (b.storeys != 0 || b.period_s != 0)
      return P{b.storeys != 0 ? "storeys" : "period_s",
               "give either storeys and period_s (a uniform building) or floor_mass and storey_stiffness, not both"};
    const std::size_t n = b.floor_mass.size();
    if (n < 1 || n > std::size_t(building_max_floors))
      return P{"floor_mass", "must hold 1 to " + std::to_string(building_max_floors) + " masses (got " +
                                 std::to_string(n) + ")"};
    if (b.storey_stiffness.size() != n)
      return P{"storey_stiffness", "has " + std::to_string(b.storey_stiffness.size()) + " values for the " +
                                       std::to_string(n) + " floors of floor_mass (one per storey)"};
    for (auto [key, values] : {std::pair{"floor_mass", &b.floor_mass}, std::pair{"storey_stiffness", &b.storey_stiffness}})
      for (std::size_t i = 0; i < n; ++i)
        if (!((*values)[i] > 0) || !std::isfinite((*values)[i]))
          return P{std::string(key) + "[" + std::to_string(i) + "]", "must be positive and finite" + got((*values)[i])};
  }
  if (!(b.damping_ratio >= 0 && b.damping_ratio < 1))
    return P{"damping_ratio", "must lie in [0, 1)" + got(b.damping_ratio)};
  const int n = b.floors();
  if (b.storey < 1 || b.storey > n)
    return P{"storey", "must be a floor from 1 (above the ground storey) to " + std::to_string(n) +
                           " (the roof); the ground is no building (got " + std::to_string(b.storey) + ")"};
  const auto [r1, r2] = b.rayleigh_modes;
  if ((r1 != 0 || r2 != 0) && !(r1 >= 1 && r2 > r1 && r2 <= n))
    return P{"rayleigh_modes", "must be two modes 1 <= i < j <= " + std::to_string(n) + " (got [" + std::to_string(r1) +
                                   ", " + std::to_string(r2) + "])"};
  try {  // Rayleigh damping that overdamps a mode
    (void)building_modes(shear_building_of(b));
  } catch (const InputError& e) {
    return P{"rayleigh_modes", e.what()};
  }
  return std::nullopt;
}

// The numbers of an array under `key`, each finite (the reader's types; values are checked after).
inline std::vector<double> read_numbers(const json_io::ObjectReader& r, std::string_view key) {
  std::vector<double> out;
  r.array(key, [&](const json& v, const std::string& path) {
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      r.fail(path, "expected a finite number, got " + json_io::ObjectReader::describe(v));
    out.push_back(v.get<double>());
  });
  return out;
}

inline BuildingSpec parse_building(const json_io::ObjectReader& r) {
  r.allow_only({"storeys", "period_s", "floor_mass", "storey_stiffness", "damping_ratio", "rayleigh_modes", "storey"});
  BuildingSpec b;
  const bool arrays = r.has("floor_mass") || r.has("storey_stiffness");
  if (!arrays && !(r.has("storeys") && r.has("period_s")))
    r.fail(r.path(), "give storeys and period_s (a uniform building) or floor_mass and storey_stiffness (per storey)");
  if (arrays && !(r.has("floor_mass") && r.has("storey_stiffness")))
    r.fail(r.path(r.has("floor_mass") ? "storey_stiffness" : "floor_mass"),
           "required with " + std::string(r.has("floor_mass") ? "floor_mass" : "storey_stiffness") + " (one per storey)");
  if (r.has("storeys")) {
    const long long n = *r.optional_integer("storeys");
    r.require(n >= 1 && n <= building_max_floors, "storeys", "must be 1 to " + std::to_string(building_max_floors));
    b.storeys = static_cast<int>(n);
  }
  b.period_s = r.number("period_s", 0);
  if (r.has("period_s")) r.positive("period_s");
  b.floor_mass = read_numbers(r, "floor_mass");
  b.storey_stiffness = read_numbers(r, "storey_stiffness");
  b.damping_ratio = r.number("damping_ratio", b.damping_ratio);
  if (r.has("rayleigh_modes")) {
    const json& v = r.raw("rayleigh_modes");
    if (!v.is_array() || v.size() != 2 || !v[0].is_number_integer() || !v[1].is_number_integer())
      r.fail(r.path("rayleigh_modes"), "expected two mode numbers [i, j], got " + json_io::ObjectReader::describe(v));
    b.rayleigh_modes = {static_cast<int>(std::clamp<long long>(v[0].get<long long>(), -1, building_max_floors + 1)),
                        static_cast<int>(std::clamp<long long>(v[1].get<long long>(), -1, building_max_floors + 1))};
  }
  if (!r.has("storey")) r.fail(r.path("storey"), "required: the floor that is the table (1 to the roof)");
  b.storey = static_cast<int>(std::clamp<long long>(*r.optional_integer("storey"), -1, building_max_floors + 1));
  if (const auto problem = building_problem(b)) {
    const std::string key = problem->first.substr(0, problem->first.find('['));
    r.fail(r.path(problem->first), problem->second + (r.has(key) ? "" : " (" + key + " not given: its default)"));
  }
  return b;
}

inline json building_json(const BuildingSpec& b) {
  json j;
  if (b.uniform()) {
    j["storeys"] = b.storeys;
    j["period_s"] = b.period_s;
  } else {
    j["floor_mass"] = b.floor_mass;
    j["storey_stiffness"] = b.storey_stiffness;
  }
  j["damping_ratio"] = b.damping_ratio;
  if (b.rayleigh_modes[0] != 0 || b.rayleigh_modes[1] != 0) j["rayleigh_modes"] = b.rayleigh_modes;
  j["storey"] = b.storey;
  return j;
}

// The table's motion on the building's storey: the horizontal components through the building (from
// rest at the motion's first sample), the vertical one as it is (a shear building has no axial mode).
inline TableMotion building_floor_motion(const SceneSpec& s, const TableMotion& ground) {
  const BuildingSpec& b = *s.ground_motion.building;
  if (const auto problem = building_problem(b))
    throw InputError(s.source, 0, "ground_motion.building." + problem->first, problem->second);
  const ShearBuilding sb = shear_building_of(b);
  TableMotion m = ground;
  m.x = storey_motion(sb, b.storey, ground.x);
  if (ground.has_y) m.y = storey_motion(sb, b.storey, ground.y);
  return m;
}

}  // namespace furniture_fem::detail
