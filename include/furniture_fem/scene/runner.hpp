#pragma once
// furniture_fem/scene/runner.hpp: the run loop.
//
//   RunSummary run_scene(const SceneSpec&, const RunOptions& = {}, const std::vector<RunObserver*>& extra = {})
//
// Builds the scene's simulation (the contact law is the registered law's kernel, chosen at run time; the
// linear solver a compile-time policy, picked here from the scene's choice),
// then steps it, calling the observers (observer.hpp) at the start, after every step and at the end:
// the standard ones picked from the scene's outputs and the options (observers.hpp), then `extra`. A
// stop request (Ctrl-C), a diverging step or a step that creates energy ends the run early, with
// everything written so far readable and the reason in the summary.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "../furniture/named_points.hpp"
#include "observer.hpp"
#include "forecast.hpp"
#include "observers.hpp"
#include "results_folder.hpp"
#include "run_checkpoint.hpp"
#include "scene_simulation.hpp"
#include "simulation_view.hpp"

#define FURNITURE_FEM_SCENE_INTERNAL
#include "detail/compiled_entry_points.hpp"
#undef FURNITURE_FEM_SCENE_INTERNAL

namespace furniture_fem {

// The scene's output requests resolved to nodes and elements; errors name the request.
inline ResolvedOutputs resolve_output_requests(const SceneSpec& spec, const Model& model, const std::vector<ItemInfo>& items) {
  const auto item_by_name = [&](const std::string& name, const std::string& key) -> const ItemInfo& {
    for (const auto& it : items)
      if (it.name == name) return it;
    throw InputError(spec.source, 0, key, "no item named '" + name + "'");
  };
  ResolvedOutputs out;
  for (size_t i = 0; i < spec.outputs.markers.size(); ++i) {
    const auto& m = spec.outputs.markers[i];
    const std::string key = "outputs.markers[" + std::to_string(i) + "]";
    const ItemInfo& it = item_by_name(m.item, key + ".item");
    int node = -1;
    if (m.point) node = nearest_node(model, it.body, it.to_world(*m.point));
    else if (const Marker* mk = it.marker(m.marker)) node = mk->node;
    else if (const auto local = named_point_local(it, m.marker)) node = nearest_node(model, it.body, it.to_world(*local));
    else throw InputError(spec.source, 0, key + ".marker", "item '" + m.item + "' has no marker '" + m.marker + "'");
    out.markers.push_back({m.name.empty() ? m.item + "." + m.marker : m.name, node});
  }
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
    out.sections.push_back({r.item + ":" + r.member + "#" + std::to_string(r.element), model.member(m).first_element + r.element});
  }
  return out;
}

// RunOptions::output_interval in steps of dt, rounded as SceneSpec::refresh_interval_steps() rounds.
inline int row_interval_steps(const RunOptions& opt, double dt) {
  if (!(opt.output_interval > 0) || !std::isfinite(opt.output_interval))
    throw InputError("RunOptions", 0, "output_interval",
                     "must be a positive time in s (got " + std::to_string(opt.output_interval) + ")");
  // Rounded and clamped as a double: lround of 1e300 / dt is out of long's range (undefined).
  return static_cast<int>(std::clamp(std::round(opt.output_interval / dt), 1.0, 1e9));
}

inline constexpr double max_run_steps = 1e9;  // at 1 ms: 11.6 days of simulated time

// The run's length (RunOptions::duration over the scene's): positive, finite and at most 1e9 steps of
// dt. `--duration 1e300` ran forever, `-1` and `0` completed after 0 steps (issue 13).
inline void check_run_length(const SceneSpec& spec, const RunOptions& opt) {
  const double t_end = opt.duration.value_or(spec.duration);
  const std::string key = opt.duration ? opt.duration_key : "duration";
  const std::string source = opt.duration ? opt.duration_source : spec.source;
  if (!(t_end >= spec.dt) || !std::isfinite(t_end))
    throw InputError(source, 0, key,
                     "must be a finite time of at least one step dt = " + detail::fmt(spec.dt) + " s (got " +
                         detail::fmt(t_end) + ")");
  if (!(t_end / spec.dt <= max_run_steps))
    throw InputError(source, 0, key,
                     detail::fmt(t_end) + " s is " + detail::fmt(t_end / spec.dt) + " steps of dt = " +
                         detail::fmt(spec.dt) + " s; a run may have at most 1e9");
}

// The results folder of a run: RunOptions::out_dir, or the scene's outputs.folder; empty when the run
// writes no files.
inline std::string results_folder_of(const SceneSpec& spec, const RunOptions& opt) {
  return opt.write_files ? (opt.out_dir.empty() ? spec.outputs.folder : opt.out_dir) : std::string();
}

