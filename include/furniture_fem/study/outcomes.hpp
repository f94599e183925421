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

#include <array>
#include <atomic>
#include <string>
#include <vector>

#include "../scene/run_summary.hpp"
#include "spec.hpp"

#define FURNITURE_FEM_STUDY_INTERNAL
#include "detail/compiled_study.hpp"
#undef FURNITURE_FEM_STUDY_INTERNAL

namespace furniture_fem {

// One body's outcome (separated cabinets give two: "<item>/lower", "<item>/upper"): its final state as
// the run reports it (scene/run_summary.hpp; written with final_state.json's keys) and the largest
// magnitude over the run's steps of the summed contact force on the body from the floor, from the walls
// and a ceiling together, and from other items and mesh obstacles (N).
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
  std::vector<RestraintOutcome> restraints;  // the scene's restraints (docs/restraints/restraints.md)
  std::vector<OccupantOutcome> occupants;    // the scene's occupants (docs/harm/occupants.md)
  std::vector<ExitOutcome> exits;            // the scene's exits (docs/harm/harm.md, "Exits")
};

inline constexpr std::array<const char*, 6> section_components{"N", "Qy", "Qz", "Mx", "My", "Mz"};

// The runs that did not complete: how many, the first of them (by run index) and how many share its
// reason (failure_reason).
struct StudyFailures {
  long completed = 0, not_completed = 0, same_reason = 0;
  RunResult first;  // run -1: every run completed
  StudyFailures() { first.run = -1; }
};

// Runs realisation run / variants under variant run % variants (stop: the user's stop request).
FFEM_STUDY_ENTRY RunResult run_realisation(const StudySpec& s, long run, const std::atomic<bool>* stop = nullptr);
// A run's reason for not completing, its numbers aside (a realisation's index, a time, a depth): its
// status and diagnosis with each number that stands alone, sign included, as '#' (names such as
// items[0] or synthetic_1 keep theirs).
FFEM_STUDY_ENTRY std::string failure_reason(const RunResult& r);
FFEM_STUDY_ENTRY StudyFailures study_failures(const std::vector<RunResult>& rows);  // rows in run order
FFEM_STUDY_ENTRY nlohmann::json to_json(const RunResult& r);
// Reads a record back (a resumed study, an MPI worker's message); nlohmann's numbers round-trip
// exactly. Throws nlohmann::json::exception on a malformed record.
FFEM_STUDY_ENTRY RunResult run_result_from_json(const nlohmann::json& j);

}  // namespace furniture_fem

#ifndef FFEM_STUDY_DECLARED_ONLY
#define FURNITURE_FEM_STUDY_INTERNAL
#include "detail/outcomes_impl.hpp"
#undef FURNITURE_FEM_STUDY_INTERNAL
#endif
