#pragma once
// furniture_fem/scene/writer.hpp: a SceneSpec as JSON, every value written out, so that reading it back
// (scene/reader.hpp) gives the same scene and writing that gives the same JSON.
#include <nlohmann/json.hpp>

#include <fstream>
#include <string>

#include "../core/errors.hpp"
#include "../furniture/item_kinds.hpp"
#include "item_parameters.hpp"
#include "spec.hpp"

#define FURNITURE_FEM_SCENE_INTERNAL
#include "detail/scene_building.hpp"
#include "detail/scene_occupants.hpp"
#include "detail/scene_exits.hpp"
#include "detail/scene_restraints.hpp"
#include "detail/scene_json.hpp"
#include "detail/scene_names.hpp"
#undef FURNITURE_FEM_SCENE_INTERNAL

namespace furniture_fem {

namespace detail {
// The ground motion as the reader takes it: a "points" motion has only its level and points.
inline nlohmann::json ground_motion_json(const GroundMotionSpec& g) {
  using nlohmann::json;
  json gm = {{"source", enum_name(source_names, g.source)}, {"level", g.level}};
  if (g.source == MotionSource::points) {
    gm["x"] = points_to_json(g.points_x);
    if (!g.points_y.empty()) gm["y"] = points_to_json(g.points_y);
    if (!g.points_z.empty()) gm["z"] = points_to_json(g.points_z);
    return gm;
  }
  gm["dimensions"] = enum_name(dimension_names, g.dimensions);
  gm["pad_after_end"] = g.pad_after_end;
  if (g.building) gm["building"] = building_json(*g.building);
  if (g.source == MotionSource::synthetic) {  // no low-pass, no window: the reader refuses them
    gm["seed"] = g.seed;
    gm["pga"] = g.pga;
    gm["duration"] = g.synthetic_duration;
  } else {
    gm["lowpass_hz"] = g.lowpass_hz;
    gm["window"] = {{"start", g.window_start}};
    if (g.window_end) gm["window"]["end"] = *g.window_end;
    gm["check_pga"] = g.check_pga;
    if (g.scale_to) gm["scale_to"] = {{enum_name(scale_measure_names, g.scale_to->measure), g.scale_to->value}};
    gm["format"] = enum_name(format_names, g.format);
    gm["files"] = {{"x", g.file_x}};
    if (!g.file_y.empty()) gm["files"]["y"] = g.file_y;
    if (!g.file_z.empty()) gm["files"]["z"] = g.file_z;
    if (g.units) gm["units"] = enum_name(unit_names, *g.units);
    if (g.dt) gm["dt"] = *g.dt;
  }
  return gm;
}
}  // namespace detail

// The scene as JSON, every value written out: parse_scene_json(to_json(s)) gives s back, and
// to_json of that gives the same JSON.
inline nlohmann::json to_json(const SceneSpec& s) {
  using nlohmann::json;
  using detail::enum_name;
  json j;
  j["name"] = s.name;
  j["table"] = {{"size_x", s.table.size_x}, {"size_y", s.table.size_y}, {"floor_z", s.table.floor_z}};
  j["walls"] = json::array();
  for (const auto& w : s.walls)
    j["walls"].push_back({{"name", w.name},
                          {"point", detail::to_json_vec3(w.point)},
                          {"normal", detail::to_json_vec3(w.normal)},
                          {"height", w.height},
                          {"width", w.width}});
  if (s.ceiling) j["ceiling"] = {{"height", s.ceiling->height}};  // a scene without one is written as before
  j["obstacles"] = json::array();
  for (const auto& o : s.obstacles)
    j["obstacles"].push_back({{"name", o.name},
                              {"file", o.file},
                              {"position", detail::to_json_vec3(o.position)},
                              {"yaw_deg", o.yaw_deg},
                              {"scale", o.scale}});
  j["items"] = json::array();
  for (const auto& it : s.items) {
    json item = {{"name", it.name},
                 {"kind", to_string(it.kind)},
                 {"x", it.x},
                 {"y", it.y},
                 {"yaw_deg", it.yaw_deg},
                 {"fidelity", to_string(it.fidelity)}};
    json params = json::object();
    for (const auto& c : common_item_parameters)
      if (it.params.*(c.field)) params[std::string(c.parameter.key)] = *(it.params.*(c.field));
    const ItemKindEntry* kind = item_kind_registry().find(it.kind.name());
    for (const auto& [key, value] : it.params.kind_values) {
      const ItemParameter* declared = kind ? kind->parameter(key) : nullptr;
      if (declared && declared->integer)
        params[key] = static_cast<long long>(value);
      else
        params[key] = value;
    }
    if (!params.empty()) item["params"] = params;
    j["items"].push_back(item);
  }
  if (!s.restraints.empty()) {  // written when there are some: scene.json without them unchanged
    j["restraints"] = json::array();
    for (const auto& r : s.restraints) j["restraints"].push_back(detail::restraint_json(r));
  }
  if (!s.occupants.empty()) {  // written when there are some, as restraints
    j["occupants"] = json::array();
    for (const auto& o : s.occupants) j["occupants"].push_back(detail::occupant_json(o));
    j["strike_thresholds"] = detail::strike_thresholds_json(s.strike_thresholds);
  }
  if (!s.exits.empty()) {  // as restraints: scene.json without exits unchanged
    j["exits"] = json::array();
    for (const auto& e : s.exits) j["exits"].push_back(detail::exit_json(e));
  }
  j["ground_motion"] = detail::ground_motion_json(s.ground_motion);
  json contact = {{"law", std::string(scene_law(s.contact.law).name)},
                  {"implicit", enum_name(detail::implicit_contact_names, implicit_contact(s.contact))},
                  {"velocity_regularisation", s.contact.velocity_regularisation},
                  {"plane_contact_at", enum_name(detail::plane_contact_at_names, s.contact.plane_contact_at)},
                  {"rigid_pairs", enum_name(detail::rigid_pair_contact_names, s.contact.rigid_pairs)},
                  {"start", enum_name(detail::contact_start_names, s.contact.start)}};
  if (scene_law(s.contact.law).own_stick_spring.empty()) contact["stick_length"] = s.contact.stick_length;
  if (s.contact.flexible_pairs)  // written when set: older scene.json unchanged
    contact["flexible_pairs"] = enum_name(detail::flexible_pair_contact_names, *s.contact.flexible_pairs);
  for (auto [key, o] : {std::pair{"floor", &s.contact.floor}, std::pair{"wall", &s.contact.wall},
                        std::pair{"item", &s.contact.item}}) {
    const json ov = detail::overrides_to_json(*o);
    if (!ov.empty()) contact[key] = ov;
  }
  j["contact"] = contact;
  j["integrator"] = {{"scheme", enum_name(detail::integrator_names, s.integrator.scheme)},
                     {"rho_inf", s.integrator.rho_inf},
                     {"iterate_to_equilibrium", s.integrator.iterate_to_equilibrium},
                     {"impact_substeps", s.integrator.impact_substeps},
                     {"stiffness_damping", s.integrator.stiffness_damping},
                     {"frame_drift_refresh", s.integrator.frame_drift_refresh}};
  j["solver"] = enum_name(detail::solver_names, s.solver);
  j["refresh_every"] = s.refresh_every;
  j["duration"] = s.duration;
  j["dt"] = s.dt;
  if (s.allow_coarse_dt) j["allow_coarse_dt"] = true;  // written when set: older scene.json unchanged
  json markers = json::array();
  for (const auto& m : s.outputs.markers) {
    if (m.point)
      markers.push_back({{"name", m.name}, {"item", m.item}, {"point", detail::to_json_vec3(*m.point)}});
    else if (m.name == m.item + "." + m.marker)
      markers.push_back(m.name);
    else
      markers.push_back({{"name", m.name}, {"item", m.item}, {"marker", m.marker}});
  }
  json forces = json::array();
  for (const auto& f : s.outputs.sectional_forces)
    forces.push_back({{"item", f.item}, {"member", f.member}, {"element", f.element}});
  j["outputs"] = {{"folder", s.outputs.folder},
                  {"markers", markers},
                  {"sectional_forces", forces},
                  {"vtu_every", s.outputs.vtu_every},
                  {"figures", s.outputs.figures}};
  // Written only when set: scene files and checkpoints written before the key existed stay the same.
  if (s.outputs.contact_pairs != ContactPairOutput::automatic)
    j["outputs"]["contact_pairs"] = enum_name(detail::contact_pair_output_names, s.outputs.contact_pairs);
  return j;
}

// Writes the scene as an indented JSON file.
inline void write_scene(const SceneSpec& s, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw InputError(path, 0, "", "cannot write the scene file");
  out << to_json(s).dump(2) << '\n';
}

}  // namespace furniture_fem
