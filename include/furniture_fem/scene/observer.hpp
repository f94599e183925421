#pragma once
// furniture_fem/scene/observer.hpp: the interface of the observers that watch a run
// (docs/io/output.md, "Observers"); what a run is asked to do and what it reports (RunOptions,
// RunSummary) are in run_summary.hpp.
//
//   SimulationView   a read-only, type-erased view of the stepping simulation
//   RunView          what every observer receives: the scene, the model, the view, the options
//   RunObserver      begin / after_step / end: the one interface of every output
//
// Nothing here depends on the contact law or the linear solver: observers are compiled once, and only
// the stepping is instantiated per law and solver (runner.hpp).
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "../contact/pair_force.hpp"
#include "../core/checkpoint.hpp"
#include "../core/elements.hpp"
#include "../core/integrators.hpp"
#include "../core/node_states.hpp"
#include "../core/rotation.hpp"
#include "../core/step_report.hpp"
#include "../excitation/excitation.hpp"
#include "../furniture/furniture.hpp"
#include "../harm/item_box.hpp"
#include "../restraints/restraint_set.hpp"
#include "run_summary.hpp"
#include "spec.hpp"

namespace furniture_fem {

// A read-only view of the stepping simulation, whatever its contact law and linear solver (the
// methods of Simulation an observer needs; see docs/core for their meaning).
class SimulationView {
 public:
  virtual ~SimulationView() = default;
  virtual double time() const = 0;                       // s
  virtual long steps() const = 0;
  virtual const Vec3& position(int node) const = 0;      // m, world axes
  virtual const Vec3& displacement(int node) const = 0;  // m, relative to the table
  virtual const Mat3& rotation(int node) const = 0;
  virtual Vec6 velocity(int node) const = 0;
  virtual Vec6 acceleration(int node) const = 0;         // m/s^2, rad/s^2, relative to the table
  virtual double nodal_mass(int node) const = 0;         // kg
  virtual double kinetic_energy(int node) const = 0;     // J, its mass's and rotary inertia's
  virtual SectionForces section_forces(int element) const = 0;
  virtual EnergyLedger energy() const = 0;               // J; costs a sweep over the elements
  // Contact force on body_a from body_b, summed per pair, in the last contact evaluation (body_b may be
  // PairForce::floor_id, wall_id, obstacle_id or ceiling_id).
  virtual const std::vector<PairForce>& pair_forces() const = 0;
  virtual const RestraintSet& restraints() const = 0;  // the room's restraints and their committed states
  virtual long factorizations() const = 0;
  virtual double factor_reuse_error() const = 0;  // Simulation::factor_reuse_error
  // Refactorisations for a member's frame drift, and the largest drift a reused factorisation solved
  // with (Simulation::drift_refreshes, max_frame_drift; integrator.frame_drift_refresh).
  virtual long drift_refreshes() const = 0;
  virtual double max_frame_drift() const = 0;
  // Steps divided for impacts, and the sub-steps they took (Simulation::impact_steps, impact_substeps).
  virtual long impact_steps() const = 0;
  virtual long impact_substeps() const = 0;
  virtual const StepTimings& timings() const = 0;
  virtual std::string integrator_name() const = 0;
  virtual std::string_view solver_name() const = 0;
  virtual std::string_view element_name() const = 0;
};

// The stepping side, seen only by the runner.
class SteppedSimulation : public SimulationView {
 public:
  virtual StepInfo step() = 0;
  // Simulation::save_state / load_state (core/checkpoint.hpp).
  virtual void save_state(StateWriter& w) const = 0;
  virtual void load_state(StateReader& r) = 0;
  // Every node's state at time t copied into `into` in one call, array by array (five virtual calls
  // per node took 5 % of a rigid study run: docs/performance.md section 8): t the current time, or
  // the start of the last step (what is left of a step that diverged); false for any other t.
  virtual bool copy_node_states_at(double t, NodeStates& into) const = 0;
  // The first node whose position, rotation or velocity is not finite, -1 if none.
  virtual int first_non_finite_node() const = 0;
};

// The scene's outputs requests resolved to nodes and elements (resolve_output_requests, runner.hpp).
struct MarkerOutput {
  std::string name;  // the column prefix: item.marker, or the request's name
  int node;
};
struct SectionOutput {
  std::string name;  // item:member#element
  int element;
};
struct ResolvedOutputs {
  std::vector<MarkerOutput> markers;
  std::vector<SectionOutput> sections;
};

// What every observer receives: the scene and its model, the simulation (read-only), the options,
// and the run's schedule. One RunView lives for the whole run; its `sim` always shows the current state.
// The table's velocity and displacement, integrated from its acceleration (RunView::motion) step by
// step from rest: exact for an acceleration linear over each step (a record sampled at dt). The runner
// integrates the table's motion once per run (RunView::table); an observer may integrate another motion
// (input_motion.csv: the ground's beside a building's storey).
class TableMotionIntegrator {
 public:
  void start(const TableMotion& m, double t) {
    t_ = t;
    a_ = m.at(t);
    v_.setZero();
    d_.setZero();
  }
  void advance(const TableMotion& m, double t) {
    const double h = t - t_;
    const Vec3 a1 = m.at(t);
    d_ += h * v_ + h * h / 6.0 * (2.0 * a_ + a1);
    v_ += 0.5 * h * (a_ + a1);
    a_ = a1;
    t_ = t;
  }
  const Vec3& acceleration() const { return a_; }
  const Vec3& velocity() const { return v_; }
  const Vec3& displacement() const { return d_; }
  template <class Self, class Archive>
    requires std::is_same_v<std::remove_const_t<Self>, TableMotionIntegrator>
  friend void transfer_state(Self& m, Archive& ar) {
    ar(m.t_, m.a_, m.v_, m.d_);
  }

