#pragma once
// furniture_fem/study/report.hpp: a study's results turned into the statistics users cite
// (docs/study/studies.md, "Outputs"), and written as CSV and JSON.
//
//   StudyReport study_report(study, results)     probabilities, distributions, fragility fits, paired comparisons
//   write_report(report, folder)                 probabilities.csv, distributions.csv, fragility.csv,
//                                                comparisons.csv, statistics.json
//
// Damage states of a body, from its outcome in a completed run: "slid" (final slide above
// outcomes.slide_threshold), "tilted" (largest tilt during the run above outcomes.tilt_threshold_deg),
// "overturned" (final state overturned), "fallen" (off its feet at some time: tipped past 60 deg or came
// down more than 5 cm, has_fallen in scene/run_summary.hpp; an upper cabinet that fell off the lower one
// counts whether it ends lying, upright or leaning on the desk), "device_broke" (a restraint on the body
// broke: its outcome in the run's record; a state only of bodies that some run of the study fastens).
// Runs that diverged or failed are not outcomes: they are counted apart (`excluded`) and never enter a probability.
#include <algorithm>
#include <array>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "../scene/run_summary.hpp"
#include "outcomes.hpp"
#include "spec.hpp"
#include "statistics.hpp"

#define FURNITURE_FEM_STUDY_INTERNAL
#include "detail/compiled_study.hpp"
#undef FURNITURE_FEM_STUDY_INTERNAL

namespace furniture_fem {

inline constexpr std::array<const char*, 5> damage_states{"slid", "tilted", "overturned", "fallen", "device_broke"};
inline constexpr std::array<const char*, 6> continuous_outcomes{"slide_m", "max_tilt_deg", "lift_m",
                                                                "floor_force_peak_N", "wall_force_peak_N",
                                                                "item_force_peak_N"};

inline bool in_damage_state(const OutcomeSpec& o, const BodyOutcome& b, std::string_view state) {
  if (state == "slid") return b.slide > o.slide_threshold;
  if (state == "tilted") return b.max_tilt_deg > o.tilt_threshold_deg;
  if (state == "fallen") return has_fallen(b.max_tilt_deg, b.lift);
  if (state == "overturned") return b.state == "overturned";
  throw std::invalid_argument("in_damage_state: state \"" + std::string(state) +
                              "\" is not a body's own (device_broke needs the run's record)");
}
// Whether a restraint fastening `body` broke in run `r`.
inline bool device_broke(const RunResult& r, const std::string& body) {
  return std::any_of(r.restraints.begin(), r.restraints.end(),
                     [&](const RestraintOutcome& o) { return o.item == body && o.broke; });
}
// Every damage state, the body's own and its devices'.
inline bool in_damage_state(const OutcomeSpec& o, const RunResult& r, const BodyOutcome& b, std::string_view state) {
  return state == "device_broke" ? device_broke(r, b.name) : in_damage_state(o, b, state);
}
inline double continuous_outcome(const BodyOutcome& b, std::string_view name) {
  if (name == "slide_m") return b.slide;
  if (name == "max_tilt_deg") return b.max_tilt_deg;
  if (name == "lift_m") return b.lift;
  if (name == "floor_force_peak_N") return b.floor_force_peak;
  if (name == "wall_force_peak_N") return b.wall_force_peak;
  return b.item_force_peak;
}

struct ProbabilityRow {
  std::string variant, body, state;
  int level_index = 0;
  double level = 0;
  ProportionEstimate estimate;
  long excluded = 0;  // runs of this cell that diverged or failed
};
struct DistributionRow {
  std::string variant, body, outcome;
  int level_index = 0;
  double level = 0;
  Distribution distribution;
};
struct FragilityRow {
  std::string variant, body, state;
  LognormalFragility fit;
  FragilityInterval interval;
};
struct ComparisonRow {
  std::string variant_a, variant_b, body, state;
  int level_index = 0;
  double level = 0;
  PairedDifference difference;
};

struct StudyReport {
  std::string measure;  // the intensity measure of `level`
  std::vector<ProbabilityRow> probabilities;
  std::vector<DistributionRow> distributions;
  std::vector<FragilityRow> fragility;
  std::vector<ComparisonRow> comparisons;
};

FFEM_STUDY_ENTRY StudyReport study_report(const StudySpec& s, const std::vector<RunResult>& results);
FFEM_STUDY_ENTRY void write_report(const StudyReport& rep, const std::filesystem::path& dir);

}  // namespace furniture_fem

#ifndef FFEM_STUDY_DECLARED_ONLY
#define FURNITURE_FEM_STUDY_INTERNAL
#include "detail/report_impl.hpp"
#undef FURNITURE_FEM_STUDY_INTERNAL
#endif
