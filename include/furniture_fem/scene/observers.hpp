#pragma once
// furniture_fem/scene/observers.hpp: the run's built-in observers (observer.hpp), one per output.
//
//   ProgressBar            progress and ETA on stderr                   RunOptions::progress
//   FinalStates            every item's final state -> RunSummary::items                 always
//   SectionPeaks           sectional force extremes -> RunSummary::section_peaks         always
//   EnergyCheck            the energy ledger's verdict -> RunSummary::energy             always
//   MarkerHistory          markers.csv                                   files
//   SectionalForceHistory  sectional_forces.csv                          files
//   EnergyHistory          energy.csv                                    files
//   ContactForceHistory    contact_forces.csv (contact_pairs.csv)        files (contact_force_history.hpp)
//   InputMotionHistory     input_motion.csv                              files
//   RestraintOutcomes      each restraint's peak and break -> RunSummary::restraints   restraints
//   RestraintHistory       restraints.csv, restraints.png                files, restraints (restraint_observers.hpp)
//   OccupantStrikes        each strike on an occupant -> RunSummary::occupants, strikes.csv   occupants
//                                                                        (occupant_observers.hpp)
//   ExitOutcomes           each exit's clear width -> RunSummary::exits  exits (exit_observers.hpp)
//   ExitHistory            exits.csv                                     files, exits
//   HarmFigures            plan.png, timeline.png                        files, figures, occupants or exits
//                                                                        (harm_figures.hpp)
//   VtuSeries              room.pvd, vtu/room_<step>.vtu                 files, outputs.vtu_every > 0
//   FinalStateFile         final_state.json                              files
//   SummaryFile            summary.json                                  files
//   Figures                marker_*.png, shear_*.png, input_motion.png,  files, figures on
//                          energy.png, room_final.png (input_spectra.png on a building's storey)
//
// standard_observers() picks them from the scene's outputs and the RunOptions. The file formats are
// described in docs/io/output.md.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../figures/plot.hpp"
#include "../io/csv.hpp"
#include "../io/vtk.hpp"
#include "contact_force_history.hpp"
#include "exit_observers.hpp"
#include "harm_figures.hpp"
#include "observer.hpp"
#include "occupant_observers.hpp"
#include "restraint_observers.hpp"
#include "row_history.hpp"
#include "writer.hpp"

#define FURNITURE_FEM_SCENE_INTERNAL
#include "detail/floor_outputs.hpp"
#undef FURNITURE_FEM_SCENE_INTERNAL

namespace furniture_fem {

// One item's final state, as final_state.json and a study's run records write it (one set of keys);
// nlohmann's numbers round-trip exactly.
inline nlohmann::json item_final_state_json(const ItemFinalState& s) {
  return {{"item", s.name},
          {"state", s.state},
          {"slide_m", s.slide},
          {"tilt_deg", s.tilt_deg},
          {"max_tilt_deg", s.max_tilt_deg},
          {"lift_m", s.lift},
          {"resting_on", s.resting_on},
          {"cog_displacement_m", {s.cog_displacement.x(), s.cog_displacement.y(), s.cog_displacement.z()}},
          {"max_node_speed_m_s", s.max_node_speed}};
}
// Reads it back; throws nlohmann::json::exception on a missing key or a wrong type.
inline ItemFinalState item_final_state_from_json(const nlohmann::json& j) {
  ItemFinalState s;
  s.name = j.at("item").get<std::string>();
  s.state = j.at("state").get<std::string>();
  s.slide = j.at("slide_m").get<double>();
  s.tilt_deg = j.at("tilt_deg").get<double>();
  s.max_tilt_deg = j.at("max_tilt_deg").get<double>();
  s.lift = j.at("lift_m").get<double>();
  s.resting_on = j.at("resting_on").get<std::string>();
  const auto c = j.at("cog_displacement_m").get<std::array<double, 3>>();
  s.cog_displacement = Vec3(c[0], c[1], c[2]);
  s.max_node_speed = j.at("max_node_speed_m_s").get<double>();
  return s;
}

namespace detail {

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  if (!f) throw OutputError("cannot write " + path);
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

inline std::array<double, 6> section_components(const SectionForces& f) { return {f.N, f.Qy, f.Qz, f.Mx, f.My, f.Mz}; }

inline const std::array<const char*, 7>& ledger_terms() {
  static const std::array<const char*, 7> names{"kinetic",      "strain",       "gravity_potential", "external_work",
                                                "contact_work", "damping_work", "plastic_work"};
  return names;
}
inline std::array<double, 7> ledger_values(const EnergyLedger& E) {
  return {E.kinetic, E.strain, E.gravity_potential, E.external_work, E.contact_work, E.damping_work, E.plastic_work};
}

inline std::string fmt3(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}

inline nlohmann::json energy_verdict_json(const EnergyVerdict& v) {
  return {{"closes", v.closes},
          {"tolerance_relative", v.tolerance},
          {"imbalance_J", v.imbalance},
          {"imbalance_relative", v.relative},
          {"scale_J", v.scale},
          {"largest_change", {{"t_from_s", v.t_from},
                              {"t_to_s", v.t_to},
                              {"imbalance_J", v.imbalance_step},
                              {"term", v.term.empty() ? nlohmann::json() : nlohmann::json(v.term)},
                              {"term_J", v.term_step}}},
          {"text", v.text}};
}

// contact.start "settled": how long the items took, the speed left, and whether they settled (if not, the
// item with the fastest node).
inline nlohmann::json settled_start_json(const SettledStart& s) {
  return {{"settling_time_s", s.settling_time},
          {"max_node_speed_m_s", s.max_node_speed},
          {"settled", s.settled},
          {"fastest_item", s.settled ? nlohmann::json() : nlohmann::json(s.fastest_item)}};
}

inline nlohmann::json final_state_json(const std::vector<ItemFinalState>& items) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& s : items) a.push_back(item_final_state_json(s));
  return a;
}

