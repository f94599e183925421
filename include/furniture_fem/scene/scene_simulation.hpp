#pragma once
// furniture_fem/scene/scene_simulation.hpp: a scene turned into a composed simulation.
//
//   SceneSimulation<Solver>         the model, items, table motion and Simulation of a scene
//   scene_body_contacts, scene_planes: the parts it is made of (the table motion: scene_motion.hpp)
//   contact_step_estimate, energy_creation_diagnosis, energy_loss_warning: when a run cannot be trusted
//
// The contact law is the registered law's kernel (scene/laws/law_list.hpp), chosen at run time; the
// linear solver is a compile-time policy, which the runner (runner.hpp) picks from the scene's choice.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../excitation/excitation.hpp"
#include "../excitation/known_records.hpp"
#include "../contact/room_contact.hpp"
#include "laws/law_list.hpp"
#include "scene.hpp"
#include "../core/simulation.hpp"
#include "scene_motion.hpp"

#define FURNITURE_FEM_SCENE_INTERNAL
#include "detail/scene_restraints.hpp"
#undef FURNITURE_FEM_SCENE_INTERNAL

namespace furniture_fem {

// Contact parameters of each body from its item's (Table 4 or rule) values, its law's set-up (the law's
// record, scene/laws/) and the scene's overrides.
inline std::vector<BodyContact> scene_body_contacts(const SceneSpec& s, const Model& model,
                                                    const std::vector<ItemInfo>& items) {
  std::vector<BodyContact> out(model.num_bodies());
  const SceneLawInfo& law = scene_law(s.contact.law);
  const LawSetup setup{s, model, items};
  // Floor and wall contact inside the implicit step where the scene asks for it; friction sticks only
  // there (a stick spring applied explicitly would be unstable). Two rigid implicit items also have
  // their pairs inside the step (solved together); every other pair is explicit.
  for (const auto& it : items) {
    BodyContact bc;
    const ItemContact& c = it.contact;
    ContactParams base;
    base.alpha = c.alpha;
    base.Dc = c.Dc;
    base.q = c.q;
    base.v_reg = s.contact.velocity_regularisation;
    bc.implicit = item_contact_inside_step(s, it);
    base.stick_length = !law.own_stick_spring.empty() || !bc.implicit ? 0.0 : s.contact.stick_length;
    // Linear and Hunt-Crossley springs get the paper penalty's stiffness at onset: alpha / L per
    // contact with L = 25 mm (half the 50 mm member width); the tangential spring of the stick-slip
    // law is as stiff; critical-ish damping for a node of ~0.1 kg.
    base.k_lin = c.alpha / 0.025;
    base.c_lin = 2.0 * std::sqrt(base.k_lin * 0.1);
    base.k_hc = base.k_lin / std::sqrt(0.025);
    base.hc_damping = 0.5;
    base.k_t = base.k_lin;
    law.set_slot_defaults(base);
    law.item_base(base, setup, it);
    bc.floor = base;
    bc.floor.mu = c.mu_floor_long;
    bc.floor.mu_long = c.mu_floor_long;
    bc.floor.mu_short = c.mu_floor_short;
    bc.wall = base;
    bc.wall.mu = bc.wall.mu_long = bc.wall.mu_short = c.mu_wall;
    bc.item = base;
    bc.item.mu = bc.item.mu_long = bc.item.mu_short = c.mu_item;
    law.item_pair(bc.item, setup);
    law.apply(bc.floor, s.contact.floor);
    law.apply(bc.wall, s.contact.wall);
    law.apply(bc.item, s.contact.item);
    bc.long_axis_node_a = it.long_axis_nodes[0];
    bc.long_axis_node_b = it.long_axis_nodes[1];
    bc.caster_nodes = it.caster_nodes;
    bc.at_nodes = c.at_nodes;
    out.at(it.body) = bc;
  }
  return out;
}

// Two finite-element items' pairs: as the scene says, else inside the step when every item's floor and
// wall contact is (`implicit` `all`), else the predictor's load (docs/scene/scene_file.md).
inline FlexiblePairContact flexible_pair_contact(const ContactSpec& c) {
  if (c.flexible_pairs) return *c.flexible_pairs;
  return implicit_contact(c) == ImplicitContact::all ? FlexiblePairContact::implicit_step
                                                     : FlexiblePairContact::explicit_load;
}

inline std::vector<RigidPlane> scene_planes(const SceneSpec& s) {
  std::vector<RigidPlane> planes;
  RigidPlane floor;
  floor.point = Vec3(0, 0, s.table.floor_z);
  floor.normal = Vec3::UnitZ();
  planes.push_back(floor);
  for (const auto& w : s.walls) {
    RigidPlane p;
    p.normal = w.normal.normalized();
    p.point = w.point + Vec3(0, 0, 0.5 * w.height);
    p.axis_u = Vec3::UnitZ().cross(p.normal).normalized();
    p.axis_v = Vec3::UnitZ();
    p.half_u = 0.5 * w.width;
    p.half_v = 0.5 * w.height;
    p.is_wall = true;
    planes.push_back(p);
  }
  if (s.ceiling) {  // last: the floor and walls keep their places (and their contacts' order) without one
    RigidPlane ceiling;
    ceiling.point = Vec3(0, 0, s.table.floor_z + s.ceiling->height);
    ceiling.normal = -Vec3::UnitZ();
    ceiling.is_ceiling = true;
    planes.push_back(ceiling);
  }
  return planes;
}

// The slope of the law's normal force at a node resting under `weight` (N) on a contact of half-width L:
// the overlap where the law at rest pushes with `weight` (by bisection, at most L), and the law's own
// stiffness there (its normal part's, plus its damping part's at rest). 0 if the law gives none.
inline double resting_normal_stiffness(const ContactLawKernel& law, const ContactParams& p, double L, double weight) {
  const auto at = [&](double overlap) {
    ContactKinematics k;
    k.L = L;
    k.l = L - overlap;
    ContactState state;
    return law.force(k, p, state);
  };
  double lo = 0, hi = L;
  if (at(hi).normal > weight)
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      (at(mid).normal < weight ? lo : hi) = mid;
    }
  return at(hi).K(2, 2);
}

