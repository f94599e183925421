#pragma once
// furniture_fem/scene/scene.hpp: what a run simulates, as plain data: the shake table and its walls, mesh
// obstacles, the furniture items and where they stand, the ground motion, the contact law, the time
// integration, and what to write out. Scenes come from JSON files (docs/scene/scene_file.md) or from
// configuration(k), the paper's three arrangements. Nothing here simulates: build_scene() turns the
// items into bodies of a Model, and validate() checks a scene before a run starts.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "../furniture/furniture.hpp"
#include "../core/model.hpp"

#define FURNITURE_FEM_SCENE_INTERNAL
#include "detail/scene_json.hpp"
#undef FURNITURE_FEM_SCENE_INTERNAL

namespace furniture_fem {

// ---------------------------------------------------------------------------------------------------
// The scene description
// ---------------------------------------------------------------------------------------------------

// The shake table: a size_x x size_y rectangle centred on the origin, its floor at z = floor_z.
struct TableSpec {
  double size_x = 4.0, size_y = 4.0;  // m (the paper's table: 4 m x 4 m)
  double floor_z = 0.0;
};

// A rigid vertical wall: the plane through `point` with horizontal unit `normal` pointing into the
// room, `height` above the floor and `width` along the wall, centred on `point`.
struct WallSpec {
  std::string name;
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitX();
  double height = 2.5;
  double width = 4.0;
};

// The paper's two walls, orthogonal to the excitation (X), facing each other at the table's edges.
inline std::vector<WallSpec> default_walls(const TableSpec& t = {}) {
  return {WallSpec{"wall_minus_x", Vec3(-0.5 * t.size_x, 0, t.floor_z), Vec3::UnitX(), 2.5, t.size_y},
          WallSpec{"wall_plus_x", Vec3(0.5 * t.size_x, 0, t.floor_z), Vec3(-1, 0, 0), 2.5, t.size_y}};
}

// A rigid obstacle given by a triangle mesh file (STL or OBJ), placed like an item.
struct ObstacleSpec {
  std::string name;
  std::string file;
  Vec3 position = Vec3::Zero();
  double yaw_deg = 0;
  double scale = 1;
};

// Per-item overrides. Which apply to which kind: docs/scene/scene_file.md (checked when parsing).
struct ItemParams {
  std::optional<double> width, depth, height;       // m, generic kinds only
  std::optional<int> shelves;                       // bookshelf only
  std::optional<double> panel_spacing, grid_scale, element_length;
  std::optional<double> mass_kg, cog_h, cog_d1;     // kg, m, m; not for separated_cabinets
  std::optional<double> mu_static_long, mu_static_short;  // generic kinds: the 0.8 rule's input
  std::optional<double> alpha_kgf, dc_kgf, mu_floor_long, mu_floor_short, mu_wall, mu_item;  // ItemContact
};

struct ItemSpec {
  std::string name;  // unique; marker and output references use it
  ItemKind kind = ItemKind::tall_cabinet;
  double x = 0, y = 0;  // footprint centre on the table (m)
  double yaw_deg = 0;   // counter-clockwise seen from above; 0: width along X, front towards -Y
  Fidelity fidelity = Fidelity::full;
  ItemParams params;
};

enum class MotionSource { synthetic, file };
enum class RecordFormat { at2, knet, jma_csv, columns };
enum class MotionDimensions { one_d, three_d };
enum class AccelerationUnits { g, gal, m_per_s2 };

struct GroundMotionSpec {
  MotionSource source = MotionSource::synthetic;
  // synthetic: a random motion of peak ground acceleration `pga` (m/s^2) lasting `synthetic_duration`
  unsigned seed = 1;
  double pga = 3.0;
  double synthetic_duration = 10.0;
  // file: one record per axis (x along the excitation; y, z needed for 3-D)
  RecordFormat format = RecordFormat::at2;
  std::string file_x, file_y, file_z;
  std::optional<AccelerationUnits> units;  // none: the format's own (AT2: g, K-NET and JMA: gal)
  std::optional<double> dt;                // s, for "columns" files without a time column
  // both
  double level = 1.0;                      // scale of the record (0.5 and 1.0 in the paper)
  MotionDimensions dimensions = MotionDimensions::one_d;
  double lowpass_hz = 10.0;                // 0: no filter
  double window_start = 0.0;               // s of record time where the run starts
  std::optional<double> window_end;        // none: the record's end
};

enum class ContactLawKind { paper, paper_anisotropic, spring_dashpot, hunt_crossley, stick_slip };

// Overrides of the contact parameters for one kind of pair (floor, wall or item-item). Unset values
// come from each item's ItemContact (Table 4 or the 0.8 rule).
struct ContactOverrides {
  std::optional<double> alpha_kgf, dc_kgf, q, mu, mu_long, mu_short;  // paper laws
  std::optional<double> stiffness, damping, restitution;             // N/m, N s/m, -
  std::optional<double> mu_static, stick_velocity;                   // stick-slip: -, m/s
};

struct ContactSpec {
  ContactLawKind law = ContactLawKind::paper;
  double velocity_regularisation = 1e-3;  // m/s: v/|v| is smoothed below this speed
  ContactOverrides floor, wall, item;
};

enum class IntegratorKind { paper_newmark, average_acceleration, generalized_alpha };
struct IntegratorSpec {
  IntegratorKind scheme = IntegratorKind::paper_newmark;
  double rho_inf = 0.5;                 // spectral radius at infinity (generalized-alpha)
  bool iterate_to_equilibrium = false;  // false: carry the unbalanced force over, as the paper's code
};

enum class SolverKind { cg, direct };

// A displacement output point: a builder's marker ("desk.top_front_centre") or, with `point` set, the
// node nearest to a point of the item frame.
struct MarkerRequest {
  std::string name;
  std::string item;    // the body's name: an item name, or "<item>/upper" and "<item>/lower"
  std::string marker;  // builder marker name (when point is not set)
  std::optional<Vec3> point;
};

// Sectional forces of one element: item (body name), member name (docs/furniture/furniture.md), element index
// within the member.
struct SectionalForceRequest {
  std::string item;
  std::string member;
  int element = 0;
};

struct OutputSpec {
  std::string folder = "out";  // relative to the run's working folder
  std::vector<MarkerRequest> markers;
  std::vector<SectionalForceRequest> sectional_forces;
  int vtu_every = 0;   // write VTU every N steps; 0: none
  bool figures = true;
};

struct SceneSpec {
  std::string name = "scene";
  TableSpec table;
  std::vector<WallSpec> walls = default_walls();
  std::vector<ObstacleSpec> obstacles;
  std::vector<ItemSpec> items;
  GroundMotionSpec ground_motion;
  ContactSpec contact;
  IntegratorSpec integrator;
  SolverKind solver = SolverKind::direct;
  // Refactorise each body's effective matrix every `refresh_every` s of simulated time (reused in
  // between with the body's rigid turn taken out). 0.1 s (100 steps at dt = 1 ms) is on the
  // speed-against-error front (docs/performance.md section 4): every 20 steps or every step costs 1.3
  // and 8 times as much for the same error. In time, not steps: at dt = 5 ms, 100 steps (0.5 s) lost
  // accuracy that every 0.1 s keeps.
  double refresh_every = 0.1;
  int refresh_interval_steps() const {
    return static_cast<int>(std::clamp(std::lround(refresh_every / dt), 1L, 1000000000L));
  }
  double duration = 10.0;  // s
  double dt = 1e-3;        // s (the paper's 1 ms)
  OutputSpec outputs;
  // Not part of the file: where it came from (error messages) and the folder relative paths are read from.
  std::string source = "<scene>";
  std::string base_dir;