// The largest nodal speed at the end over every item (m/s): a scene at rest shows it is at rest.
inline double max_node_speed(const std::vector<ItemFinalState>& items) {
  double v = 0;
  for (const auto& s : items) v = std::max(v, s.max_node_speed);
  return v;
}

inline nlohmann::json section_peaks_json(const std::vector<SectionForcePeak>& peaks) {
  nlohmann::json a = nlohmann::json::array();
  const char* names[6] = {"N", "Qy", "Qz", "Mx", "My", "Mz"};
  for (const auto& pk : peaks) {
    nlohmann::json e = {{"section", pk.section}};
    for (int c = 0; c < 6; ++c)
      e[names[c]] = {{"min", pk.min[c]}, {"t_min_s", pk.t_min[c]}, {"max", pk.max[c]}, {"t_max_s", pk.t_max[c]}};
    a.push_back(e);
  }
  return a;
}

}  // namespace detail

class ProgressBar : public RunObserver {
 public:
  void begin(const RunView& run) override {
    start_ = std::chrono::steady_clock::now();
    last_print_ = -1;
  }
  void after_step(const RunView& run, const StepInfo&) override { update(run.sim.time(), run.t_end, false); }
  void end(const RunView& run, RunSummary&) override { update(run.sim.time(), run.t_end, true); }
  void resume(const RunView& run, StateReader&) override { begin(run); }

 private:
  std::chrono::steady_clock::time_point start_;
  double last_print_ = -1;
  void update(double t, double t_end, bool last) {
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (!last && el - last_print_ < 0.25) return;
    last_print_ = el;
    const double frac = t_end > 0 ? std::clamp(t / t_end, 0.0, 1.0) : 1.0;
    const int width = 30, filled = static_cast<int>(frac * width);
    const double eta = frac > 1e-9 ? el * (1 - frac) / frac : 0;
    std::fprintf(stderr, "\r[%.*s%*s] %5.1f%%  t = %6.3f / %.3f s  elapsed %6.1f s  ETA %6.1f s ", filled,
                 "##############################", width - filled, "", 100 * frac, t, t_end, el, eta);
    if (last) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }
};

// Every item's final state (RunSummary::items): slide, tilt, lift and what it rests on. The largest
// tilt is sampled at the history rows. What an item rests on is judged from the item-item vertical
// contact forces' mean over every step of the run's last 0.5 s (a penalty contact at rest chatters
// from one step to the next); a run that ended before its last 0.5 s judges from its last step.
class FinalStates : public RunObserver {
 public:
  void begin(const RunView& run) override {
    max_tilt_.assign(run.model.num_bodies(), 0.0);
    // The slide is counted from where each item stands at t = 0: its placement, or after a settled
    // start (contact.start) where it settled.
    cog_start_.clear();
    for (int b = 0; b < run.model.num_bodies(); ++b)
      cog_start_.push_back(run.model.body_centre_of_gravity(b, [&run](int n) { return run.sim.position(n); }));
    track_tilt(run);
  }
  void after_step(const RunView& run, const StepInfo&) override {
    if (run.sim.time() >= run.settle_from - 1e-9) {
      ++settle_steps_;
      add_item_forces(run.sim.pair_forces());
    }
    if (run.row_due()) track_tilt(run);
  }
  void end(const RunView& run, RunSummary& summary) override {
    if (settle_steps_ == 0) {
      settle_steps_ = 1;
      add_item_forces(run.sim.pair_forces());
    }
    const std::vector<int> resting_on = bodies_rested_on(run.model.num_bodies());
    for (const auto& it : run.items) {
      summary.items.push_back(final_state(run, it, resting_on[it.body]));
      if (summary.status == "diverged") summary.items.back().state = "diverged";
    }
  }
  void save(StateWriter& w) override { w(max_tilt_, settle_fz_on_a_, settle_steps_, cog_start_); }
  void resume(const RunView&, StateReader& r) override { r(max_tilt_, settle_fz_on_a_, settle_steps_, cog_start_); }

 private:
  std::vector<double> max_tilt_;
  std::vector<Vec3> cog_start_;  // per body, at t = 0
  std::map<std::pair<int, int>, double> settle_fz_on_a_;
  int settle_steps_ = 0;