// A node-mass estimate of the largest stable time step of the floor contact where it is treated
// explicitly (outside the implicit step): a floor node of mass m on its normal spring k, the law's slope
// at the node's resting overlap (its share of the item's weight), is stable for dt below 2 sqrt(m / k).
// Conservative, since the structure around a node adds to its mass (the paper's penalties run stably at
// dt = 5 ms). The law's spring, not the paper's alpha / L for every law: `stiff` (2.5 um under the
// weight) diverged in 0.27 s at dt 1 ms while this said 3.76 ms was stable.
struct ContactStepEstimate {
  double dt = std::numeric_limits<double>::infinity();
  std::string item;  // the item whose floor nodes give the estimate
  // What sets the law's normal stiffness in a scene ("the penalty alpha_kgf"); empty: nothing but dt.
  std::string stiffness_key;
  std::string remedy() const { return stiffness_key.empty() ? "reduce dt" : "reduce dt or " + stiffness_key; }
};
template <class Sim>
ContactStepEstimate contact_step_estimate(const Sim& sim, const Model& model, const std::vector<ItemInfo>& items,
                                          const std::vector<BodyContact>& contacts, ContactLawKind law) {
  const std::vector<double> half = plane_contact_distances(model);
  ContactStepEstimate est;
  const SceneLawInfo& info = scene_law(law);
  est.stiffness_key = info.reads("alpha_kgf")   ? "the penalty alpha_kgf"
                      : info.reads("stiffness") ? "contact.floor.stiffness"
                                                : "";
  for (const auto& it : items) {
    if (it.bottom_nodes.empty() || contacts.at(it.body).implicit) continue;  // inside the step: no limit
    const ContactParams& p = contacts.at(it.body).floor;
    const double weight = model.body_mass(it.body) * ContactParams::newtons_per_kgf / double(it.bottom_nodes.size());
    for (int n : it.bottom_nodes) {
      if (!std::isfinite(half[n])) continue;
      const double k = resting_normal_stiffness(*info.kernel, p, half[n], weight);
      if (!(k > 0)) continue;
      const double d = 2.0 * std::sqrt(sim.nodal_mass(n) / k);
      if (d < est.dt) est.dt = d, est.item = it.name;
    }
  }
  return est;
}