 private:
  double t_ = 0;
  Vec3 a_ = Vec3::Zero(), v_ = Vec3::Zero(), d_ = Vec3::Zero();
};

struct RunView {
  const SceneSpec& spec;
  const Model& model;
  const std::vector<ItemInfo>& items;
  const TableMotion& motion;                // the table's acceleration (m/s^2)
  const std::vector<int>& rigid_bodies;     // bodies solved as rigid bodies
  const ResolvedOutputs& requests;
  const SimulationView& sim;
  const RunOptions& options;
  std::string out_dir;                      // the results folder; empty: write no files
  double t_end = 0;                         // the time the run is to reach (s)
  int row_interval_steps = 1;               // history rows every this many steps (RunOptions::output_interval)
  double settle_from = 0;                   // the run's last 0.5 s start here (s): what rests on what
  // The energy ledger at the latest history row (the runner computes it once per row).
  EnergyLedger row_energy;
  // The table's acceleration, velocity and displacement at sim.time(), integrated from rest at the run's
  // start (the runner advances it after every step, before the observers see the step).
  TableMotionIntegrator table;

  // True at the initial state and every row_interval_steps steps: history observers write a row.
  bool row_due() const { return sim.steps() % row_interval_steps == 0; }
  const ItemInfo& item(const std::string& name) const {
    for (const auto& it : items)
      if (it.name == name) return it;
    throw InputError(spec.source, 0, "item", "no item named '" + name + "'");
  }
};

// An observer of a run. The runner calls, for each observer in its list, in list order:
//   begin(run)             once, at the initial state (run.sim.steps() == 0), before the first step;
//   after_step(run, step)  after every step the run keeps (a step that throws, or that fails the
//                          energy check at a history row, ends the run before any observer sees it);
//   end(run, summary)      once, however the run ended (completed, stopped, diverged), with the summary's
//                          status, diagnosis, times, counts and energy figures filled in, plus what the
//                          observers before this one added (final states, section peaks).
// An observer reads the simulation through run.sim only, so it cannot change the run's results. A
// SimulationError thrown from after_step ends the run as "diverged"; any other exception leaves run_scene.
//
// Checkpoints (RunOptions::checkpoint_every, resume; docs/io/output.md, "Checkpoints"): save(w) writes
// what the observer needs to go on (its files flushed first); on a resumed run, resume(run, r) is
// called instead of begin: it reads that back and reopens its files where the checkpoint left them.
// An observer that keeps nothing from one call to the next needs neither.
class RunObserver {
 public:
  virtual ~RunObserver() = default;
  virtual void begin(const RunView& run) {}
  virtual void after_step(const RunView& run, const StepInfo& step) {}
  virtual void end(const RunView& run, RunSummary& summary) {}
  virtual void save(StateWriter&) {}
  virtual void resume(const RunView&, StateReader&) {}
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

}  // namespace detail

// The item's outer box where its body is now (harm/item_box.hpp): its best rigid motion applied to the
// box as placed.
inline OrientedBox current_item_box(const SimulationView& sim, const Model& model, const ItemInfo& item) {
  Vec3 shift;
  const Mat3 Q = detail::body_rotation_of(sim, model, item.body, &shift);
  Vec3 Xc = Vec3::Zero();
  for (int n : model.body(item.body).nodes) Xc += model.node(n).X;
  Xc /= double(model.body(item.body).nodes.size());
  return item_box(item, Q, Xc, Xc + shift);
}

// Angle of a body's vertical axis from the vertical (deg), from its best rigid rotation.
inline double body_tilt_deg(const SimulationView& sim, const Model& model, int body) {
  return detail::tilt_of(detail::body_rotation_of(sim, model, body));
}

}  // namespace furniture_fem
