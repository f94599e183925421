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
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "../io/folder_lock.hpp"
#include "../scene/forecast.hpp"
#include "figures.hpp"
#include "outcomes.hpp"
#include "report.hpp"
#include "spec.hpp"

#define FURNITURE_FEM_STUDY_INTERNAL
#include "detail/study_files.hpp"
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
inline std::string realisations_csv(const StudySpec& s, const std::vector<RunResult>& rows) {
  std::vector<std::string> bodies, sections;  // every body and section seen, in order of first appearance
  for (const auto& r : rows) {
    for (const auto& b : r.bodies)
      if (std::find(bodies.begin(), bodies.end(), b.name) == bodies.end()) bodies.push_back(b.name);
    for (const auto& x : r.sections)
      if (std::find(sections.begin(), sections.end(), x.section) == sections.end()) sections.push_back(x.section);
  }
  const auto params0 = parameter_columns(s, realisation_parameters(s, 0));
  std::string out = "run,realisation,variant,level_index,motion,replicate";
  for (const auto& [name, v] : params0) out += "," + detail::csv_field(name);
  out += ",status,t_end";
  static const char* body_cols[] = {"state", "slide_m", "tilt_deg", "max_tilt_deg", "lift_m", "resting_on",
                                    "floor_force_peak_N", "wall_force_peak_N", "item_force_peak_N"};
  for (const auto& b : bodies)
    for (const char* c : body_cols) (out += ',') += detail::csv_field(b + "." + c);  // not "," + &&: GCC 12's -Wrestrict
  for (const auto& x : sections)
    for (const char* c : section_components) (out += ',') += detail::csv_field(x + "." + c + "_abs_max");
  out += ",diagnosis\n";
  const auto num = detail::exact_number;
  for (const auto& r : rows) {
    const RealisationParameters p = realisation_parameters(s, r.realisation);
    out += std::to_string(r.run) + "," + std::to_string(r.realisation) + "," + detail::csv_field(s.variant_name(r.variant)) +
           "," + std::to_string(p.level_index) + "," + detail::csv_field(s.motion_name(p.motion_index)) + "," +
           std::to_string(p.replicate);
    for (const auto& [name, v] : parameter_columns(s, p)) (out += ',') += num(v);
    out += "," + r.status + "," + num(r.t_end);
    for (const auto& name : bodies) {
      const auto it = std::find_if(r.bodies.begin(), r.bodies.end(), [&](const BodyOutcome& b) { return b.name == name; });
      if (it == r.bodies.end()) {
        out += std::string(std::size(body_cols), ',');
        continue;
      }
      out += "," + it->state + "," + num(it->slide) + "," + num(it->tilt_deg) + "," + num(it->max_tilt_deg) + "," +
             num(it->lift) + "," + detail::csv_field(it->resting_on) + "," + num(it->floor_force_peak) + "," +
             num(it->wall_force_peak) + "," + num(it->item_force_peak);
    }
    for (const auto& name : sections) {
      const auto it = std::find_if(r.sections.begin(), r.sections.end(), [&](const SectionOutcome& x) { return x.section == name; });
      for (int k = 0; k < 6; ++k) {
        out += ',';  // appended piece by piece: "," + std::string&& drew GCC 12's false -Wrestrict warning
        if (it != r.sections.end()) out += num(it->abs_max[k]);
      }
    }
    out += "," + detail::csv_field(r.diagnosis) + "\n";
  }
  return out;
}