// run.json's status for a RunSummary::status: completed -> done, stopped -> interrupted, diverged ->
// diverged (a run that ended with an error, the exception's message in "error": failed).
inline std::string run_record_status(const std::string& summary_status) {
  if (summary_status == "completed") return "done";
  if (summary_status == "stopped") return "interrupted";
  return summary_status;
}

// A run longer than its ground motion (a file record after its window, or the synthetic motion's
// duration) ran on with zero table acceleration, silently (issue 12): an InputError naming the run's
// length (the scene's `duration` or the run option) and the motion's end, unless
// ground_motion.pad_after_end asks for it. Half a step of dt is allowed for rounding.
inline void check_motion_covers_run(const SceneSpec& spec, const RunOptions& opt, const TableMotion& motion) {
  const GroundMotionSpec& g = spec.ground_motion;
  if (g.pad_after_end) return;
  const double t_end = opt.duration.value_or(spec.duration), end = motion_end(spec, motion);
  if (t_end <= end + 0.5 * spec.dt + 1e-12 * end) return;
  std::string what;
  if (g.source == MotionSource::synthetic)
    what = "the synthetic motion lasts " + detail::fmt(end) + " s (ground_motion.duration)";
  else
    what = "the record ends " + detail::fmt(end) + " s after the run's start (ground_motion.window from " +
           detail::fmt(g.window_start) + " s" + (g.window_end ? " to " + detail::fmt(*g.window_end) + " s" : std::string()) +
           " of record time)";
  throw InputError(opt.duration ? opt.duration_source : spec.source, 0, opt.duration ? opt.duration_key : "duration",
                   "the run lasts " + detail::fmt(t_end) + " s but " + what + ": shorten the run to at most " +
                       detail::fmt(end) + " s, " +
                       (g.source == MotionSource::synthetic ? "lengthen ground_motion.duration"
                                                            : "move or widen ground_motion.window") +
                       ", or set ground_motion.pad_after_end: true to run on with the table at rest after the motion");
}

// A dt longer than the ground motion's sample interval steps over the table's acceleration between
// samples (dt = 1 s over a 10 s run took 10 steps and reported a slide; issue 51): an InputError naming
// dt and the interval, unless allow_coarse_dt asks for it. A "points" motion has no interval.
inline void check_motion_sampling(const SceneSpec& spec, const TableMotion& motion) {
  if (spec.allow_coarse_dt || !motion.points.empty()) return;
  double sample = motion.x.dt;
  if (motion.has_y) sample = std::min(sample, motion.y.dt);
  if (motion.has_z) sample = std::min(sample, motion.z.dt);
  if (!(spec.dt > sample * (1 + 1e-9))) return;
  const std::string what = spec.ground_motion.source == MotionSource::synthetic ? "the synthetic motion's" : "the record's";
  throw InputError(spec.source, 0, "dt",
                   detail::fmt(spec.dt) + " s is longer than the ground motion's sample interval, " +
                       detail::fmt(sample) + " s (" + what +
                       "): the run would step over the table's acceleration between its samples; use a dt of at most " +
                       detail::fmt(sample) + " s, or set allow_coarse_dt: true to run it anyway");
}

// dt up to this many times the explicit contact's estimated stable step runs (the energy diagnoses
// name the estimate if the run then creates or loses energy); beyond it the scene is refused
// (check_contact_step). The estimate is conservative: measured margins in docs/scene/scene_file.md,
// "A dt too coarse for the motion or the contact".
inline constexpr double contact_step_error_factor = 2.0;

// A dt at which the explicit contact cannot resolve an item's rocking or impacts (issue 51; at 2.66
// times the estimate a cabinet slid four times as far) is an InputError naming dt, the estimate and its
// item, unless allow_coarse_dt asks for it.
inline void check_contact_step(const SceneSpec& spec, const ContactStepEstimate& est) {
  if (spec.allow_coarse_dt || !(spec.dt > contact_step_error_factor * est.dt)) return;
  throw InputError(spec.source, 0, "dt",
                   detail::fmt(spec.dt) + " s is " + detail::fmt(spec.dt / est.dt) +
                       " times the explicit contact's stable step, estimated at " + detail::fmt(est.dt) +
                       " s for item '" + est.item +
                       "' (2 sqrt(m / k) over its floor nodes, k the contact law's normal stiffness at rest): more than " +
                       detail::fmt(contact_step_error_factor) +
                       " times it, the contact cannot resolve the item's rocking or impacts; " + est.remedy() +
                       ", or set allow_coarse_dt: true to run it anyway");
}

// The stiffest spring a restraint puts on its node (N/m): what limits an explicit step on it.
inline double restraint_spring_max(const Restraint& r) {
  const RestraintParams& q = r.p;
  switch (r.kind) {
    case RestraintKind::l_bracket: return std::max(q.stiffness, q.shear_stiffness);
    case RestraintKind::pole:
    case RestraintKind::stopper: return std::max(q.stiffness, q.lateral_stiffness);
    case RestraintKind::strap:
    case RestraintKind::mat: return q.stiffness;
  }
  return q.stiffness;
}

