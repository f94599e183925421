#pragma once
// furniture_fem/scene/results_folder.hpp: the results folder a run writes into, and its record run.json
// (docs/io/output.md, "The results folder").
//
//   results_file(relative)                   true for a file name a run writes (run.json, markers.csv,
//                                            vtu/room_12.vtu, marker_*.png, ... and their .tmp)
//   check_results_folder(dir, overwrite)     refuses a non-empty folder this program did not write
//                                            (with overwrite: one holding a file named as an output);
//                                            changes nothing on disk
//   prepare_results_folder(dir, overwrite)   checks, creates the folder, removes the old results (its
//                                            caller holds the folder's lock, io/folder_lock.hpp)
//   iso8601_utc(time)                        "2026-11-26T00:33:42.123Z"
//   write_json_atomically(path, json)        "<path>.tmp", then renamed
//
// The policy: a run writes into a folder that is new, empty, or one a run of this program wrote (it
// holds run.json; or, for folders written before run.json existed, a summary.json holding
// "furniture_fem_version"). Before writing, the old results are removed: only the files whose names a
// run writes (results_file()), never any other file. A folder whose run.json says a run is still
// "running" is refused (two runs writing into one folder would interleave their files; a run killed
// with SIGKILL leaves that status behind). RunOptions::overwrite (furniture_quake --overwrite) lifts
// both refusals: a "running" folder's results are removed in the same way; into a folder no run wrote
// the run writes beside the user's files, and refuses if one of them has an output's name (it would be
// replaced or removed).
//
// One writer per folder: a run holds the folder's lock (FolderLock, io/folder_lock.hpp) from before it
// removes or writes anything there until its last file is written; another run or study on the same
// folder is refused, naming the holder's process. The lock file is none of a run's results: it does not
// make a folder non-empty or foreign, and is never removed.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "../core/errors.hpp"
#include "../io/folder_lock.hpp"
#include "../io/vtk.hpp"

namespace furniture_fem {

inline constexpr const char* run_record_file = "run.json";

namespace detail {
inline bool starts_with(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }
inline bool ends_with(std::string_view s, std::string_view p) {
  return s.size() >= p.size() && s.substr(s.size() - p.size()) == p;
}
}  // namespace detail

// True for a path, relative to the results folder with '/' separators, that a run writes: the files
// of the observers in observers.hpp and run.json, and each of them with ".tmp" appended (an atomic
// write cut short). Extend this list when an observer writes a new file.
inline bool results_file(std::string_view rel) {
  if (detail::ends_with(rel, ".tmp")) rel.remove_suffix(4);
  for (std::string_view f : {"run.json", "summary.json", "final_state.json", "markers.csv", "sectional_forces.csv",
                             "energy.csv", "contact_forces.csv", "contact_pairs.csv", "input_motion.csv", "room.pvd",
                             "room_final.png", "input_motion.png", "input_spectra.png", "energy.png", "checkpoint.bin",
                             "restraints.csv", "restraints.png", "strikes.csv", "exits.csv", "plan.png", "timeline.png"})
    if (rel == f) return true;
  const bool png = detail::ends_with(rel, ".png") && rel.find('/') == std::string_view::npos;
  if (png && (detail::starts_with(rel, "marker_") || detail::starts_with(rel, "shear_"))) return true;
  return detail::starts_with(rel, "vtu/room_") && detail::ends_with(rel, ".vtu") &&
         rel.find('/', 4) == std::string_view::npos;
}

// "2026-11-26T00:33:42.123Z": ISO 8601, UTC, milliseconds.
inline std::string iso8601_utc(std::chrono::system_clock::time_point t) {
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(t.time_since_epoch()).count();
  const std::time_t s = static_cast<std::time_t>(ms / 1000 - (ms % 1000 < 0 ? 1 : 0));
  std::tm tm{};
  gmtime_r(&s, &tm);
  char buf[40];
  const std::size_t n = std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &tm);
  char frac[8];
  std::snprintf(frac, sizeof frac, ".%03dZ", static_cast<int>(((ms % 1000) + 1000) % 1000));
  return std::string(buf, n) + frac;
}