class StudyFolder {
 public:
  StudyFolder(const StudySpec& study, const StudyOptions& opt) : study_(study), opt_(opt) {
    dir_ = opt.out_dir.empty() ? std::filesystem::path("study_" + study.name) : std::filesystem::path(opt.out_dir);
    const nlohmann::json as_run = to_json(study);
    const std::filesystem::path study_file = dir_ / "study.json";
    const bool has_study = std::filesystem::exists(study_file);
    // Another study or run there is named before anything else is said about the folder.
    refuse_if_locked(dir_.string());
    if (opt.resume) {
      if (!has_study)
        throw InputError(dir_.string(), 0, "--resume", "no study to resume here (no study.json); run without --resume");
      lock_.emplace(dir_.string());  // before the results are read: none is being written
      nlohmann::json before;
      try {
        before = read_json_file(study_file.string(), "study record");
      } catch (const InputError&) {
        before = nullptr;
      }
      // The differing keys are named: the user sees what changed, and whether it was meant.
      if (before != as_run)
        throw InputError(study_file.string(), 0, "--resume",
                         "this folder holds another study: its study.json " +
                             (before.is_null() ? std::string("cannot be read")
                                               : "differs from " + study.source + " in " + detail::study_differences(before, as_run)) +
                             "; resume with the same study file, or use another --out");
      load_results();
    } else {
      check_reusable(has_study);
      lock_.emplace(dir_.string());  // creates the folder
      clear_previous();
      std::filesystem::create_directories(dir_ / "runs");
      detail::write_text_atomically(study_file, as_run.dump(2) + "\n");
    }
    std::filesystem::create_directories(dir_ / "runs");
  }

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
  void record(const RunResult& r) {
    if (r.status == "stopped") return;
    detail::write_text_atomically(dir_ / "runs" / detail::run_file_name(r.run), to_json(r).dump() + "\n");
    std::lock_guard<std::mutex> lock(mutex_);
    if (results_.emplace(r.run, r).second && r.status != "completed") ++failed_;
  }

  // Writes realisations.csv, the statistics, the figures and summary.json (last: its presence means the
  // others are whole; a figure that could not be written is only warned about).
  void finish(const std::string& status, const StudyTiming& timing) const {
    const std::vector<RunResult> rows = results();
    detail::write_text_atomically(dir_ / "realisations.csv", realisations_csv(study_, rows));
    const StudyReport report = study_report(study_, rows);
    write_report(report, dir_);
    // The figures are a view of the files above: one that cannot be written costs a warning, never
    // the study (its CSV results are already whole, and summary.json still follows).
    try {
      write_study_figures(study_, report, rows, dir_);
    } catch (const OutputError& e) {
      std::fprintf(stderr, "furniture_study: warning: study figures not written: %s\n", e.what());
    }
    long run_seconds_n = 0;
    double run_seconds = 0;
    for (const auto& r : rows) {
      run_seconds += r.wall_seconds;
      ++run_seconds_n;
    }
    const StudyFailures failures = study_failures(rows);
    nlohmann::json j = {{"program", "furniture_study"},
                        {"furniture_fem_version", version_string},
                        {"status", status},
                        {"study", to_json(study_)},
                        {"runs", study_.num_runs()},
                        {"realisations", study_.num_realisations()},
                        {"done", static_cast<long>(rows.size())},
                        {"not_completed", failures.not_completed},
                        {"pending", study_.num_runs() - static_cast<long>(rows.size())},
                        {"resumed_from_previous", resumed_},
                        {"wall_seconds", timing.wall_seconds},
                        {"workers", timing.workers},
                        {"ranks", timing.ranks},
                        {"mean_run_seconds", run_seconds_n ? run_seconds / run_seconds_n : 0.0},
                        {"handout_seconds_mean", timing.handout_seconds_mean ? nlohmann::json(*timing.handout_seconds_mean)
                                                                             : nlohmann::json()}};
    if (failures.not_completed > 0) j["first_not_completed"] = first_not_completed_json(failures);
    detail::write_text_atomically(dir_ / "summary.json", j.dump(2) + "\n");
  }

  // The study's status once its runs are over: completed (every run done), failed (every run done
  // and none completed), stopped (runs left: --resume continues).
  std::string status(bool all_done) const {
    if (!all_done) return "stopped";
    std::lock_guard<std::mutex> lock(mutex_);
    return failed_ == static_cast<long>(results_.size()) && failed_ > 0 ? "failed" : "completed";
  }