// A restraint on a finite-element item whose contact is outside the implicit step is a load taken at
// the step's start: a spring k on a node of lumped mass m is stable for dt up to about 2 sqrt(m / k)
// (conservative: the frame around the node adds to it). Beyond contact_step_error_factor times that the
// node rings up and the restraint breaks: a `full` tall cabinet's wall brackets (1.7e6 N/m across the
// pull on a node of 21 g: 0.22 ms) sheared off at dt 0.6 ms and above after a 0.2 m/s^2 nudge along
// the wall, and held at 0.5 ms and below, or at 1 ms inside the step (contact.implicit "all"). An
// InputError naming the restraint, its spring, the node's mass and dt, unless allow_coarse_dt asks for
// it. nodal_mass(n): NaN for a rigid item's node (the spring moves the whole body: no such limit).
inline void check_restraint_step(const SceneSpec& spec, const RestraintSet& restraints, const std::vector<BodyContact>& contacts,
                                 const std::function<double(int)>& nodal_mass) {
  if (spec.allow_coarse_dt) return;
  for (std::size_t i = 0; i < restraints.size(); ++i) {
    const Restraint& r = restraints[i];
    if (r.between_items() || contacts.at(r.body).implicit) continue;  // inside the step: no limit
    const double k = restraint_spring_max(r), m = nodal_mass(r.node), stable = 2.0 * std::sqrt(m / k);
    if (!(spec.dt > contact_step_error_factor * stable)) continue;  // NaN (rigid) too
    throw InputError(spec.source, 0, "restraints[" + std::to_string(i) + "]",
                     "restraint '" + r.name + "' (" + std::string(to_string(r.kind)) + ") puts a spring of " +
                         detail::fmt(k) + " N/m on a node of " + detail::fmt(m) + " kg of an item whose contact is outside the " +
                         "implicit step, where it is a load, stable for dt up to about 2 sqrt(m / k) = " + detail::fmt(stable) +
                         " s; dt " + detail::fmt(spec.dt) + " s is more than " + detail::fmt(contact_step_error_factor) +
                         " times that, and the restraint would ring and break. Put the item's contact inside the step " +
                         "(contact.implicit \"all\"), reduce dt, or set allow_coarse_dt: true to run it anyway");
  }
}

