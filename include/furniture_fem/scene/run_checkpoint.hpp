#pragma once
// furniture_fem/scene/run_checkpoint.hpp: a run's checkpoint file (RunOptions::checkpoint_every and
// resume; docs/io/output.md, "Checkpoints").
//
//   checkpoint.bin in the results folder, written beside the previous one (".tmp") and renamed over it
//   when whole, so a write cut short never replaces a good checkpoint:
//     a magic line, the fingerprint (the scene and the run options that shape the results, as JSON),
//     the runner's own state, the simulation's (Simulation::save_state), then each observer's (its
//     files flushed first, and where they end); last, 4 bytes: zlib's CRC-32 of every byte before
//     them, least significant byte first.
//
// A resumed run checks the CRC-32 before it reads anything else (one flipped bit was resumed from:
// issue 51), then reads the state back into a run built from the same scene and options; anything that
// does not fit (a damaged or truncated file, another scene or option, another version) is an InputError
// naming the file and, for a changed setting, the key that differs.
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "observer.hpp"
#include "results_folder.hpp"
#include "writer.hpp"

namespace furniture_fem {

inline constexpr const char* checkpoint_file = "checkpoint.bin";
// 2: the Figures observer keeps the energy series; 3: a settled start's figures and each item's start;
// 4: whether the settling finished, and its fastest item; 5: the CRC-32 at the end, and the structs that
// have padding stored member by member (no padding byte is written); 6: the table's motion integrated
// once, by the runner (RunView::table), instead of in three observers, and each flexible group's kept
// factorisation (its nodes and matrix).
inline constexpr std::string_view checkpoint_magic = "furniture_fem checkpoint 6";
inline constexpr std::size_t checkpoint_checksum_bytes = 4;  // the CRC-32 after the state

// What a resumed run must share with the run that wrote the checkpoint: the scene and every run
// option that changes a result or a file (not the threads, the progress bar or the checkpoint period).
inline nlohmann::json checkpoint_fingerprint(const SceneSpec& spec, const RunOptions& opt) {
  return {{"scene", to_json(spec)},
          {"duration_s", opt.duration.value_or(spec.duration)},
          {"output_interval_s", opt.output_interval},
          {"figures", opt.figures.value_or(spec.outputs.figures)},
          {"energy_creation_limit", opt.energy_creation_limit},
          {"energy_loss_warning", opt.energy_loss_warning},
          {"energy_tolerance", opt.energy_tolerance},
          {"vtu",
           {{"binary", opt.vtu.binary},
            {"float32_fields", opt.vtu.float32_fields},
            {"float32_points", opt.vtu.float32_points},
            {"compression_level", opt.vtu.compression_level}}}};
}

// The runner's own numbers that outlive a step.
struct RunnerState {
  static constexpr bool checkpoint_as_bytes = true;  // core/checkpoint.hpp
  EnergyLedger row_energy, trusted;  // at the last history row; of the last row that passed the energy check
  double max_energy_imbalance = 0;   // RunSummary::max_energy_imbalance so far
  double wall_seconds = 0;           // spent before this part of the run
  double settling_time = -1, settled_speed = 0;  // RunSummary::settled_start; settling_time < 0: none
  int settled = 1, fastest_item = -1;             // its settled and fastest_item (an index into the items)
};

namespace detail {

// zlib's CRC-32 of the bytes (crc32_z: any length).
inline std::uint32_t checkpoint_crc32(std::string_view bytes) {
  return static_cast<std::uint32_t>(
      crc32_z(crc32_z(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(bytes.data()), bytes.size()));
}

// The state in a checkpoint's bytes, once its CRC-32 matches; an InputError naming the file otherwise.
// A file of another format would fail the sum too: its magic line says so first.
inline std::string_view checked_checkpoint_state(std::string_view bytes, const std::string& path) {
  const auto damaged = [&](const std::string& why) {
    throw InputError(path, 0, "checkpoint", "damaged (" + why + "): it cannot be resumed from; run again without --resume");
  };
  if (bytes.size() < sizeof(std::uint64_t) + checkpoint_checksum_bytes)
    damaged(std::to_string(bytes.size()) + " bytes: too short for a checkpoint");
  const std::string_view state = bytes.substr(0, bytes.size() - checkpoint_checksum_bytes);
  std::uint32_t stored = 0;
  for (std::size_t k = 0; k < checkpoint_checksum_bytes; ++k)
    stored |= std::uint32_t(static_cast<unsigned char>(bytes[state.size() + k])) << (8 * k);
  const std::uint32_t computed = checkpoint_crc32(state);
  if (stored == computed) return state;
  constexpr std::string_view family = "furniture_fem checkpoint ";
  const std::string_view magic = bytes.substr(sizeof(std::uint64_t), checkpoint_magic.size());
  if (magic.substr(0, family.size()) == family && magic != checkpoint_magic)
    throw InputError(path, 0, "checkpoint",
                     "written by another version of furniture_fem (\"" + std::string(magic) + "\", this one reads \"" +
                         std::string(checkpoint_magic) + "\"); run again without --resume");
  char sums[64];
  std::snprintf(sums, sizeof sums, "checksum: CRC-32 %08x stored, %08x computed", static_cast<unsigned>(stored),
                static_cast<unsigned>(computed));
  damaged(sums);
  return {};
}

inline std::string checkpoint_path(const std::string& out_dir) { return out_dir + "/" + checkpoint_file; }

// The first setting in which two fingerprints differ, as "key: checkpoint <a>, this run <b>".
inline std::string first_difference(const nlohmann::json& saved, const nlohmann::json& now) {
  const nlohmann::json patch = nlohmann::json::diff(saved, now);
  if (patch.empty()) return {};
  const std::string path = patch.front().at("path").get<std::string>();
  const nlohmann::json::json_pointer p(path);
  const auto shown = [&](const nlohmann::json& j) {
    if (!j.contains(p)) return std::string("(none)");
    std::string s = j.at(p).dump();
    return s.size() > 80 ? s.substr(0, 77) + "..." : s;
  };
  std::string key = path.substr(1);
  std::replace(key.begin(), key.end(), '/', '.');
  return key + ": the checkpoint's run had " + shown(saved) + ", this run has " + shown(now);
}

}  // namespace detail

// Writes the checkpoint of a run between two steps.
inline void write_checkpoint(const std::string& out_dir, const nlohmann::json& fingerprint, const RunnerState& state,
                             const TableMotionIntegrator& table, const SteppedSimulation& sim,
                             const std::vector<RunObserver*>& observers) {
  StateWriter w;
  w(std::string(checkpoint_magic), fingerprint.dump(), state, table);
  sim.save_state(w);
  w(observers.size());
  for (RunObserver* o : observers) o->save(w);
  const std::uint32_t crc = detail::checkpoint_crc32(w.bytes());
  for (std::size_t k = 0; k < checkpoint_checksum_bytes; ++k) w(static_cast<std::uint8_t>(crc >> (8 * k)));
  detail::vtk::write_atomically(detail::checkpoint_path(out_dir), w.bytes(), "checkpoint");
}

// Refuses, naming the folder, one that holds no run to go on with.
inline void check_resumable_folder(const std::string& out_dir) {
  const auto refuse = [&](const std::string& why) {
    throw InputError(out_dir, 0, "--resume", why);
  };
  std::error_code ec;
  if (!std::filesystem::is_directory(out_dir, ec)) refuse("no such results folder");
  const nlohmann::json record = detail::read_run_record(out_dir);
  const std::string status = record.is_object() ? record.value("status", "") : "";
  if (status == "done") refuse("the run there completed (run.json: \"done\"); there is nothing to resume");
  if (!std::filesystem::exists(detail::checkpoint_path(out_dir), ec))
    refuse("holds no checkpoint (" + std::string(checkpoint_file) +
           "): the run was not stopped by a signal and wrote none (RunOptions::checkpoint_every, "
           "--checkpoint-every S), or it ended (completed, diverged or failed)");
}

// Reads a checkpoint into a run built from the same scene and options: the runner's state is
// returned, the table's motion, the simulation's and the observers' are loaded (the observers reopen
// their files).
inline RunnerState resume_from_checkpoint(const std::string& out_dir, const nlohmann::json& fingerprint,
                                          SteppedSimulation& sim, const std::vector<RunObserver*>& observers,
                                          RunView& run) {
  const std::string path = detail::checkpoint_path(out_dir);
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path, 0, "--resume", "cannot open the checkpoint");
  const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  StateReader r(detail::checked_checkpoint_state(bytes, path), path);
  std::string magic, saved;
  r(magic);
  if (magic != checkpoint_magic)
    throw InputError(path, 0, "checkpoint", "not a checkpoint of this version of furniture_fem");
  r(saved);
  nlohmann::json saved_fingerprint;
  try {
    saved_fingerprint = nlohmann::json::parse(saved);
  } catch (const nlohmann::json::exception&) {
    throw InputError(path, 0, "checkpoint", "its settings do not parse: the file is damaged");
  }
  if (const std::string diff = detail::first_difference(saved_fingerprint, fingerprint); !diff.empty())
    throw InputError(path, 0, "--resume",
                     "the run is not the one that wrote the checkpoint (" + diff +
                         "); resume with the same scene file and options");
  RunnerState state;
  r(state, run.table);
  sim.load_state(r);
  std::size_t count = 0;
  r(count);
  r.expect(count, observers.size(), "observers");
  for (RunObserver* o : observers) o->resume(run, r);
  r.finish();
  return state;
}

}  // namespace furniture_fem