  // Why runs did not complete, in a sentence: the first one and how many others share its reason.
  std::string not_completed_text(const StudyFailures& f) const {
    return "the first, run " + std::to_string(f.first.run) + " (realisation " + std::to_string(f.first.realisation) +
           ", variant '" + study_.variant_name(f.first.variant) + "'), " + f.first.status + ": " + f.first.diagnosis +
           " [" + std::to_string(f.same_reason) + " of the " + std::to_string(f.not_completed) +
           " runs not completed for this reason]";
  }

 private:
  const StudySpec& study_;
  StudyOptions opt_;
  std::filesystem::path dir_;
  std::optional<FolderLock> lock_;
  mutable std::mutex mutex_;
  std::map<long, RunResult> results_;
  long failed_ = 0, resumed_ = 0;

  nlohmann::json first_not_completed_json(const StudyFailures& f) const {
    return {{"run", f.first.run},
            {"variant", study_.variant_name(f.first.variant)},
            {"status", f.first.status},
            {"diagnosis", f.first.diagnosis},
            {"runs_for_this_reason", f.same_reason}};
  }

  void load_results() {
    for (const auto& e : std::filesystem::directory_iterator(dir_ / "runs")) {
      const std::string name = e.path().filename().string();
      if (name.size() != 17 || name.rfind("run_", 0) != 0 || e.path().extension() != ".json") continue;
      try {
        std::ifstream f(e.path(), std::ios::binary);
        const RunResult r = run_result_from_json(nlohmann::json::parse(f));
        if (r.run < 0 || r.run >= study_.num_runs() || detail::run_file_name(r.run) != name) continue;
        results_.emplace(r.run, r);
        failed_ += r.status != "completed";
      } catch (const std::exception&) {  // a torn or foreign file: the run is done again
      }
    }
    resumed_ = static_cast<long>(results_.size());
  }

  // A folder with a previous study's results is refused unless overwrite, and so is one that holds
  // other files (the lock file is none of them). Changes nothing on disk: the folder is not yet locked.
  void check_reusable(bool has_study) const {
    if (!std::filesystem::exists(dir_)) return;
    if (!std::filesystem::is_directory(dir_))
      throw InputError(dir_.string(), 0, "--out", "exists and is not a folder");
    const bool has_runs = std::filesystem::exists(dir_ / "runs");
    if ((has_study || has_runs) && !opt_.overwrite)
      throw InputError(dir_.string(), 0, "--out",
                       "holds a previous study's results: --resume continues it, --overwrite replaces it");
    if (!has_study && !has_runs && !detail::empty_but_lock(dir_) && !opt_.overwrite)
      throw InputError(dir_.string(), 0, "--out", "is not empty and holds no study; choose another folder or --overwrite");
  }
  // Only the study's own files and the runs/ folder are removed, never the user's other files.
  void clear_previous() {
    for (const auto& f : detail::study_result_files()) std::filesystem::remove(dir_ / f);
    std::filesystem::remove_all(dir_ / "runs");
  }
};

// The study's size before its first run (issue 51): its runs as levels x motions x realisations x
// variants, and the steps of a run and of them all (a variant may set its own dt or duration).
inline std::string study_size_line(const StudySpec& s) {
  long lo = 0, hi = 0;
  double steps = 0;
  for (int v = 0; v < s.num_variants(); ++v) {
    const SceneSpec scene = study_scene(s, detail::study_scene_json(s, v, 0), "variant '" + s.variant_name(v) + "'");
    const long n = std::lround(scene.duration / scene.dt);
    lo = v == 0 ? n : std::min(lo, n), hi = std::max(hi, n);
    steps += double(n) * double(s.num_realisations());
  }
  const auto count = [](long n, const char* what) { return std::to_string(n) + " " + what + (n == 1 ? "" : "s"); };
  return "study: " + std::to_string(s.num_runs()) + " runs = " + count(s.num_levels(), "level") + " x " +
         count(s.num_motions(), "motion") + " x " + count(s.realisations, "realisation") + " x " +
         count(s.num_variants(), "variant") + "; " + (lo == hi ? std::to_string(lo) : std::to_string(lo) + " to " + std::to_string(hi)) +
         " steps a run, " + detail::fmt(steps) + " steps in all";
}