namespace detail {

// The steps line of a run: how many, of what dt, to when, and the contact's stable step when explicit.
inline std::string run_steps_line(const SceneSpec& spec, double t, double t_end, long done, long total,
                                  const ContactStepEstimate& est) {
  std::string line = "run: " + std::to_string(total - done) + " steps" + (done > 0 ? " left" : "") +
                     " of dt = " + fmt(spec.dt) + " s from t = " + fmt(t) + " s to " + fmt(t_end) + " s";
  if (std::isfinite(est.dt))
    line += " (the explicit contact's stable step: " + fmt(est.dt) + " s, item '" + est.item + "')";
  return line;
}

// When a run started: the steady clock for its wall time, the system clock for run.json.
struct RunStart {
  std::chrono::steady_clock::time_point steady = std::chrono::steady_clock::now();
  std::chrono::system_clock::time_point utc = std::chrono::system_clock::now();
};

// run.json: written when the run starts (status "running") and again as the last file when it ends.
class RunRecord {
 public:
  RunRecord(const SceneSpec& spec, const RunOptions& opt, std::string out_dir, const RunStart& start)
      : path_(out_dir + "/" + run_record_file), start_(start) {
    j_ = {{"program", "furniture_fem"},
          {"furniture_fem_version", version_string},
          {"git_hash", opt.git_hash.empty() ? nlohmann::json() : nlohmann::json(opt.git_hash)},
          {"status", "running"},
          {"start_utc", iso8601_utc(start.utc)},
          {"end_utc", nullptr},
          {"wall_seconds", nullptr},
          {"out_dir", out_dir},
          {"options",
           {{"duration_s", opt.duration ? nlohmann::json(*opt.duration) : nlohmann::json()},
            {"output_interval_s", opt.output_interval},
            {"figures", opt.figures.value_or(spec.outputs.figures)},
            {"overwrite", opt.overwrite}}},
          {"scene", to_json(spec)}};
    write();
  }
  // A resumed run: from when (s of simulated time).
  void note_resume(double t) {
    j_["resumed_from_t_s"] = t;
    write();
  }
  // The end: status, the summary's status word and diagnosis (or the error), end time, wall time, and
  // the results files in the folder.
  void finish(const std::string& status, const std::string& summary_status, const std::string& diagnosis,
              const std::string& error = {}) {
    const auto now_utc = std::chrono::system_clock::now();
    j_["status"] = status;
    j_["summary_status"] = summary_status.empty() ? nlohmann::json() : nlohmann::json(summary_status);
    j_["diagnosis"] = diagnosis;
    if (!error.empty()) j_["error"] = error;
    j_["end_utc"] = iso8601_utc(now_utc);
    j_["wall_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_.steady).count();
    std::vector<std::string> files = results_files_in(std::filesystem::path(path_).parent_path());
    files.erase(std::remove(files.begin(), files.end(), std::string(run_record_file)), files.end());
    files.push_back(run_record_file);
    j_["files"] = files;  // the results files in the folder at the end, run.json last
    write();
  }

 private:
  void write() const { write_json_atomically(path_, j_); }
  std::string path_;
  RunStart start_;
  nlohmann::json j_;
};

// The index of the item named `name` in items, -1 if none (a checkpoint keeps an item by its index).
inline int item_index(const std::vector<ItemInfo>& items, const std::string& name) {
  for (std::size_t i = 0; i < items.size(); ++i)
    if (items[i].name == name) return static_cast<int>(i);
  return -1;
}
// The name of the item that is body `body` ("" if none).
inline std::string item_of_body(const std::vector<ItemInfo>& items, int body) {
  for (const auto& it : items)
    if (it.body == body) return it.name;
  return {};
}

// The parts of a composed scene the loop needs, whatever its law and solver.
struct ComposedScene {
  const Model& model;
  const std::vector<ItemInfo>& items;
  const TableMotion& motion;
  const std::vector<int>& rigid_bodies;
  SteppedSimulation& sim;
  double motion_scale = 1.0;  // SceneSimulation::motion_scale
  std::optional<SettledStart> settled_start;  // settle_at_rest's, for a settled start
  ContactStepEstimate estimate;               // the explicit contact's stable step (check_contact_step)
};

// The state after the last step the observers saw: what the observers' end() see of a run that
// diverged, whose simulation may by then hold NaN (its final state read "overturned, tilt 90, lift
// 999999999.975 m"; issue 13). The time, the pair forces and the requested sections' forces are copied
// after every step; the nodes' positions, displacements, rotations, velocities and accelerations once,
// when the run has ended (copy_nodes: the simulation keeps the start of a step that diverged); energy()
// is the ledger of the last history row that passed the energy check; the rest is the live simulation's.
// (Copied after every step, the nodes took 11 % of the instructions of configuration 3 rigid by hulls.)
class LastStepView final : public SimulationView {
 public:
  LastStepView(const SteppedSimulation& sim, const ResolvedOutputs& requests) : sim_(sim) {
    for (const auto& s : requests.sections) sections_.push_back({s.element, {}});
    commit();
  }
  // The step the observers have seen becomes the view's.
  void commit() {
    t_ = sim_.time();
    steps_ = sim_.steps();
    pair_forces_ = sim_.pair_forces();
    for (auto& [e, f] : sections_) f = sim_.section_forces(e);
  }
  // The nodes' state at the view's time, once the run has ended.
  void copy_nodes() {
    if (!sim_.copy_node_states_at(t_, now_))
      throw std::logic_error("LastStepView: the simulation keeps no node states at t = " + std::to_string(t_));
  }
  void set_energy(const EnergyLedger& E) { energy_ = E; }

  double time() const override { return t_; }
  long steps() const override { return steps_; }
  const Vec3& position(int n) const override { return now_.x[n]; }
  const Vec3& displacement(int n) const override { return now_.u[n]; }
  const Mat3& rotation(int n) const override { return now_.R[n]; }
  Vec6 velocity(int n) const override { return now_.v.segment<6>(6 * n); }
  Vec6 acceleration(int n) const override { return now_.a.segment<6>(6 * n); }
  double nodal_mass(int n) const override { return sim_.nodal_mass(n); }
  double kinetic_energy(int n) const override { return sim_.kinetic_energy(n); }
  SectionForces section_forces(int e) const override {
    for (const auto& [element, f] : sections_)
      if (element == e) return f;
    return sim_.section_forces(e);  // not a requested section: not copied
  }
  EnergyLedger energy() const override { return energy_; }
  const std::vector<PairForce>& pair_forces() const override { return pair_forces_; }
  const RestraintSet& restraints() const override { return sim_.restraints(); }
  long factorizations() const override { return sim_.factorizations(); }
  double factor_reuse_error() const override { return sim_.factor_reuse_error(); }
  long drift_refreshes() const override { return sim_.drift_refreshes(); }
  double max_frame_drift() const override { return sim_.max_frame_drift(); }
  long impact_steps() const override { return sim_.impact_steps(); }
  long impact_substeps() const override { return sim_.impact_substeps(); }
  const StepTimings& timings() const override { return sim_.timings(); }
  std::string integrator_name() const override { return sim_.integrator_name(); }
  std::string_view solver_name() const override { return sim_.solver_name(); }
  std::string_view element_name() const override { return sim_.element_name(); }

