#pragma once
// Internal: the names scene files use for enumerations (the contact laws' are in their registry,
// scene/laws/law_list.hpp); shared
// by the reader and the writer. Users include furniture_fem/scene/scene.hpp, not this file.
#ifndef FURNITURE_FEM_SCENE_INTERNAL
#error "furniture_fem/scene/detail/scene_names.hpp is internal: include <furniture_fem/scene/scene.hpp>"
#endif
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include <string_view>

#include "../laws/law_list.hpp"
#include "../spec.hpp"
#include "scene_json.hpp"

namespace furniture_fem::detail {

inline constexpr EnumNames<Fidelity, 4> fidelity_names{
    {{Fidelity::full, "full"}, {Fidelity::coarse, "coarse"}, {Fidelity::rigid, "rigid"}, {Fidelity::automatic, "auto"}}};
inline constexpr EnumNames<MotionSource, 3> source_names{
    {{MotionSource::synthetic, "synthetic"}, {MotionSource::file, "file"}, {MotionSource::points, "points"}}};
inline constexpr EnumNames<RecordFormat, 4> format_names{{{RecordFormat::at2, "at2"},
                                                          {RecordFormat::knet, "knet"},
                                                          {RecordFormat::jma_csv, "jma_csv"},
                                                          {RecordFormat::columns, "columns"}}};
inline constexpr EnumNames<MotionDimensions, 2> dimension_names{
    {{MotionDimensions::one_d, "1d"}, {MotionDimensions::three_d, "3d"}}};
inline constexpr EnumNames<AccelerationUnits, 3> unit_names{
    {{AccelerationUnits::g, "g"}, {AccelerationUnits::gal, "gal"}, {AccelerationUnits::m_per_s2, "m/s2"}}};
inline constexpr EnumNames<ImplicitContact, 3> implicit_contact_names{
    {{ImplicitContact::none, "none"}, {ImplicitContact::rigid, "rigid"}, {ImplicitContact::all, "all"}}};
inline constexpr EnumNames<FlexiblePairContact, 2> flexible_pair_contact_names{
    {{FlexiblePairContact::explicit_load, "explicit"}, {FlexiblePairContact::implicit_step, "implicit"}}};
inline constexpr EnumNames<PlaneContactAt, 2> plane_contact_at_names{
    {{PlaneContactAt::centre_lines, "centre_lines"}, {PlaneContactAt::surfaces, "surfaces"}}};
inline constexpr EnumNames<RigidPairContact, 2> rigid_pair_contact_names{
    {{RigidPairContact::members, "members"}, {RigidPairContact::hulls, "hulls"}}};
inline constexpr EnumNames<ContactPairOutput, 3> contact_pair_output_names{
    {{ContactPairOutput::automatic, "auto"}, {ContactPairOutput::columns, "columns"}, {ContactPairOutput::rows, "rows"}}};
inline constexpr EnumNames<ContactStart, 2> contact_start_names{
    {{ContactStart::touching, "touching"}, {ContactStart::settled, "settled"}}};
inline constexpr EnumNames<IntegratorKind, 3> integrator_names{
    {{IntegratorKind::paper_newmark, "paper_newmark"},
     {IntegratorKind::average_acceleration, "average_acceleration"},
     {IntegratorKind::generalized_alpha, "generalized_alpha"}}};
inline constexpr EnumNames<ScaleMeasure, 3> scale_measure_names{
    {{ScaleMeasure::pga, "pga"}, {ScaleMeasure::pgv, "pgv"}, {ScaleMeasure::jma, "jma"}}};
inline constexpr EnumNames<SolverKind, 2> solver_names{{{SolverKind::cg, "cg"}, {SolverKind::direct, "direct"}}};

inline void read_range(const ObjectReader& r, std::string_view key, double lo, double hi, bool lo_exclusive) {
  if (!r.has(key)) return;
  const double v = r.raw(key).get<double>();
  r.require((lo_exclusive ? v > lo : v >= lo) && v <= hi, key,
            std::string("must lie in ") + (lo_exclusive ? "(" : "[") + fmt(lo) + ", " + fmt(hi) + "]");
}

// What is wrong with a "points" component (ground_motion.x, .y, .z), as (key path, message), or
// nothing: at least one point, finite values, times strictly increasing. Shared by the reader and
// validate() (a SceneSpec made in code).
inline std::optional<std::pair<std::string, std::string>> points_problem(const std::vector<std::pair<double, double>>& pts,
                                                                         const std::string& path) {
  if (pts.empty()) return std::pair{path, std::string("needs at least one [t, a] point")};
  for (size_t i = 0; i < pts.size(); ++i) {
    const std::string at = index_path(path, i);
    if (!std::isfinite(pts[i].first)) return std::pair{at + "[0]", "expected a finite time (got " + fmt(pts[i].first) + ")"};
    if (!std::isfinite(pts[i].second))
      return std::pair{at + "[1]", "expected a finite acceleration (got " + fmt(pts[i].second) + ")"};
    if (i > 0 && !(pts[i].first > pts[i - 1].first))
      return std::pair{at + "[0]", "times must increase strictly: " + fmt(pts[i].first) + " s follows " +
                                       fmt(pts[i - 1].first) + " s"};
  }
  return std::nullopt;
}

inline json points_to_json(const std::vector<std::pair<double, double>>& pts) {
  json j = json::array();
  for (const auto& [t, a] : pts) j.push_back(json::array({t, a}));
  return j;
}

inline json overrides_to_json(const ContactOverrides& o) {
  json j = json::object();
  for (const auto& [key, value] : o.values) j[key] = value;
  return j;
}

}  // namespace furniture_fem::detail