  // A path from the scene file, made usable: relative paths are relative to the scene file's folder.
  std::string resolve(const std::string& path) const {
    if (path.empty() || base_dir.empty() || std::filesystem::path(path).is_absolute()) return path;
    return (std::filesystem::path(base_dir) / path).lexically_normal().string();
  }
};

// ---------------------------------------------------------------------------------------------------
// Names used in scene files
// ---------------------------------------------------------------------------------------------------

namespace detail {
inline constexpr EnumNames<Fidelity, 4> fidelity_names{
    {{Fidelity::full, "full"}, {Fidelity::coarse, "coarse"}, {Fidelity::rigid, "rigid"}, {Fidelity::automatic, "auto"}}};
inline constexpr EnumNames<ItemKind, 8> kind_names = item_kind_names;
inline constexpr EnumNames<MotionSource, 2> source_names{{{MotionSource::synthetic, "synthetic"}, {MotionSource::file, "file"}}};
inline constexpr EnumNames<RecordFormat, 4> format_names{{{RecordFormat::at2, "at2"},
                                                          {RecordFormat::knet, "knet"},
                                                          {RecordFormat::jma_csv, "jma_csv"},
                                                          {RecordFormat::columns, "columns"}}};
inline constexpr EnumNames<MotionDimensions, 2> dimension_names{
    {{MotionDimensions::one_d, "1d"}, {MotionDimensions::three_d, "3d"}}};
inline constexpr EnumNames<AccelerationUnits, 3> unit_names{
    {{AccelerationUnits::g, "g"}, {AccelerationUnits::gal, "gal"}, {AccelerationUnits::m_per_s2, "m/s2"}}};
inline constexpr EnumNames<ContactLawKind, 5> law_names{{{ContactLawKind::paper, "paper"},
                                                         {ContactLawKind::paper_anisotropic, "paper_anisotropic"},
                                                         {ContactLawKind::spring_dashpot, "spring_dashpot"},
                                                         {ContactLawKind::hunt_crossley, "hunt_crossley"},
                                                         {ContactLawKind::stick_slip, "stick_slip"}}};
inline constexpr EnumNames<IntegratorKind, 3> integrator_names{
    {{IntegratorKind::paper_newmark, "paper_newmark"},
     {IntegratorKind::average_acceleration, "average_acceleration"},
     {IntegratorKind::generalized_alpha, "generalized_alpha"}}};
inline constexpr EnumNames<SolverKind, 2> solver_names{{{SolverKind::cg, "cg"}, {SolverKind::direct, "direct"}}};

// Which item parameters a kind accepts.
enum class ParamScope { any, generic, single_body };
struct ItemParamField {
  std::string_view key;
  std::optional<double> ItemParams::*field;
  ParamScope scope;
  double lo, hi;      // accepted range, both included
  bool lo_exclusive;  // (lo, hi] instead
};
inline constexpr std::array<ItemParamField, 17> item_param_fields{{
    {"width", &ItemParams::width, ParamScope::generic, 0.15, 10.0, false},
    {"depth", &ItemParams::depth, ParamScope::generic, 0.15, 10.0, false},
    {"height", &ItemParams::height, ParamScope::generic, 0.15, 10.0, false},
    {"panel_spacing", &ItemParams::panel_spacing, ParamScope::any, 0.02, 5.0, false},
    {"grid_scale", &ItemParams::grid_scale, ParamScope::any, 0.1, 20.0, false},
    {"element_length", &ItemParams::element_length, ParamScope::any, 0.005, 1.0, false},
    {"mass_kg", &ItemParams::mass_kg, ParamScope::single_body, 0.0, 1e4, true},
    {"cog_h", &ItemParams::cog_h, ParamScope::single_body, 0.0, 10.0, true},
    {"cog_d1", &ItemParams::cog_d1, ParamScope::single_body, 0.0, 10.0, true},
    {"mu_static_long", &ItemParams::mu_static_long, ParamScope::generic, 0.0, 5.0, false},
    {"mu_static_short", &ItemParams::mu_static_short, ParamScope::generic, 0.0, 5.0, false},
    {"alpha_kgf", &ItemParams::alpha_kgf, ParamScope::any, 0.0, 1e6, true},
    {"dc_kgf", &ItemParams::dc_kgf, ParamScope::any, 0.0, 1e6, false},
    {"mu_floor_long", &ItemParams::mu_floor_long, ParamScope::any, 0.0, 5.0, false},
    {"mu_floor_short", &ItemParams::mu_floor_short, ParamScope::any, 0.0, 5.0, false},
    {"mu_wall", &ItemParams::mu_wall, ParamScope::any, 0.0, 5.0, false},
    {"mu_item", &ItemParams::mu_item, ParamScope::any, 0.0, 5.0, false},
}};

// Which contact override a law reads: a value the chosen law ignores is a mistake worth reporting.
struct ContactField {
  std::string_view key;
  std::optional<double> ContactOverrides::*field;
  double lo, hi;
  bool lo_exclusive;
  std::array<bool, 5> used_by;  // paper, paper_anisotropic, spring_dashpot, hunt_crossley, stick_slip
  bool floor_only;
};
inline constexpr std::array<ContactField, 11> contact_fields{{
    {"alpha_kgf", &ContactOverrides::alpha_kgf, 0.0, 1e6, true, {true, true, false, false, true}, false},
    {"dc_kgf", &ContactOverrides::dc_kgf, 0.0, 1e6, false, {true, true, false, false, true}, false},
    {"q", &ContactOverrides::q, 0.0, 10.0, true, {true, true, false, true, true}, false},
    {"mu", &ContactOverrides::mu, 0.0, 5.0, false, {true, true, true, true, true}, false},
    {"mu_long", &ContactOverrides::mu_long, 0.0, 5.0, false, {true, true, true, true, true}, true},
    {"mu_short", &ContactOverrides::mu_short, 0.0, 5.0, false, {true, true, true, true, true}, true},
    {"stiffness", &ContactOverrides::stiffness, 0.0, 1e12, true, {false, false, true, true, false}, false},
    {"damping", &ContactOverrides::damping, 0.0, 1e12, false, {false, false, true, false, false}, false},
    {"restitution", &ContactOverrides::restitution, 0.0, 1.0, false, {false, false, false, true, false}, false},
    {"mu_static", &ContactOverrides::mu_static, 0.0, 5.0, false, {false, false, false, false, true}, false},
    {"stick_velocity", &ContactOverrides::stick_velocity, 0.0, 10.0, true, {false, false, false, false, true}, false},
}};

inline bool param_applies(ParamScope scope, ItemKind kind) {
  switch (scope) {
    case ParamScope::any: return true;
    case ParamScope::generic: return !is_paper_item(kind);
    case ParamScope::single_body: return kind != ItemKind::separated_cabinets;
  }
  return false;
}

inline void read_range(const ObjectReader& r, std::string_view key, double lo, double hi, bool lo_exclusive) {
  if (!r.has(key)) return;
  const double v = r.raw(key).get<double>();
  r.require((lo_exclusive ? v > lo : v >= lo) && v <= hi, key,
            std::string("must lie in ") + (lo_exclusive ? "(" : "[") + fmt(lo) + ", " + fmt(hi) + "]");
}

// ---- parsing ----

inline ItemParams parse_item_params(const ObjectReader& r, ItemKind kind) {
  ItemParams p;
  std::vector<std::string_view> allowed{"shelves"};
  for (const auto& f : item_param_fields) allowed.push_back(f.key);
  r.allow_only(allowed, "item parameter");
  auto read = [&](const ItemParamField& f) {
    if (!r.has(f.key)) return;
    if (!param_applies(f.scope, kind))
      r.fail(r.path(f.key), "not a parameter of kind \"" + to_string(kind) + "\"" +
                                (f.scope == ParamScope::generic ? " (Table 2 fixes the paper items)"
                                                                : " (two bodies: each cabinet follows Table 2)"));
    p.*(f.field) = r.optional_number(f.key);
    read_range(r, f.key, f.lo, f.hi, f.lo_exclusive);
  };
  for (const auto& f : item_param_fields) read(f);
  if (r.has("shelves")) {
    if (kind != ItemKind::bookshelf) r.fail(r.path("shelves"), "only a bookshelf has a shelf count");
    const long long n = *r.optional_integer("shelves");
    r.require(n >= 0 && n <= 50, "shelves", "must lie in [0, 50]");
    p.shelves = static_cast<int>(n);
  }
  return p;
}

inline ContactOverrides parse_contact_overrides(const ObjectReader& r, ContactLawKind law, bool is_floor) {
  ContactOverrides o;
  std::vector<std::string_view> allowed;
  for (const auto& f : contact_fields)
    if (is_floor || !f.floor_only) allowed.push_back(f.key);
  r.allow_only(allowed, "contact parameter");
  for (const auto& f : contact_fields) {
    if (!r.has(f.key)) continue;
    if (!f.used_by[static_cast<size_t>(law)])
      r.fail(r.path(f.key), "not used by the contact law \"" + enum_name(law_names, law) + "\"");
    o.*(f.field) = r.optional_number(f.key);
    read_range(r, f.key, f.lo, f.hi, f.lo_exclusive);
  }
  return o;
}

}  // namespace detail

// ---------------------------------------------------------------------------------------------------
// Sizes, building
// ---------------------------------------------------------------------------------------------------

// Outer size (W, D, H) of an item as it will be built: Table 2 for the paper's items (the separated
// cabinets stacked: H = 1120 + 730 mm), the parameters or these defaults for generic ones.
inline Vec3 item_size(const ItemSpec& item) {
  const auto paper = [](PaperItem p) {
    const auto& r = paper_item(p);
    return Vec3(r.W, r.D, r.H);
  };
  Vec3 fallback = Vec3::Zero();
  switch (item.kind) {
    case ItemKind::tall_cabinet: return paper(PaperItem::tall_cabinet);
    case ItemKind::separated_cabinets:
      return paper(PaperItem::lower_separated_cabinet) + Vec3(0, 0, paper_item(PaperItem::upper_separated_cabinet).H);
    case ItemKind::side_table: return paper(PaperItem::side_table);
    case ItemKind::desk: return paper(PaperItem::desk);
    case ItemKind::office_chair: return paper(PaperItem::office_chair);
    case ItemKind::bookshelf: fallback = Vec3(0.9, 0.3, 1.8); break;
    case ItemKind::locker: fallback = Vec3(0.9, 0.515, 1.79); break;
    case ItemKind::table: fallback = Vec3(1.2, 0.75, 0.72); break;
  }
  return {item.params.width.value_or(fallback.x()), item.params.depth.value_or(fallback.y()),
          item.params.height.value_or(fallback.z())};
}
inline constexpr int default_bookshelf_shelves = 4;

// Builds item `index` of the scene into `model`: one ItemInfo per body (the separated cabinets give
// "<name>/lower" then "<name>/upper"), with the item's contact overrides applied.
inline std::vector<ItemInfo> build_item(const SceneSpec& scene, size_t index, Model& model) {
  const ItemSpec& item = scene.items.at(index);
  const ItemParams& p = item.params;
  BuildOptions o;
  o.name = item.name;
  o.fidelity = item.fidelity;
  o.grid_scale = p.grid_scale.value_or(o.grid_scale);
  o.element_length = p.element_length.value_or(o.element_length);
  o.panel_spacing = p.panel_spacing;
  o.mass_kg = p.mass_kg;
  o.cog_h = p.cog_h;
  o.cog_d1 = p.cog_d1;
  o.mu_static_long = p.mu_static_long;
  o.mu_static_short = p.mu_static_short;
  const Placement at = Placement::at(item.x, item.y, item.yaw_deg, scene.table.floor_z);
  const Vec3 size = item_size(item);
  std::vector<ItemInfo> out;
  switch (item.kind) {
    case ItemKind::tall_cabinet: out.push_back(build_tall_cabinet(model, at, o)); break;
    case ItemKind::separated_cabinets: {
      auto pair = build_separated_cabinets(model, at, o);
      out.push_back(std::move(pair.lower));
      out.push_back(std::move(pair.upper));
      break;
    }
    case ItemKind::side_table: out.push_back(build_side_table(model, at, o)); break;
    case ItemKind::desk: out.push_back(build_desk(model, at, o)); break;
    case ItemKind::office_chair: out.push_back(build_office_chair(model, at, o)); break;
    case ItemKind::bookshelf:
      out.push_back(build_bookshelf(model, at, size.x(), size.y(), size.z(), p.shelves.value_or(default_bookshelf_shelves), o));
      break;
    case ItemKind::locker: out.push_back(build_locker(model, at, size.x(), size.y(), size.z(), o)); break;
    case ItemKind::table: out.push_back(build_table(model, at, size.x(), size.y(), size.z(), o)); break;
  }
  for (auto& info : out) {
    auto& c = info.contact;
    if (p.alpha_kgf) c.alpha = *p.alpha_kgf * newtons_per_kgf;
    if (p.dc_kgf) c.Dc = *p.dc_kgf * newtons_per_kgf;
    if (p.mu_floor_long) c.mu_floor_long = *p.mu_floor_long;
    if (p.mu_floor_short) c.mu_floor_short = *p.mu_floor_short;
    if (p.mu_wall) c.mu_wall = *p.mu_wall;
    if (p.mu_item) c.mu_item = *p.mu_item;
  }
  return out;
}

// All items of the scene as bodies of one Model, in the order of the scene's items.
inline std::vector<ItemInfo> build_scene(const SceneSpec& scene, Model& model) {
  std::vector<ItemInfo> infos;
  for (size_t i = 0; i < scene.items.size(); ++i)
    for (auto& info : build_item(scene, i, model)) infos.push_back(std::move(info));
  return infos;
}

// ---------------------------------------------------------------------------------------------------
// JSON
// ---------------------------------------------------------------------------------------------------

namespace detail {

inline ItemSpec parse_item(const json& v, const std::string& path, const std::string& source) {
  ObjectReader r(v, path, source);
  r.allow_only({"name", "kind", "x", "y", "yaw_deg", "fidelity", "params"});
  ItemSpec item;
  if (!r.has("kind")) r.fail(r.path("kind"), "required; one of: " + enum_choices(kind_names));
  item.kind = r.enumeration("kind", kind_names, ItemKind::tall_cabinet, "item kind");
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
  if (r.has("params")) item.params = parse_item_params(r.object("params"), item.kind);
  return item;
}

inline void parse_ground_motion(const ObjectReader& r, GroundMotionSpec& g) {
  g.source = r.enumeration("source", source_names, MotionSource::synthetic, "ground motion source");
  const bool synthetic = g.source == MotionSource::synthetic;
  const std::vector<std::string_view> common{"source", "level", "dimensions", "lowpass_hz", "window"};
  const std::vector<std::string_view> only_synthetic{"seed", "pga", "duration"};
  const std::vector<std::string_view> only_file{"format", "files", "units", "dt"};
  for (auto key : synthetic ? only_file : only_synthetic)
    if (r.has(key))
      r.fail(r.path(key), std::string("only used with source \"") + (synthetic ? "file" : "synthetic") + "\"");
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
  if (synthetic) {
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
  if (g.dimensions == MotionDimensions::three_d)
    for (auto [key, file] : {std::pair{"y", &g.file_y}, std::pair{"z", &g.file_z}})
      if (file->empty()) files.fail(files.path(key), "required for dimensions \"3d\"");
  if (r.has("units")) g.units = r.enumeration("units", unit_names, AccelerationUnits::g, "acceleration unit");
  g.dt = r.optional_number("dt");
  r.positive("dt");
}

inline json overrides_to_json(const ContactOverrides& o) {
  json j = json::object();
  for (const auto& f : contact_fields)
    if (o.*(f.field)) j[std::string(f.key)] = *(o.*(f.field));
  return j;
}

}  // namespace detail

// Reads a scene from parsed JSON. `source_name` names it in error messages (a file name).
inline SceneSpec parse_scene_json(const nlohmann::json& j, const std::string& source_name) {
  using detail::ObjectReader;
  const std::string source = source_name;
  SceneSpec s;
  s.source = source;
  const ObjectReader r(j, "", source);
  r.allow_only({"name", "table", "walls", "obstacles", "items", "ground_motion", "contact", "integrator", "solver",
                "refresh_every", "duration", "dt", "outputs"});
  s.name = r.string("name", s.name);

  if (r.has("table")) {
    const ObjectReader t = r.object("table");
    t.allow_only({"size_x", "size_y", "floor_z"});
    s.table.size_x = t.number("size_x", s.table.size_x);
    s.table.size_y = t.number("size_y", s.table.size_y);
    s.table.floor_z = t.number("floor_z", s.table.floor_z);
    t.positive("size_x");
    t.positive("size_y");
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
      wall.normal = w.vec3("normal", wall.normal);
      if (std::abs(wall.normal.z()) > 1e-12 || wall.normal.norm() < 1e-12)
        w.fail(w.path("normal"), "must be a non-zero horizontal vector (walls are vertical), got [" +
                                     detail::fmt(wall.normal.x()) + ", " + detail::fmt(wall.normal.y()) + ", " +
                                     detail::fmt(wall.normal.z()) + "]");
      wall.normal.normalize();
      wall.height = w.number("height", wall.height);
      wall.width = w.number("width", wall.width);
      w.positive("height");
      w.positive("width");
      s.walls.push_back(wall);
    });
  }