 private:
  const SteppedSimulation& sim_;
  double t_ = 0;
  long steps_ = 0;
  NodeStates now_;  // the nodes' state at t_ (copy_nodes)
  std::vector<PairForce> pair_forces_;
  std::vector<std::pair<int, SectionForces>> sections_;
  EnergyLedger energy_;
};

// The energy check at the history rows: a run creating energy ends as "diverged" before anything of
// the row is written (energy_creation_diagnosis).
inline void check_energy_creation(const RunView& run, const ContactStepEstimate& estimate) {
  // A ledger that overflowed compares false with every limit: it would pass silently (even with the
  // creation check off, a run whose energies are not finite is diverged).
  const EnergyLedger& E = run.row_energy;
  if (!std::isfinite(E.imbalance()) || !std::isfinite(E.scale()))
    throw SimulationError(run.sim.time(), "the energy ledger is not finite (its kinetic energy, strain energy or a "
                                          "work overflowed): the run diverged (try a smaller dt or a softer penalty)");
  const std::string why =
      energy_creation_diagnosis(run.row_energy, run.spec.dt, run.options.energy_creation_limit, estimate);
  if (!why.empty()) throw SimulationError(run.sim.time(), why);
}

inline RunSummary run_observed_in(const SceneSpec& spec, const RunOptions& opt, const ComposedScene& scene,
                                  const std::vector<RunObserver*>& extra, const RunStart& t_start,
                                  RunRecord* record = nullptr);

// Locks and clears the results folder, writes run.json (status "running"), runs, and writes run.json again as
// the last file: its final status, or "failed" and the error when an exception leaves the run.
inline RunSummary run_observed(const SceneSpec& spec, const RunOptions& opt, const ComposedScene& scene,
                               const std::vector<RunObserver*>& extra, const RunStart& t_start) {
  const std::string out_dir = results_folder_of(spec, opt);
  if (out_dir.empty()) return run_observed_in(spec, opt, scene, extra, t_start);
  // Held until run.json's last write: before the old results are removed or the checkpoint is read.
  const FolderLock lock(out_dir);
  if (!opt.resume) prepare_results_folder(out_dir, opt.overwrite);
  RunRecord record(spec, opt, out_dir, t_start);
  RunSummary sum;
  try {
    sum = run_observed_in(spec, opt, scene, extra, t_start, &record);
  } catch (const std::exception& e) {
    try {
      record.finish("failed", "", "", e.what());
    } catch (...) {  // the original error is the one to report
    }
    throw;
  }
  record.finish(run_record_status(sum.status), sum.status, sum.diagnosis);
  return sum;
}

inline RunSummary run_observed_in(const SceneSpec& spec, const RunOptions& opt, const ComposedScene& scene,
                                  const std::vector<RunObserver*>& extra, const RunStart& t_start, RunRecord* record) {
  SteppedSimulation& sim = scene.sim;
  const ResolvedOutputs requests = resolve_output_requests(spec, scene.model, scene.items);
  const double t_end = opt.duration.value_or(spec.duration);
  RunView run{spec,
              scene.model,
              scene.items,
              scene.motion,
              scene.rigid_bodies,
              requests,
              sim,
              opt,
              results_folder_of(spec, opt),
              t_end,
              row_interval_steps(opt, spec.dt),
              t_end - 0.5,
              sim.energy(),
              TableMotionIntegrator{}};
  const ContactStepEstimate& estimate = scene.estimate;

  RunSummary sum;
  sum.out_dir = run.out_dir;
  sum.duration = run.t_end;
  sum.ground_motion_scale = scene.motion_scale;
  sum.settled_start = scene.settled_start;
  sum.elements = scene.model.num_elements();
  sum.nodes = scene.model.num_nodes();
  sum.bodies = scene.model.num_bodies();
  const auto standard = standard_observers(run);
  std::vector<RunObserver*> observers;
  for (const auto& o : standard) observers.push_back(o.get());
  observers.insert(observers.end(), extra.begin(), extra.end());

  // A checkpoint, or going on from one, needs the results folder (checkpoint.bin).
  const nlohmann::json fingerprint = run.out_dir.empty() ? nlohmann::json() : checkpoint_fingerprint(spec, opt);
  EnergyLedger trusted = run.row_energy;  // the ledger of the last row that passed the energy check
  double wall_before = 0;                 // a resumed run: the wall time of its earlier parts
  if (opt.resume) {
    if (run.out_dir.empty()) throw InputError("RunOptions", 0, "resume", "a run that writes no files has no checkpoint");
    const RunnerState saved = resume_from_checkpoint(run.out_dir, fingerprint, sim, observers, run);
    run.row_energy = saved.row_energy;
    trusted = saved.trusted;
    sum.max_energy_imbalance = saved.max_energy_imbalance;
    wall_before = saved.wall_seconds;
    if (saved.settling_time >= 0)
      sum.settled_start = SettledStart{saved.settling_time, saved.settled_speed, saved.settled != 0,
                                       saved.fastest_item >= 0 ? run.items.at(saved.fastest_item).name : ""};
    if (record) record->note_resume(sim.time());
  } else {
    run.table.start(run.motion, sim.time());
    for (RunObserver* o : observers) o->begin(run);
  }
  const auto wall_now = [&] {
    return wall_before + std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start.steady).count();
  };
  const auto checkpoint = [&] {
    const SettledStart settled = sum.settled_start.value_or(SettledStart{-1, 0, true, {}});
    write_checkpoint(run.out_dir, fingerprint,
                     {run.row_energy, trusted, sum.max_energy_imbalance, wall_now(), settled.settling_time,
                      settled.max_node_speed, settled.settled ? 1 : 0, item_index(run.items, settled.fastest_item)},
                     run.table, sim, observers);
  };
  auto last_checkpoint = std::chrono::steady_clock::now();
  const bool periodic = !run.out_dir.empty() && opt.checkpoint_every > 0;
  LastStepView last(sim, requests);
  const long total_steps = std::lround(run.t_end / spec.dt);
  RunForecast forecast(opt, sim.steps(), total_steps,
                       run_steps_line(spec, sim.time(), run.t_end, sim.steps(), total_steps, estimate));
  try {
    while (sim.time() < run.t_end - 0.5 * spec.dt) {
      if (opt.stop && opt.stop->load()) {
        sum.status = "stopped";
        sum.diagnosis = "stopped by the user (interrupt) at t = " + std::to_string(sim.time()) + " s";
        if (sum.settled_start && sum.settled_start->interrupted) {
          sum.diagnosis += " while the items settled (contact.start \"settled\", after " +
                           std::to_string(sum.settled_start->settling_time) +
                           " s of settling): nothing run, no checkpoint; run it again";
          break;
        }
        if (!run.out_dir.empty()) {
          checkpoint();
          sum.diagnosis += "; resume with --resume (RunOptions::resume)";
        }
        break;
      }
      const StepInfo step = sim.step();
      // A step can end with an overflow the solver's own checks miss (a finite increment that takes a
      // position to infinity): no observer sees such a state, the run ends at the step before.
      if (const int n = sim.first_non_finite_node(); n >= 0)
        throw SimulationError(sim.time(), "node " + std::to_string(n) + " of body '" +
                                              scene.model.body(scene.model.node(n).body).name +
                                              "' has a non-finite position, rotation or velocity after the step: "
                                              "the step diverged (try a smaller dt or a softer penalty)");
      run.table.advance(run.motion, sim.time());
      if (run.row_due()) {
        run.row_energy = sim.energy();
        check_energy_creation(run, estimate);
        trusted = run.row_energy;
        sum.max_energy_imbalance = std::max(sum.max_energy_imbalance, std::abs(trusted.imbalance()) / trusted.scale());
      }
      for (RunObserver* o : observers) o->after_step(run, step);
      last.commit();
      forecast.after_step(sim.steps());
      if (periodic && std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint).count() >=
                          opt.checkpoint_every) {
        checkpoint();
        last_checkpoint = std::chrono::steady_clock::now();
      }
    }
  } catch (const SimulationError& e) {
    sum.status = "diverged";
    sum.diagnosis = e.what();
  }