// A progress line on stderr: runs done of all, failures, elapsed and estimated time left. At the first
// result of this session, once, the projected wall time of the runs left (issue 51): the first run's time
// over the runs `parallel` at once; without the progress line (quiet) only when past a minute.
class StudyProgress {
 public:
  StudyProgress(long total, long already_done, bool on, int parallel = 1)
      : total_(total), start_done_(already_done), on_(on), parallel_(std::max(1, parallel)) {}
  void update(long done, long failed, bool last = false) {
    std::lock_guard<std::mutex> lock(mutex_);
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (!forecast_said_ && done > start_done_) forecast(el);
    if (!on_) return;
    if (!last && el - last_print_ < 0.5) return;
    last_print_ = el;
    const long new_done = done - start_done_, left = total_ - done;
    const double eta = new_done > 0 ? el / new_done * left : 0;
    std::fprintf(stderr, "\rruns %ld / %ld  (%ld not completed)  elapsed %.0f s  ETA %.0f s   ", done, total_, failed, el, eta);
    if (last) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }

 private:
  long total_, start_done_;
  bool on_;
  int parallel_;
  bool forecast_said_ = false;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  double last_print_ = -1;

  void forecast(double el) {
    forecast_said_ = true;
    const long runs = total_ - start_done_;
    const double projected = el * std::ceil(double(runs) / std::min<double>(parallel_, double(runs)));
    if (!on_ && !(projected > detail::quiet_forecast_seconds)) return;
    const std::string text = "study: the first run took " + detail::wall_time_text(el) + " of wall time: about " +
                             detail::wall_time_text(projected) + " for the " + std::to_string(runs) + " runs" +
                             (start_done_ > 0 ? " left" : "") + " on " + std::to_string(parallel_) + " worker" +
                             (parallel_ == 1 ? "" : "s");
    std::fprintf(stderr, on_ ? "\r%-100s\n" : "%s\n", text.c_str());
    std::fflush(stderr);
  }
};

// Runs `pending` on `workers` threads, each taking the next run when it is free; records every result.
// Returns false when stopped (the runs in progress are dropped and done again on resume).
inline bool run_local(StudyFolder& folder, const std::vector<long>& pending, int workers,
                      const std::atomic<bool>* stop, bool progress) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stopped{false};
  const int n = std::max(1, std::min<int>(workers, static_cast<int>(pending.size())));
  StudyProgress bar(folder.study().num_runs(), folder.done(), progress, n);
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto work = [&] {
    try {
      for (std::size_t k; (k = next.fetch_add(1)) < pending.size();) {
        if (stop && stop->load()) break;
        const RunResult r = run_realisation(folder.study(), pending[k], stop);
        if (r.status == "stopped") break;
        folder.record(r);
        bar.update(folder.done(), folder.failed());
      }
    } catch (...) {  // a write error: the study stops, the error is reported
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next = pending.size();
    }
    if (stop && stop->load()) stopped = true;
  };
  std::vector<std::thread> threads;
  for (int i = 1; i < n; ++i) threads.emplace_back(work);
  work();
  for (auto& t : threads) t.join();
  bar.update(folder.done(), folder.failed(), true);
  if (error) std::rethrow_exception(error);
  return !stopped && folder.done() == folder.study().num_runs();
}

// The whole study on this machine: the folder, the pending runs on `workers` threads, the outputs.
// Returns the status written to summary.json: completed, failed (no run completed), or stopped.
inline std::string run_study(const StudySpec& study, const StudyOptions& opt, const std::atomic<bool>* stop = nullptr) {
  const auto t0 = std::chrono::steady_clock::now();
  StudyFolder folder(study, opt);
  StudyTiming timing;
  timing.workers = opt.workers > 0 ? opt.workers : std::max(1u, std::thread::hardware_concurrency());
  const bool all = run_local(folder, folder.pending(), timing.workers, stop, opt.progress);
  timing.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string status = folder.status(all);
  folder.finish(status, timing);
  return status;
}

}  // namespace furniture_fem