// Empty while the energy ledger shows no energy created beyond `limit` times its scale; otherwise
// why the run cannot be trusted and what to change. Penalty contact can only give back what it
// stored (a little, unless items start interpenetrated), so net positive contact work means the
// explicit contact is pumping energy in; a positive imbalance means the time integration made it.
inline std::string energy_creation_diagnosis(const EnergyLedger& E, double dt, double limit,
                                             const ContactStepEstimate& est) {
  if (!(limit > 0)) return {};
  const double scale = E.scale(), imbalance = E.imbalance();
  // The contact's work as applied: the trapezoidal estimate can be positive at an impact in which the
  // items gained nothing (docs/core/theory.md, "Energy ledger").
  const bool by_contact = E.contact_work_applied > limit * scale, by_integrator = imbalance > limit * scale;
  if (!by_contact && !by_integrator) return {};
  const auto fmt = [](double v) {
    std::ostringstream o;
    o.precision(3);
    o << v;
    return o.str();
  };
  std::string why = "energy is being created: ";
  if (by_contact)
    why += "the contact forces have done " + fmt(E.contact_work_applied) + " J of net positive work (" +
           fmt(100 * E.contact_work_applied / scale) + " % of the energy ledger's scale, " + fmt(scale) + " J)";
  else
    why += "the energy ledger's imbalance is +" + fmt(imbalance) + " J (" + fmt(100 * imbalance / scale) +
           " % of its scale, " + fmt(scale) + " J)";
  why += ", more than the " + fmt(100 * limit) + " % a run may create (RunOptions::energy_creation_limit). ";
  if (dt > est.dt)
    why += "The contact penalty is too stiff for the time step: dt = " + fmt(1e3 * dt) +
           " ms exceeds the explicit contact's stable step, estimated at " + fmt(1e3 * est.dt) + " ms for item '" +
           est.item + "' (2 sqrt(m / k) over its floor nodes, k the contact law's normal stiffness at rest); " +
           est.remedy() + ".";
  else
    why += "dt = " + fmt(1e3 * dt) + " ms is within the explicit contact's estimated stable step (" +
           fmt(1e3 * est.dt) + " ms, item '" + est.item +
           "'): items starting interpenetrated (the penalty releases the energy stored in the overlap) are the "
           "likely cause; check the placement, or " + est.remedy() + ".";
  return why;
}

// The warning a completed run carries when the ledger lost more than `limit` of its scale; empty if not.
inline std::string energy_loss_warning(const EnergyLedger& E, double dt, double limit, const ContactStepEstimate& est) {
  const double scale = E.scale(), imbalance = E.imbalance();
  if (!(limit > 0) || !(-imbalance > limit * scale)) return {};
  std::ostringstream o;
  o.precision(3);
  o << "warning: the energy ledger does not close: " << -imbalance << " J (" << 100 * -imbalance / scale
    << " % of its scale, " << scale << " J) lost beyond what contact, damping and plastic hinges account for, "
    << "more than the " << 100 * limit << " % (RunOptions::energy_loss_warning) a trusted run may lose. ";
  if (dt > est.dt)
    o << "The contact penalty is too stiff for the time step: dt = " << 1e3 * dt
      << " ms exceeds the explicit contact's stable step, estimated at " << 1e3 * est.dt << " ms for item '" << est.item
      << "'; " << est.remedy() << ".";
  else
    o << "Impacts (items landing or striking each other) lose energy with the carried-over penalty contact at "
         "this dt (docs/performance.md, stability); a smaller dt reduces the loss.";
  return o.str();
}