  // A diverged run ends at the last step the observers saw, with every item's state "diverged".
  const bool diverged = sum.status == "diverged";
  last.set_energy(trusted);
  if (diverged) last.copy_nodes();
  const SimulationView& end_state = diverged ? static_cast<const SimulationView&>(last) : sim;
  const EnergyLedger E = diverged ? trusted : sim.energy();
  sum.energy_imbalance = std::abs(E.imbalance()) / E.scale();
  if (sum.status == "completed") sum.diagnosis = energy_loss_warning(E, spec.dt, opt.energy_loss_warning, estimate);
  sum.t_end = end_state.time();
  if (diverged) sum.t_diverged = last.time() + spec.dt;
  sum.steps = end_state.steps();
  sum.factorizations = sim.factorizations();
  sum.factor_reuse_error = sim.factor_reuse_error();
  sum.drift_refreshes = sim.drift_refreshes();
  sum.max_frame_drift = sim.max_frame_drift();
  sum.impact_steps = sim.impact_steps();
  sum.impact_substeps = sim.impact_substeps();
  sum.wall_seconds = wall_now();
  const RunView end_view{run.spec,      run.model,   run.items, run.motion,
                         run.rigid_bodies, run.requests, end_state, run.options,
                         run.out_dir,   run.t_end,   run.row_interval_steps, run.settle_from,
                         diverged ? trusted : run.row_energy, run.table};
  for (RunObserver* o : observers) o->end(end_view, sum);
  // Only a stopped run is to be gone on with (a killed one keeps its last periodic checkpoint).
  if (!run.out_dir.empty() && sum.status != "stopped") {
    std::error_code ignored;
    std::filesystem::remove(detail::checkpoint_path(run.out_dir), ignored);
  }
  return sum;
}

