#pragma once
// furniture_fem/scene/reader.hpp: scene files (docs/scene/scene_file.md) read into a SceneSpec, strictly:
// an unknown key, a wrong type, an out-of-range value or an unknown name throws InputError naming the
// file, the key path and the value. Item kinds and their parameters come from item_kind_registry().
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../core/errors.hpp"
#include "../core/step_length.hpp"
#include "../furniture/item_kinds.hpp"
#include "item_parameters.hpp"
#include "spec.hpp"

#define FURNITURE_FEM_SCENE_INTERNAL
#include "detail/compiled_entry_points.hpp"
#include "detail/scene_building.hpp"
#include "detail/scene_json.hpp"
#include "detail/scene_names.hpp"
#include "detail/scene_occupants.hpp"
#include "detail/scene_exits.hpp"
#include "detail/scene_restraints.hpp"
#undef FURNITURE_FEM_SCENE_INTERNAL

namespace furniture_fem {

namespace detail {

// A parameter's value against its declared range, the value in the message.
inline void check_parameter(const ObjectReader& r, const ItemParameter& p) {
  if (const auto why = p.violation(r.raw(p.key).get<double>())) r.require(false, p.key, *why);
}

inline ItemParams parse_item_params(const ObjectReader& r, const ItemKindEntry& kind) {
  const auto accepted = accepted_item_parameters(kind);
  for (auto it = r.raw_object().begin(); it != r.raw_object().end(); ++it)
    if (std::find(accepted.begin(), accepted.end(), it.key()) == accepted.end())
      r.fail(r.path(it.key()), not_a_parameter_message(kind));
  ItemParams p;
  for (const auto& c : common_item_parameters) {
    if (!r.has(c.parameter.key)) continue;
    p.*(c.field) = r.optional_number(c.parameter.key);
    check_parameter(r, c.parameter);
  }
  for (const auto& q : kind.parameters) {
    if (!r.has(q.key)) continue;
    const double value = q.integer ? static_cast<double>(*r.optional_integer(q.key)) : *r.optional_number(q.key);
    check_parameter(r, q);
    p.kind_values[std::string(q.key)] = value;
  }
  return p;
}

// The override keys of one pair kind: those the law declares (floor-only keys on the floor); a key the law
// does not declare, or sets from each item itself (and why), is an error naming the key and the law; a
// value out of range names the range, the value and the law.
inline ContactOverrides parse_contact_overrides(const ObjectReader& r, ContactLawKind kind, bool is_floor) {
  const SceneLawInfo& law = scene_law(kind);
  const std::string of_law = "contact law \"" + std::string(law.name) + "\"";
  std::vector<std::string_view> allowed;
  for (const auto& p : law.parameters)  // a key setting two fields is declared twice, allowed once
    if ((is_floor || !p.floor_only) && std::find(allowed.begin(), allowed.end(), p.key) == allowed.end())
      allowed.push_back(p.key);
  for (std::string_view key : law.rule_parameters)
    if (r.has(key)) r.fail(r.path(key), "not used by the " + of_law + ": " + std::string(law.rule_parameters_why));
  // Another registered law's key: not this law's (allow_only would call it unknown).
  for (const auto& other : contact_law_registry().laws())
    for (const auto& p : other.parameters)
      if (r.has(p.key) && !law.reads(p.key)) r.fail(r.path(p.key), "not used by the " + of_law);
  r.allow_only(allowed, "contact parameter of the " + of_law);
  ContactOverrides o;
  for (const auto& p : law.parameters) {
    if (!r.has(p.key) || o.values.count(std::string(p.key))) continue;
    const double value = r.number(p.key, p.default_value);
    if (!p.accepts(value))
      r.fail(r.path(p.key), "must lie in " + p.range_text() + " (got " + ObjectReader::brief(r.raw(p.key), 60) +
                                "), under the " + of_law);
    o.values[std::string(p.key)] = value;
  }
  return o;
}

// contact.law: a registered law's name (an unknown name lists the registered ones).
inline ContactLawKind parse_contact_law(const ObjectReader& r, ContactLawKind fallback) {
  const auto name = r.optional_string("law");
  if (!name) return fallback;
  if (const auto kind = contact_law_kind(*name)) return *kind;
  r.fail(r.path("law"), "unknown contact law \"" + *name + "\"; expected one of: " + contact_law_registry().names());
}

// `v`, the value of `key`, within scene_reach of `centre` (each coordinate): "<what> must lie within
// 10000 m of <from>" otherwise.
inline void check_reach(const ObjectReader& r, std::string_view key, const Vec3& v, const Vec3& centre,
                        const std::string& what, const std::string& from) {
  if ((v - centre).cwiseAbs().maxCoeff() <= scene_reach) return;
  r.fail(r.path(key), "out of reach (got [" + fmt(v.x()) + ", " + fmt(v.y()) + ", " + fmt(v.z()) + "]); " + what +
                          " must lie within " + fmt(scene_reach) + " m of " + from);
}

inline ItemSpec parse_item(const json& v, const std::string& path, const std::string& source) {
  ObjectReader r(v, path, source);
  r.allow_only({"name", "kind", "x", "y", "yaw_deg", "fidelity", "params"});
  ItemSpec item;
  const ItemKindRegistry& kinds = item_kind_registry();
  if (!r.has("kind")) r.fail(r.path("kind"), "required; one of: " + kinds.names());
  const std::string kind_name = *r.optional_string("kind");
  const ItemKindEntry* kind = kinds.find(kind_name);
  if (!kind) r.fail(r.path("kind"), "unknown item kind \"" + kind_name + "\"; expected one of: " + kinds.names());
  item.kind = kind->kind;
  item.name = r.string("name", "");
  if (r.has("name")) {
    r.require(!item.name.empty(), "name", "must not be empty");
    r.require(item.name.find_first_of("./") == std::string::npos, "name",
              "must not contain '.' or '/' (they separate item, body and marker in references)");
  }
  item.x = r.number("x", 0);
  item.y = r.number("y", 0);
  item.yaw_deg = r.number("yaw_deg", 0);
  r.in_range("yaw_deg", -360, 360);
  item.fidelity = r.enumeration("fidelity", fidelity_names, Fidelity::full, "fidelity");
  if (r.has("params")) item.params = parse_item_params(r.object("params"), *kind);
  return item;
}

// One component of a "points" motion: [[t, a], ...], checked (points_problem) with the point's path.
inline std::vector<std::pair<double, double>> parse_points(const ObjectReader& r, std::string_view key) {
  const json& v = r.raw(key);
  if (!v.is_array()) r.fail(r.path(key), "expected an array of [t, a] points, got " + ObjectReader::describe(v));
  std::vector<std::pair<double, double>> pts;
  for (size_t i = 0; i < v.size(); ++i) {
    const std::string at = index_path(r.path(key), i);
    const json& p = v[i];
    if (!p.is_array() || p.size() != 2)
      r.fail(at, "expected a [t, a] pair (time in s, acceleration in m/s^2), got " + ObjectReader::describe(p));
    for (size_t k = 0; k < 2; ++k)
      if (!p[k].is_number()) r.fail(index_path(at, k), "expected a number, got " + ObjectReader::describe(p[k]));
    pts.emplace_back(p[0].get<double>(), p[1].get<double>());
  }
  if (const auto problem = points_problem(pts, r.path(key))) r.fail(problem->first, problem->second);
  return pts;
}

// source "points": the table acceleration as given, scaled by level; nothing else applies to it.
inline void parse_points_motion(const ObjectReader& r, GroundMotionSpec& g) {
  for (auto key : {"dimensions", "lowpass_hz", "window", "seed", "pga", "duration", "format", "files", "units", "dt",
                   "scale_to", "check_pga", "pad_after_end", "building"})
    if (r.has(key))
      r.fail(r.path(key), "not used with source \"points\" (the points are the table acceleration as given: no "
                          "filter, no window, no scaling but level, zero after the last point; the components "
                          "are the keys x, y, z)");
  r.allow_only({"source", "level", "x", "y", "z"});
  g.level = r.number("level", g.level);
  r.non_negative("level");
  if (!r.has("x")) r.fail(r.path("x"), "required with source \"points\": [[t, a], ...] (s, m/s^2)");
  g.points_x = parse_points(r, "x");
  if (r.has("y")) g.points_y = parse_points(r, "y");
  if (r.has("z")) g.points_z = parse_points(r, "z");
  g.dimensions = r.has("y") || r.has("z") ? MotionDimensions::three_d : MotionDimensions::one_d;
}

inline void parse_ground_motion(const ObjectReader& r, GroundMotionSpec& g) {
  g.source = r.enumeration("source", source_names, MotionSource::synthetic, "ground motion source");
  if (g.source == MotionSource::points) return parse_points_motion(r, g);
  const bool synthetic = g.source == MotionSource::synthetic;
  const std::vector<std::string_view> common{"source", "level", "dimensions", "lowpass_hz", "window", "pad_after_end",
                                             "building"};
  const std::vector<std::string_view> only_synthetic{"seed", "pga", "duration"};
  const std::vector<std::string_view> only_file{"format", "files", "units", "dt", "scale_to", "check_pga"};
  for (auto key : synthetic ? only_file : only_synthetic)
    if (r.has(key))
      r.fail(r.path(key), std::string("only used with source \"") + (synthetic ? "file" : "synthetic") + "\"");
  for (auto key : {"x", "y", "z"})
    if (r.has(key)) r.fail(r.path(key), "only used with source \"points\"");
  std::vector<std::string_view> allowed = common;
  for (auto key : synthetic ? only_synthetic : only_file) allowed.push_back(key);
  r.allow_only(allowed);

  g.level = r.number("level", g.level);
  r.non_negative("level");
  g.dimensions = r.enumeration("dimensions", dimension_names, g.dimensions, "dimensions");
  g.lowpass_hz = r.number("lowpass_hz", g.lowpass_hz);
  r.non_negative("lowpass_hz");
  if (r.has("window")) {
    const ObjectReader w = r.object("window");
    w.allow_only({"start", "end"});
    g.window_start = w.number("start", 0);
    w.non_negative("start");
    g.window_end = w.optional_number("end");
    if (g.window_end) w.require(*g.window_end > g.window_start, "end", "must be later than window.start");
  }
  g.pad_after_end = r.boolean("pad_after_end", g.pad_after_end);
  if (r.has("building")) g.building = parse_building(r.object("building"));
  if (synthetic) {
    // The synthetic motion is generated band-limited from t = 0 for `duration`: a low-pass corner or a
    // window were read and not applied (issue 12).
    for (auto key : {"lowpass_hz", "window"})
      if (r.has(key))
        r.fail(r.path(key), std::string("not applied to a synthetic motion (it is generated band-limited, from t = 0, "
                                        "for ground_motion.duration); only used with source \"file\""));
    const long long seed = r.integer("seed", g.seed);
    if (r.has("seed")) r.require(seed >= 0 && seed <= 4294967295LL, "seed", "must lie in [0, 4294967295]");
    g.seed = static_cast<unsigned>(seed);
    g.pga = r.number("pga", g.pga);
    r.positive("pga");
    g.synthetic_duration = r.number("duration", g.synthetic_duration);
    r.positive("duration");
    return;
  }
  g.format = r.enumeration("format", format_names, g.format, "record format");
  if (!r.has("files")) r.fail(r.path("files"), "required when source is \"file\" (an object with x, and y, z for 3-D)");
  const ObjectReader files = r.object("files");
  files.allow_only({"x", "y", "z"});
  g.file_x = files.string("x", "");
  g.file_y = files.string("y", "");
  g.file_z = files.string("z", "");
  if (g.file_x.empty()) files.fail(files.path("x"), "required: the record along X (the excitation direction)");
  // A JMA CSV file holds NS, EW and UD: files.y and files.z were required for 3-D and then not read.
  const bool one_file = g.format == RecordFormat::jma_csv;
  for (auto [key, file] : {std::pair{"y", &g.file_y}, std::pair{"z", &g.file_z}})
    if (one_file && !file->empty())
      files.fail(files.path(key), "not used with format \"jma_csv\": the file of files.x holds the three components "
                                  "(NS along X, EW along Y, UD along Z)");
    else if (!one_file && g.dimensions == MotionDimensions::three_d && file->empty())
      files.fail(files.path(key), "required for dimensions \"3d\"");
  // Only a column file takes its unit and sample spacing from the scene; the other formats state
  // theirs in the file, and these keys were read and ignored.
  for (auto key : {"units", "dt"})
    if (r.has(key) && g.format != RecordFormat::columns)
      r.fail(r.path(key), "only used with format \"columns\" (a file of format \"" + enum_name(format_names, g.format) +
                              "\" states its own " + (std::string(key) == "dt" ? "time step" : "unit") + ")");
  if (r.has("units")) g.units = r.enumeration("units", unit_names, AccelerationUnits::g, "acceleration unit");
  g.dt = r.optional_number("dt");
  // The sample spacing of a column file, as plausible as a record header's (1e-300 or 1e300 ran).
  read_range(r, "dt", 1e-5, 1.0, false);
  g.check_pga = r.boolean("check_pga", g.check_pga);
  if (r.has("scale_to")) {
    const ObjectReader t = r.object("scale_to");
    t.allow_only({"pga", "pgv", "jma"}, "scale target (pga in m/s^2, pgv in m/s or jma, the JMA intensity)");
    if (int(t.has("pga")) + int(t.has("pgv")) + int(t.has("jma")) != 1)
      t.fail(t.path(), "give exactly one of \"pga\" (m/s^2), \"pgv\" (m/s) and \"jma\" (the JMA intensity), "
                       "e.g. {\"pga\": 3.0} or {\"jma\": 6.2}");
    ScaleTarget target;
    target.measure = t.has("pga") ? ScaleMeasure::pga : t.has("pgv") ? ScaleMeasure::pgv : ScaleMeasure::jma;
    const std::string key = enum_name(scale_measure_names, target.measure);
    target.value = *t.optional_number(key);
    t.positive(key);
    g.scale_to = target;
  }
}

}  // namespace detail

// Reads a scene from parsed JSON. `source_name` names it in error messages (a file name).
inline SceneSpec parse_scene_json(const nlohmann::json& j, const std::string& source_name) {
  using detail::ObjectReader;
  const std::string source = source_name;
  SceneSpec s;
  s.source = source;
  const ObjectReader r(j, "", source);
  r.allow_only({"name", "table", "walls", "ceiling", "obstacles", "items", "restraints", "occupants", "strike_thresholds",
                "exits", "ground_motion", "contact", "integrator", "solver", "refresh_every", "duration", "dt",
                "allow_coarse_dt", "outputs"});
  s.name = r.string("name", s.name);

  if (r.has("table")) {
    const ObjectReader t = r.object("table");
    t.allow_only({"size_x", "size_y", "floor_z"});
    s.table.size_x = t.number("size_x", s.table.size_x);
    s.table.size_y = t.number("size_y", s.table.size_y);
    s.table.floor_z = t.number("floor_z", s.table.floor_z);
    for (auto key : {"size_x", "size_y"}) {
      t.positive(key);
      t.in_range(key, 0, 2 * scene_reach);
    }
    t.in_range("floor_z", -scene_reach, scene_reach);
  }

  s.walls = default_walls(s.table);
  if (r.has("walls")) {
    s.walls.clear();
    r.array("walls", [&](const nlohmann::json& v, const std::string& path) {
      const ObjectReader w(v, path, source);
      w.allow_only({"name", "point", "normal", "height", "width"});
      WallSpec wall;
      wall.name = w.string("name", "wall_" + std::to_string(s.walls.size() + 1));
      wall.point = w.vec3("point", wall.point);
      detail::check_reach(w, "point", wall.point, Vec3(0, 0, s.table.floor_z), "a wall", "the table's centre");
      wall.normal = w.vec3("normal", wall.normal);
      if (std::abs(wall.normal.z()) > 1e-12 || wall.normal.norm() < 1e-12)
        w.fail(w.path("normal"), "must be a non-zero horizontal vector (walls are vertical), got [" +
                                     detail::fmt(wall.normal.x()) + ", " + detail::fmt(wall.normal.y()) + ", " +
                                     detail::fmt(wall.normal.z()) + "]");
      // Kept as written (every use normalises it): normalised here, [1, 1, 0] moved by an ulp at each
      // read / to_json round trip.
      wall.height = w.number("height", wall.height);
      wall.width = w.number("width", wall.width);
      for (auto key : {"height", "width"}) {
        w.positive(key);
        w.in_range(key, 0, 2 * scene_reach);
      }
      s.walls.push_back(wall);
    });
  }

  if (r.has("ceiling")) {
    const ObjectReader c = r.object("ceiling");
    c.allow_only({"height"});
    if (!c.has("height")) c.fail(c.path("height"), "required: the ceiling's height above the table's floor (m)");
    s.ceiling = CeilingSpec{c.number("height", 0)};
    c.positive("height");
    c.in_range("height", 0, scene_reach);
  }

  r.array("obstacles", [&](const nlohmann::json& v, const std::string& path) {
    const ObjectReader o(v, path, source);
    o.allow_only({"name", "file", "position", "yaw_deg", "scale"});
    ObstacleSpec ob;
    ob.name = o.string("name", "obstacle_" + std::to_string(s.obstacles.size() + 1));
    if (!o.has("file")) o.fail(o.path("file"), "required: an STL, OBJ or OFF mesh file");
    ob.file = *o.optional_string("file");
    std::string ext = std::filesystem::path(ob.file).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    if (ext != ".stl" && ext != ".obj" && ext != ".off")
      o.fail(o.path("file"), "expected an .stl, .obj or .off mesh file, got \"" + ob.file + "\"");
    ob.position = o.vec3("position", ob.position);
    ob.yaw_deg = o.number("yaw_deg", 0);
    o.in_range("yaw_deg", -360, 360);
    ob.scale = o.number("scale", 1);
    o.positive("scale");
    s.obstacles.push_back(ob);
  });

  r.array("items", [&](const nlohmann::json& v, const std::string& path) {
    s.items.push_back(detail::parse_item(v, path, source));
  });
  // Unnamed items take their kind's name, numbered from the second of a kind on ("desk", "desk_2").
  std::map<std::string, int> seen;
  for (auto& item : s.items)
    if (item.name.empty()) {
      const std::string base = to_string(item.kind);
      const int n = ++seen[base];
      item.name = n == 1 ? base : base + "_" + std::to_string(n);
    }

  if (r.has("ground_motion")) detail::parse_ground_motion(r.object("ground_motion"), s.ground_motion);

  if (r.has("contact")) {
    const ObjectReader c = r.object("contact");
    c.allow_only({"law", "implicit", "velocity_regularisation", "stick_length", "plane_contact_at", "rigid_pairs",
                   "flexible_pairs", "start", "floor", "wall", "item"});
    s.contact.law = detail::parse_contact_law(c, s.contact.law);
    const SceneLawInfo& law = scene_law(s.contact.law);
    if (c.has("implicit"))
      s.contact.implicit = c.enumeration("implicit", detail::implicit_contact_names, implicit_contact(s.contact),
                                         "implicit contact");
    s.contact.velocity_regularisation = c.number("velocity_regularisation", s.contact.velocity_regularisation);
    c.positive("velocity_regularisation");
    if (c.has("stick_length") && !law.own_stick_spring.empty())
      c.fail(c.path("stick_length"),
             "not used by the contact law \"" + std::string(law.name) + "\" (" + std::string(law.own_stick_spring) + ")");
    s.contact.stick_length = c.number("stick_length", s.contact.stick_length);
    detail::read_range(c, "stick_length", 0.0, 0.01, false);
    s.contact.plane_contact_at = c.enumeration("plane_contact_at", detail::plane_contact_at_names,
                                               s.contact.plane_contact_at, "plane contact place");
    s.contact.rigid_pairs = c.enumeration("rigid_pairs", detail::rigid_pair_contact_names, s.contact.rigid_pairs,
                                          "rigid pair contact");
    if (c.has("flexible_pairs"))
      s.contact.flexible_pairs = c.enumeration("flexible_pairs", detail::flexible_pair_contact_names,
                                               FlexiblePairContact::explicit_load, "flexible pair contact");
    if (s.contact.flexible_pairs == FlexiblePairContact::implicit_step && implicit_contact(s.contact) != ImplicitContact::all)
      c.fail(c.path("flexible_pairs"), "\"implicit\" needs \"implicit\": \"all\" (a flexible item's contact inside the step)");
    s.contact.start = c.enumeration("start", detail::contact_start_names, s.contact.start, "start");
    if (c.has("floor")) s.contact.floor = detail::parse_contact_overrides(c.object("floor"), s.contact.law, true);
    if (c.has("wall")) s.contact.wall = detail::parse_contact_overrides(c.object("wall"), s.contact.law, false);
    if (c.has("item")) s.contact.item = detail::parse_contact_overrides(c.object("item"), s.contact.law, false);
  }

  if (r.has("integrator")) {
    const ObjectReader in = r.object("integrator");
    in.allow_only({"scheme", "rho_inf", "iterate_to_equilibrium", "impact_substeps", "stiffness_damping",
                  "frame_drift_refresh"});
    s.integrator.scheme = in.enumeration("scheme", detail::integrator_names, s.integrator.scheme, "integrator");
    s.integrator.rho_inf = in.number("rho_inf", s.integrator.rho_inf);
    in.in_range("rho_inf", 0, 1);
    s.integrator.iterate_to_equilibrium = in.boolean("iterate_to_equilibrium", s.integrator.iterate_to_equilibrium);
    const long long substeps = in.integer("impact_substeps", s.integrator.impact_substeps);
    in.in_range("impact_substeps", 1, 1000);
    s.integrator.impact_substeps = static_cast<int>(substeps);
    s.integrator.stiffness_damping = in.number("stiffness_damping", s.integrator.stiffness_damping);
    in.in_range("stiffness_damping", 0, 1);
    s.integrator.frame_drift_refresh = in.number("frame_drift_refresh", s.integrator.frame_drift_refresh);
    in.in_range("frame_drift_refresh", 0, 0.1);
  }
  s.solver = r.enumeration("solver", detail::solver_names, s.solver, "solver");
  s.refresh_every = r.number("refresh_every", s.refresh_every);
  r.positive("refresh_every");
  s.duration = r.number("duration", s.duration);
  r.positive("duration");
  s.dt = r.number("dt", s.dt);
  if (r.has("dt"))
    if (const std::string why = step_length_problem(s.dt, SceneSpec::min_dt); !why.empty()) r.fail(r.path("dt"), why);
  if (r.has("dt")) r.require(s.dt <= s.duration, "dt", "must not exceed duration (" + detail::fmt(s.duration) + " s)");
  r.array("restraints", [&](const nlohmann::json& v, const std::string& path) {
    s.restraints.push_back(detail::read_restraint(v, path, source, s.restraints.size()));
    if (const auto problem = detail::restraint_problem(s.restraints.back(), s))
      r.fail(path + "." + problem->first, problem->second);
  });
  r.array("occupants", [&](const nlohmann::json& v, const std::string& path) {
    s.occupants.push_back(detail::read_occupant(v, path, source, s.occupants.size(), s));
    if (const auto problem = detail::occupant_problem(s.occupants.back(), s)) r.fail(path + "." + problem->first, problem->second);
  });
  if (r.has("strike_thresholds")) s.strike_thresholds = detail::read_strike_thresholds(r.object("strike_thresholds"));
  r.array("exits", [&](const nlohmann::json& v, const std::string& path) {
    s.exits.push_back(detail::read_exit(v, path, source, s.exits.size()));
    for (std::size_t k = 0; k + 1 < s.exits.size(); ++k)
      if (s.exits[k].name == s.exits.back().name) r.fail(path + ".name", "duplicate exit name \"" + s.exits[k].name + "\"");
    if (const auto problem = detail::exit_problem(s.exits.back(), s)) r.fail(path + "." + problem->first, problem->second);
  });
  s.allow_coarse_dt = r.boolean("allow_coarse_dt", s.allow_coarse_dt);

  if (r.has("outputs")) {
    const ObjectReader o = r.object("outputs");
    o.allow_only({"folder", "markers", "sectional_forces", "vtu_every", "figures", "contact_pairs"});
    s.outputs.folder = o.string("folder", s.outputs.folder);
    o.require(!s.outputs.folder.empty(), "folder", "must not be empty");
    o.array("markers", [&](const nlohmann::json& v, const std::string& path) {
      MarkerRequest m;
      if (v.is_string()) {
        // "item.marker": item names hold no '.', so the first '.' separates them.
        const std::string text = v.get<std::string>();
        const auto dot = text.find('.');
        if (dot == std::string::npos || dot == 0 || dot + 1 == text.size())
          o.fail(path, "expected \"item.marker\" (e.g. \"desk.top_front_centre\"), got \"" + text + "\"");
        m.name = text;
        m.item = text.substr(0, dot);
        m.marker = text.substr(dot + 1);
      } else {
        const ObjectReader mr(v, path, source);
        mr.allow_only({"name", "item", "marker", "point"});
        for (auto key : {"item", "name"})
          if (!mr.has(key)) mr.fail(mr.path(key), "required");
        m.name = *mr.optional_string("name");
        m.item = *mr.optional_string("item");
        if (mr.has("marker") == mr.has("point"))
          mr.fail(mr.path("point"), "give exactly one of \"marker\" (a builder marker) and \"point\" (item frame, m)");
        m.marker = mr.string("marker", "");
        m.point = mr.optional_vec3("point");
        if (m.point) detail::check_reach(mr, "point", *m.point, Vec3::Zero(), "a marker's point", "its item's origin");
      }
      s.outputs.markers.push_back(m);
    });
    o.array("sectional_forces", [&](const nlohmann::json& v, const std::string& path) {
      const ObjectReader f(v, path, source);
      f.allow_only({"item", "member", "element"});
      for (auto key : {"item", "member"})
        if (!f.has(key)) f.fail(f.path(key), "required");
      SectionalForceRequest req;
      req.item = *f.optional_string("item");
      req.member = *f.optional_string("member");
      const long long e = f.integer("element", 0);
      if (f.has("element")) f.require(e >= 0 && e < 100000, "element", "must lie in [0, 100000)");
      req.element = static_cast<int>(e);
      s.outputs.sectional_forces.push_back(req);
    });
    const long long every = o.integer("vtu_every", s.outputs.vtu_every);
    if (o.has("vtu_every")) o.require(every >= 0 && every <= 100000000, "vtu_every", "must lie in [0, 1e8] (0: no VTU)");
    s.outputs.vtu_every = static_cast<int>(every);
    s.outputs.figures = o.boolean("figures", s.outputs.figures);
    s.outputs.contact_pairs = o.enumeration("contact_pairs", detail::contact_pair_output_names,
                                            s.outputs.contact_pairs, "contact pair output");
  }
  return s;
}

namespace detail {
// A scene is a few kilobytes with a handful of levels. Deeper or larger input is refused before the
// JSON library sees it: its serializer (used in error messages) recurses once per level, and a
// 100 000-deep array overflowed the stack (issue 13).
inline constexpr std::size_t scene_max_bytes = std::size_t{64} << 20;
inline constexpr int scene_max_depth = 64;

// The first problem of a scene's structure that the JSON library would not report, with its line
// (0: none): a bracket nested deeper than scene_max_depth (outside strings), or a key given twice in
// one object, which the library reads silently as the last value (`"dt": 0.001, ..., "dt": 0.01`
// ran at 0.01, issue 13). Keys are compared as written (escapes not decoded). Linear in the text.
inline std::pair<long, std::string> structure_problem(const std::string& text) {
  std::vector<std::pair<bool, std::set<std::string>>> open;  // (is an object, its keys so far)
  long line = 1;
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
    } else if (c == '"') {
      const long at = line;
      std::string word;
      std::size_t j = i + 1;
      for (; j < text.size() && text[j] != '"'; ++j) {
        if (text[j] == '\\' && j + 1 < text.size()) word += text[j++];
        if (text[j] == '\n') ++line;
        word += text[j];
      }
      i = j;  // the closing quote
      std::size_t k = j + 1;
      while (k < text.size() && blank(text[k])) ++k;
      if (k < text.size() && text[k] == ':' && !open.empty() && open.back().first &&
          !open.back().second.insert(word).second)
        return {at, "key \"" + (word.size() > 60 ? word.substr(0, 57) + "..." : word) +
                        "\" given twice in one object (only one value can be meant)"};
    } else if (c == '[' || c == '{') {
      if (open.size() >= static_cast<std::size_t>(scene_max_depth))
        return {line, "values nested more than " + std::to_string(scene_max_depth) +
                          " levels deep (arrays and objects)"};
      open.push_back({c == '{', {}});
    } else if ((c == ']' || c == '}') && !open.empty()) {
      open.pop_back();
    }
  }
  return {0, {}};
}