  void track_tilt(const RunView& run) {
    for (int b = 0; b < run.model.num_bodies(); ++b) max_tilt_[b] = std::max(max_tilt_[b], body_tilt_deg(run.sim, run.model, b));
  }
  void add_item_forces(const std::vector<PairForce>& forces) {
    for (const auto& pf : forces)
      if (pf.body_a >= 0 && pf.body_b >= 0) settle_fz_on_a_[{pf.body_a, pf.body_b}] += pf.force_on_a.z();
  }
  // Per body, the body it rests (or leans) on: the one that pushes it up the most, more than 1 N on
  // average over the last 0.5 s (an item pressed down by another one does not rest on it); -1: none.
  // One pass over the pairs, in their order, for every body (a pass per item was quadratic).
  std::vector<int> bodies_rested_on(int bodies) const {
    std::vector<int> on(bodies, -1);
    std::vector<double> most_up(bodies, 1.0);
    const auto consider = [&](int body, int other, double up) {
      if (up > most_up[body]) most_up[body] = up, on[body] = other;
    };
    for (const auto& [pair, fz_sum] : settle_fz_on_a_) {
      const auto [a, b] = pair;
      consider(a, b, fz_sum / settle_steps_);
      consider(b, a, -fz_sum / settle_steps_);
    }
    return on;
  }
  ItemFinalState final_state(const RunView& run, const ItemInfo& it, int resting_on) const {
    const Model& model = run.model;
    const SimulationView& sim = run.sim;
    ItemFinalState st;
    st.name = it.name;
    const Mat3 Q = detail::body_rotation_of(sim, model, it.body);
    const Vec3 cog = model.body_centre_of_gravity(it.body, [&sim](int n) { return sim.position(n); });
    st.cog_displacement = cog - cog_start_[it.body];
    st.slide = std::hypot(st.cog_displacement.x(), st.cog_displacement.y());
    st.tilt_deg = detail::tilt_of(Q);
    st.max_tilt_deg = max_tilt_[it.body];
    double low = 1e9, low0 = 1e9;
    for (int n : model.body(it.body).nodes) {
      low = std::min(low, sim.position(n).z());
      low0 = std::min(low0, model.node(n).X.z());
      st.max_node_speed = std::max(st.max_node_speed, sim.velocity(n).head<3>().norm());
    }
    st.lift = low - low0;
    if (resting_on >= 0) st.resting_on = model.body(resting_on).name;
    if (st.tilt_deg > overturned_tilt_deg) st.state = "overturned";
    else if (!st.resting_on.empty() && (st.tilt_deg > 5 || st.lift > 0.03)) st.state = "resting_on_item";
    else if (st.tilt_deg > 5) st.state = "tilted";
    else if (has_fallen(st.max_tilt_deg, st.lift)) st.state = "fell";
    else if (st.slide > 0.01) st.state = "slid";
    else st.state = "standing";
    return st;
  }
};

// Extremes of the requested sectional forces over every step (RunSummary::section_peaks): the
// history rows can miss an impact's peak, which lasts a few ms.
class SectionPeaks : public RunObserver {
 public:
  void begin(const RunView& run) override {
    name_peaks(run);
    track(run);
  }
  void after_step(const RunView& run, const StepInfo&) override { track(run); }
  void end(const RunView&, RunSummary& summary) override { summary.section_peaks = peaks_; }
  void save(StateWriter& w) override {
    for (const auto& pk : peaks_) w(pk.min, pk.max, pk.t_min, pk.t_max);
  }
  void resume(const RunView& run, StateReader& r) override {
    name_peaks(run);
    for (auto& pk : peaks_) r(pk.min, pk.max, pk.t_min, pk.t_max);
  }

 private:
  std::vector<SectionForcePeak> peaks_;
  void name_peaks(const RunView& run) {
    for (const auto& s : run.requests.sections) {
      SectionForcePeak pk;
      pk.section = s.name;
      pk.min.fill(std::numeric_limits<double>::infinity());
      pk.max.fill(-std::numeric_limits<double>::infinity());
      pk.t_min.fill(0);
      pk.t_max.fill(0);
      peaks_.push_back(pk);
    }
  }
  void track(const RunView& run) {
    const double t = run.sim.time();
    for (size_t i = 0; i < peaks_.size(); ++i) {
      const auto v = detail::section_components(run.sim.section_forces(run.requests.sections[i].element));
      auto& pk = peaks_[i];
      for (int c = 0; c < 6; ++c) {
        if (v[c] < pk.min[c]) pk.min[c] = v[c], pk.t_min[c] = t;
        if (v[c] > pk.max[c]) pk.max[c] = v[c], pk.t_max[c] = t;
      }
    }
  }
};

