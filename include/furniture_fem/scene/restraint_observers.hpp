#pragma once
// furniture_fem/scene/restraint_observers.hpp: what the run writes of its restraints (restraints/,
// docs/restraints/restraints.md). Built-in observers of observers.hpp, only for a scene with restraints.
//
//   RestraintOutcomes  each restraint's peak force, its ratio to its strength, whether, when and how it
//                      broke, what it dissipated -> RunSummary::restraints (summary.json, the final print)
//   RestraintHistory   restraints.csv; restraints.png (each one's force over time against its strength)
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../figures/plot.hpp"
#include "observer.hpp"
#include "row_history.hpp"

namespace furniture_fem {

namespace detail {

// The strength a restraint's failure is judged by (RestraintOutcome::strength).
inline double governing_strength(const Restraint& r) {
  return r.kind == RestraintKind::pole ? std::min(r.p.slip_strength, r.p.board_strength) : r.p.strength;
}

}  // namespace detail

// One restraint's outcome as summary.json and a study's run records write it (one set of keys), and back.
inline nlohmann::json restraint_outcome_json(const RestraintOutcome& o) {
  return {{"name", o.name},
          {"kind", o.kind},
          {"item", o.item},
          {"peak_force_n", o.peak_force},
          {"strength_n", o.strength},
          {"peak_ratio", o.peak_ratio},
          {"broke", o.broke},
          {"broke_at_s", o.broke ? nlohmann::json(o.broke_at) : nlohmann::json()},
          {"failure", o.failure},
          {"dissipated_j", o.dissipated},
          {"stored_j", o.stored}};
}
inline RestraintOutcome restraint_outcome_from_json(const nlohmann::json& j) {
  RestraintOutcome o;
  o.name = j.at("name").get<std::string>();
  o.kind = j.at("kind").get<std::string>();
  o.item = j.at("item").get<std::string>();
  o.peak_force = j.at("peak_force_n").get<double>();
  o.strength = j.at("strength_n").get<double>();
  o.peak_ratio = j.at("peak_ratio").get<double>();
  o.broke = j.at("broke").get<bool>();
  o.broke_at = o.broke ? j.at("broke_at_s").get<double>() : -1;
  o.failure = j.at("failure").get<std::string>();
  o.dissipated = j.at("dissipated_j").get<double>();
  o.stored = j.at("stored_j").get<double>();
  return o;
}
inline nlohmann::json restraint_outcomes_json(const std::vector<RestraintOutcome>& list) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& o : list) out.push_back(restraint_outcome_json(o));
  return out;
}

class RestraintOutcomes : public RunObserver {
 public:
  void end(const RunView& run, RunSummary& summary) override {
    const RestraintSet& set = run.sim.restraints();
    summary.restraints.clear();
    for (std::size_t i = 0; i < set.size(); ++i) {
      const Restraint& r = set[i];
      const RestraintState& s = set.states()[i];
      RestraintOutcome o;
      o.name = r.name;
      o.kind = std::string(to_string(r.kind));
      o.item = run.model.body(r.body).name;
      o.peak_force = s.peak_force;
      o.strength = detail::governing_strength(r);
      o.peak_ratio = o.peak_force / o.strength;
      o.broke = s.broken();
      o.broke_at = s.broke_at;
      o.failure = std::string(to_string(s.failure));
      o.dissipated = set.dissipated_energy(i);
      o.stored = s.stored;
      summary.restraints.push_back(o);
    }
  }
};

// restraints.csv: t, then per restraint <name>_force (N, its kind's measure: a bracket's pull force, a
// strap's tension, a mat's shear, a pole's compression), <name>_extension (m: pull, stretch beyond taut,
// shear slip, rise less shortening) and <name>_regime (0 idle, 1 elastic, 2 yielding, 3 softening,
// 4 slipping, 5 broken), at each history row (the committed step's).
class RestraintHistory : public RowHistory {
 public:
  void end(const RunView& run, RunSummary& summary) override {
    RowHistory::end(run, summary);
    if (run.options.figures.value_or(run.spec.outputs.figures)) draw(run);
  }

 private:
  std::vector<double> t_;
  std::vector<std::vector<double>> force_;  // per restraint, at the rows
  void save_rows(StateWriter& w) override { w(t_, force_); }
  void resume_rows(StateReader& r) override { r(t_, force_); }

  std::string file() const override { return "restraints.csv"; }
  std::vector<std::string> columns(const RunView& run) const override {
    std::vector<std::string> cols{"t"};
    for (const Restraint& r : run.sim.restraints().restraints())
      for (const char* c : {"_force", "_extension", "_regime"}) cols.push_back(r.name + c);
    return cols;
  }
  void write_row(const RunView& run) override {
    const RestraintSet& set = run.sim.restraints();
    std::vector<double> row{run.sim.time()};
    force_.resize(set.size());
    t_.push_back(row.front());
    for (std::size_t i = 0; i < set.size(); ++i) {
      const RestraintState& s = set.states()[i];
      row.insert(row.end(), {s.force, s.extension, static_cast<double>(s.regime)});
      force_[i].push_back(s.force);
    }
    csv().row(row);
  }
  // restraints.png: one panel per restraint, its force and its strength (dashed), a broken one's title
  // saying when it broke.
  void draw(const RunView& run) const {
    const RestraintSet& set = run.sim.restraints();
    LinePlot p;
    const int panels = static_cast<int>(set.size());
    p.title("Restraint forces against their strengths").xlabel("time (s)").panels(panels);
    for (int i = 0; i < panels; ++i) {
      const Restraint& r = set[i];
      const RestraintState& s = set.states()[i];
      const double strength = detail::governing_strength(r);
      std::string label = r.name + " (" + std::string(to_string(r.kind)) + ")";
      if (s.broken()) label += ": broke at " + detail::fmt(s.broke_at) + " s, " + std::string(to_string(s.failure));
      p.ylabel("N", i);
      p.add(t_, force_[i], label, i);
      p.add({t_.front(), t_.back()}, {strength, strength}, "strength " + detail::fmt(strength) + " N", i);
    }
    p.save_png(run.out_dir + "/restraints.png", 1000, 250 + 200 * panels);
  }
};

}  // namespace furniture_fem
