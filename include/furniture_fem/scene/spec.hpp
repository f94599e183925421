#pragma once
// furniture_fem/scene/spec.hpp: what a run simulates, as plain data: the shake table, its walls and
// ceiling, mesh obstacles, the furniture items and where they stand, the ground motion, the contact law,
// the time integration, and what to write out. Read from JSON by scene/reader.hpp (docs/scene/scene_file.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "../core/model.hpp"
#include "../furniture/furniture.hpp"
#include "../harm/strike.hpp"
#include "../restraints/restraint.hpp"

namespace furniture_fem {

// ---------------------------------------------------------------------------------------------------
// The scene description
// ---------------------------------------------------------------------------------------------------

// How far a scene reaches from the table's centre (m, each coordinate): the floor's height, the table's
// half-size, walls, obstacles and marker points. A room is metres across; far beyond it lengths and
// areas are lost to rounding (a floor_z of 1e300 failed as a "zero-length member").
inline constexpr double scene_reach = 1e4;

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

// A rigid horizontal ceiling over the whole room, `height` (m) above the table's floor, facing down. Its
// contact with the items takes the walls' parameters (docs/contact/contact.md, "The ceiling").
struct CeilingSpec {
  double height = 2.5;
};

// A rigid obstacle given by a triangle mesh file (STL, OBJ or OFF), placed like an item.
struct ObstacleSpec {
  std::string name;
  std::string file;
  Vec3 position = Vec3::Zero();
  double yaw_deg = 0;
  double scale = 1;
};

// Per-item parameters (docs/scene/scene_file.md, table made by item_parameter_tables()). Those every kind
// takes (mesh, mass, contact) are fields; a kind's own (a bookshelf's width, its shelves...) are
// declared by the kind (furniture/item_kinds.hpp) and kept by key, only those the file gives.
struct ItemParams {
  std::optional<double> panel_spacing, grid_scale, element_length;  // m, -, m
  std::optional<double> mass_kg, cog_h, cog_d1;                      // kg, m, m; single-body kinds only
  std::optional<double> alpha_kgf, dc_kgf, mu_floor_long, mu_floor_short, mu_wall, mu_item;  // ItemContact
  // Factors on the values above as built (given or default): every mass of the item (its centre of
  // gravity kept), every friction coefficient (floor, wall, item), the penalty alpha. For studies that
  // perturb an item without knowing its kind's defaults (docs/study/studies.md).
  std::optional<double> mass_scale, friction_scale, alpha_scale;
  // A factor on the Young's modulus of the item's members (BuildOptions::stiffness_scale): finite-element
  // items only, since a rigid one has no stiffness to scale.
  std::optional<double> stiffness_scale;
  std::map<std::string, double> kind_values;                         // the kind's own parameters
};

struct ItemSpec {
  std::string name;  // unique; marker and output references use it
  ItemKind kind = ItemKind::tall_cabinet;
  double x = 0, y = 0;  // footprint centre on the table (m)
  double yaw_deg = 0;   // counter-clockwise seen from above; 0: width along X, front towards -Y
  Fidelity fidelity = Fidelity::full;
  ItemParams params;
};

// A fastening device (docs/restraints/restraints.md): `kind` between the named point `point` of the body
// `item` (furniture/named_points.hpp; an item's name, or "<item>/upper" and "<item>/lower") and its
// anchor: an l_bracket or a strap on the wall `wall` at `height` above the floor (none: the point's
// height) or to the named point `anchor_point` of another body `anchor_item`, a mat on the floor under
// the point, a pole against the ceiling above it, a stopper under it. `values`: the kind's parameters
// the file gives (key -> value, SI; the others take the kind's defaults).
struct RestraintSpec {
  std::string name;
  RestraintKind kind = RestraintKind::l_bracket;
  std::string item, point;
  std::string wall;               // l_bracket and strap
  std::optional<double> height;   // m above the floor; l_bracket and strap
  std::string anchor_item, anchor_point;  // l_bracket and strap joining two items, instead of a wall
  ScrewBase screws = ScrewBase::stud;  // l_bracket: what its screws go into (sets its strengths' defaults)
  std::map<std::string, double> values;
};

// An escape route (docs/harm/harm.md, "Exits"): a polyline on the floor (m, the table's axes; two or more
// points on the table) and the clear width it needs (m). Each cross-section counts up to a wall or the
// table's edge, or only `side_reach` (m) to each side of the path when given.
struct ExitSpec {
  static constexpr double default_width = 0.75;  // m (docs/harm/harm.md: the rules that bracket it)
  std::string name;
  std::vector<Eigen::Vector2d> path;
  double width = default_width;
  std::optional<double> side_reach;
};

enum class MotionSource { synthetic, file, points };
enum class RecordFormat { at2, knet, jma_csv, columns };
enum class MotionDimensions { one_d, three_d };
enum class AccelerationUnits { g, gal, m_per_s2 };

// ground_motion.scale_to: the record scaled (every component by one factor) so that its horizontal peak
// acceleration (pga, m/s^2) or peak velocity (pgv, m/s; trapezoid from rest) is `value`, or its JMA
// instrumental intensity (jma; excitation/seismic_intensity.hpp) is. The peak is the largest absolute
// value over the horizontal components the run uses (x, and y for 3-D); the intensity is that of every
// component the run uses (x; x, y and z for 3-D); both on the record as the run gets it (windowed and
// low-passed). `level` multiplies after the scaling.
enum class ScaleMeasure { pga, pgv, jma };
struct ScaleTarget {
  ScaleMeasure measure = ScaleMeasure::pga;
  double value = 0;  // m/s^2 (pga), m/s (pgv) or the intensity (jma); positive
};

// The plausible band of a record's peak acceleration, in g, read with its declared unit: outside it the
// unit is probably wrong (a record in gal read as g peaks near 1000 g). GroundMotionSpec::check_pga.
inline constexpr double plausible_pga_min_g = 0.0005, plausible_pga_max_g = 5.0;

// ground_motion.building: the table is the floor of storey `storey` of a linear shear building
// (excitation/building.hpp): its horizontal components are that floor's absolute acceleration under
// the ground motion (after window, filter, scale_to and level), its vertical one the ground's. Either a
// uniform building (storeys and period_s; its floor mass cancels out of the floor's acceleration, so
// none is asked) or per-storey floor_mass and storey_stiffness, bottom up. docs/excitation/building.md.
struct BuildingSpec {
  int storeys = 0;          // uniform: N (0: per-storey arrays instead)
  double period_s = 0;      // uniform: the first mode's period T1 (s)
  std::vector<double> floor_mass, storey_stiffness;  // kg and N/m, floors and storeys 1..N
  double damping_ratio = 0.02;                       // every mode's, or Rayleigh's at rayleigh_modes
  std::array<int, 2> rayleigh_modes = {0, 0};        // 1-based; {0, 0}: modal damping
  int storey = 0;           // the floor that is the table, 1 (above the ground storey) to N (the roof)
  bool uniform() const { return floor_mass.empty() && storey_stiffness.empty(); }
  int floors() const { return uniform() ? storeys : static_cast<int>(floor_mass.size()); }
};

struct GroundMotionSpec {
  MotionSource source = MotionSource::synthetic;
  // synthetic: a random motion of peak ground acceleration `pga` (m/s^2) lasting `synthetic_duration`
  // (default_table_motion; no low-pass and no window apply to it)
  unsigned seed = 1;
  double pga = 3.0;
  double synthetic_duration = 10.0;
  // file: one record per axis (x along the excitation; y, z needed for 3-D)
  RecordFormat format = RecordFormat::at2;
  std::string file_x, file_y, file_z;
  std::optional<AccelerationUnits> units;  // none: the format's own (AT2: g, K-NET and JMA: gal)
  std::optional<double> dt;                // s, for "columns" files without a time column
  // points: the table acceleration per component as (t s, a m/s^2) points, linear in between and zero
  // outside; x required, y and z optional (empty: zero). Scaled by `level`; no filter, no window.
  std::vector<std::pair<double, double>> points_x, points_y, points_z;
  // both
  double level = 1.0;                      // scale of the record (0.5 and 1.0 in the paper)
  MotionDimensions dimensions = MotionDimensions::one_d;
  double lowpass_hz = 10.0;                // 0: no filter
  double window_start = 0.0;               // s of record time where the run starts
  std::optional<double> window_end;        // none: the record's end
  // file: scale the record to a target peak (ScaleTarget); none: as recorded
  std::optional<ScaleTarget> scale_to;
  // file: a record whose peak lies outside [plausible_pga_min_g, plausible_pga_max_g] in its declared
  // unit is an error naming the likely unit mistake; false accepts it as given.
  bool check_pga = true;
  // file and synthetic: a run longer than the motion (after the window) is an error; true runs on with
  // the table at rest (zero acceleration) after the motion's end, and lets window.end pass the record's end.
  bool pad_after_end = false;
  // file and synthetic: the table on a storey of a building (BuildingSpec); none: the table is the ground.
  std::optional<BuildingSpec> building;
};

// A scene contact law: its place in the contact law registry (scene/laws/law_list.hpp), written
// law_kind<StiffSceneLaw> for a built-in law, or as register_contact_law<R>() returned it; the first
// built-in law ("paper") is the default.
struct ContactLawKind {
  std::size_t index = 0;
  friend constexpr bool operator==(ContactLawKind, ContactLawKind) = default;
};

// Overrides of the contact parameters for one kind of pair (floor, wall or item-item): key -> value, the
// keys the law declares (LawParameter: its parts' and its own; docs/scene/scene_file.md's key table),
// in their scene units. Unset values come from each item's ItemContact (Table 4 or the 0.8 rule).
struct ContactOverrides {
  std::map<std::string, double> values;
};

// Which items have their floor and wall contact inside the implicit step (docs/contact/implicit_contact.md):
// rigid items only (6 x 6 systems: no cost), every item (flexible ones pay a low-rank update of their
// factorisation: 1.6x on the main job), or none (the paper's explicit treatment).
enum class ImplicitContact { none, rigid, all };

// Where a rigid item touches the floor and walls: at its members' centre lines (the paper judges
// floor contact from nodal coordinates), or at their surfaces (its outer envelope: a cabinet tips
// about its outer edge; docs/contact/contact.md, "At the surface"). Flexible items: centre lines.
enum class PlaneContactAt { centre_lines, surfaces };

// How two rigid items meet: by their members' element pairs (as flexible items do), or by their hulls
// (one hull's face clipped to the other's: a few points instead of hundreds of element pairs;
// docs/contact/contact.md, "Rigid pairs by their hulls").
enum class RigidPairContact { members, hulls };

// Where the items start: placed just touching the floor (the paper's start; they then sink into their
// penalty springs under gravity), or settled there first, at rest on their contacts. The paper's law
// damps the normal motion by a force of constant size below velocity_regularisation, so an item that
// carries its weight unevenly sinks into its resting penetrations over about half a minute, leaning
// as it goes (docs/contact/verification_contact.md, "A settled start"). A settled start
// steps the scene with the table still and that damping's regularisation raised until every node is
// at rest, then starts the run there, at t = 0, with every velocity zero (docs/scene/scene_file.md).
enum class ContactStart { touching, settled };

// Two flexible items' pairs (under `implicit` all): forces from the step's predictor, or inside the
// step, the two items solved together (docs/contact/implicit_contact.md, "Flexible groups").
enum class FlexiblePairContact { explicit_load, implicit_step };

struct ContactSpec {
  ContactLawKind law;  // the list's first law, "paper", unless set
  // Unset: the law's default, else all; read it through implicit_contact(ContactSpec).
  // Optional so that a spec built in C++ gets the same default as a scene file naming the law.
  std::optional<ImplicitContact> implicit;
  double velocity_regularisation = 1e-3;  // m/s: v/|v| is smoothed below this speed
  // m: elastic range of the stick spring of Coulomb friction (holds still below mu N); 0: friction
  // regularised by velocity_regularisation instead (it creeps). Not read by stick_slip (its own spring);
  // used only by items whose contact is implicit.
  double stick_length = 1e-5;
  // Where floor and wall contact act on an item's members: at their outer surfaces (the paper's code
  // and its reproductions, configuration(k), use the centre lines, half a member's width inside).
  PlaneContactAt plane_contact_at = PlaneContactAt::surfaces;
  // Hulls by default (issue 52: Coulomb sliding of a stack within 0.6 % against 1.9 % by members, and
  // configuration 3 all rigid at 0.6 to 1.3 times MuJoCo's time against 3 to 4 times; docs/contact/contact.md).
  RigidPairContact rigid_pairs = RigidPairContact::hulls;
  ContactStart start = ContactStart::touching;
  // Unset: inside the step (`implicit`) when `implicit` is `all`, else the predictor's load; read it
  // through flexible_pair_contact(ContactSpec) (issue 52: explicit, the upper of two stacked full
  // cabinets creeps 17 mm in 5 s at rest; solved together it settles within 1.2 mm and stays).
  std::optional<FlexiblePairContact> flexible_pairs;
  ContactOverrides floor, wall, item;
};

enum class IntegratorKind { paper_newmark, average_acceleration, generalized_alpha };
struct IntegratorSpec {
  IntegratorKind scheme = IntegratorKind::paper_newmark;
  double rho_inf = 0.5;                 // spectral radius at infinity (generalized-alpha)
  bool iterate_to_equilibrium = false;  // false: carry the unbalanced force over, as the paper's code
  // A step in which an item closes on the floor or a wall faster than 0.5 mm a step is divided into
  // up to this many sub-steps (SimulationOptions::max_impact_substeps); 1: never, as the paper's code.
  // 32: a 5 m/s impact goes 0.6 to 0.8 mm in at dt 1 ms under `stiff` instead of 2.7 to 3.2 mm
  // (docs/contact/implicit_contact.md, "Impacts: sub-steps").
  int impact_substeps = 32;
  // Structural damping of the flexible members (s; SimulationOptions::stiffness_damping): a frame mode
  // at f Hz gets the damping ratio pi f times this. 0: none, as the paper's code.
  double stiffness_damping = 0;
  // A flexible item's reused factorisation is refreshed when one of its members turned more than this
  // (rad) away from the item's rotation since (SimulationOptions::frame_drift_refresh). 5e-4: a full
  // chair under `stiff` that lands on its side completes (it diverged without; 1e-3 was not enough), and
  // the default job's energy ledger closes (4.7 % against 5.8 %) for 4 % more time
  // (docs/contact/verification_contact.md, "The chair's divergence"). 0: never, as the paper's code.
  double frame_drift_refresh = 5e-4;
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

// How contact_forces.csv holds the forces between items (docs/io/output.md): three columns for every
// pair of bodies (a room of n bodies has n (n - 1) / 2 pairs), or one row per touching pair and history
// row in contact_pairs.csv; automatic: columns up to OutputSpec::max_pair_column_bodies bodies.
enum class ContactPairOutput { automatic, columns, rows };

struct OutputSpec {
  // Above this many bodies, `automatic` writes rows: 100 bodies are 4 950 pairs, 14 850 columns; 10 000
  // would be 150 million.
  static constexpr int max_pair_column_bodies = 100;
  std::string folder = "out";  // relative to the run's working folder
  std::vector<MarkerRequest> markers;
  std::vector<SectionalForceRequest> sectional_forces;
  int vtu_every = 0;   // write VTU every N steps; 0: none
  bool figures = true;
  ContactPairOutput contact_pairs = ContactPairOutput::automatic;
  bool pair_columns(int bodies) const {
    return contact_pairs == ContactPairOutput::columns ||
           (contact_pairs == ContactPairOutput::automatic && bodies <= max_pair_column_bodies);
  }
};

struct SceneSpec {
  std::string name = "scene";
  TableSpec table;
  std::vector<WallSpec> walls = default_walls();
  std::optional<CeilingSpec> ceiling;  // none by default
  std::vector<ObstacleSpec> obstacles;
  std::vector<ItemSpec> items;
  std::vector<RestraintSpec> restraints;
  // People in the room (docs/harm/occupants.md): sensors that record the items' strikes, judged against
  // strike_thresholds.
  std::vector<Occupant> occupants;
  StrikeThresholds strike_thresholds;
  std::vector<ExitSpec> exits;  // escape routes, measured over the run (scene/exit_observers.hpp)
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
    // Rounded and clamped as a double: lround(1e300 / dt) is out of long's range (it became every step).
    return static_cast<int>(std::clamp(std::round(refresh_every / dt), 1.0, 1e9));
  }
  double duration = 10.0;  // s
  double dt = 1e-3;        // s (the paper's 1 ms); at least min_dt
  // The shortest time step a scene may ask for: a thousandth of the paper's (the stiffest penalties'
  // stable steps are around 0.1 ms). dt = 1e-300 was accepted and then "diverged; try a smaller dt".
  // Checked by step_length_problem (core/step_length.hpp), as every step length is; the core's own
  // bound, min_step_length, is lower (an impact's sub-steps of a scene's step).
  static constexpr double min_dt = 1e-6;
  // A dt longer than the ground motion's sample interval or than contact_step_error_factor times the
  // explicit contact's stable step is an error unless this is true (runner.hpp: check_motion_sampling,
  // check_contact_step).
  bool allow_coarse_dt = false;
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

}  // namespace furniture_fem