// The line of byte `at` of `text` (1 for the first).
inline long line_at(const std::string& text, std::size_t at) {
  return 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(std::min(at, text.size())), '\n');
}

// The key path ("items[0].x") at which the JSON library stops, from its SAX events: its own messages
// name only the byte, and an out-of-range number (1e400) not even that.
class KeyPathAtError final : public nlohmann::json_sax<nlohmann::json> {
 public:
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(true); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(string_t& k) override {
    levels_.back().key = k;
    levels_.back().done = false;
    return true;
  }
  bool parse_error(std::size_t position, const std::string& token, const nlohmann::detail::exception& e) override {
    const bool overflow = e.id == 406;
    if (overflow) begin();  // the number is a value being read: in an array, the next element
    const bool after = !overflow && (levels_.empty() ? top_done_ : levels_.back().done);
    error = {position, token, e.what(), overflow, key_path_here(), after};
    return false;
  }

  struct Error {
    std::size_t position = 0;  // bytes read when the library stopped
    std::string token, what;
    bool overflow = false;  // a number beyond a double's range (the library's out_of_range 406)
    std::string path;       // the key or element being read, or the last one read when `after`
    bool after = false;     // the value at `path` was whole: the problem follows it
  };
  Error error;

 private:
  struct Level {
    bool object = false;
    std::optional<std::string> key;  // none before the object's first key
    std::size_t index = 0;
    bool done = false;  // the value of `key` (the element `index`) is whole
  };
  std::vector<Level> levels_;
  bool top_done_ = false;