  r.array("obstacles", [&](const nlohmann::json& v, const std::string& path) {
    const ObjectReader o(v, path, source);
    o.allow_only({"name", "file", "position", "yaw_deg", "scale"});
    ObstacleSpec ob;
    ob.name = o.string("name", "obstacle_" + std::to_string(s.obstacles.size() + 1));
    if (!o.has("file")) o.fail(o.path("file"), "required: an STL or OBJ mesh file");
    ob.file = *o.optional_string("file");
    const std::string ext = std::filesystem::path(ob.file).extension().string();
    if (ext != ".stl" && ext != ".STL" && ext != ".obj" && ext != ".OBJ")
      o.fail(o.path("file"), "expected an .stl or .obj mesh file, got \"" + ob.file + "\"");
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
    c.allow_only({"law", "velocity_regularisation", "floor", "wall", "item"});
    s.contact.law = c.enumeration("law", detail::law_names, s.contact.law, "contact law");
    s.contact.velocity_regularisation = c.number("velocity_regularisation", s.contact.velocity_regularisation);
    c.positive("velocity_regularisation");
    if (c.has("floor")) s.contact.floor = detail::parse_contact_overrides(c.object("floor"), s.contact.law, true);
    if (c.has("wall")) s.contact.wall = detail::parse_contact_overrides(c.object("wall"), s.contact.law, false);
    if (c.has("item")) s.contact.item = detail::parse_contact_overrides(c.object("item"), s.contact.law, false);
  }

  if (r.has("integrator")) {
    const ObjectReader in = r.object("integrator");
    in.allow_only({"scheme", "rho_inf", "iterate_to_equilibrium"});
    s.integrator.scheme = in.enumeration("scheme", detail::integrator_names, s.integrator.scheme, "integrator");
    s.integrator.rho_inf = in.number("rho_inf", s.integrator.rho_inf);
    in.in_range("rho_inf", 0, 1);
    s.integrator.iterate_to_equilibrium = in.boolean("iterate_to_equilibrium", s.integrator.iterate_to_equilibrium);
  }
  s.solver = r.enumeration("solver", detail::solver_names, s.solver, "solver");
  s.refresh_every = r.number("refresh_every", s.refresh_every);
  r.positive("refresh_every");
  s.duration = r.number("duration", s.duration);
  r.positive("duration");
  s.dt = r.number("dt", s.dt);
  r.positive("dt");
  if (r.has("dt")) r.require(s.dt <= s.duration, "dt", "must not exceed duration (" + detail::fmt(s.duration) + " s)");

  if (r.has("outputs")) {
    const ObjectReader o = r.object("outputs");
    o.allow_only({"folder", "markers", "sectional_forces", "vtu_every", "figures"});
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
  }
  return s;
}

// Reads a scene file. JSON syntax errors report the line; relative paths inside the file are taken
// relative to the file's folder (SceneSpec::resolve).
inline SceneSpec parse_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open the scene file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    const auto upto = text.begin() + static_cast<std::ptrdiff_t>(std::min(text.size(), static_cast<size_t>(e.byte)));
    const long line = 1 + std::count(text.begin(), upto, '\n');
    throw InputError(path, line, "", std::string("not valid JSON: ") + e.what());
  }
  SceneSpec s = parse_scene_json(j, path);
  s.base_dir = std::filesystem::path(path).parent_path().string();
  return s;
}

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
    for (const auto& f : detail::item_param_fields)
      if (it.params.*(f.field)) params[std::string(f.key)] = *(it.params.*(f.field));
    if (it.params.shelves) params["shelves"] = *it.params.shelves;
    if (!params.empty()) item["params"] = params;
    j["items"].push_back(item);
  }
  const auto& g = s.ground_motion;
  json gm = {{"source", enum_name(detail::source_names, g.source)},
             {"level", g.level},
             {"dimensions", enum_name(detail::dimension_names, g.dimensions)},
             {"lowpass_hz", g.lowpass_hz}};
  gm["window"] = {{"start", g.window_start}};
  if (g.window_end) gm["window"]["end"] = *g.window_end;
  if (g.source == MotionSource::synthetic) {
    gm["seed"] = g.seed;
    gm["pga"] = g.pga;
    gm["duration"] = g.synthetic_duration;
  } else {
    gm["format"] = enum_name(detail::format_names, g.format);
    gm["files"] = {{"x", g.file_x}};
    if (!g.file_y.empty()) gm["files"]["y"] = g.file_y;
    if (!g.file_z.empty()) gm["files"]["z"] = g.file_z;
    if (g.units) gm["units"] = enum_name(detail::unit_names, *g.units);
    if (g.dt) gm["dt"] = *g.dt;
  }
  j["ground_motion"] = gm;
  json contact = {{"law", enum_name(detail::law_names, s.contact.law)},
                  {"velocity_regularisation", s.contact.velocity_regularisation}};
  for (auto [key, o] : {std::pair{"floor", &s.contact.floor}, std::pair{"wall", &s.contact.wall},
                        std::pair{"item", &s.contact.item}}) {
    const json ov = detail::overrides_to_json(*o);
    if (!ov.empty()) contact[key] = ov;
  }
  j["contact"] = contact;
  j["integrator"] = {{"scheme", enum_name(detail::integrator_names, s.integrator.scheme)},
                     {"rho_inf", s.integrator.rho_inf},
                     {"iterate_to_equilibrium", s.integrator.iterate_to_equilibrium}};
  j["solver"] = enum_name(detail::solver_names, s.solver);
  j["refresh_every"] = s.refresh_every;
  j["duration"] = s.duration;
  j["dt"] = s.dt;
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
  return j;
}

