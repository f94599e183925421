#pragma once
// Internal: the names scene files use for enumerations, and the contact overrides each law reads; shared
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
inline constexpr EnumNames<ContactLawKind, 6> law_names{{{ContactLawKind::paper, "paper"},
                                                         {ContactLawKind::paper_anisotropic, "paper_anisotropic"},
                                                         {ContactLawKind::spring_dashpot, "spring_dashpot"},
                                                         {ContactLawKind::hunt_crossley, "hunt_crossley"},
                                                         {ContactLawKind::stick_slip, "stick_slip"},
                                                         {ContactLawKind::stiff, "stiff"}}};
inline constexpr EnumNames<ImplicitContact, 3> implicit_contact_names{
    {{ImplicitContact::none, "none"}, {ImplicitContact::rigid, "rigid"}, {ImplicitContact::all, "all"}}};
inline constexpr EnumNames<IntegratorKind, 3> integrator_names{
    {{IntegratorKind::paper_newmark, "paper_newmark"},
     {IntegratorKind::average_acceleration, "average_acceleration"},
     {IntegratorKind::generalized_alpha, "generalized_alpha"}}};
inline constexpr EnumNames<ScaleMeasure, 2> scale_measure_names{{{ScaleMeasure::pga, "pga"}, {ScaleMeasure::pgv, "pgv"}}};
inline constexpr EnumNames<SolverKind, 2> solver_names{{{SolverKind::cg, "cg"}, {SolverKind::direct, "direct"}}};

// Which contact override a law reads: a value the chosen law ignores is a mistake worth reporting.
struct ContactField {
  std::string_view key;
  std::optional<double> ContactOverrides::*field;
  double lo, hi;
  bool lo_exclusive;
  std::array<bool, 6> used_by;  // paper, paper_anisotropic, spring_dashpot, hunt_crossley, stick_slip, stiff
  bool floor_only;
};
// mu_long is read by every law (the isotropic ones take it as their floor mu, the paper's rule);
// mu_short only by the anisotropic one.
inline constexpr std::array<ContactField, 8> contact_fields{{
    {"alpha_kgf", &ContactOverrides::alpha_kgf, 0.0, 1e6, true, {true, true, false, false, true, false}, false},
    {"dc_kgf", &ContactOverrides::dc_kgf, 0.0, 1e6, false, {true, true, false, false, true, false}, false},
    {"q", &ContactOverrides::q, 0.0, 10.0, true, {true, true, false, false, true, false}, false},
    {"mu", &ContactOverrides::mu, 0.0, 5.0, false, {true, true, true, true, true, true}, false},
    {"mu_long", &ContactOverrides::mu_long, 0.0, 5.0, false, {true, true, true, true, true, true}, true},
    {"mu_short", &ContactOverrides::mu_short, 0.0, 5.0, false, {false, true, false, false, false, false}, true},
    {"stiffness", &ContactOverrides::stiffness, 0.0, 1e12, true, {false, false, true, true, true, false}, false},
    {"damping", &ContactOverrides::damping, 0.0, 1e12, false, {false, false, true, false, true, false}, false},
}};

// Why the linear solver cannot run with the contact law, or "": the runner builds the CG solver for the
// paper's laws only (each law-solver pair is a separate instantiation of the stepping). `solver: "cg"`
// with another law was replaced by "direct" silently (issue 12).
inline std::string solver_problem(SolverKind solver, ContactLawKind law) {
  if (solver != SolverKind::cg || law == ContactLawKind::paper || law == ContactLawKind::paper_anisotropic) return {};
  return "\"cg\" is available with the contact laws \"paper\" and \"paper_anisotropic\" only; the law \"" +
         enum_name(law_names, law) + "\" runs with \"direct\" (set \"solver\": \"direct\")";
}

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
  for (const auto& f : contact_fields)
    if (o.*(f.field)) j[std::string(f.key)] = *(o.*(f.field));
  return j;
}

}  // namespace furniture_fem::detail