  void begin() {  // a value starts: in an array, after a whole element, the next element
    if (levels_.empty() || levels_.back().object || !levels_.back().done) return;
    ++levels_.back().index;
    levels_.back().done = false;
  }
  void done() { (levels_.empty() ? top_done_ : levels_.back().done) = true; }
  bool value() {
    begin();
    done();
    return true;
  }
  bool open(bool object) {
    begin();
    levels_.push_back({object, {}, 0, false});
    return true;
  }
  bool close() {
    levels_.pop_back();
    done();
    return true;
  }
  std::string key_path_here() const {
    std::string path;
    for (const Level& l : levels_) {
      if (l.object && !l.key) break;
      path = l.object ? json_io::key_path(path, *l.key) : json_io::index_path(path, l.index);
    }
    return path;
  }
};

// The InputError for a text the JSON library refuses, naming the key path where it stopped.
[[noreturn]] inline void throw_json_error(const std::string& path, const std::string& text) {
  KeyPathAtError where;
  nlohmann::json::sax_parse(text, &where);
  const KeyPathAtError::Error& e = where.error;
  const long line = line_at(text, e.position);
  if (e.overflow)
    throw InputError(path, line, e.path.empty() ? "(top level)" : e.path,
                     "number out of range (got " + e.token + "): a number's magnitude must be below 1.8e308");
  const std::string place = !e.after ? "" : e.path.empty() ? " after the top-level value" : " after its value";
  throw InputError(path, line, e.path, "not valid JSON" + place + ": " + e.what);
}
}  // namespace detail