// The energy ledger's verdict (RunSummary::energy): closes when |imbalance| <= RunOptions::energy_tolerance
// of its scale at the end; if not, how much was lost or created, the history-row interval in which the
// imbalance changed most, and the ledger term that changed most in that interval.
class EnergyCheck : public RunObserver {
 public:
  void begin(const RunView& run) override {
    prev_ = run.row_energy;
    t_prev_ = run.sim.time();
  }
  void after_step(const RunView& run, const StepInfo&) override {
    if (!run.row_due()) return;
    const EnergyLedger& E = run.row_energy;
    const double step = E.imbalance() - prev_.imbalance();
    if (std::isfinite(step) && std::abs(step) > std::abs(v_.imbalance_step)) {
      v_.imbalance_step = step;
      v_.t_from = t_prev_;
      v_.t_to = run.sim.time();
      const auto now = detail::ledger_values(E), before = detail::ledger_values(prev_);
      double most = -1;
      for (std::size_t k = 0; k < now.size(); ++k)
        if (std::abs(now[k] - before[k]) > most) {
          most = std::abs(now[k] - before[k]);
          v_.term = detail::ledger_terms()[k];
          v_.term_step = now[k] - before[k];
        }
    }
    prev_ = E;
    t_prev_ = run.sim.time();
  }
  void end(const RunView& run, RunSummary& summary) override {
    const EnergyLedger E = run.sim.energy();  // of a diverged run: its last trusted row's
    v_.tolerance = run.options.energy_tolerance;
    v_.imbalance = E.imbalance();
    v_.scale = E.scale();
    v_.relative = v_.imbalance / v_.scale;
    v_.closes = std::abs(v_.relative) <= v_.tolerance;
    using detail::fmt3;
    const std::string of = fmt3(100 * std::abs(v_.relative)) + " % of its scale, " + fmt3(v_.scale) + " J";
    const std::string tol = fmt3(100 * v_.tolerance) + " % tolerance (RunOptions::energy_tolerance)";
    if (!std::isfinite(v_.relative)) {
      v_.closes = false;
      v_.text = "the energy ledger is not finite: it cannot be checked";
    } else if (v_.closes) {
      v_.text = "the energy ledger closes: imbalance " + fmt3(v_.imbalance) + " J (" + of + "), within the " + tol;
    } else {
      v_.text = "the energy ledger does not close: " + fmt3(std::abs(v_.imbalance)) + " J " +
                (v_.imbalance < 0 ? "lost beyond what contact, damping and plastic hinges account for"
                                  : "created (no term of the ledger may create energy)") +
                " (" + of + "; " + tol + ")";
      if (!v_.term.empty())
        v_.text += ". The imbalance changed most between t = " + fmt3(v_.t_from) + " and " + fmt3(v_.t_to) +
                   " s, by " + fmt3(v_.imbalance_step) + " J, while " + v_.term + " changed by " +
                   fmt3(v_.term_step) + " J";
      if (v_.imbalance < 0)
        v_.text += (v_.term == "contact_work" || v_.term == "kinetic")
                       ? ": impacts lose energy with the penalty contact at this dt (a smaller dt reduces the loss)"
                       : "";
      else if (E.contact_work > 0)
        v_.text += ": the contact forces did " + fmt3(E.contact_work) + " J of net positive work (interpenetrating "
                   "items, or a penalty too stiff for dt)";
    }
    summary.energy = v_;
  }
  void save(StateWriter& w) override { transfer(w); }
  void resume(const RunView&, StateReader& r) override { transfer(r); }

 private:
  template <class Archive>
  void transfer(Archive& ar) {
    ar(prev_, t_prev_, v_.t_from, v_.t_to, v_.imbalance_step, v_.term, v_.term_step);
  }
  EnergyLedger prev_;
  double t_prev_ = 0;
  EnergyVerdict v_;
};

// markers.csv: t, then per marker <marker>_x, _y, _z (displacement relative to the table, m) and
// <marker>_ax, _ay, _az: the absolute acceleration (m/s^2; the table's plus the marker's relative to
// it), as its mean over the steps since the previous row, (v(t) - v(t_prev)) / (t - t_prev) for the
// marker's velocity relative to the table and the table's own (integrated as input_motion.csv): a
// penalty contact at rest chatters from one step to the next, and single steps sampled one phase of
// it. The first row: the initial state's acceleration.
class MarkerHistory : public RowHistory {
  std::vector<Vec3> v_prev_;  // each marker's absolute velocity at the previous row (m/s)
  double t_prev_ = 0;
  void save_rows(StateWriter& w) override { w(v_prev_, t_prev_); }
  void resume_rows(StateReader& r) override { r(v_prev_, t_prev_); }

  std::string file() const override { return "markers.csv"; }
  std::vector<std::string> columns(const RunView& run) const override {
    std::vector<std::string> cols{"t"};
    for (const auto& m : run.requests.markers)
      for (const char* c : {"_x", "_y", "_z", "_ax", "_ay", "_az"}) cols.push_back(m.name + c);
    return cols;
  }
  void write_row(const RunView& run) override {
    const double t = run.sim.time();
    const bool first = v_prev_.empty();
    v_prev_.resize(run.requests.markers.size());
    std::vector<double> row{t};
    for (std::size_t i = 0; i < run.requests.markers.size(); ++i) {
      const int node = run.requests.markers[i].node;
      const Vec3 d = run.sim.displacement(node);
      const Vec3 v = run.sim.velocity(node).head<3>() + run.table.velocity();
      const Vec3 a = first ? Vec3(run.sim.acceleration(node).head<3>() + run.table.acceleration())
                           : Vec3((v - v_prev_[i]) / (t - t_prev_));
      v_prev_[i] = v;
      row.insert(row.end(), {d[0], d[1], d[2], a[0], a[1], a[2]});
    }
    t_prev_ = t;
    csv().row(row);
  }
};

