#pragma once
// furniture_fem/scene/scene_runner.hpp: run a scene (scene.hpp) end to end and write its results folder.
//
//   RunSummary run_scene(const SceneSpec&, const RunOptions&)
//
// Builds the model, loads and processes the ground motion, composes the solver for the scene's
// contact law and linear solver (compile-time policies, picked here from the scene's runtime choice),
// steps it with a progress bar, and writes: marker displacement histories, contact force histories per
// pair of bodies, sectional force histories, the energy ledger (CSV); the final state of every item and
// a run summary (JSON); a VTU/PVD time series; PNG figures (marker histories, the room's final state,
// the requested sectional forces). A stop request (Ctrl-C) or a diverging step ends the run early with
// everything written so far readable and the reason in the summary.
#include <Eigen/Core>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "../io/csv.hpp"
#include "../excitation/excitation.hpp"
#include "../figures/plot.hpp"
#include "../contact/room_contact.hpp"
#include "scene.hpp"
#include "../core/simulation.hpp"
#include "../io/vtk.hpp"

namespace furniture_fem {

inline constexpr const char* version_string = "0.1.0";

struct RunOptions {
  std::string out_dir;                        // empty: the scene's outputs.folder
  bool progress = true;                       // progress bar on stderr
  std::optional<double> duration;             // overrides the scene's duration
  int output_every = 10;                      // history rows every N steps (10 ms at dt = 1 ms)
  const std::atomic<bool>* stop = nullptr;    // set by a signal handler to stop cleanly
  std::optional<bool> figures;                // overrides outputs.figures
  // A run that creates energy cannot be trusted: it ends as "diverged", with a diagnosis, as soon as
  // the contact forces' net work or the ledger's imbalance exceeds this fraction of the ledger's scale
  // (the contact laws only store and dissipate energy, the integrators only dissipate; checked at
  // every output row). 0: never. See energy_creation_diagnosis().
  double energy_creation_limit = 0.25;
  // A run that completes having lost more than this fraction of the ledger's scale (impacts with the
  // carried-over penalty contact, or a time step too long for the penalty) is kept, but its summary's
  // diagnosis warns that the energy ledger does not close. See energy_loss_warning().
  double energy_loss_warning = 0.15;
};

struct ItemFinalState {
  std::string name;
  std::string state;          // standing, slid, tilted, fell, overturned, resting_on_item
                              // (fell: upright again at the end, but it tipped past 60 degrees or came
                              // down more than 5 cm on the way, e.g. off the item it stood on)
  double slide = 0;           // horizontal displacement of the centre of gravity (m)
  double tilt_deg = 0;        // angle of the item's vertical axis from the vertical
  double max_tilt_deg = 0;    // during the run
  double lift = 0;            // height of the lowest node above the floor contact onset (m)
  std::string resting_on;     // the item it leans or rests on, if any
  Vec3 cog_displacement = Vec3::Zero();
};

struct RunSummary {
  std::string status = "completed";  // completed, stopped, diverged
  std::string diagnosis;             // why it stopped; for a completed run, empty or an energy-loss warning
  double t_end = 0, duration = 0;
  long steps = 0;
  double wall_seconds = 0;
  double energy_imbalance = 0;        // |imbalance| / scale of the ledger at the end
  double max_energy_imbalance = 0;    // the largest during the run
  long factorizations = 0;
  int elements = 0, nodes = 0, bodies = 0;
  std::vector<ItemFinalState> items;
  std::string out_dir;
};

namespace detail {

inline Record scene_record(const SceneSpec& s, const std::string& file, const char* axis) {
  const auto& g = s.ground_motion;
  const std::string path = s.resolve(file);
  if (path.empty())
    throw InputError(s.source, 0, std::string("ground_motion.file_") + axis, "no record file given for this axis");
  if (!std::filesystem::exists(path))
    throw InputError(s.source, 0, std::string("ground_motion.file_") + axis, "record file not found: " + path);
  ReadOptions ro;
  if (g.units) ro.unit = *g.units == AccelerationUnits::g ? Unit::g : *g.units == AccelerationUnits::gal ? Unit::gal : Unit::m_s2;
  else if (g.format == RecordFormat::columns) ro.unit = Unit::gal;
  if (g.dt) ro.dt = *g.dt;
  Format f = Format::automatic;
  switch (g.format) {
    case RecordFormat::at2: f = Format::peer_at2; break;
    case RecordFormat::knet: f = Format::knet; break;
    case RecordFormat::jma_csv: f = Format::jma_csv; break;
    case RecordFormat::columns: f = Format::columns; break;
  }
  return read_record(path, f, ro);
}

// Window, low-pass and scale one component; the run's time 0 is the window's start.
inline Record process_record(Record r, const GroundMotionSpec& g) {
  if (g.lowpass_hz > 0 && g.lowpass_hz < 0.5 / r.dt) r = low_pass(r, g.lowpass_hz);
  const double t0 = std::max(g.window_start, r.t0);
  const double t1 = g.window_end ? std::min(*g.window_end, r.t_end()) : r.t_end();
  if (t0 > 0 || t1 < r.t_end()) r = window(r, t0, t1, 0.0);
  r.t0 = 0;
  return r.scaled(g.level);
}

}  // namespace detail

// The shake table's acceleration for a scene (m/s^2, table axes), as the scene asks for it.
inline TableMotion scene_table_motion(const SceneSpec& s) {
  const auto& g = s.ground_motion;
  const bool three_d = g.dimensions == MotionDimensions::three_d;
  if (g.source == MotionSource::synthetic) {
    TableMotion m = default_table_motion(g.seed);
    // Scale so the X component's peak is the requested PGA; Y and Z keep their ratios to X.
    const double k = g.pga / std::max(m.x.peak(), 1e-12);
    m = m.scaled(k * g.level);
    if (!three_d) m.has_y = m.has_z = false;
    return m;
  }
  if (g.format == RecordFormat::jma_csv) {
    ReadOptions ro;
    const auto c = read_jma_csv(s.resolve(g.file_x));
    if (!three_d) return TableMotion::one_d(detail::process_record(c[0], g));
    return TableMotion::three_d(detail::process_record(c[0], g), detail::process_record(c[1], g),
                                detail::process_record(c[2], g));
  }
  Record x = detail::process_record(detail::scene_record(s, g.file_x, "x"), g);
  if (!three_d) return TableMotion::one_d(std::move(x));
  Record y = detail::process_record(detail::scene_record(s, g.file_y, "y"), g);
  Record z = detail::process_record(detail::scene_record(s, g.file_z, "z"), g);
  return TableMotion::three_d(std::move(x), std::move(y), std::move(z));
}

// Contact parameters of each body from its item's (Table 4 or rule) values and the scene's overrides.
inline std::vector<BodyContact> scene_body_contacts(const SceneSpec& s, const Model& model,
                                                    const std::vector<ItemInfo>& items) {
  std::vector<BodyContact> out(model.num_bodies());
  const auto apply = [&](ContactParams& p, const ContactOverrides& o) {
    if (o.alpha_kgf) p.alpha = *o.alpha_kgf * newtons_per_kgf;
    if (o.dc_kgf) p.Dc = *o.dc_kgf * newtons_per_kgf;
    if (o.q) p.q = *o.q;
    if (o.mu) p.mu = p.mu_long = p.mu_short = *o.mu;
    if (o.mu_long) p.mu_long = *o.mu_long;
    if (o.mu_short) p.mu_short = *o.mu_short;
  };
  for (const auto& it : items) {
    BodyContact bc;
    const ItemContact& c = it.contact;
    ContactParams base;
    base.alpha = c.alpha;
    base.Dc = c.Dc;
    base.q = c.q;
    base.v_reg = s.contact.velocity_regularisation;
    // Linear and Hunt-Crossley springs get the paper penalty's stiffness at onset: alpha / L per
    // contact with L = 25 mm (half the 50 mm member width); the tangential spring of the stick-slip
    // law is as stiff; critical-ish damping for a node of ~0.1 kg.
    base.k_lin = c.alpha / 0.025;
    base.c_lin = 2.0 * std::sqrt(base.k_lin * 0.1);
    base.k_hc = base.k_lin / std::sqrt(0.025);
    base.hc_damping = 0.5;
    base.k_t = base.k_lin;
    bc.floor = base;
    bc.floor.mu = c.mu_floor_long;
    bc.floor.mu_long = c.mu_floor_long;
    bc.floor.mu_short = c.mu_floor_short;
    bc.wall = base;
    bc.wall.mu = bc.wall.mu_long = bc.wall.mu_short = c.mu_wall;
    bc.item = base;
    bc.item.mu = bc.item.mu_long = bc.item.mu_short = c.mu_item;
    apply(bc.floor, s.contact.floor);
    apply(bc.wall, s.contact.wall);
    apply(bc.item, s.contact.item);
    if (s.contact.floor.stiffness) bc.floor.k_lin = bc.floor.k_t = *s.contact.floor.stiffness;
    if (s.contact.floor.damping) bc.floor.c_lin = *s.contact.floor.damping;
    bc.long_axis_node_a = it.long_axis_nodes[0];
    bc.long_axis_node_b = it.long_axis_nodes[1];
    bc.caster_nodes = it.caster_nodes;
    out.at(it.body) = bc;
  }
  return out;
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
  return planes;
}

// A node-mass estimate of the largest stable time step of the contact penalty, which the solver
// treats explicitly (contact forces are not in the effective matrix): a floor node of mass m on the
// penalty spring alpha / L is stable for dt below 2 sqrt(m L / alpha). Conservative, since the
// structure around a node adds to its mass (the paper's penalties run stably at dt = 5 ms).
struct ContactStepEstimate {
  double dt = std::numeric_limits<double>::infinity();
  std::string item;  // the item whose floor nodes give the estimate
};
template <class Sim>
ContactStepEstimate contact_step_estimate(const Sim& sim, const Model& model, const std::vector<ItemInfo>& items,
                                          const std::vector<BodyContact>& contacts) {
  std::vector<double> half(model.num_nodes(), std::numeric_limits<double>::infinity());
  for (int e = 0; e < model.num_elements(); ++e)
    for (int n : {model.elements()[e].n1, model.elements()[e].n2})
      half[n] = std::min(half[n], 0.5 * model.section_of(e).contact_width());
  ContactStepEstimate est;
  for (const auto& it : items) {
    const double alpha = contacts.at(it.body).floor.alpha;
    if (!(alpha > 0)) continue;
    for (int n : it.bottom_nodes) {
      const double d = 2.0 * std::sqrt(sim.nodal_mass(n) * half[n] / alpha);
      if (d < est.dt) est = {d, it.name};
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
  const bool by_contact = E.contact_work > limit * scale, by_integrator = imbalance > limit * scale;
  if (!by_contact && !by_integrator) return {};
  const auto fmt = [](double v) {
    std::ostringstream o;
    o.precision(3);
    o << v;
    return o.str();
  };
  std::string why = "energy is being created: ";
  if (by_contact)
    why += "the contact forces have done " + fmt(E.contact_work) + " J of net positive work (" +
           fmt(100 * E.contact_work / scale) + " % of the energy ledger's scale, " + fmt(scale) + " J)";
  else
    why += "the energy ledger's imbalance is +" + fmt(imbalance) + " J (" + fmt(100 * imbalance / scale) +
           " % of its scale, " + fmt(scale) + " J)";
  why += ", more than the " + fmt(100 * limit) + " % a run may create (RunOptions::energy_creation_limit). ";
  if (dt > est.dt)
    why += "The contact penalty is too stiff for the time step: dt = " + fmt(1e3 * dt) +
           " ms exceeds the explicit contact's stable step, estimated at " + fmt(1e3 * est.dt) + " ms for item '" +
           est.item + "' (2 sqrt(m L / alpha) over its floor nodes); reduce dt or the penalty alpha_kgf.";
  else
    why += "dt = " + fmt(1e3 * dt) + " ms is within the explicit contact's estimated stable step (" +
           fmt(1e3 * est.dt) + " ms, item '" + est.item +
           "'): items starting interpenetrated (the penalty releases the energy stored in the overlap) are the "
           "likely cause; check the placement, or reduce dt or the penalty alpha_kgf.";
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
      << "'; reduce dt or the penalty alpha_kgf.";
  else
    o << "Impacts (items landing or striking each other) lose energy with the carried-over penalty contact at "
         "this dt (docs/performance.md, stability); a smaller dt reduces the loss.";
  return o.str();
}

// A scene turned into a composed solver: the model, its items, the table motion and the simulation
// (owned here so the model outlives the simulation that refers to it). Fidelity per item: "rigid"
// items are solved as rigid bodies; "auto" items are rigid unless the scene asks for their sectional
// forces (model only what the scene needs); "full" and "coarse" are finite-element bodies. The element
// policy is a compile-time choice (the scene file always means ASI-Gauss; studies swap it here).
template <class Law, class Solver, class Element = AsiGaussTimoshenko>
struct SceneSimulation {
  using Sim = Simulation<Element, RuntimeIntegrator, Solver, RoomContact<Law>>;
  std::unique_ptr<Model> model = std::make_unique<Model>();
  std::vector<ItemInfo> items;
  TableMotion motion;
  RuntimeIntegrator integrator;
  std::unique_ptr<Sim> sim;
  std::vector<int> rigid_bodies;

  // refresh_interval 0: the scene's (SceneSpec::refresh_every, in steps); threads 0: all hardware threads.
  explicit SceneSimulation(const SceneSpec& spec, int refresh_interval = 0, int threads = 0) {
    items = build_scene(spec, *model);
    motion = scene_table_motion(spec);
    RoomContact<Law> contact(*model, scene_body_contacts(spec, *model, items), scene_planes(spec));
    // Obstacle placement (ObstacleSpec): file units times `scale`, turned by `yaw_deg` about z, the
    // file's origin moved to `position`.
    for (const auto& ob : spec.obstacles) {
      TriangleMesh mesh = read_triangle_mesh(spec.resolve(ob.file));
      const Mat3 R = Eigen::AngleAxisd(ob.yaw_deg * std::numbers::pi / 180.0, Vec3::UnitZ()).toRotationMatrix();
      for (Vec3& v : mesh.vertices) v = R * (ob.scale * v) + ob.position;
      contact.add_obstacle(MeshObstacle(std::move(mesh), spec.resolve(ob.file)));
    }
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
    so.refresh_interval = refresh_interval > 0 ? refresh_interval : spec.refresh_interval_steps();
    so.threads = threads;
    sim = std::make_unique<Sim>(*model, integrator, so, std::move(contact));
    const TableMotion* m = &motion;
    sim->set_table_acceleration([m](double t) { return m->at(t); });
    for (size_t i = 0; i < items.size(); ++i) {
      bool rigid = items[i].fidelity == Fidelity::rigid;
      if (items[i].fidelity == Fidelity::automatic) {
        rigid = true;
        const std::string item_name = items[i].name;
        for (const auto& r : spec.outputs.sectional_forces)
          if (r.item == item_name) rigid = false;
      }
      if (rigid) {
        sim->set_rigid(items[i].body);
        rigid_bodies.push_back(items[i].body);
      }
    }
  }
};

namespace detail {

// Best rigid rotation of a body from its initial to its current nodes (for tilt and final state).
template <class Sim>
Mat3 body_rotation_of(const Sim& sim, const Model& model, int body, Vec3* centroid_shift = nullptr) {
  const auto& nodes = model.body(body).nodes;
  Vec3 Xc = Vec3::Zero(), xc = Vec3::Zero();
  for (int n : nodes) {
    Xc += model.node(n).X;
    xc += sim.position(n);
  }
  Xc /= double(nodes.size());
  xc /= double(nodes.size());
  if (centroid_shift) *centroid_shift = xc - Xc;
  return best_rotation(
      static_cast<int>(nodes.size()),
      [&](int i) { return std::pair<Vec3, Vec3>(model.node(nodes[i]).X, sim.position(nodes[i])); }, Xc, xc);
}

inline double tilt_of(const Mat3& Q) {
  return std::acos(std::clamp((Q * Vec3::UnitZ()).z(), -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << text;
}

// Geometry of the whole model for the VTU files and the 3-D figure.
template <class Sim>
LineMesh line_mesh(const Sim& sim, const Model& model, bool forces) {
  LineMesh mesh;
  mesh.points.reserve(model.num_nodes());
  for (int n = 0; n < model.num_nodes(); ++n) mesh.points.push_back(sim.position(n));
  std::vector<Vec3> disp(model.num_nodes());
  for (int n = 0; n < model.num_nodes(); ++n) disp[n] = sim.displacement(n);
  std::vector<double> body(model.num_elements()), axial(model.num_elements()), shear(model.num_elements()),
      moment(model.num_elements());
  for (int e = 0; e < model.num_elements(); ++e) {
    mesh.lines.push_back({model.elements()[e].n1, model.elements()[e].n2});
    body[e] = model.elements()[e].body;
    if (forces) {
      const auto f = sim.section_forces(e);
      axial[e] = f.N;
      shear[e] = std::hypot(f.Qy, f.Qz);
      moment[e] = std::hypot(f.My, f.Mz);
    }
  }
  mesh.add_point_vector("displacement", disp);
  mesh.add_cell_scalar("body", body);
  if (forces) {
    mesh.add_cell_scalar("N", axial);
    mesh.add_cell_scalar("Q", shear);
    mesh.add_cell_scalar("M", moment);
  }
  return mesh;
}

struct Progress {
  bool on = true;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  double last_print = -1;
  void update(double t, double t_end, bool force = false) {
    if (!on) return;
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!force && el - last_print < 0.25) return;
    last_print = el;
    const double frac = t_end > 0 ? std::clamp(t / t_end, 0.0, 1.0) : 1.0;
    const int width = 30, filled = static_cast<int>(frac * width);
    const double eta = frac > 1e-9 ? el * (1 - frac) / frac : 0;
    std::fprintf(stderr, "\r[%.*s%*s] %5.1f%%  t = %6.3f / %.3f s  elapsed %6.1f s  ETA %6.1f s ", filled,
                 "##############################", width - filled, "", 100 * frac, t, t_end, el, eta);
    if (force) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }
};

template <class Law, class Solver>
RunSummary run_composed(const SceneSpec& spec, const RunOptions& opt) {
  namespace fs = std::filesystem;
  RunSummary sum;
  const auto t_start = std::chrono::steady_clock::now();
  const std::string out = opt.out_dir.empty() ? spec.outputs.folder : opt.out_dir;
  fs::create_directories(out);
  sum.out_dir = out;
  const bool figures = opt.figures.value_or(spec.outputs.figures);

  SceneSimulation<Law, Solver> scene(spec);
  using Sim = typename SceneSimulation<Law, Solver>::Sim;
  const Model& model = *scene.model;
  const std::vector<ItemInfo>& items = scene.items;
  const TableMotion& motion = scene.motion;
  const RuntimeIntegrator& integ = scene.integrator;
  Sim& sim = *scene.sim;
  sum.elements = model.num_elements();
  sum.nodes = model.num_nodes();
  sum.bodies = model.num_bodies();

  // Output requests resolved to nodes and elements (errors name the request).
  struct MarkerOut {
    std::string name;
    int node;
  };
  std::vector<MarkerOut> markers;
  const auto item_by_name = [&](const std::string& name, const std::string& key) -> const ItemInfo& {
    for (const auto& it : items)
      if (it.name == name) return it;
    throw InputError(spec.source, 0, key, "no item named '" + name + "'");
  };
  for (size_t i = 0; i < spec.outputs.markers.size(); ++i) {
    const auto& m = spec.outputs.markers[i];
    const std::string key = "outputs.markers[" + std::to_string(i) + "]";
    const ItemInfo& it = item_by_name(m.item, key + ".item");
    int node = -1;
    if (m.point) node = nearest_node(model, it.body, it.to_world(*m.point));
    else if (const Marker* mk = it.marker(m.marker)) node = mk->node;
    else throw InputError(spec.source, 0, key + ".marker", "item '" + m.item + "' has no marker '" + m.marker + "'");
    markers.push_back({m.name.empty() ? m.item + "." + m.marker : m.name, node});
  }
  struct SectionOut {
    std::string name;
    int element;
  };
  std::vector<SectionOut> sections;
  for (size_t i = 0; i < spec.outputs.sectional_forces.size(); ++i) {
    const auto& r = spec.outputs.sectional_forces[i];
    const std::string key = "outputs.sectional_forces[" + std::to_string(i) + "]";
    const ItemInfo& it = item_by_name(r.item, key + ".item");
    const int m = find_member(model, it.body, r.member);
    if (m < 0) throw InputError(spec.source, 0, key + ".member", "item '" + r.item + "' has no member '" + r.member + "'");
    if (r.element < 0 || r.element >= model.member(m).element_count)
      throw InputError(spec.source, 0, key + ".element",
                       "member '" + r.member + "' has " + std::to_string(model.member(m).element_count) +
                           " elements (got " + std::to_string(r.element) + ")");
    sections.push_back({r.item + ":" + r.member + "#" + std::to_string(r.element), model.member(m).first_element + r.element});
  }

  // History files.
  std::vector<std::string> mcols{"t"};
  for (const auto& m : markers)
    for (const char* c : {"_x", "_y", "_z"}) mcols.push_back(m.name + c);
  CsvWriter marker_csv(out + "/markers.csv", mcols);
  std::vector<std::string> scols{"t"};
  for (const auto& s : sections)
    for (const char* c : {"_N", "_Qy", "_Qz", "_Mx", "_My", "_Mz"}) scols.push_back(s.name + c);
  CsvWriter section_csv(out + "/sectional_forces.csv", scols);
  CsvWriter energy_csv(out + "/energy.csv", {"t", "kinetic", "strain", "gravity_potential", "external_work",
                                             "contact_work", "damping_work", "plastic_work", "imbalance"});
  CsvWriter contact_csv(out + "/contact_forces.csv", {"t", "body_a", "body_b", "fx", "fy", "fz"});
  std::vector<std::string> body_names(model.num_bodies());
  for (int b = 0; b < model.num_bodies(); ++b) body_names[b] = model.body(b).name;
  PvdWriter pvd(out + "/room.pvd");
  if (spec.outputs.vtu_every > 0) fs::create_directories(out + "/vtu");

  std::vector<double> th;
  std::vector<std::vector<double>> mh(markers.size() * 3), sh(sections.size() * 2);
  std::vector<double> max_tilt(model.num_bodies(), 0.0);
  // Contact forces are averaged over every step: a penalty contact at rest chatters from one step to
  // the next, and rows every output_every steps sampled one phase of it (a cabinet at rest showed
  // -75 N from the floor on average). contact_forces.csv gets each pair's mean over the steps since
  // the previous row; what an item rests on is judged from the item-item vertical forces' mean over
  // every step of the run's last 0.5 s.
  const double t_end = opt.duration.value_or(spec.duration);
  const double settle_from = t_end - 0.5;
  std::map<std::pair<int, int>, double> settle_fz_on_a;
  int settle_rows = 0;
  std::map<std::pair<int, int>, Vec3> contact_sum;
  int contact_steps = 0;
  auto accumulate_contact = [&](const Sim& s) {
    const bool settling = s.time() >= settle_from - 1e-9;
    settle_rows += settling;
    ++contact_steps;
    for (const auto& pf : s.contact_model().pair_forces()) {
      contact_sum.try_emplace({pf.body_a, pf.body_b}, Vec3::Zero()).first->second += pf.force_on_a;
      if (settling && pf.body_a >= 0 && pf.body_b >= 0) settle_fz_on_a[{pf.body_a, pf.body_b}] += pf.force_on_a.z();
    }
  };

  const ContactStepEstimate step_estimate =
      contact_step_estimate(sim, model, items, scene_body_contacts(spec, model, items));
  auto record = [&](const Sim& s) {
    const double t = s.time();
    // Checked before anything of this row is written: a run creating energy stops here.
    const auto E = s.energy();
    if (s.steps() > 0) {
      const std::string why = energy_creation_diagnosis(E, spec.dt, opt.energy_creation_limit, step_estimate);
      if (!why.empty()) throw SimulationError(t, why);
    }
    th.push_back(t);
    std::vector<double> row{t};
    for (size_t i = 0; i < markers.size(); ++i) {
      const Vec3 d = s.displacement(markers[i].node);
      for (int c = 0; c < 3; ++c) {
        row.push_back(d[c]);
        mh[3 * i + c].push_back(d[c]);
      }
    }
    marker_csv.row(row);
    row.assign(1, t);
    for (size_t i = 0; i < sections.size(); ++i) {
      const auto f = s.section_forces(sections[i].element);
      for (double v : {f.N, f.Qy, f.Qz, f.Mx, f.My, f.Mz}) row.push_back(v);
      sh[2 * i].push_back(f.Qy);
      sh[2 * i + 1].push_back(f.Qz);
    }
    section_csv.row(row);
    energy_csv.row({t, E.kinetic, E.strain, E.gravity_potential, E.external_work, E.contact_work, E.damping_work,
                    E.plastic_work, E.imbalance()});
    if (s.steps() > 0) sum.max_energy_imbalance = std::max(sum.max_energy_imbalance, std::abs(E.imbalance()) / E.scale());
    if (contact_steps == 0) {  // the first row: the forces of the initial state
      for (const auto& pf : s.contact_model().pair_forces())
        contact_csv.row({t, double(pf.body_a), double(pf.body_b), pf.force_on_a.x(), pf.force_on_a.y(), pf.force_on_a.z()});
    } else {
      for (const auto& [pair, f] : contact_sum) {
        const Vec3 mean = f / contact_steps;
        if (mean.squaredNorm() > 0) contact_csv.row({t, double(pair.first), double(pair.second), mean.x(), mean.y(), mean.z()});
      }
    }
    contact_sum.clear();
    contact_steps = 0;
    for (int b = 0; b < model.num_bodies(); ++b) max_tilt[b] = std::max(max_tilt[b], tilt_of(body_rotation_of(s, model, b)));
  };
  // Peaks of the requested sectional forces over every step (the CSV rows are every output_every
  // steps and can miss an impact's peak, which lasts a few ms).
  struct SectionPeak {
    std::array<double, 6> min, max, t_min, t_max;
  };
  std::vector<SectionPeak> section_peaks(sections.size());
  for (auto& pk : section_peaks) {
    pk.min.fill(std::numeric_limits<double>::infinity());
    pk.max.fill(-std::numeric_limits<double>::infinity());
    pk.t_min.fill(0);
    pk.t_max.fill(0);
  }
  auto track_section_peaks = [&](const Sim& s) {
    for (size_t i = 0; i < sections.size(); ++i) {
      const auto f = s.section_forces(sections[i].element);
      const std::array<double, 6> v{f.N, f.Qy, f.Qz, f.Mx, f.My, f.Mz};
      auto& pk = section_peaks[i];
      for (int c = 0; c < 6; ++c) {
        if (v[c] < pk.min[c]) pk.min[c] = v[c], pk.t_min[c] = s.time();
        if (v[c] > pk.max[c]) pk.max[c] = v[c], pk.t_max[c] = s.time();
      }
    }
  };
  track_section_peaks(sim);
  auto write_vtu_frame = [&](const Sim& s) {
    const std::string name = "vtu/room_" + std::to_string(s.steps()) + ".vtu";
    write_vtu(out + "/" + name, line_mesh(s, model, true));
    pvd.add(s.time(), name);
    pvd.write();
  };

  sum.duration = t_end;
  Progress progress;
  progress.on = opt.progress;
  record(sim);
  if (spec.outputs.vtu_every > 0) write_vtu_frame(sim);
  try {
    while (sim.time() < t_end - 0.5 * spec.dt) {
      if (opt.stop && opt.stop->load()) {
        sum.status = "stopped";
        sum.diagnosis = "stopped by the user (interrupt) at t = " + std::to_string(sim.time()) + " s";
        break;
      }
      sim.step();
      track_section_peaks(sim);
      accumulate_contact(sim);
      if (sim.steps() % opt.output_every == 0) record(sim);
      if (spec.outputs.vtu_every > 0 && sim.steps() % spec.outputs.vtu_every == 0) write_vtu_frame(sim);
      progress.update(sim.time(), t_end);
    }
  } catch (const SimulationError& e) {
    sum.status = "diverged";
    sum.diagnosis = e.what();
  }
  progress.update(sim.time(), t_end, true);
  marker_csv.flush();
  section_csv.flush();
  energy_csv.flush();
  contact_csv.flush();

  // Final state of every item. A run that ended before its last 0.5 s judges support from its last step.
  if (settle_rows == 0) {
    settle_rows = 1;
    for (const auto& pf : sim.contact_model().pair_forces())
      if (pf.body_a >= 0 && pf.body_b >= 0) settle_fz_on_a[{pf.body_a, pf.body_b}] += pf.force_on_a.z();
  }
  for (const auto& it : items) {
    ItemFinalState st;
    st.name = it.name;
    Vec3 shift;
    const Mat3 Q = body_rotation_of(sim, model, it.body, &shift);
    const Vec3 cog0 = model.body_centre_of_gravity(it.body);
    Vec3 cog = Vec3::Zero();
    double m = 0;
    for (int e : model.body(it.body).elements) {
      const double me = model.elements()[e].line_mass * model.element_length(e);
      cog += me * 0.5 * (sim.position(model.elements()[e].n1) + sim.position(model.elements()[e].n2));
      m += me;
    }
    cog /= m;
    st.cog_displacement = cog - cog0;
    st.slide = std::hypot(st.cog_displacement.x(), st.cog_displacement.y());
    st.tilt_deg = tilt_of(Q);
    st.max_tilt_deg = max_tilt[it.body];
    double low = 1e9, low0 = 1e9;
    for (int n : model.body(it.body).nodes) {
      low = std::min(low, sim.position(n).z());
      low0 = std::min(low0, model.node(n).X.z());
    }
    st.lift = low - low0;
    // It rests (or leans) on the item that pushes it up the most (more than 1 N on average over the
    // last 0.5 s): an item pressed down by another one does not rest on it.
    double most_up = 1.0;
    for (const auto& [pair, fz_sum] : settle_fz_on_a) {
      const auto [a, b] = pair;
      const int other = a == it.body ? b : b == it.body ? a : -100;
      if (other < 0 || settle_rows == 0) continue;
      const double up = (a == it.body ? fz_sum : -fz_sum) / settle_rows;
      if (up > most_up) most_up = up, st.resting_on = body_names[other];
    }
    if (st.tilt_deg > 60) st.state = "overturned";
    else if (!st.resting_on.empty() && (st.tilt_deg > 5 || st.lift > 0.03)) st.state = "resting_on_item";
    else if (st.tilt_deg > 5) st.state = "tilted";
    else if (st.max_tilt_deg > 60 || st.lift < -0.05) st.state = "fell";
    else if (st.slide > 0.01) st.state = "slid";
    else st.state = "standing";
    sum.items.push_back(st);
  }
  const auto E = sim.energy();
  sum.energy_imbalance = std::abs(E.imbalance()) / E.scale();
  if (sum.status == "completed")
    sum.diagnosis = energy_loss_warning(E, spec.dt, opt.energy_loss_warning, step_estimate);
  sum.t_end = sim.time();
  sum.steps = sim.steps();
  sum.factorizations = sim.factorizations();
  sum.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();

  nlohmann::json final_state = nlohmann::json::array();
  for (const auto& s : sum.items)
    final_state.push_back({{"item", s.name},
                           {"state", s.state},
                           {"slide_m", s.slide},
                           {"tilt_deg", s.tilt_deg},
                           {"max_tilt_deg", s.max_tilt_deg},
                           {"lift_m", s.lift},
                           {"resting_on", s.resting_on},
                           {"cog_displacement_m", {s.cog_displacement.x(), s.cog_displacement.y(), s.cog_displacement.z()}}});
  write_text(out + "/final_state.json", final_state.dump(2) + "\n");
  auto section_peak_json = [&] {
    nlohmann::json a = nlohmann::json::array();
    const char* names[6] = {"N", "Qy", "Qz", "Mx", "My", "Mz"};
    for (size_t i = 0; i < sections.size(); ++i) {
      nlohmann::json e = {{"section", sections[i].name}};
      for (int c = 0; c < 6; ++c)
        e[names[c]] = {{"min", section_peaks[i].min[c]}, {"t_min_s", section_peaks[i].t_min[c]},
                       {"max", section_peaks[i].max[c]}, {"t_max_s", section_peaks[i].t_max[c]}};
      a.push_back(e);
    }
    return a;
  };
  nlohmann::json summary = {
      {"furniture_fem_version", version_string},
      {"scene", to_json(spec)},
      {"status", sum.status},
      {"diagnosis", sum.diagnosis},
      {"t_end_s", sum.t_end},
      {"duration_s", sum.duration},
      {"steps", sum.steps},
      {"dt_s", spec.dt},
      {"wall_seconds", sum.wall_seconds},
      {"elements", sum.elements},
      {"nodes", sum.nodes},
      {"bodies", sum.bodies},
      {"element_policy", std::string(AsiGaussTimoshenko::name)},
      {"integrator", integ.name()},
      {"linear_solver", std::string(Solver::name)},
      {"factorizations", sum.factorizations},
      {"rigid_bodies", [&] {
         nlohmann::json a = nlohmann::json::array();
         for (int b : scene.rigid_bodies) a.push_back(model.body(b).name);
         return a;
       }()},
      // Wall seconds: contact, the sweep over the bodies, the rest, total; inside the sweep, thread
      // seconds summed over the bodies (Simulation's StepTimings): solve, factorize, elements.
      {"step_time_s", {{"contact", sim.timings().contact},
                       {"bodies", sim.timings().bodies},
                       {"other", sim.timings().other()},
                       {"total", sim.timings().total},
                       {"solve_thread", sim.timings().solve},
                       {"factorize_thread", sim.timings().factorize},
                       {"elements_thread", sim.timings().elements}}},
      {"energy_imbalance_relative", sum.energy_imbalance},
      {"max_energy_imbalance_relative", sum.max_energy_imbalance},
      {"ground_motion_peak_m_s2", {motion.x.peak(), motion.has_y ? motion.y.peak() : 0.0, motion.has_z ? motion.z.peak() : 0.0}},
      {"final_state", final_state},
      {"sectional_force_peaks", section_peak_json()},
      {"eigen_version", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
                            std::to_string(EIGEN_MINOR_VERSION)}};
  write_text(out + "/summary.json", summary.dump(2) + "\n");

  if (figures) {
    // Marker histories, as the paper's Figures 16-18: one figure per marker, X / Y / Z panels.
    for (size_t i = 0; i < markers.size(); ++i) {
      LinePlot p;
      p.title("Displacement relative to the table: " + markers[i].name).xlabel("time (s)").panels(3);
      const char* axis[3] = {"X (m)", "Y (m)", "Z (m)"};
      for (int c = 0; c < 3; ++c) {
        p.ylabel(axis[c], c);
        p.add(th, mh[3 * i + c], markers[i].name, c);
      }
      std::string file = markers[i].name;
      for (char& ch : file)
        if (ch == '/' || ch == ' ' || ch == ':') ch = '_';
      p.save_png(out + "/marker_" + file + ".png", 1000, 750);
    }
    for (size_t i = 0; i < sections.size(); ++i) {
      LinePlot p;
      p.title("Shear force: " + sections[i].name).xlabel("time (s)").panels(2);
      p.ylabel("Qy (N)", 0).ylabel("Qz (N)", 1);
      p.add(th, sh[2 * i], "Qy", 0);
      p.add(th, sh[2 * i + 1], "Qz", 1);
      p.save_png(out + "/shear_" + std::to_string(i) + ".png", 1000, 600);
    }
    Wireframe3D w;
    w.title(spec.name + ": final state at t = " + std::to_string(sim.time()).substr(0, 5) + " s").camera(-60, 25);
    std::vector<Segment3> segs;
    std::vector<RGB> cols;
    for (int e = 0; e < model.num_elements(); ++e) {
      segs.push_back({sim.position(model.elements()[e].n1), sim.position(model.elements()[e].n2)});
      cols.push_back(palette_color(model.elements()[e].body));
    }
    w.add_segments(segs, cols);
    w.floor_grid(-0.5 * spec.table.size_x, 0.5 * spec.table.size_x, -0.5 * spec.table.size_y,
                 0.5 * spec.table.size_y, spec.table.floor_z, 0.5);
    for (const auto& wall : spec.walls) {
      const Vec3 u = Vec3::UnitZ().cross(wall.normal).normalized() * 0.5 * wall.width;
      const Vec3 h(0, 0, wall.height);
      w.add_quad({wall.point - u, wall.point + u, wall.point + u + h, wall.point - u + h}, RGB{150, 150, 150}, 0.15);
    }
    for (const auto& it : items) w.legend(it.name, palette_color(it.body));
    w.save_png(out + "/room_final.png", 1000, 800);
  }
  return sum;
}

}  // namespace detail

// Runs a scene; the contact law and the linear solver are compile-time policies, chosen here from
// the scene's runtime choice (each combination is one instantiation of the solver).
inline RunSummary run_scene(const SceneSpec& spec, const RunOptions& opt = {}) {
  validate(spec);
  const bool direct = spec.solver == SolverKind::direct;
  switch (spec.contact.law) {
    case ContactLawKind::paper:
      return direct ? detail::run_composed<PaperLaw, DirectLdltSolver>(spec, opt)
                    : detail::run_composed<PaperLaw, ConjugateGradientSolver>(spec, opt);
    case ContactLawKind::paper_anisotropic:
      return direct ? detail::run_composed<PaperAnisotropicFloorLaw, DirectLdltSolver>(spec, opt)
                    : detail::run_composed<PaperAnisotropicFloorLaw, ConjugateGradientSolver>(spec, opt);
    case ContactLawKind::spring_dashpot:
      return detail::run_composed<SpringDashpotLaw, DirectLdltSolver>(spec, opt);
    case ContactLawKind::hunt_crossley:
      return detail::run_composed<HuntCrossleyLaw, DirectLdltSolver>(spec, opt);
    case ContactLawKind::stick_slip:
      return detail::run_composed<StickSlipLaw, DirectLdltSolver>(spec, opt);
  }
  throw InputError(spec.source, 0, "contact.law", "unknown contact law");
}

}  // namespace furniture_fem