// contact.start "settled" (spec.hpp, ContactStart). The paper's normal damping, a force of constant size
// below velocity_regularisation, makes an item settle on its contacts over half a minute at 1 mm/s; at
// 0.1 m/s the same contact settles within a few tenths of a second (measured: docs/contact/verification_contact.md,
// "A settled start"). The other laws settle in their first steps at either value.
inline constexpr double settling_velocity_regularisation = 0.1;  // m/s
inline constexpr double settled_speed = 1e-5;                   // m/s: every node slower than this
// s: for this long (an item rocking on its contact passes through rest at each turn: stopped at a turn,
// a side table under spring_dashpot rocked on and moved 0.15 to 0.32 mm after t = 0), and at most this long.
inline constexpr double settled_quiet_time = 0.2, settling_max_time = 5.0;

// Steps a copy of the scene with the table still and the raised regularisation until every node has been
// slower than settled_speed for settled_quiet_time (at most settling_max_time), then loads its state into
// `sim` at rest at t = 0 (Simulation::restart_at_rest). A stop request ends it before its next step
// (`interrupted`, `sim` left as placed).
template <class Solver>
SettledStart settle_at_rest(const SceneSpec& spec, int threads, typename SceneSimulation<Solver>::Sim& sim,
                            const std::atomic<bool>* stop = nullptr) {
  SceneSpec settling_spec = spec;
  settling_spec.contact.velocity_regularisation =
      std::max(spec.contact.velocity_regularisation, settling_velocity_regularisation);
  SceneSimulation<Solver> settling(settling_spec, 0, threads);
  auto& s = *settling.sim;
  s.set_table_acceleration([](double) { return Vec3::Zero(); });
  int fastest_node = 0;
  const auto fastest = [&] {
    double v = 0;
    for (int n = 0; n < settling.model->num_nodes(); ++n)
      if (const double vn = s.velocity(n).template head<3>().norm(); vn > v) v = vn, fastest_node = n;
    return v;
  };
  SettledStart settled;
  double moving_at = 0;  // the last time a node was faster than settled_speed
  const auto quiet = [&] { return settled.settling_time - moving_at >= settled_quiet_time - 0.5 * spec.dt; };
  do {
    if (stop && stop->load()) {
      settled.settled = false;
      settled.interrupted = true;
      return settled;
    }
    s.step();
    if (const int n = s.first_non_finite_node(); n >= 0)
      throw SimulationError(s.time(), "contact.start \"settled\": the settling steps diverged at node " +
                                          std::to_string(n) + " (try a smaller dt)");
    settled.settling_time = s.time();
    settled.max_node_speed = fastest();
    if (settled.max_node_speed >= settled_speed) moving_at = settled.settling_time;
  } while (settled.settling_time < settling_max_time - 0.5 * spec.dt && !quiet());
  settled.settled = quiet();
  if (!settled.settled) settled.fastest_item = item_of_body(settling.items, settling.model->node(fastest_node).body);
  StateWriter w;
  s.save_state(w);
  StateReader r(w.bytes(), "the settled start");
  sim.load_state(r);
  sim.restart_at_rest();
  return settled;
}

// The explicit contact's stable step of a built scene, checked against its dt (check_contact_step).
template <class Solver>
ContactStepEstimate checked_contact_step(const SceneSpec& spec, const SceneSimulation<Solver>& scene) {
  const auto contacts = scene_body_contacts(spec, *scene.model, scene.items);
  const ContactStepEstimate est = contact_step_estimate(*scene.sim, *scene.model, scene.items, contacts, spec.contact.law);
  check_contact_step(spec, est);
  check_restraint_step(spec, scene.sim->contact().restraints(), contacts,
                       [&](int n) {
                         const int b = scene.model->node(n).body;
                         const bool rigid = std::find(scene.rigid_bodies.begin(), scene.rigid_bodies.end(), b) != scene.rigid_bodies.end();
                         return rigid ? std::numeric_limits<double>::quiet_NaN() : scene.sim->nodal_mass(n);
                       });
  return est;
}

// The summary of a run stopped before its model was built: no steps, no results folder (out_dir empty).
inline RunSummary stopped_before_start(const SceneSpec& spec, const RunOptions& opt) {
  RunSummary sum;
  sum.status = "stopped";
  sum.duration = opt.duration.value_or(spec.duration);
  sum.diagnosis = "stopped by the user (interrupt) while the ground motion was read: nothing run, nothing written";
  return sum;
}

