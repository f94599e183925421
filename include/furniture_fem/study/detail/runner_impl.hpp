#pragma once
// Internal: running a study and keeping its results (study/runner.hpp's entry points: StudyFolder's and
// StudyProgress's members, run_local, run_study ...), defined inline when the study is used header-only
// and once in the compiled study (src/study/study_results.cpp).
#ifndef FURNITURE_FEM_STUDY_INTERNAL
#error "furniture_fem/study/detail/runner_impl.hpp is internal: include <furniture_fem/study/runner.hpp>"
#endif
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
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "../../scene/forecast.hpp"
#include "../../scene/reader.hpp"  // read_json_file
#include "../figures.hpp"
#include "../realisation.hpp"
#include "../runner.hpp"

#define FURNITURE_FEM_STUDY_INTERNAL
#include "study_files.hpp"
#undef FURNITURE_FEM_STUDY_INTERNAL

namespace furniture_fem {

FFEM_STUDY_ENTRY std::string realisations_csv(const StudySpec& s, const std::vector<RunResult>& rows) {
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

FFEM_STUDY_ENTRY StudyFolder::StudyFolder(const StudySpec& study, const StudyOptions& opt) : study_(study), opt_(opt) {
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

FFEM_STUDY_ENTRY void StudyFolder::record(const RunResult& r) {
  if (r.status == "stopped") return;
  detail::write_text_atomically(dir_ / "runs" / detail::run_file_name(r.run), to_json(r).dump() + "\n");
  std::lock_guard<std::mutex> lock(mutex_);
  if (results_.emplace(r.run, r).second && r.status != "completed") ++failed_;
}

FFEM_STUDY_ENTRY void StudyFolder::finish(const std::string& status, const StudyTiming& timing) const {
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

FFEM_STUDY_ENTRY std::string StudyFolder::status(bool all_done) const {
  if (!all_done) return "stopped";
  std::lock_guard<std::mutex> lock(mutex_);
  return failed_ == static_cast<long>(results_.size()) && failed_ > 0 ? "failed" : "completed";
}

FFEM_STUDY_ENTRY std::string StudyFolder::not_completed_text(const StudyFailures& f) const {
  return "the first, run " + std::to_string(f.first.run) + " (realisation " + std::to_string(f.first.realisation) +
         ", variant '" + study_.variant_name(f.first.variant) + "'), " + f.first.status + ": " + f.first.diagnosis +
         " [" + std::to_string(f.same_reason) + " of the " + std::to_string(f.not_completed) +
         " runs not completed for this reason]";
}

FFEM_STUDY_ENTRY nlohmann::json StudyFolder::first_not_completed_json(const StudyFailures& f) const {
  return {{"run", f.first.run},
          {"variant", study_.variant_name(f.first.variant)},
          {"status", f.first.status},
          {"diagnosis", f.first.diagnosis},
          {"runs_for_this_reason", f.same_reason}};
}

FFEM_STUDY_ENTRY void StudyFolder::load_results() {
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

FFEM_STUDY_ENTRY void StudyFolder::check_reusable(bool has_study) const {
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

FFEM_STUDY_ENTRY void StudyFolder::clear_previous() {
  for (const auto& f : detail::study_result_files()) std::filesystem::remove(dir_ / f);
  std::filesystem::remove_all(dir_ / "runs");
}

FFEM_STUDY_ENTRY std::string study_size_line(const StudySpec& s) {
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

FFEM_STUDY_ENTRY void StudyProgress::update(long done, long failed, bool last) {
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

FFEM_STUDY_ENTRY void StudyProgress::forecast(double el) {
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

FFEM_STUDY_ENTRY bool run_local(StudyFolder& folder, const std::vector<long>& pending, int workers,
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

FFEM_STUDY_ENTRY std::string run_study(const StudySpec& study, const StudyOptions& opt, const std::atomic<bool>* stop) {
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
