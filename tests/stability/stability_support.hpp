#pragma once
// Shared by the stability suite (tests/stability/*.cpp): the short / full switch, a stepping harness
// for scenes that run_scene() cannot express (a pulse, an initial velocity, a tilted gravity, a
// start inside the floor), and the results table every case appends to.
//
// Short version (default, CI): every case on a mesh and duration that keep the whole executable
// under ~4 minutes on one core. Full version: FFEM_FULL_STABILITY=1 (full fidelity, long durations;
// about 40 minutes on one core, see docs/performance.md). Each case prints one line
//   [stability] <case> | <status> | imbalance <end> (max <max>) | bound <bound> | <wall> s
// and appends it to <build>/tests/tmp/stability/results.csv.
#include <catch2/catch.hpp>

#include <furniture_fem/scene/scene_runner.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace stability {

using namespace furniture_fem;
namespace fs = std::filesystem;

inline bool full_mode() {
  const char* e = std::getenv("FFEM_FULL_STABILITY");
  return e != nullptr && std::string(e) == "1";
}
inline const char* mode_name() { return full_mode() ? "full" : "short"; }

// A fresh, empty folder under the test temp folder.
inline std::string fresh_dir(const std::string& name) {
  const fs::path p = fs::path(FFEM_TEST_TMP) / "stability" / name;
  fs::remove_all(p);
  fs::create_directories(p.parent_path());
  return p.string();
}

// The paper's law with anisotropic floor friction (the configurations' choice), direct solver.
using Scene = SceneSimulation<DirectLdltSolver>;

struct ItemOutcome {
  std::string name;
  double tilt_deg = 0, max_tilt_deg = 0;
  Vec3 shift = Vec3::Zero();  // centroid of the nodes, from the start
};

// What a run ended with. Imbalances are the ledger's imbalance over its scale (signed: negative is
// energy the scheme lost, positive energy it made).
struct Outcome {
  std::string status = "completed";  // completed or diverged
  std::string diagnosis;
  double t_end = 0;
  double imbalance = 0;          // signed, at the end
  double max_imbalance = 0;      // largest |imbalance| / scale during the run
  double max_contact_work = 0;   // largest contact work / scale during the run (positive: energy given back)
  double wall = 0;
  long steps = 0;
  int elements = 0;
  bool finite = true;            // every position and velocity finite at the end
  std::vector<ItemOutcome> items;
  double min_z = 0;                          // lowest node at the end (m; the floor's contact onset is +L)
  double max_pair_force = 0;                 // largest item-item contact force during the run (N)

  const ItemOutcome& item(const std::string& name) const {
    for (const auto& it : items)
      if (it.name == name) return it;
    FAIL("no item " << name);
    return items.front();
  }
};

// Steps a scene to t_end with the runner's own energy check (energy_creation_diagnosis, checked every
// 10 steps as the runner does at its output rows): a run that creates energy, or whose state stops
// being finite, ends as "diverged" with the diagnosis.
inline Outcome run(Scene& scene, const SceneSpec& spec, double t_end,
                   double energy_creation_limit = RunOptions{}.energy_creation_limit) {
  auto& sim = *scene.sim;
  const Model& model = *scene.model;
  Outcome o;
  o.elements = model.num_elements();
  const double dt = sim.options().dt;
  const ContactStepEstimate est = contact_step_estimate(sim, model, scene.items, scene_body_contacts(spec, model, scene.items), spec.contact.law);
  std::vector<double> max_tilt(model.num_bodies(), 0.0);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    while (sim.time() < t_end - 0.5 * dt) {
      sim.step();
      for (const auto& pf : sim.contact_model().pair_forces())
        if (pf.body_a >= 0 && pf.body_b >= 0) o.max_pair_force = std::max(o.max_pair_force, pf.force_on_a.norm());
      if (sim.steps() % 10 == 0) {
        const auto E = sim.energy();
        o.max_imbalance = std::max(o.max_imbalance, std::abs(E.imbalance()) / E.scale());
        o.max_contact_work = std::max(o.max_contact_work, E.contact_work / E.scale());
        for (const auto& it : scene.items)
          max_tilt[it.body] = std::max(max_tilt[it.body], detail::tilt_of(detail::body_rotation_of(sim, model, it.body)));
        const std::string why = energy_creation_diagnosis(E, dt, energy_creation_limit, est);
        if (!why.empty()) throw SimulationError(sim.time(), why);
      }
    }
  } catch (const SimulationError& e) {
    o.status = "diverged";
    o.diagnosis = e.what();
  }
  o.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  o.t_end = sim.time();
  o.steps = sim.steps();
  const auto E = sim.energy();
  o.imbalance = E.imbalance() / E.scale();
  for (int n = 0; n < model.num_nodes(); ++n)
    o.finite = o.finite && sim.position(n).allFinite() && sim.velocity(n).allFinite();
  o.min_z = std::numeric_limits<double>::infinity();
  for (int n = 0; n < model.num_nodes(); ++n) o.min_z = std::min(o.min_z, sim.position(n).z());
  for (const auto& it : scene.items) {
    ItemOutcome io;
    io.name = it.name;
    Vec3 shift;
    io.tilt_deg = detail::tilt_of(detail::body_rotation_of(sim, model, it.body, &shift));
    io.max_tilt_deg = std::max(max_tilt[it.body], io.tilt_deg);
    io.shift = shift;
    o.items.push_back(io);
  }
  return o;
}