namespace detail {

// Obstacles and their meshes must stay this close to the table's centre (m, each coordinate): a room
// is metres across, and far beyond it the triangles' areas and the contact distances are lost to
// rounding (a mesh with a coordinate of 1e166, a scale of 1e300 or a position of 1e300 ran or failed
// with a message naming no key; issue 13).
inline constexpr double obstacle_reach = scene_reach;

// The mesh of obstacles[i], placed (ObstacleSpec: file units times `scale`, turned by `yaw_deg` about z,
// the file's origin moved to `position`). A vertex beyond obstacle_reach of the table's centre is an
// InputError naming the key to blame: `position` when it alone is out of reach, `file` when the file's
// own coordinate is, `scale` when the scaled coordinate is.
inline TriangleMesh placed_obstacle_mesh(const SceneSpec& spec, std::size_t i) {
  const ObstacleSpec& ob = spec.obstacles[i];
  const std::string key = "obstacles[" + std::to_string(i) + "]";
  const std::string path = spec.resolve(ob.file);
  const Vec3 centre(0, 0, spec.table.floor_z);
  const auto out_of_reach = [](const Vec3& v) { return !(v.cwiseAbs().maxCoeff() <= obstacle_reach); };
  const auto fail = [&](const std::string& field, const std::string& message) {
    throw InputError(spec.source, 0, key + "." + field,
                     message + "; an obstacle must lie within " + fmt(obstacle_reach) + " m of the table's centre");
  };
  const auto vec = [](const Vec3& v) { return "[" + fmt(v.x()) + ", " + fmt(v.y()) + ", " + fmt(v.z()) + "]"; };
  if (out_of_reach(ob.position - centre)) fail("position", "out of reach (got " + vec(ob.position) + ")");
  TriangleMesh mesh = read_triangle_mesh(path);
  const Mat3 R = Eigen::AngleAxisd(ob.yaw_deg * std::numbers::pi / 180.0, Vec3::UnitZ()).toRotationMatrix();
  for (std::size_t k = 0; k < mesh.vertices.size(); ++k) {
    Vec3& v = mesh.vertices[k];
    const Vec3 scaled = ob.scale * v, placed = R * scaled + ob.position;
    if (!out_of_reach(placed - centre)) {
      v = placed;
      continue;
    }
    const std::string vertex = "vertex " + std::to_string(k + 1) + " of \"" + path + "\", " + vec(v) + ",";
    if (out_of_reach(v)) fail("file", vertex + " is out of reach");
    if (out_of_reach(scaled)) fail("scale", fmt(ob.scale) + " puts " + vertex + " at " + vec(scaled) + ", out of reach");
    fail("position", vec(ob.position) + " puts " + vertex + " at " + vec(placed) + ", out of reach");
  }
  return mesh;
}

// obstacles[i] as a rigid obstacle; a mesh left without a triangle of non-zero area names the key.
inline MeshObstacle scene_obstacle(const SceneSpec& spec, std::size_t i) {
  const ObstacleSpec& ob = spec.obstacles[i];
  try {
    return MeshObstacle(placed_obstacle_mesh(spec, i), spec.resolve(ob.file));
  } catch (const ModelError& e) {
    throw InputError(spec.source, 0, "obstacles[" + std::to_string(i) + "].file",
                     e.what() + (ob.scale != 1 ? " at scale " + fmt(ob.scale) : std::string()));
  }
}

// The index in spec.items of the item whose body is `info` (separated cabinets: "<item>/lower").
inline std::size_t spec_item_index(const SceneSpec& spec, const ItemInfo& info) {
  const std::string name = info.name.substr(0, info.name.find('/'));
  for (std::size_t j = 0; j < spec.items.size(); ++j)
    if (spec.items[j].name == name) return j;
  return spec.items.size();
}

// Deeper than this (m) into an item's member at t = 0, an obstacle passes through it (as 1 um for the
// footprints of two items: touching is allowed).
inline constexpr double obstacle_clearance = 1e-6;

// How deep `obstacle` reaches into a member of `item` at t = 0 (a member's half contact width, where its
// contact acts, minus its centre line's distance to the mesh) and where, on the centre line; depth <= 0:
// clear. A mesh between two nodes of a member is caught too (the contact, by nodes, would miss it).
struct ObstacleIntrusion {
  double depth = 0;
  Vec3 point = Vec3::Zero();
  int member = -1;
};
inline ObstacleIntrusion obstacle_intrusion(const Model& model, const ItemInfo& item, const MeshObstacle& obstacle) {
  const std::vector<int>& elements = model.body(item.body).elements;
  std::vector<MeshQuerySegment> segments;
  double reach = 0;
  for (int e : elements) {
    const ElementData& el = model.elements()[e];
    segments.push_back({model.node(el.n1).X, model.node(el.n2).X});
    reach = std::max(reach, 0.5 * model.section_of(e).contact_width());
  }
  ObstacleIntrusion deepest;
  for (const SegmentMeshContact& c : obstacle.segments_within(segments, reach)) {
    const int e = elements[c.segment];
    const double depth = 0.5 * model.section_of(e).contact_width() - c.closest.distance;
    if (depth > deepest.depth) deepest = {depth, c.closest.p_WA, model.elements()[e].member};
  }
  return deepest;
}

// An obstacle passing through an item at t = 0 is an InputError naming both: the penalty would push
// them apart at the first steps with energy that comes from nowhere (the ledger 6.7 % off, exit 0;
// issue 51).
inline void check_obstacles_clear(const SceneSpec& spec, const Model& model, const std::vector<ItemInfo>& items,
                                  const std::vector<MeshObstacle>& obstacles) {
  const auto vec = [](const Vec3& v) { return "(" + fmt(v.x()) + ", " + fmt(v.y()) + ", " + fmt(v.z()) + ")"; };
  for (std::size_t i = 0; i < obstacles.size(); ++i)
    for (const ItemInfo& it : items) {
      const ObstacleIntrusion in = obstacle_intrusion(model, it, obstacles[i]);
      if (!(in.depth > obstacle_clearance)) continue;
      throw InputError(spec.source, 0, "obstacles[" + std::to_string(i) + "]",
                       "obstacle \"" + spec.resolve(spec.obstacles[i].file) + "\" passes through item '" + it.name +
                           "' (items[" + std::to_string(spec_item_index(spec, it)) + "]) at t = 0: " + fmt(in.depth) +
                           " m into its member '" + model.member(in.member).name + "' at " + vec(in.point) +
                           " m; move the obstacle or the item");
    }
}

// The highest point of each item's contact at t = 0 above the floor (m): its nodes' heights plus their
// contact distance against a plane (plane_contact_distances).
inline std::vector<double> item_tops(const SceneSpec& spec, const Model& model, const std::vector<ItemInfo>& items) {
  const std::vector<double> half = plane_contact_distances(model);
  std::vector<double> tops;
  for (const ItemInfo& it : items) {
    double top = -std::numeric_limits<double>::infinity();
    for (int n : model.body(it.body).nodes)
      top = std::max(top, model.node(n).X.z() + (std::isfinite(half[n]) ? half[n] : 0.0));
    tops.push_back(top - spec.table.floor_z);
  }
  return tops;
}

// An item reaching above the ceiling at t = 0 is an InputError naming both: the ceiling would push it
// down through the floor's contact with energy from nowhere, as an obstacle through an item would.
// Touching (to 1 um, as obstacle_clearance) is allowed.
inline void check_ceiling_clear(const SceneSpec& spec, const Model& model, const std::vector<ItemInfo>& items) {
  if (!spec.ceiling) return;
  const std::vector<double> tops = item_tops(spec, model, items);
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (!(tops[i] > spec.ceiling->height + obstacle_clearance)) continue;
    throw InputError(spec.source, 0, "ceiling.height",
                     "item '" + items[i].name + "' (items[" + std::to_string(spec_item_index(spec, items[i])) +
                         "]) reaches " + fmt(tops[i]) + " m, above the ceiling at " + fmt(spec.ceiling->height) +
                         " m (heights above the table's floor); raise the ceiling or lower the item");
  }
}