// sectional_forces.csv: t, then <section>_N, _Qy, _Qz, _Mx, _My, _Mz per request (N, N m).
class SectionalForceHistory : public RowHistory {
  std::string file() const override { return "sectional_forces.csv"; }
  std::vector<std::string> columns(const RunView& run) const override {
    std::vector<std::string> cols{"t"};
    for (const auto& s : run.requests.sections)
      for (const char* c : {"_N", "_Qy", "_Qz", "_Mx", "_My", "_Mz"}) cols.push_back(s.name + c);
    return cols;
  }
  void write_row(const RunView& run) override {
    std::vector<double> row{run.sim.time()};
    for (const auto& s : run.requests.sections) {
      const auto v = detail::section_components(run.sim.section_forces(s.element));
      row.insert(row.end(), v.begin(), v.end());
    }
    csv().row(row);
  }
};

// energy.csv: the energy ledger at each row (J).
class EnergyHistory : public RowHistory {
  std::string file() const override { return "energy.csv"; }
  std::vector<std::string> columns(const RunView&) const override {
    return {"t", "kinetic", "strain", "gravity_potential", "external_work", "contact_work", "damping_work", "plastic_work",
            "imbalance", "contact_work_applied"};
  }
  void write_row(const RunView& run) override {
    const EnergyLedger& E = run.row_energy;
    csv().row({run.sim.time(), E.kinetic, E.strain, E.gravity_potential, E.external_work, E.contact_work, E.damping_work,
               E.plastic_work, E.imbalance(), E.contact_work_applied});
  }
};

// input_motion.csv: the table's motion as the run applies it: t, acceleration ax, ay, az (m/s^2),
// velocity vx, vy, vz (m/s) and displacement dx, dy, dz (m), integrated from rest every step (no
// baseline correction: a record whose acceleration does not average to zero drifts). On a building's
// storey, the ground's beside it (ground_ax ... ground_dz).
class InputMotionHistory : public RowHistory {
 public:
  void begin(const RunView& run) override {
    ground_ = detail::ground_under_table(run.spec);
    if (ground_) ground_table_.start(*ground_, run.sim.time());
    RowHistory::begin(run);
  }
  void after_step(const RunView& run, const StepInfo& step) override {
    if (ground_) ground_table_.advance(*ground_, run.sim.time());
    RowHistory::after_step(run, step);
  }
  void resume(const RunView& run, StateReader& r) override {
    ground_ = detail::ground_under_table(run.spec);
    RowHistory::resume(run, r);
  }

 private:
  TableMotionIntegrator ground_table_;
  std::optional<TableMotion> ground_;
  void save_rows(StateWriter& w) override {
    if (ground_) w(ground_table_);
  }
  void resume_rows(StateReader& r) override {
    if (ground_) r(ground_table_);
  }
  std::string file() const override { return "input_motion.csv"; }
  std::vector<std::string> columns(const RunView& run) const override {
    std::vector<std::string> cols{"t", "ax", "ay", "az", "vx", "vy", "vz", "dx", "dy", "dz"};
    if (run.spec.ground_motion.building)
      for (auto& c : detail::ground_columns()) cols.push_back(c);
    return cols;
  }
  void write_row(const RunView& run) override {
    std::vector<double> row{run.sim.time()};
    for (const TableMotionIntegrator* m : {&run.table, &std::as_const(ground_table_)}) {
      if (m == &ground_table_ && !ground_) break;
      for (const Vec3* q : {&m->acceleration(), &m->velocity(), &m->displacement()}) row.insert(row.end(), q->begin(), q->end());
    }
    csv().row(row);
  }
};

// room.pvd and vtu/room_<step>.vtu every outputs.vtu_every steps (the model's lines, displacements,
// body ids and the element forces N, |Q|, |M|).
class VtuSeries : public RunObserver {
 public:
  void begin(const RunView& run) override {
    std::filesystem::create_directories(run.out_dir + "/vtu");
    pvd_.emplace(run.out_dir + "/room.pvd");
    write_frame(run);
  }
  void after_step(const RunView& run, const StepInfo&) override {
    if (run.sim.steps() % run.spec.outputs.vtu_every == 0) write_frame(run);
  }
  void save(StateWriter& w) override { w(*pvd_); }
  // The frames after the checkpoint are written again, under the same names.
  void resume(const RunView& run, StateReader& r) override {
    std::filesystem::create_directories(run.out_dir + "/vtu");
    pvd_.emplace(run.out_dir + "/room.pvd");
    r(*pvd_);
  }

 private:
  std::optional<PvdWriter> pvd_;
  void write_frame(const RunView& run) {
    const std::string name = "vtu/room_" + std::to_string(run.sim.steps()) + ".vtu";
    write_vtu(run.out_dir + "/" + name, detail::line_mesh(run.sim, run.model, true), run.options.vtu);
    pvd_->add(run.sim.time(), name);
    pvd_->write();
  }
};

// final_state.json: RunSummary::items.
class FinalStateFile : public RunObserver {
 public:
  void end(const RunView& run, RunSummary& summary) override {
    detail::write_text(run.out_dir + "/final_state.json", detail::final_state_json(summary.items).dump(2) + "\n");
  }
};

