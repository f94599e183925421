#pragma once
// furniture_fem/study/spec.hpp: what a study runs, as plain data, and its JSON file (docs/study/studies.md).
//
//   StudySpec parse_study(path) / parse_study_json(json, source, base_dir)    errors name the key path
//   nlohmann::json to_json(const StudySpec&)                                    read back: the same study
//
// A study is a base scene and factors: intensity levels, a suite of ground motions, seeded
// perturbations, a number of realisations per (level, motion) cell, and variants of the scene to
// compare on the same realisations. Which realisation gets which values: study/realisation.hpp.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "../scene/spec.hpp"

#define FURNITURE_FEM_STUDY_INTERNAL
#include "detail/compiled_study.hpp"
#undef FURNITURE_FEM_STUDY_INTERNAL

namespace furniture_fem {

// How the intensity levels scale the ground motion: `scale` multiplies the motion (its `level`), `pga`
// and `pgv` scale a record file to that horizontal peak (m/s^2, m/s; ground_motion.scale_to); `pga`
// also sets a synthetic motion's peak.
enum class IntensityMeasure { scale, pga, pgv };

struct IntensitySpec {
  IntensityMeasure measure = IntensityMeasure::scale;
  std::vector<double> levels{1.0};
};

// One ground motion of the suite: a name and a ground_motion object as a scene file takes it (it
// replaces the base scene's).
struct StudyMotion {
  std::string name;
  nlohmann::json ground_motion;
};

// Seeded perturbations, each drawn uniformly in [-value, +value] (start time: [0, value]) for each
// realisation, independently per item. 0: not perturbed.
struct PerturbationSpec {
  double x = 0, y = 0;    // m, item placement
  double yaw_deg = 0;     // deg
  double friction = 0;    // relative: every friction coefficient of the item times 1 + U(-f, f)
  double alpha = 0;       // relative: the item's penalty alpha times 1 + U(-a, a)
  double mass = 0;        // relative: the item's mass times 1 + U(-m, m)
  double start_time = 0; // s: the record window starts U(0, s) later (record files only)
  std::vector<std::string> items;  // the items perturbed; empty: every item
  bool any() const { return x > 0 || y > 0 || yaw_deg > 0 || friction > 0 || alpha > 0 || mass > 0 || start_time > 0; }
};

// A variant of the scene run on every realisation: a JSON merge patch (RFC 7386) applied to the base
// scene ({"items": ...} replaces the list; {"contact": {"law": "stiff"}} changes one key).
struct StudyVariant {
  std::string name;
  nlohmann::json patch = nlohmann::json::object();
  // Every item's fidelity ("full", "coarse", "rigid", "auto"), set after the patch: comparing
  // fidelities needs no copy of the item list. Empty: as the scene says.
  std::string fidelity;
};

// What the statistics call a damage state of an item (study/report.hpp).
struct OutcomeSpec {
  double slide_threshold = 0.05;  // m: "slid" when the final slide exceeds it
  double tilt_threshold_deg = 10; // deg: "tilted" when the largest tilt during the run exceeds it
};

struct StudySpec {
  std::string name = "study";
  std::uint64_t seed = 1;
  nlohmann::json scene;              // the base scene, as JSON (a file's content, or given inline)
  std::string scene_file;            // where it came from (empty: inline)
  IntensitySpec intensity;
  std::vector<StudyMotion> motions;  // empty: the base scene's own motion
  PerturbationSpec perturb;
  int realisations = 1;              // per (level, motion) cell
  std::vector<StudyVariant> variants;  // empty: the base scene alone ("base")
  OutcomeSpec outcomes;
  std::optional<double> duration;    // s: overrides the scene's
  // Not part of the file: where it came from (error messages) and the folder relative paths are read from.
  std::string source = "<study>";
  std::string base_dir;

  int num_levels() const { return static_cast<int>(intensity.levels.size()); }
  int num_motions() const { return motions.empty() ? 1 : static_cast<int>(motions.size()); }
  int num_variants() const { return variants.empty() ? 1 : static_cast<int>(variants.size()); }
  long num_realisations() const { return long(num_levels()) * num_motions() * realisations; }
  long num_runs() const { return num_realisations() * num_variants(); }
  std::string motion_name(int m) const { return motions.empty() ? "scene" : motions[m].name; }
  std::string variant_name(int v) const { return variants.empty() ? "base" : variants[v].name; }
};


// Reads a study from JSON. The base scene (`scene`: a file name relative to `base_dir`, or an object)
// is read and validated here, so that a bad scene fails before anything runs; the variants and the
// motions are checked by applying each to it (a bad patch names its key path in the study).
FFEM_STUDY_ENTRY StudySpec parse_study_json(const nlohmann::json& j, const std::string& source, const std::string& base_dir = {});
// Reads a study file (read_json_file's checks); relative paths in it (the scene file) are taken from its folder.
FFEM_STUDY_ENTRY StudySpec parse_study(const std::string& path);
// The study as JSON: parse_study_json(to_json(s)) gives the same study (the scene written inline).
FFEM_STUDY_ENTRY nlohmann::json to_json(const StudySpec& s);
// A scene of the study as a SceneSpec (reading errors name the study and what was applied).
FFEM_STUDY_ENTRY SceneSpec study_scene(const StudySpec& s, const nlohmann::json& scene_json, const std::string& what);

namespace detail {
// The base scene with one variant and one motion applied, as the realisations see it before their
// perturbations (study/realisation.hpp applies those).
inline nlohmann::json study_scene_json(const StudySpec& s, int variant, int motion) {
  nlohmann::json scene = s.scene;
  if (!s.variants.empty()) {
    scene.merge_patch(s.variants[variant].patch);
    if (const std::string& f = s.variants[variant].fidelity; !f.empty() && scene.contains("items"))
      for (auto& item : scene["items"])
        if (item.is_object()) item["fidelity"] = f;
  }
  if (!s.motions.empty()) scene["ground_motion"] = s.motions[motion].ground_motion;
  if (s.duration) scene["duration"] = *s.duration;
  return scene;
}
// The scene's folder: relative paths inside the scene (record files, meshes) are taken from there.
inline std::string study_scene_dir(const StudySpec& s) {
  if (s.scene_file.empty()) return s.base_dir;
  return std::filesystem::path(s.scene_file).parent_path().string();
}
}  // namespace detail

}  // namespace furniture_fem

#ifndef FFEM_STUDY_DECLARED_ONLY
#define FURNITURE_FEM_STUDY_INTERNAL
#include "detail/spec_impl.hpp"
#undef FURNITURE_FEM_STUDY_INTERNAL
#endif
