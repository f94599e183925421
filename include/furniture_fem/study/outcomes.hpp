#pragma once
// furniture_fem/study/outcomes.hpp: what one run of a study yields, collected through the scene
// runner's observers (not read back from result files), and its record as JSON.
//
//   RunResult run_realisation(study, run_index, stop)    runs realisation run_index / variants, variant run_index % variants
//   nlohmann::json to_json(const RunResult&) / RunResult run_result_from_json(json)   exact round trip
//   StudyFailures study_failures(results)                 the runs that did not complete, the first one's reason
//
// A run that diverges, or whose scene is refused (an item placed into another by its perturbation),
// is a result too: status "diverged" or "failed", with its diagnosis. Only a run stopped by the user
// is not a result (status "stopped": the study runs it again when resumed).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include "../scene/observer.hpp"
#include "../scene/observers.hpp"
#include "../scene/run_scene.hpp"
#include "realisation.hpp"

namespace furniture_fem {

// One body's outcome (separated cabinets give two: "<item>/lower", "<item>/upper"): its final state as
// the run reports it (scene/run_summary.hpp; written with final_state.json's keys) and the largest
// magnitude over the run's steps of the summed contact force on the body from the floor, from the walls
// and from other items (N).
struct BodyOutcome : ItemFinalState {
  double floor_force_peak = 0, wall_force_peak = 0, item_force_peak = 0;
};

// The largest absolute value of each sectional force component (N, Qy, Qz, Mx, My, Mz) of one
// requested section (the scene's outputs.sectional_forces).
struct SectionOutcome {
  std::string section;
  std::array<double, 6> abs_max{};
};

struct RunResult {
  long run = 0;                 // realisation * variants + variant
  long realisation = 0;
  int variant = 0;
  std::string status;           // completed, diverged, failed (stopped runs are not results)
  std::string diagnosis;
  double t_end = 0;             // s reached
  double wall_seconds = 0;      // not compared between runs of a study: it depends on the machine
  std::vector<BodyOutcome> bodies;
  std::vector<SectionOutcome> sections;
};

inline constexpr std::array<const char*, 6> section_components{"N", "Qy", "Qz", "Mx", "My", "Mz"};

// Contact-force peaks per body, from the pair forces of every step.
class ContactForcePeaks : public RunObserver {
 public:
  void begin(const RunView& run) override { peaks_.assign(run.model.num_bodies(), {0.0, 0.0, 0.0}); }
  void after_step(const RunView& run, const StepInfo&) override {
    const int nb = run.model.num_bodies();
    sums_.assign(nb, {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
    for (const PairForce& p : run.sim.pair_forces()) {
      const int kind = p.body_b == -1 ? 0 : p.body_b == -2 ? 1 : 2;  // floor, wall, item
      if (p.body_a >= 0 && p.body_a < nb) sums_[p.body_a][kind] += p.force_on_a;
      if (kind == 2 && p.body_b < nb) sums_[p.body_b][2] -= p.force_on_a;
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

inline RunResult run_realisation(const StudySpec& s, long run, const std::atomic<bool>* stop = nullptr) {
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
  } catch (const std::exception& e) {  // a refused scene or model: recorded, the study goes on
    r.status = "failed";
    r.diagnosis = e.what();
    r.bodies.clear();
    r.sections.clear();
  }
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

// A run's reason for not completing, its numbers aside (a realisation's index, a time, a depth): its
// status and diagnosis with each number that stands alone, sign included, as '#' (names such as
// items[0] or synthetic_1 keep theirs).
inline std::string failure_reason(const RunResult& r) {
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

// The runs that did not complete: how many, the first of them (by run index) and how many share its
// reason (failure_reason).
struct StudyFailures {
  long completed = 0, not_completed = 0, same_reason = 0;
  RunResult first;  // run -1: every run completed
  StudyFailures() { first.run = -1; }
};

inline StudyFailures study_failures(const std::vector<RunResult>& rows) {  // rows in run order
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

inline nlohmann::json to_json(const RunResult& r) {
  nlohmann::json bodies = nlohmann::json::array(), sections = nlohmann::json::array();
  for (const auto& b : r.bodies) {
    nlohmann::json j = item_final_state_json(b);
    j["floor_force_peak_N"] = b.floor_force_peak;
    j["wall_force_peak_N"] = b.wall_force_peak;
    j["item_force_peak_N"] = b.item_force_peak;
    bodies.push_back(std::move(j));
  }
  for (const auto& s : r.sections) sections.push_back({{"section", s.section}, {"abs_max", s.abs_max}});
  return {{"run", r.run},     {"realisation", r.realisation}, {"variant", r.variant},
          {"status", r.status}, {"diagnosis", r.diagnosis},   {"t_end", r.t_end},
          {"wall_seconds", r.wall_seconds}, {"bodies", bodies}, {"sections", sections}};
}

// Reads a record back (a resumed study, an MPI worker's message); nlohmann's numbers round-trip
// exactly. Throws nlohmann::json::exception on a malformed record.
inline RunResult run_result_from_json(const nlohmann::json& j) {
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
  return r;
}

}  // namespace furniture_fem