inline std::string num(double v, int precision = 3) {
  std::ostringstream o;
  o.precision(precision);
  o << v;
  return o.str();
}

// One line of the results table (stdout and results.csv).
inline void report(const std::string& name, const std::string& status, double imbalance, double max_imbalance,
                   const std::string& bound, double wall, const std::string& note = "") {
  char line[512];
  std::snprintf(line, sizeof line, "%s | %s | %s | %.3g | %.3g | %s | %.1f | %s", name.c_str(), mode_name(),
                status.c_str(), imbalance, max_imbalance, bound.c_str(), wall, note.c_str());
  std::printf("[stability] %s\n", line);
  std::fflush(stdout);
  const fs::path csv = fs::path(FFEM_TEST_TMP) / "stability" / "results.csv";
  fs::create_directories(csv.parent_path());
  const bool fresh = !fs::exists(csv);
  std::ofstream f(csv, std::ios::app);
  if (fresh) f << "case | mode | status | imbalance_end | max_abs_imbalance | bound | wall_s | note\n";
  f << line << "\n";
}
inline void report(const std::string& name, const Outcome& o, const std::string& bound, const std::string& note = "") {
  report(name, o.status, o.imbalance, o.max_imbalance, bound, o.wall, note);
}
inline void report(const std::string& name, const RunSummary& s, const std::string& bound, const std::string& note = "") {
  report(name, s.status, s.energy_imbalance, s.max_energy_imbalance, bound, s.wall_seconds, note);
}

// What every trusted run must show: it completed, its state is finite, and the ledger closes within
// `bound` (|imbalance| / scale at the end and at worst).
inline void require_trusted(const Outcome& o, double bound) {
  INFO("status " << o.status << " " << o.diagnosis);
  INFO("imbalance " << o.imbalance << " (max " << o.max_imbalance << "), contact work up to " << o.max_contact_work
                    << " of the scale, wall " << o.wall << " s");
  REQUIRE(o.status == "completed");
  REQUIRE(o.finite);
  CHECK(std::abs(o.imbalance) < bound);
  CHECK(o.max_imbalance < bound);
}

inline void require_trusted(const RunSummary& s, double bound) {
  INFO("status " << s.status << " " << s.diagnosis);
  INFO("imbalance " << s.energy_imbalance << " (max " << s.max_energy_imbalance << "), wall " << s.wall_seconds << " s");
  REQUIRE(s.status == "completed");
  for (const auto& it : s.items) {
    INFO(it.name);
    REQUIRE(std::isfinite(it.slide));
    REQUIRE(std::isfinite(it.tilt_deg));
    REQUIRE(it.cog_displacement.allFinite());
  }
  CHECK(s.energy_imbalance < bound);
  CHECK(s.max_energy_imbalance < bound);
}

// Run options for run_scene(): no progress bar, no figures, a fresh folder.
inline RunOptions quiet(const std::string& case_name) {
  RunOptions o;
  o.out_dir = fresh_dir(case_name);
  o.progress = false;
  o.figures = false;
  o.output_interval = 0.01;  // s: rows (and energy checks) every 10 ms of simulated time
  return o;
}

// A scene with no walls and the configurations' contact law; items added by the caller.
inline SceneSpec open_floor(const std::string& name, double dt, double duration) {
  SceneSpec s;
  s.name = name;
  s.source = name;
  s.walls = {};
  s.contact.law = law_kind<PaperAnisotropicSceneLaw>;
  s.dt = dt;
  s.duration = duration;
  s.outputs = OutputSpec{};
  s.outputs.figures = false;
  return s;
}

// The paper's configuration k under the built-in synthetic 3-D motion of peak `pga` along X.
inline SceneSpec synthetic_configuration(int k, double pga, double dt, double duration, Fidelity fidelity) {
  SceneSpec s = configuration(k, "");
  s.ground_motion = GroundMotionSpec{};
  s.ground_motion.source = MotionSource::synthetic;
  s.ground_motion.pga = pga;
  s.ground_motion.dimensions = MotionDimensions::three_d;
  s.outputs = OutputSpec{};
  s.outputs.figures = false;
  s.dt = dt;
  s.duration = duration;
  for (auto& it : s.items) it.fidelity = fidelity;
  return s;
}

}  // namespace stability