// Writes the scene as an indented JSON file.
inline void write_scene(const SceneSpec& s, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw InputError(path, 0, "", "cannot write the scene file");
  out << to_json(s).dump(2) << '\n';
}

// ---------------------------------------------------------------------------------------------------
// Validation
// ---------------------------------------------------------------------------------------------------

namespace detail {

// Footprint of an item on the table: centre, unit axes along its width and depth, half extents.
struct Footprint {
  Eigen::Vector2d centre, u, v;
  double half_w = 0, half_d = 0;
  std::array<Eigen::Vector2d, 4> corners() const {
    return {centre - half_w * u - half_d * v, centre + half_w * u - half_d * v, centre + half_w * u + half_d * v,
            centre - half_w * u + half_d * v};
  }
};

inline Footprint footprint(const ItemSpec& item) {
  const double yaw = item.yaw_deg * std::numbers::pi / 180.0;
  const Vec3 size = item_size(item);
  return {Eigen::Vector2d(item.x, item.y), Eigen::Vector2d(std::cos(yaw), std::sin(yaw)),
          Eigen::Vector2d(-std::sin(yaw), std::cos(yaw)), 0.5 * size.x(), 0.5 * size.y()};
}

// Depth of overlap of two footprints (separating axes); <= 0 when they are apart or only touch.
inline double overlap_depth(const Footprint& a, const Footprint& b) {
  double depth = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& axis : {a.u, a.v, b.u, b.v}) {
    const double ra = a.half_w * std::abs(a.u.dot(axis)) + a.half_d * std::abs(a.v.dot(axis));
    const double rb = b.half_w * std::abs(b.u.dot(axis)) + b.half_d * std::abs(b.v.dot(axis));
    depth = std::min(depth, ra + rb - std::abs((b.centre - a.centre).dot(axis)));
  }
  return depth;
}

}  // namespace detail