// Reads a JSON input file (a scene, a study; `what` names it in messages) with the checks every input
// file gets: at most 64 MiB, nesting at most 64 deep, syntax errors and out-of-range numbers reported
// with their line and key path, nothing after the top-level value (the library stops at a NUL byte).
inline nlohmann::json read_json_file(const std::string& path, const std::string& what = "scene") {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open the " + what + " file");
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::size_t>(std::max<std::streamoff>(0, in.tellg()));
  if (size > detail::scene_max_bytes)
    throw InputError(path, 0, "", "the " + what + " file has " + std::to_string(size) + " bytes; a " + what +
                                      " file may have at most " + std::to_string(detail::scene_max_bytes) + " (64 MiB)");
  in.seekg(0);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  if (const auto [line, problem] = detail::structure_problem(text); line > 0) throw InputError(path, line, "", problem);
  nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded()) detail::throw_json_error(path, text);
  // A parse that succeeded read up to a NUL byte at most: one here is after the top-level value.
  if (const auto nul = text.find('\0'); nul != std::string::npos)
    throw InputError(path, detail::line_at(text, nul), "",
                     "not valid JSON after the top-level value: a NUL byte (byte " + std::to_string(nul + 1) +
                         " of " + std::to_string(text.size()) + "); a JSON file holds text only");
  return j;
}

// Reads a scene file (read_json_file's checks); relative paths inside the file are taken relative to
// the file's folder (SceneSpec::resolve). Declared only for the compiled scene runner's users
// (detail/compiled_entry_points.hpp).
#ifndef FFEM_SCENE_DECLARED_ONLY
FFEM_SCENE_ENTRY_INLINE SceneSpec parse_scene(const std::string& path) {
  const nlohmann::json j = read_json_file(path, "scene");
  SceneSpec s = parse_scene_json(j, path);
  s.base_dir = std::filesystem::path(path).parent_path().string();
  return s;
}
#endif

}  // namespace furniture_fem
