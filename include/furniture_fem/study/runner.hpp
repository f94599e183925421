#pragma once
// furniture_fem/study/runner.hpp: running a study's realisations and keeping their results.
//
//   StudyFolder folder(study, options)       the results folder: locked for the folder's life (one study
//                                             or run per folder, io/folder_lock.hpp), checked, resumed or
//                                             cleared; study.json
//   folder.pending()                          the runs not yet done (every run, or those a killed study left)
//   folder.record(result)                     one result, written atomically as runs/<run>.json
//   run_local(folder, pending, workers, stop) one thread per worker, runs handed out one at a time
//   folder.finish(status, timing)             realisations.csv, the statistics (report.hpp), the figures
//                                             (figures.hpp), summary.json
//
// Runs are handed out dynamically (a run takes 0.1 to 10 times the median), and every result depends
// only on the study and the run's index: realisations.csv is the same to the bit whatever the number
// of workers or MPI ranks and however often the study was stopped and resumed. An MPI program hands out
// the same runs from rank 0 (examples/furniture_study) and records them through the same folder.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "../io/folder_lock.hpp"
#include "outcomes.hpp"
#include "report.hpp"
#include "spec.hpp"

#define FURNITURE_FEM_STUDY_INTERNAL
#include "detail/compiled_study.hpp"
#undef FURNITURE_FEM_STUDY_INTERNAL

namespace furniture_fem {

struct StudyOptions {
  std::string out_dir;         // empty: "study_<name>" in the working folder
  int workers = 0;             // local worker threads; 0: one per hardware thread
  bool resume = false;         // continue a stopped or killed study in out_dir, skipping finished runs
  bool overwrite = false;      // remove a previous study's results from out_dir first
  bool progress = true;        // progress line on stderr
};

// How the runs were spread (summary.json).
struct StudyTiming {
  double wall_seconds = 0;
  int workers = 1, ranks = 1;
  // MPI only: the mean time a worker waited between asking for a run and getting it (s).
  std::optional<double> handout_seconds_mean;
};

// realisations.csv: one row per run (realisation x variant) in index order, its parameters, status
// and outcomes; numbers in their shortest exact form.
FFEM_STUDY_ENTRY std::string realisations_csv(const StudySpec& s, const std::vector<RunResult>& rows);

class StudyFolder {
 public:
  StudyFolder(const StudySpec& study, const StudyOptions& opt);

  const StudySpec& study() const { return study_; }
  const std::filesystem::path& dir() const { return dir_; }

  // The runs without a result, in index order.
  std::vector<long> pending() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<long> out;
    for (long r = 0; r < study_.num_runs(); ++r)
      if (!results_.count(r)) out.push_back(r);
    return out;
  }
  long done() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return static_cast<long>(results_.size());
  }
  long failed() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return failed_;
  }
  long resumed() const { return resumed_; }
  // Every result so far, in run order.
  std::vector<RunResult> results() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<RunResult> out;
    for (const auto& [run, r] : results_) out.push_back(r);
    return out;
  }

  // Keeps a result (a stopped run is not one) and writes it atomically: a study killed at any moment
  // leaves only whole records.
  void record(const RunResult& r);
  // Writes realisations.csv, the statistics, the figures and summary.json (last: its presence means the
  // others are whole; a figure that could not be written is only warned about).
  void finish(const std::string& status, const StudyTiming& timing) const;
  // The study's status once its runs are over: completed (every run done), failed (every run done
  // and none completed), stopped (runs left: --resume continues).
  std::string status(bool all_done) const;
  // Why runs did not complete, in a sentence: the first one and how many others share its reason.
  std::string not_completed_text(const StudyFailures& f) const;

 private:
  const StudySpec& study_;
  StudyOptions opt_;
  std::filesystem::path dir_;
  std::optional<FolderLock> lock_;
  mutable std::mutex mutex_;
  std::map<long, RunResult> results_;
  long failed_ = 0, resumed_ = 0;

  nlohmann::json first_not_completed_json(const StudyFailures& f) const;
  void load_results();
  // A folder with a previous study's results is refused unless overwrite, and so is one that holds
  // other files (the lock file is none of them). Changes nothing on disk: the folder is not yet locked.
  void check_reusable(bool has_study) const;
  // Only the study's own files and the runs/ folder are removed, never the user's other files.
  void clear_previous();
};

// The study's size before its first run (issue 51): its runs as levels x motions x realisations x
// variants, and the steps of a run and of them all (a variant may set its own dt or duration).
FFEM_STUDY_ENTRY std::string study_size_line(const StudySpec& s);

// A progress line on stderr: runs done of all, failures, elapsed and estimated time left. At the first
// result of this session, once, the projected wall time of the runs left (issue 51): the first run's time
// over the runs `parallel` at once; without the progress line (quiet) only when past a minute.
class StudyProgress {
 public:
  StudyProgress(long total, long already_done, bool on, int parallel = 1)
      : total_(total), start_done_(already_done), on_(on), parallel_(std::max(1, parallel)) {}
  void update(long done, long failed, bool last = false);

 private:
  long total_, start_done_;
  bool on_;
  int parallel_;
  bool forecast_said_ = false;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  double last_print_ = -1;

  void forecast(double el);
};

// Runs `pending` on `workers` threads, each taking the next run when it is free; records every result.
// Returns false when stopped (the runs in progress are dropped and done again on resume).
FFEM_STUDY_ENTRY bool run_local(StudyFolder& folder, const std::vector<long>& pending, int workers,
                                const std::atomic<bool>* stop, bool progress);

// The whole study on this machine: the folder, the pending runs on `workers` threads, the outputs.
// Returns the status written to summary.json: completed, failed (no run completed), or stopped.
FFEM_STUDY_ENTRY std::string run_study(const StudySpec& study, const StudyOptions& opt,
                                       const std::atomic<bool>* stop = nullptr);

}  // namespace furniture_fem

#ifndef FFEM_STUDY_DECLARED_ONLY
#define FURNITURE_FEM_STUDY_INTERNAL
#include "detail/runner_impl.hpp"
#undef FURNITURE_FEM_STUDY_INTERNAL
#endif