// summary.json: the scene, how the run went, the model's size, the solver's parts and timings, the
// final states and the sectional force peaks.
class SummaryFile : public RunObserver {
 public:
  void end(const RunView& run, RunSummary& sum) override {
    const SimulationView& sim = run.sim;
    const StepTimings& timings = sim.timings();
    nlohmann::json rigid = nlohmann::json::array();
    for (int b : run.rigid_bodies) rigid.push_back(run.model.body(b).name);
    const auto ground = detail::ground_under_table(run.spec);  // on a storey: the ground's peaks, and the floor's
    const TableMotion& motion = ground ? *ground : run.motion;
    nlohmann::json summary = {
        {"furniture_fem_version", version_string},
        {"scene", to_json(run.spec)},
        {"status", sum.status},
        {"diagnosis", sum.diagnosis},
        {"t_end_s", sum.t_end},
        {"t_diverged_s", sum.t_diverged ? nlohmann::json(*sum.t_diverged) : nlohmann::json()},
        {"duration_s", sum.duration},
        {"steps", sum.steps},
        {"dt_s", run.spec.dt},
        {"wall_seconds", sum.wall_seconds},
        {"elements", sum.elements},
        {"nodes", sum.nodes},
        {"bodies", sum.bodies},
        {"element_policy", std::string(sim.element_name())},
        {"integrator", sim.integrator_name()},
        {"linear_solver", std::string(sim.solver_name())},
        {"factorizations", sum.factorizations},
        {"factor_reuse_error", sum.factor_reuse_error},
        {"frame_drift_refreshes", sum.drift_refreshes},
        {"max_frame_drift_rad", sum.max_frame_drift},
        {"impact_steps", sum.impact_steps},
        {"impact_substeps", sum.impact_substeps},
        {"max_node_speed_m_s", detail::max_node_speed(sum.items)},
        {"rigid_bodies", rigid},
        // Wall seconds: contact, the sweep over the bodies, the rest, total; inside the sweep, thread
        // seconds summed over the bodies (Simulation's StepTimings): solve, factorize, elements.
        {"step_time_s", {{"contact", timings.contact},
                         {"bodies", timings.bodies},
                         {"other", timings.other()},
                         {"total", timings.total},
                         {"solve_thread", timings.solve},
                         {"factorize_thread", timings.factorize},
                         {"elements_thread", timings.elements}}},
        {"energy_imbalance_relative", sum.energy_imbalance},
        {"max_energy_imbalance_relative", sum.max_energy_imbalance},
        {"energy_verdict", detail::energy_verdict_json(sum.energy)},
        {"ground_motion_scale_factor", sum.ground_motion_scale},
        {"settled_start", sum.settled_start ? detail::settled_start_json(*sum.settled_start) : nlohmann::json()},
        {"ground_motion_peak_m_s2",
         {motion.peaks().x(), motion.peaks().y(), motion.peaks().z()}},
        {"final_state", detail::final_state_json(sum.items)},
        {"sectional_force_peaks", detail::section_peaks_json(sum.section_peaks)},
        {"restraints", restraint_outcomes_json(sum.restraints)},
        {"eigen_version", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
                              std::to_string(EIGEN_MINOR_VERSION)}};
    if (!sum.occupants.empty()) summary["occupants"] = occupant_outcomes_json(sum.occupants);  // only with occupants
    if (!sum.exits.empty()) {  // only with exits: summary.json without them unchanged
      summary["exits"] = exit_outcomes_json(sum.exits);
      summary["floor_covered_by_fallen_items_m2"] = *sum.floor_covered_by_fallen_items;
    }
    if (ground) summary["floor_motion_peak_m_s2"] = {run.motion.peaks().x(), run.motion.peaks().y(), run.motion.peaks().z()};
    detail::write_text(run.out_dir + "/summary.json", summary.dump(2) + "\n");
  }
};

// The PNG figures, drawn at the end from histories sampled at the rows: one figure per marker with
// X / Y / Z panels (as the paper's Figures 16-18), the shear forces Qy and Qz of each requested
// section, and the room's final state in 3-D.
class Figures : public RunObserver {
 public:
  void begin(const RunView& run) override {
    marker_series_.resize(3 * run.requests.markers.size());
    shear_series_.resize(2 * run.requests.sections.size());
    motion_series_.resize(9);
    energy_series_.resize(detail::ledger_terms().size() + 1);
    sample(run);
  }
  void after_step(const RunView& run, const StepInfo&) override {
    if (run.row_due()) sample(run);
  }
  void end(const RunView& run, RunSummary&) override {
    draw_markers(run);
    draw_shears(run);
    draw_input_motion(run);
    draw_energy(run);
    draw_room(run);
  }
  void save(StateWriter& w) override { w(t_, marker_series_, shear_series_, motion_series_, energy_series_); }
  void resume(const RunView&, StateReader& r) override {
    r(t_, marker_series_, shear_series_, motion_series_, energy_series_);
  }

 private:
  std::vector<double> t_;
  std::vector<std::vector<double>> marker_series_, shear_series_;
  std::vector<std::vector<double>> motion_series_;  // acceleration x y z, velocity x y z, displacement x y z
  std::vector<std::vector<double>> energy_series_;  // the ledger's terms (detail::ledger_terms()), then the imbalance