// A person standing as a rigid obstacle (Occupant::obstacle): its head and body zones as capsules, the
// body's axis down to the floor (legs stand on it: a low item does not slip under a rounded end).
inline void add_occupant_capsules(RoomContact& contact, const Occupant& o, int i) {
  const Vec3 foot(o.position.x(), o.position.y(), o.floor_z);
  contact.add_capsule(Capsule{o.head_centre(), o.head_centre(), o.head_radius}, occupant_capsule(i, OccupantZone::head));
  contact.add_capsule(Capsule{foot, o.body_top(), o.body_radius}, occupant_capsule(i, OccupantZone::body));
}

}  // namespace detail

// A scene turned into a composed solver: the model, its items, the table motion and the simulation
// (owned here so the model outlives the simulation that refers to it). Fidelity per item: "rigid"
// items are solved as rigid bodies; "auto" items are rigid unless the scene asks for their sectional
// forces (model only what the scene needs); "full" and "coarse" are finite-element bodies. The contact
// law is the scene's registered law (its kernel), so one SceneSimulation<Solver> serves every law. The
// element policy is a compile-time choice (the scene file always means ASI-Gauss; studies swap it here).
template <class Solver, class Element = AsiGaussTimoshenko>
struct SceneSimulation {
  using Sim = Simulation<Element, RuntimeIntegrator, Solver, RoomContact>;
  std::unique_ptr<Model> model = std::make_unique<Model>();
  std::vector<ItemInfo> items;
  TableMotion motion;
  RuntimeIntegrator integrator;
  std::unique_ptr<Sim> sim;
  std::vector<int> rigid_bodies;
  double motion_scale = 1.0;  // the factor of ground_motion.scale_to (1 without one); `level` multiplies after