// Checks what parsing alone cannot: item names, items inside the table, clear of the walls and of
// each other; record and mesh files present; markers and sectional-force elements that exist on the
// built items; and that every item can be built (mass and centre-of-gravity targets reachable).
// Throws InputError naming the key path and the item.
inline void validate(const SceneSpec& s) {
  const auto fail = [&](const std::string& path, const std::string& message) {
    throw InputError(s.source, 0, path, message);
  };
  const auto item_label = [&](size_t i) { return "item '" + s.items[i].name + "'"; };
  if (!(s.dt > 0) || !(s.duration > 0) || s.dt > s.duration)
    fail("dt", "must be positive and not exceed duration (dt = " + detail::fmt(s.dt) +
                   " s, duration = " + detail::fmt(s.duration) + " s)");
  if (s.ground_motion.level < 0) fail("ground_motion.level", "must not be negative (got " + detail::fmt(s.ground_motion.level) + ")");
  if (s.items.empty()) fail("items", "a scene needs at least one item");

  std::set<std::string> names;
  for (size_t i = 0; i < s.items.size(); ++i) {
    const std::string path = "items[" + std::to_string(i) + "]";
    const auto& item = s.items[i];
    if (item.name.empty() || item.name.find_first_of("./") != std::string::npos)
      fail(path + ".name", "must be non-empty and hold no '.' or '/' (got \"" + item.name + "\")");
    if (!names.insert(item.name).second) fail(path + ".name", "duplicate item name \"" + item.name + "\"");
    const Vec3 size = item_size(item);
    if (item.params.cog_h && *item.params.cog_h >= size.z())
      fail(path + ".params.cog_h", "must lie below the item's height " + detail::fmt(size.z()) + " m (got " +
                                       detail::fmt(*item.params.cog_h) + ")");
    if (item.params.cog_d1 && *item.params.cog_d1 >= size.y())
      fail(path + ".params.cog_d1", "must lie within the item's depth " + detail::fmt(size.y()) + " m (got " +
                                        detail::fmt(*item.params.cog_d1) + ")");
    const auto fp = detail::footprint(item);
    const double hx = 0.5 * s.table.size_x, hy = 0.5 * s.table.size_y, tol = 1e-9;
    for (const auto& c : fp.corners())
      if (std::abs(c.x()) > hx + tol || std::abs(c.y()) > hy + tol)
        fail(path, item_label(i) + " lies partly outside the " + detail::fmt(s.table.size_x) + " m x " +
                       detail::fmt(s.table.size_y) + " m table: its footprint corner (" + detail::fmt(c.x()) + ", " +
                       detail::fmt(c.y()) + ") m is off the table");
    for (const auto& wall : s.walls) {
      const Eigen::Vector2d n = wall.normal.head<2>().normalized(), p = wall.point.head<2>();
      const Eigen::Vector2d t(-n.y(), n.x());
      for (const auto& c : fp.corners()) {
        const double inside = (c - p).dot(n), along = (c - p).dot(t);
        if (inside < -tol && std::abs(along) <= 0.5 * wall.width + tol)
          fail(path, item_label(i) + " passes through wall '" + wall.name + "' by " + detail::fmt(-inside) + " m");
      }
    }
    for (size_t k = 0; k < i; ++k) {
      const double depth = detail::overlap_depth(detail::footprint(s.items[k]), fp);
      if (depth > 1e-6)
        fail(path, item_label(i) + " and " + item_label(k) + " (items[" + std::to_string(k) +
                       "]) overlap: their footprints intersect by " + detail::fmt(depth) + " m");
    }
  }

  const auto& g = s.ground_motion;
  if (g.source == MotionSource::file) {
    for (auto [key, file] : {std::pair{"x", &g.file_x}, std::pair{"y", &g.file_y}, std::pair{"z", &g.file_z}}) {
      if (file->empty()) {
        if (std::string(key) == "x" || g.dimensions == MotionDimensions::three_d)
          fail(std::string("ground_motion.files.") + key, "required (dimensions \"" +
                                                              detail::enum_name(detail::dimension_names, g.dimensions) + "\")");
        continue;
      }
      if (!std::filesystem::is_regular_file(s.resolve(*file)))
        fail(std::string("ground_motion.files.") + key, "record file not found: \"" + s.resolve(*file) + "\"");
    }
  }
  if (g.window_end && *g.window_end <= g.window_start)
    fail("ground_motion.window.end", "must be later than window.start (" + detail::fmt(g.window_start) + " s)");
  for (size_t i = 0; i < s.obstacles.size(); ++i)
    if (!std::filesystem::is_regular_file(s.resolve(s.obstacles[i].file)))
      fail("obstacles[" + std::to_string(i) + "].file", "mesh file not found: \"" + s.resolve(s.obstacles[i].file) + "\"");

  // Build every item once: it proves the calibration targets reachable and gives markers and members.
  Model scratch;
  std::map<std::string, ItemInfo> bodies;
  for (size_t i = 0; i < s.items.size(); ++i) {
    try {
      for (auto& info : build_item(s, i, scratch)) bodies.emplace(info.name, std::move(info));
    } catch (const ModelError& e) {
      fail("items[" + std::to_string(i) + "]", item_label(i) + " cannot be built: " + e.what());
    }
  }
  const auto body_names = [&] {
    std::string list;
    for (const auto& [name, info] : bodies) list += (list.empty() ? "" : ", ") + name;
    return list;
  };
  for (size_t k = 0; k < s.outputs.markers.size(); ++k) {
    const auto& m = s.outputs.markers[k];
    const std::string path = "outputs.markers[" + std::to_string(k) + "]";
    const auto it = bodies.find(m.item);
    if (it == bodies.end())
      fail(path, "marker \"" + m.name + "\" is on no item: \"" + m.item + "\" is not one of: " + body_names());
    if (!m.point && !it->second.marker(m.marker)) {
      std::string list;
      for (const auto& mk : it->second.markers) list += (list.empty() ? "" : ", ") + mk.name;
      fail(path, "item \"" + m.item + "\" has no marker \"" + m.marker + "\"; its markers: " + list);
    }
  }
  for (size_t k = 0; k < s.outputs.sectional_forces.size(); ++k) {
    const auto& f = s.outputs.sectional_forces[k];
    const std::string path = "outputs.sectional_forces[" + std::to_string(k) + "]";
    const auto it = bodies.find(f.item);
    if (it == bodies.end()) fail(path + ".item", "\"" + f.item + "\" is not one of: " + body_names());
    const int member = find_member(scratch, it->second.body, f.member);
    if (member < 0) fail(path + ".member", "item \"" + f.item + "\" has no member \"" + f.member + "\"");
    if (f.element >= scratch.member(member).element_count)
      fail(path + ".element", "member \"" + f.member + "\" has " + std::to_string(scratch.member(member).element_count) +
                                  " elements (got index " + std::to_string(f.element) + ")");
  }
}