// Written to "<path>.tmp" and renamed: a reader never sees half a run.json.
inline void write_json_atomically(const std::string& path, const nlohmann::json& j) {
  detail::vtk::write_atomically(path, j.dump(2) + "\n", "run record");
}

namespace detail {

// The folder's run.json, or null if it has none or it does not parse.
inline nlohmann::json read_run_record(const std::filesystem::path& dir) {
  std::ifstream f(dir / run_record_file);
  if (!f) return nullptr;
  try {
    return nlohmann::json::parse(f);
  } catch (const nlohmann::json::exception&) {
    return nullptr;
  }
}

// A summary.json written by this program before run.json existed.
inline bool legacy_results(const std::filesystem::path& dir) {
  std::ifstream f(dir / "summary.json");
  if (!f) return false;
  try {
    const nlohmann::json j = nlohmann::json::parse(f);
    return j.is_object() && j.contains("furniture_fem_version");
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

// The files under `dir` (relative, '/' separators) that results_file() claims, sorted.
inline std::vector<std::string> results_files_in(const std::filesystem::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec); !ec && it != std::filesystem::recursive_directory_iterator();
       it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    const std::string rel = it->path().lexically_relative(dir).generic_string();
    if (results_file(rel)) out.push_back(rel);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace detail

// Refuses, with an InputError naming the folder, a folder a run must not write into (the policy above).
// Changes nothing on disk.
inline void check_results_folder(const std::string& dir, bool overwrite) {
  namespace fs = std::filesystem;
  const auto refuse = [&](const std::string& why) {
    throw InputError("results folder '" + dir + "': " + why);
  };
  std::error_code ec;
  const fs::path p(dir);
  if (!fs::exists(p, ec)) return;  // new: created by the run
  if (!fs::is_directory(p, ec)) refuse("exists and is not a folder");
  if (detail::empty_but_lock(p)) return;
  const nlohmann::json record = detail::read_run_record(p);
  if (record.is_object()) {
    if (!overwrite && record.value("status", "") == "running")
      refuse("run.json says a run started " + record.value("start_utc", std::string("at an unknown time")) +
             " is still writing there (status \"running\"); if that run is no longer alive (killed), pass "
             "--overwrite (RunOptions::overwrite) to remove its results");
    return;
  }
  if (detail::legacy_results(p)) return;
  // A folder no run wrote: its files are the user's, even those named like a run's outputs (a user's own
  // energy.csv). --overwrite writes beside them, and refuses rather than remove or replace one.
  if (!overwrite)
    refuse("is not empty and was not written by furniture_fem (it has no run.json); choose a new or empty "
           "folder (--out DIR), or pass --overwrite (RunOptions::overwrite) to write beside its files");
  const std::vector<std::string> clash = detail::results_files_in(p);
  if (clash.empty()) return;
  std::string names;
  for (std::size_t i = 0; i < clash.size() && i < 5; ++i) names += (i ? ", " : "") + clash[i];
  if (clash.size() > 5) names += ", ... (" + std::to_string(clash.size()) + " in all)";
  refuse("was not written by furniture_fem (it has no run.json) and has files named as a run's outputs (" + names +
         "); --overwrite removes only a run's own results: move those files or choose another folder (--out DIR)");
}

// Checks (check_results_folder), creates the folder, and removes the old results in it: only the files
// results_file() claims, then vtu/ if that leaves it empty. Returns the files removed (relative).
inline std::vector<std::string> prepare_results_folder(const std::string& dir, bool overwrite) {
  namespace fs = std::filesystem;
  check_results_folder(dir, overwrite);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw OutputError("results folder '" + dir + "': cannot create it: " + ec.message());
  const std::vector<std::string> old = detail::results_files_in(dir);
  for (const auto& rel : old) {
    fs::remove(fs::path(dir) / rel, ec);
    if (ec) throw OutputError("results folder '" + dir + "': cannot remove the old '" + rel + "': " + ec.message());
  }
  const fs::path vtu = fs::path(dir) / "vtu";
  if (fs::is_directory(vtu, ec) && fs::is_empty(vtu, ec)) fs::remove(vtu, ec);
  return old;
}

}  // namespace furniture_fem