// The only code instantiated per linear solver: building the simulation and its view (the contact law
// is the scene's registered law, a run-time kernel).
template <class Solver>
RunSummary run_composed(const SceneSpec& spec, const RunOptions& opt, const std::vector<RunObserver*>& extra,
                        const RunStart& t_start) {
  SceneSimulation<Solver> scene(spec, 0, opt.threads);
  const ContactStepEstimate estimate = checked_contact_step(spec, scene);  // before settling, too
  std::optional<SettledStart> settled;
  // A run going on from its checkpoint has its settled state there.
  if (spec.contact.start == ContactStart::settled && !opt.resume)
    settled = settle_at_rest<Solver>(spec, opt.threads, *scene.sim, opt.stop);
  SimulationViewOf<typename SceneSimulation<Solver>::Sim> view(*scene.sim);
  return run_observed(
      spec, opt,
      {*scene.model, scene.items, scene.motion, scene.rigid_bodies, view, scene.motion_scale, settled, estimate}, extra,
      t_start);
}

// The run of a checked scene with its linear solver, whatever its law (a run-time kernel: every law with
// either solver, a law registered by the user's program too). The compiled scene runner (target
// furniture_fem::scene_compiled, src/scene/run_scene.cpp) defines it once and defines
// FURNITURE_FEM_COMPILED_SCENE for its users, who then see this declaration only and compile none of the
// simulation; header-only use (furniture_fem::scene) defines it here.
#ifdef FFEM_SCENE_DECLARED_ONLY
RunSummary run_checked_scene(const SceneSpec& spec, const RunOptions& opt, const std::vector<RunObserver*>& extra,
                             const RunStart& t_start);
#else
FFEM_SCENE_ENTRY_INLINE RunSummary run_checked_scene(const SceneSpec& spec, const RunOptions& opt,
                                                     const std::vector<RunObserver*>& extra, const RunStart& t_start) {
  if (spec.solver != SolverKind::direct) return run_composed<ConjugateGradientSolver>(spec, opt, extra, t_start);
  return run_composed<DirectLdltSolver>(spec, opt, extra, t_start);
}
#endif

}  // namespace detail

// Declared only for the compiled scene runner's users (detail/compiled_entry_points.hpp).
#ifndef FFEM_SCENE_DECLARED_ONLY
// What run_scene refuses before it builds the model: the scene (validate), the output interval, the
// run's length, and the ground motion, read and checked (a record's unit, window, filter and scale)
// and set against the run's length and dt. A study checks each of its scenes with it before its first run.
FFEM_SCENE_ENTRY_INLINE void check_run_start(const SceneSpec& spec, const RunOptions& opt) {
  validate(spec);
  row_interval_steps(opt, spec.dt);
  check_run_length(spec, opt);
  // The simulation reads the motion again: a record is small.
  const TableMotion motion = scene_table_motion(spec);
  check_motion_covers_run(spec, opt, motion);
  check_motion_sampling(spec, motion);
}

// What run_scene refuses once the model is built, before the first step: an obstacle passing through
// an item at t = 0 (detail::check_obstacles_clear), an item above the ceiling (check_ceiling_clear) and
// a dt too long for the explicit contact (check_contact_step). A study checks each variant's scene with
// it before its first run.
FFEM_SCENE_ENTRY_INLINE void check_scene_model(const SceneSpec& spec) {
  if (spec.solver != SolverKind::direct) {
    const SceneSimulation<ConjugateGradientSolver> scene(spec, 0, 1);
    detail::checked_contact_step(spec, scene);
  } else {
    const SceneSimulation<DirectLdltSolver> scene(spec, 0, 1);
    detail::checked_contact_step(spec, scene);
  }
}

// Runs a scene with the standard observers (its outputs, as RunOptions asks) and then `extra`, in
// that order; returns its summary. RunOptions::write_files = false runs it without writing anything
// (the summary still holds the final states and the section peaks). A stop request (RunOptions::stop)
// already made when the ground motion has been read returns "stopped" with nothing built or written;
// one made later stops the run before its next step, its outputs written.
FFEM_SCENE_ENTRY_INLINE RunSummary run_scene(const SceneSpec& spec, const RunOptions& opt = {}, const std::vector<RunObserver*>& extra = {}) {
  const detail::RunStart t_start;
  check_run_start(spec, opt);
  // A stop request seen once the scene's records are read (Ctrl-C while a long record was read): nothing
  // run, nothing written, as when stopped while the scene was read (docs/command_line.md).
  if (opt.stop && opt.stop->load()) return detail::stopped_before_start(spec, opt);
  // A results folder that must not be written into fails before the model is built, too (the run takes
  // its lock once built: detail::run_observed).
  if (const std::string out = results_folder_of(spec, opt); !out.empty()) {
    refuse_if_locked(out);
    if (opt.resume) check_resumable_folder(out);
    else check_results_folder(out, opt.overwrite);
  }
  return detail::run_checked_scene(spec, opt, extra, t_start);
}
#endif

}  // namespace furniture_fem