// ---------------------------------------------------------------------------------------------------
// The paper's configurations (section 3; Figure 7's drawings are not available: docs/furniture/furniture.md
// gives the coordinates chosen and why)
// ---------------------------------------------------------------------------------------------------

// Configuration k = 1, 2 or 3 on the 4 m x 4 m table with walls at x = -2 and x = +2, excited by the
// JMA-Kobe record (PEER RSN1106: NS along X) at 100 %, 1-D, low-passed at 10 Hz, over record time
// 4-16 s. `records_dir` is where the AT2 files are (relative paths: relative to the working folder).
inline SceneSpec configuration(int k, const std::string& records_dir = "../shared/ground_motions") {
  if (k < 1 || k > 3)
    throw InputError("configuration", 0, "k", "the paper has configurations 1, 2 and 3 (got " + std::to_string(k) + ")");
  SceneSpec s;
  s.name = "configuration " + std::to_string(k);
  s.source = s.name;
  // Cabinets: backs 30 mm from the wall at x = +2, fronts towards -X (yaw -90 deg puts the item's
  // front, -y, on -X and its width along -Y).
  const double wall_gap = 0.03, cabinet_x = 2.0 - wall_gap - 0.5 * paper_item(PaperItem::tall_cabinet).D;
  const ItemSpec tall{"tall_cabinet", ItemKind::tall_cabinet, cabinet_x, -0.5, -90.0, Fidelity::full, {}};
  const ItemSpec pair{"separated_cabinets", ItemKind::separated_cabinets, cabinet_x, 0.5, -90.0, Fidelity::full, {}};
  // Centre group: desk with its depth along X, front towards the chair on the -X side; side table
  // with its casters (longer edge) along X. Gaps exceed the heights of the items that could fall
  // into them (configuration 2's clearances).
  const ItemSpec desk{"desk", ItemKind::desk, 0.6, 0.0, -90.0, Fidelity::full, {}};
  const ItemSpec side{"side_table", ItemKind::side_table, 0.6, -1.45, 0.0, Fidelity::full, {}};
  const ItemSpec chair{"office_chair", ItemKind::office_chair, -0.82, 0.0, 90.0, Fidelity::full, {}};
  if (k == 1 || k == 3) s.items = {tall, pair};
  if (k == 2 || k == 3) s.items.insert(s.items.end(), {side, desk, chair});

  auto& g = s.ground_motion;
  g.source = MotionSource::file;
  g.format = RecordFormat::at2;
  const std::string dir = records_dir.empty() || records_dir.back() == '/' ? records_dir : records_dir + "/";
  g.file_x = dir + "jma_kobe_1995_NS_PEER_RSN1106_KJM000.AT2";
  g.file_y = dir + "jma_kobe_1995_EW_PEER_RSN1106_KJM090.AT2";
  g.file_z = dir + "jma_kobe_1995_UD_PEER_RSN1106_KJM-UP.AT2";
  g.level = 1.0;
  g.dimensions = MotionDimensions::one_d;
  g.lowpass_hz = 10.0;
  g.window_start = 4.0;
  g.window_end = 16.0;
  s.duration = 12.0;
  s.dt = 1e-3;
  s.contact.law = ContactLawKind::paper_anisotropic;
  s.integrator = {IntegratorKind::paper_newmark, 0.5, false};
  s.solver = SolverKind::direct;
  s.outputs.folder = "out/configuration_" + std::to_string(k);
  s.outputs.vtu_every = 100;
  const auto marker = [](const std::string& item, const std::string& name) {
    return MarkerRequest{item + "." + name, item, name, std::nullopt};
  };
  // The paper's evaluation points (Figures 16-18): the upper separated cabinet, the desk, the chair.
  if (k == 1 || k == 3) s.outputs.markers.push_back(marker("separated_cabinets/upper", "top_front_centre"));
  if (k == 1) s.outputs.markers.push_back(marker("tall_cabinet", "top_front_centre"));
  if (k == 2 || k == 3) {
    s.outputs.markers.push_back(marker("desk", "top_back_centre"));
    s.outputs.markers.push_back(marker("office_chair", "seat_centre"));
    // Figure 19: shear in the top board element next to the desk's evaluation point, on the edge
    // the falling tall cabinet strikes (the desk's back, facing the cabinets).
    Model scratch;
    const ItemInfo built = build_desk(scratch);
    const auto [member, element] = element_near(scratch, built, built.marker("top_back_centre")->local_point);
    s.outputs.sectional_forces.push_back({"desk", member, element});
  }
  return s;
}

}  // namespace furniture_fem