  void sample(const RunView& run) {
    t_.push_back(run.sim.time());
    for (int c = 0; c < 3; ++c) {
      motion_series_[c].push_back(run.table.acceleration()[c]);
      motion_series_[3 + c].push_back(run.table.velocity()[c]);
      motion_series_[6 + c].push_back(run.table.displacement()[c]);
    }
    const auto terms = detail::ledger_values(run.row_energy);
    for (std::size_t k = 0; k < terms.size(); ++k) energy_series_[k].push_back(terms[k]);
    energy_series_[terms.size()].push_back(run.row_energy.imbalance());
    for (size_t i = 0; i < run.requests.markers.size(); ++i) {
      const Vec3 d = run.sim.displacement(run.requests.markers[i].node);
      for (int c = 0; c < 3; ++c) marker_series_[3 * i + c].push_back(d[c]);
    }
    for (size_t i = 0; i < run.requests.sections.size(); ++i) {
      const auto f = run.sim.section_forces(run.requests.sections[i].element);
      shear_series_[2 * i].push_back(f.Qy);
      shear_series_[2 * i + 1].push_back(f.Qz);
    }
  }
  void draw_markers(const RunView& run) const {
    const auto& markers = run.requests.markers;
    for (size_t i = 0; i < markers.size(); ++i) {
      LinePlot p;
      p.title("Displacement relative to the table: " + markers[i].name).xlabel("time (s)").panels(3);
      const char* axis[3] = {"X (m)", "Y (m)", "Z (m)"};
      for (int c = 0; c < 3; ++c) {
        p.ylabel(axis[c], c);
        p.add(t_, marker_series_[3 * i + c], markers[i].name, c);
      }
      std::string file = markers[i].name;
      for (char& ch : file)
        if (ch == '/' || ch == ' ' || ch == ':') ch = '_';
      p.save_png(run.out_dir + "/marker_" + file + ".png", 1000, 750);
    }
  }
  void draw_shears(const RunView& run) const {
    const auto& sections = run.requests.sections;
    for (size_t i = 0; i < sections.size(); ++i) {
      LinePlot p;
      p.title("Shear force: " + sections[i].name).xlabel("time (s)").panels(2);
      p.ylabel("Qy (N)", 0).ylabel("Qz (N)", 1);
      p.add(t_, shear_series_[2 * i], "Qy", 0);
      p.add(t_, shear_series_[2 * i + 1], "Qz", 1);
      p.save_png(run.out_dir + "/shear_" + std::to_string(i) + ".png", 1000, 600);
    }
  }
  // input_motion.png: the table's acceleration, velocity and displacement, X, Y and Z in each panel.
  void draw_input_motion(const RunView& run) const {
    LinePlot p;
    p.title("Input motion (table)").xlabel("time (s)").panels(3);
    const char* quantity[3] = {"acceleration (m/s^2)", "velocity (m/s)", "displacement (m)"};
    const char* axis[3] = {"X", "Y", "Z"};
    for (int q = 0; q < 3; ++q) {
      p.ylabel(quantity[q], q);
      for (int c = 0; c < 3; ++c) p.add(t_, motion_series_[3 * q + c], axis[c], q);
    }
    if (const auto ground = detail::ground_under_table(run.spec)) {  // the ground under the storey
      p.title("Input motion (table: floor " + std::to_string(run.spec.ground_motion.building->storey) + "; and ground)");
      for (const auto& [rec, axis] : detail::horizontal(*ground)) {
        auto [t, a] = detail::samples_until(*rec, t_.empty() ? 0.0 : t_.back());
        p.add(std::move(t), std::move(a), "ground " + axis, 0);
      }
      detail::draw_floor_spectra(run.spec, *ground, run.motion, run.out_dir + "/input_spectra.png");
    }
    p.save_png(run.out_dir + "/input_motion.png", 1000, 900);
  }
  // energy.png: the energy ledger's terms against time, each as its change since the first row (the
  // gravity potential's absolute value depends on the datum and would flatten the rest), and the
  // imbalance below; sampled at the history rows (the rows of energy.csv).
  void draw_energy(const RunView& run) const {
    LinePlot p;
    p.title("Energy ledger: change of each term since t = " + detail::fmt3(t_.empty() ? 0.0 : t_.front()) + " s")
        .xlabel("time (s)")
        .panels(2);
    p.ylabel("change (J)", 0).ylabel("imbalance (J)", 1);
    p.style().legend = LegendPos::top_left;  // a run starts quiet: the curves spread out later, to the right
    const auto& names = detail::ledger_terms();
    for (std::size_t k = 0; k < names.size(); ++k) {
      std::string label = names[k];
      std::replace(label.begin(), label.end(), '_', ' ');
      std::vector<double> change = energy_series_[k];
      for (double& e : change) e -= energy_series_[k].front();
      p.add(t_, std::move(change), label, 0);
    }
    p.add(t_, energy_series_[names.size()], "imbalance", 1);
    p.save_png(run.out_dir + "/energy.png", 1000, 800);
  }
  // room_final.png: every member at the end (the item's colour) over its initial position (light grey),
  // each item's name next to its highest point.
  void draw_room(const RunView& run) const {
    const SceneSpec& spec = run.spec;
    const Model& model = run.model;
    Wireframe3D w;
    w.title(spec.name + ": final state at t = " + std::to_string(run.sim.time()).substr(0, 5) + " s (grey: initial)")
        .camera(-60, 25);
    std::vector<Segment3> segs, initial;
    std::vector<RGB> cols;
    for (int e = 0; e < model.num_elements(); ++e) {
      const auto& el = model.elements()[e];
      segs.push_back({run.sim.position(el.n1), run.sim.position(el.n2)});
      initial.push_back({model.node(el.n1).X, model.node(el.n2).X});
      cols.push_back(palette_color(el.body));
    }
    w.add_reference_segments(initial, RGB{195, 195, 195}, 1.5);
    w.add_segments(segs, cols);
    w.floor_grid(-0.5 * spec.table.size_x, 0.5 * spec.table.size_x, -0.5 * spec.table.size_y,
                 0.5 * spec.table.size_y, spec.table.floor_z, 0.5);
    for (const auto& wall : spec.walls) {
      const Vec3 u = Vec3::UnitZ().cross(wall.normal).normalized() * 0.5 * wall.width;
      const Vec3 h(0, 0, wall.height);
      w.add_quad({wall.point - u, wall.point + u, wall.point + u + h, wall.point - u + h}, RGB{150, 150, 150}, 0.15);
    }
    if (spec.ceiling) {  // its outline over the table (it is unbounded; a fill would hide the items)
      const double hx = 0.5 * spec.table.size_x, hy = 0.5 * spec.table.size_y;
      const double z = spec.table.floor_z + spec.ceiling->height;
      w.add_quad({Vec3(-hx, -hy, z), Vec3(hx, -hy, z), Vec3(hx, hy, z), Vec3(-hx, hy, z)}, RGB{150, 150, 150}, 0.0);
    }
    for (const auto& it : run.items) {
      w.legend(it.name, palette_color(it.body));
      // The label sits over the item's highest point now: the centre of its nodes within 1 mm of the top.
      double zmax = -std::numeric_limits<double>::infinity();
      for (int n = 0; n < model.num_nodes(); ++n)
        if (model.node(n).body == it.body) zmax = std::max(zmax, run.sim.position(n).z());
      Vec3 sum = Vec3::Zero();
      int count = 0;
      for (int n = 0; n < model.num_nodes(); ++n)
        if (model.node(n).body == it.body && run.sim.position(n).z() >= zmax - 1e-3) sum += run.sim.position(n), ++count;
      if (count > 0) w.label(sum / count, it.name, palette_color(it.body));
    }
    draw_restraints(run, w);
    w.legend("initial position", RGB{195, 195, 195}, 1.5);
    w.save_png(run.out_dir + "/room_final.png", 1000, 800);
  }
  // Each restraint as a line from its anchor to its node (green), a broken one red and labelled.
  static void draw_restraints(const RunView& run, Wireframe3D& w) {
    const RestraintSet& ties = run.sim.restraints();
    const RGB held{30, 150, 30}, broke{220, 30, 30};
    bool any_broken = false;
    for (std::size_t i = 0; i < ties.size(); ++i) {
      const bool broken = ties.states()[i].broken();
      any_broken = any_broken || broken;
      w.add_segments({Segment3{ties[i].anchor, run.sim.position(ties[i].node)}}, broken ? broke : held);
      if (broken) w.label(ties[i].anchor, ties[i].name + " broke", broke);
    }
    if (!ties.empty()) w.legend("restraint", held);
    if (any_broken) w.legend("broken restraint", broke);
  }
};