  // refresh_interval_steps 0: the scene's (SceneSpec::refresh_every, converted to steps); threads 0: all
  // hardware threads.
  explicit SceneSimulation(const SceneSpec& spec, int refresh_interval_steps = 0, int threads = 0) {
    items = build_scene(spec, *model);
    motion = scene_table_motion(spec, &motion_scale);
    RoomContact contact(*model, scene_body_contacts(spec, *model, items), scene_planes(spec),
                        scene_law(spec.contact.law).kernel);
    contact.set_surface(*model, spec.contact.plane_contact_at == PlaneContactAt::surfaces);
    contact.set_rigid_pair_hulls(*model, spec.contact.rigid_pairs == RigidPairContact::hulls);
    contact.flexible_pairs_implicit = flexible_pair_contact(spec.contact) == FlexiblePairContact::implicit_step;
    std::vector<MeshObstacle> obstacles;
    for (std::size_t i = 0; i < spec.obstacles.size(); ++i) obstacles.push_back(detail::scene_obstacle(spec, i));
    detail::check_obstacles_clear(spec, *model, items, obstacles);
    detail::check_ceiling_clear(spec, *model, items);
    for (auto& ob : obstacles) contact.add_obstacle(std::move(ob));
    for (std::size_t i = 0; i < spec.occupants.size(); ++i)
      if (spec.occupants[i].obstacle) detail::add_occupant_capsules(contact, spec.occupants[i], static_cast<int>(i));
    contact.set_restraints(detail::scene_restraint_set(spec, *model, items, detail::scene_ceiling_z(spec)));
    switch (spec.integrator.scheme) {
      case IntegratorKind::paper_newmark: integrator = RuntimeIntegrator::from(Newmark::paper()); break;
      case IntegratorKind::average_acceleration:
        integrator = RuntimeIntegrator::from(Newmark::average_acceleration());
        break;
      case IntegratorKind::generalized_alpha:
        integrator = RuntimeIntegrator::from(GeneralizedAlpha{spec.integrator.rho_inf});
        break;
    }
    integrator.mode = spec.integrator.iterate_to_equilibrium ? EquilibriumMode::iterate : EquilibriumMode::carry_over;
    SimulationOptions so;
    so.dt = spec.dt;
    so.refresh_interval_steps = refresh_interval_steps > 0 ? refresh_interval_steps : spec.refresh_interval_steps();
    so.threads = threads;
    so.max_impact_substeps = spec.integrator.impact_substeps;
    so.stiffness_damping = spec.integrator.stiffness_damping;
    so.frame_drift_refresh = spec.integrator.frame_drift_refresh;
    sim = std::make_unique<Sim>(*model, integrator, so, std::move(contact));
    const TableMotion* m = &motion;
    sim->set_table_acceleration([m](double t) { return m->at(t); });
    for (size_t i = 0; i < items.size(); ++i)
      if (item_is_rigid(spec, items[i])) rigid_bodies.push_back(items[i].body);
    sim->set_rigid(rigid_bodies);
  }
};

// The compiled scene runner (furniture_fem::scene_compiled) instantiates what a run needs of the scene
// simulation with each linear solver (its constructor and step; the contact law is a run-time kernel, so
// one simulation serves every law), once, in src/scene/scene_simulation_<solver>.cpp. Its users see the
// declarations below and compile none of that solver code (both are defined out of the class, so
// `extern` holds them back; docs/performance.md section 6). The statics, which no run calls, stay
// implicit. Header-only use instantiates whatever it uses, as before.
#if defined(FURNITURE_FEM_COMPILED_SCENE) || defined(FURNITURE_FEM_BUILDING_SCENE_LIBRARY) || \
    defined(FURNITURE_FEM_BUILDING_SCENE_SIMULATIONS)
// `extern` (a declaration) or nothing (the definition, in the library's unit of that solver).
#define FFEM_SCENE_RUN_MEMBERS(EXTERN, SOLVER) \
  FFEM_SIMULATION_RUN_MEMBERS(EXTERN, AsiGaussTimoshenko, RuntimeIntegrator, SOLVER, RoomContact)
FFEM_SCENE_RUN_MEMBERS(extern, DirectLdltSolver)
FFEM_SCENE_RUN_MEMBERS(extern, ConjugateGradientSolver)
#endif

}  // namespace furniture_fem
