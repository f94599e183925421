#pragma once
// Internal: one run of a study and its record (study/outcomes.hpp's entry points), defined inline when
// the study is used header-only and once in the compiled study (src/study/study_runs.cpp).
#ifndef FURNITURE_FEM_STUDY_INTERNAL
#error "furniture_fem/study/detail/outcomes_impl.hpp is internal: include <furniture_fem/study/outcomes.hpp>"
#endif
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "../../scene/observer.hpp"
#include "../../scene/observers.hpp"
#include "../../scene/run_scene.hpp"
#include "../outcomes.hpp"
#include "../realisation.hpp"

namespace furniture_fem {

// Contact-force peaks per body, from the pair forces of every step.
class ContactForcePeaks : public RunObserver {
 public:
  void begin(const RunView& run) override { peaks_.assign(run.model.num_bodies(), {0.0, 0.0, 0.0}); }
  void after_step(const RunView& run, const StepInfo&) override {
    const int nb = run.model.num_bodies();
    sums_.assign(nb, {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
    for (const PairForce& p : run.sim.pair_forces()) {
      // The floor; the walls and the ceiling (wall_force_peak_N); items and mesh obstacles.
      const bool wall_or_ceiling = p.body_b == PairForce::wall_id || p.body_b == PairForce::ceiling_id;
      const int kind = p.body_b == PairForce::floor_id ? 0 : wall_or_ceiling ? 1 : 2;
      if (p.body_a >= 0 && p.body_a < nb) sums_[p.body_a][kind] += p.force_on_a;
      if (p.body_b >= 0 && p.body_b < nb) sums_[p.body_b][2] -= p.force_on_a;  // an item's reaction
    }
    for (int b = 0; b < nb; ++b)
      for (int k = 0; k < 3; ++k) peaks_[b][k] = std::max(peaks_[b][k], sums_[b][k].norm());
  }
  const std::array<double, 3>& peaks(int body) const { return peaks_.at(body); }

 private:
  std::vector<std::array<double, 3>> peaks_;
  std::vector<std::array<Vec3, 3>> sums_;
};

// The body index of each final state, in the summary's order (FinalStates writes one per ItemInfo).
class BodyOrder : public RunObserver {
 public:
  void begin(const RunView& run) override {
    bodies_.clear();
    for (const auto& it : run.items) bodies_.push_back(it.body);
  }
  const std::vector<int>& bodies() const { return bodies_; }

 private:
  std::vector<int> bodies_;
};

FFEM_STUDY_ENTRY RunResult run_realisation(const StudySpec& s, long run, const std::atomic<bool>* stop) {
  const auto t0 = std::chrono::steady_clock::now();
  RunResult r;
  r.run = run;
  r.realisation = run / s.num_variants();
  r.variant = static_cast<int>(run % s.num_variants());
  ContactForcePeaks peaks;
  BodyOrder order;
  try {
    const RealisationParameters p = realisation_parameters(s, r.realisation);
    const std::string what = "realisation " + std::to_string(r.realisation) + ", variant '" + s.variant_name(r.variant) + "'";
    const SceneSpec scene = study_scene(s, realisation_scene_json(s, p, r.variant), what);
    RunOptions o;
    o.write_files = false;
    o.progress = false;
    o.threads = 1;  // one realisation per worker: more throughput than threads inside one run
    o.stop = stop;
    const RunSummary sum = run_scene(scene, o, {&peaks, &order});
    r.status = sum.status;
    r.diagnosis = sum.diagnosis;
    r.t_end = sum.t_end;
    for (std::size_t i = 0; i < sum.items.size(); ++i) {
      const ItemFinalState& f = sum.items[i];
      BodyOutcome b{f};
      if (i < order.bodies().size()) {
        const auto& pk = peaks.peaks(order.bodies()[i]);
        b.floor_force_peak = pk[0];
        b.wall_force_peak = pk[1];
        b.item_force_peak = pk[2];
      }
      r.bodies.push_back(b);
    }
    for (const auto& sp : sum.section_peaks) {
      SectionOutcome so{sp.section, {}};
      for (int k = 0; k < 6; ++k) so.abs_max[k] = std::max(std::abs(sp.min[k]), std::abs(sp.max[k]));
      r.sections.push_back(so);
    }
    r.restraints = sum.restraints;
    r.occupants = sum.occupants;
    r.exits = sum.exits;
  } catch (const std::exception& e) {  // a refused scene or model: recorded, the study goes on
    r.status = "failed";
    r.diagnosis = e.what();
    r.bodies.clear();
    r.sections.clear();
    r.restraints.clear();
    r.occupants.clear();
    r.exits.clear();
  }
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

FFEM_STUDY_ENTRY std::string failure_reason(const RunResult& r) {
  const std::string& d = r.diagnosis;
  const auto digit = [&](std::size_t i) { return i < d.size() && std::isdigit(static_cast<unsigned char>(d[i])); };
  const auto sign = [&](std::size_t i) { return i < d.size() && (d[i] == '-' || d[i] == '+'); };
  const auto in_name = [&](std::size_t i) {
    const unsigned char c = static_cast<unsigned char>(d[i]);
    return std::isalnum(c) || c == '_' || c == '[' || c == '.';
  };
  std::string out = r.status + ": ";
  for (std::size_t i = 0; i < d.size();) {
    if (!digit(sign(i) ? i + 1 : i) || (i > 0 && in_name(i - 1))) {
      out += d[i++];
      continue;
    }
    i += sign(i);
    while (digit(i) || (i < d.size() && (d[i] == '.' || d[i] == 'e' || d[i] == 'E')) ||
           (sign(i) && (d[i - 1] == 'e' || d[i - 1] == 'E')))
      ++i;
    out += '#';
  }
  return out;
}

FFEM_STUDY_ENTRY StudyFailures study_failures(const std::vector<RunResult>& rows) {
  StudyFailures f;
  std::string reason;
  for (const auto& r : rows) {
    if (r.status == "completed") {
      ++f.completed;
      continue;
    }
    if (++f.not_completed == 1) f.first = r, reason = failure_reason(r);
    f.same_reason += failure_reason(r) == reason;
  }
  return f;
}

FFEM_STUDY_ENTRY nlohmann::json to_json(const RunResult& r) {
  nlohmann::json bodies = nlohmann::json::array(), sections = nlohmann::json::array();
  for (const auto& b : r.bodies) {
    nlohmann::json j = item_final_state_json(b);
    j["floor_force_peak_N"] = b.floor_force_peak;
    j["wall_force_peak_N"] = b.wall_force_peak;
    j["item_force_peak_N"] = b.item_force_peak;
    bodies.push_back(std::move(j));
  }
  for (const auto& s : r.sections) sections.push_back({{"section", s.section}, {"abs_max", s.abs_max}});
  nlohmann::json j = {{"run", r.run},     {"realisation", r.realisation}, {"variant", r.variant},
                      {"status", r.status}, {"diagnosis", r.diagnosis},   {"t_end", r.t_end},
                      {"wall_seconds", r.wall_seconds}, {"bodies", bodies}, {"sections", sections}};
  if (!r.restraints.empty()) j["restraints"] = restraint_outcomes_json(r.restraints);  // records without: as before
  if (!r.occupants.empty()) j["occupants"] = occupant_outcomes_json(r.occupants);
  if (!r.exits.empty()) j["exits"] = exit_outcomes_json(r.exits);  // as restraints
  return j;
}

FFEM_STUDY_ENTRY RunResult run_result_from_json(const nlohmann::json& j) {
  RunResult r;
  r.run = j.at("run").get<long>();
  r.realisation = j.at("realisation").get<long>();
  r.variant = j.at("variant").get<int>();
  r.status = j.at("status").get<std::string>();
  r.diagnosis = j.at("diagnosis").get<std::string>();
  r.t_end = j.at("t_end").get<double>();
  r.wall_seconds = j.at("wall_seconds").get<double>();
  for (const auto& b : j.at("bodies")) {
    BodyOutcome o{item_final_state_from_json(b)};
    o.floor_force_peak = b.at("floor_force_peak_N").get<double>();
    o.wall_force_peak = b.at("wall_force_peak_N").get<double>();
    o.item_force_peak = b.at("item_force_peak_N").get<double>();
    r.bodies.push_back(std::move(o));
  }
  for (const auto& s : j.at("sections"))
    r.sections.push_back({s.at("section").get<std::string>(), s.at("abs_max").get<std::array<double, 6>>()});
  if (j.contains("restraints"))
    for (const auto& o : j.at("restraints")) r.restraints.push_back(restraint_outcome_from_json(o));
  if (j.contains("occupants")) r.occupants = occupant_outcomes_from_json(j.at("occupants"));
  if (j.contains("exits"))
    for (const auto& o : j.at("exits")) r.exits.push_back(exit_outcome_from_json(o));
  return r;
}

}  // namespace furniture_fem