// The observers a run gets from its scene's outputs and its options, in the order they are called:
// the progress bar, the outcomes (final states, section peaks, filled into the RunSummary), then, when
// the run writes files, the histories, the VTU series, final_state.json, summary.json and the figures.
inline std::vector<std::unique_ptr<RunObserver>> standard_observers(const RunView& run) {
  std::vector<std::unique_ptr<RunObserver>> list;
  if (run.options.progress) list.push_back(std::make_unique<ProgressBar>());
  list.push_back(std::make_unique<FinalStates>());
  list.push_back(std::make_unique<SectionPeaks>());
  list.push_back(std::make_unique<EnergyCheck>());
  if (!run.spec.restraints.empty()) list.push_back(std::make_unique<RestraintOutcomes>());
  if (!run.spec.occupants.empty()) list.push_back(std::make_unique<OccupantStrikes>());
  if (!run.spec.exits.empty()) list.push_back(std::make_unique<ExitOutcomes>());
  if (run.out_dir.empty()) return list;
  list.push_back(std::make_unique<MarkerHistory>());
  list.push_back(std::make_unique<SectionalForceHistory>());
  list.push_back(std::make_unique<EnergyHistory>());
  list.push_back(std::make_unique<ContactForceHistory>());
  list.push_back(std::make_unique<InputMotionHistory>());
  if (!run.spec.restraints.empty()) list.push_back(std::make_unique<RestraintHistory>());
  if (!run.spec.exits.empty()) list.push_back(std::make_unique<ExitHistory>());
  if (run.spec.outputs.vtu_every > 0) list.push_back(std::make_unique<VtuSeries>());
  list.push_back(std::make_unique<FinalStateFile>());
  list.push_back(std::make_unique<SummaryFile>());
  if (run.options.figures.value_or(run.spec.outputs.figures)) {
    list.push_back(std::make_unique<Figures>());
    if (!run.spec.occupants.empty() || !run.spec.exits.empty()) list.push_back(std::make_unique<HarmFigures>());
  }
  return list;
}

}  // namespace furniture_fem
