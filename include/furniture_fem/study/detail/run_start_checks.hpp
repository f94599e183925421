#pragma once
// Internal: each scene a study will run, checked as its runs will start (scene/run_scene.hpp's
// check_run_start: the scene, the run's length, the ground motion read and set against it), for every
// variant, motion and intensity level, before the first run. A study that cannot succeed fails when
// it is read, naming the study's key, the variant, the motion, the level and the value, instead of
// recording every run as failed.
#ifndef FURNITURE_FEM_STUDY_INTERNAL
#error "furniture_fem/study/detail/run_start_checks.hpp is internal: include <furniture_fem/study/spec.hpp>"
#endif
#include <nlohmann/json.hpp>

#include <set>
#include <string>

#include "../../scene/json_reader.hpp"
#include "../../scene/run_scene.hpp"

namespace furniture_fem {
namespace detail {

// How an intensity level sets a realisation's ground_motion (the study's measure). A scene without
// one has the default motion: an object with the level alone (null made every run fail).
inline void apply_intensity(const StudySpec& s, double level, nlohmann::json& gm) {
  if (gm.is_null()) gm = nlohmann::json::object();
  const std::string source = gm.value("source", "synthetic");
  switch (s.intensity.measure) {
    case IntensityMeasure::scale:
      gm["level"] = gm.value("level", 1.0) * level;
      return;
    case IntensityMeasure::pga:
      if (source == "synthetic")
        gm["pga"] = level;
      else
        gm["scale_to"] = {{"pga", level}};
      return;
    case IntensityMeasure::pgv:
      gm["scale_to"] = {{"pgv", level}};
      return;
  }
}

// A record window `shift` s later (a realisation's start-time perturbation).
inline void shift_window(nlohmann::json& gm, double shift) {
  if (!(shift > 0)) return;
  nlohmann::json& window = gm["window"];
  if (!window.is_object()) window = nlohmann::json::object();
  window["start"] = window.value("start", 0.0) + shift;
}

inline bool key_under(const std::string& key, const std::string& prefix) {
  return key == prefix || key.rfind(prefix + ".", 0) == 0 || key.rfind(prefix + "[", 0) == 0;
}

// The study's key that set a key of the scene run by variant v, motion m at level l: the study's own
// duration, an intensity level, a motion of the suite, a variant's patch, or the base scene.
inline std::string study_key_of(const StudySpec& s, int v, int m, int l, const std::string& scene_key) {
  const std::string motion = s.motions.empty() ? "scene.ground_motion" : "ground_motions[" + std::to_string(m) + "].ground_motion";
  if (scene_key.empty()) return motion;
  if (scene_key == "duration" && s.duration) return "duration";
  if (s.intensity.measure != IntensityMeasure::scale &&
      (key_under(scene_key, "ground_motion.scale_to") || scene_key == "ground_motion.pga"))
    return "intensity.levels[" + std::to_string(l) + "]";
  if (key_under(scene_key, "ground_motion")) return motion + scene_key.substr(std::string("ground_motion").size());
  const std::string first = scene_key.substr(0, scene_key.find_first_of(".["));
  if (!s.variants.empty() && s.variants[v].patch.contains(first))
    return "compare[" + std::to_string(v) + "].scene." + scene_key;
  return "scene." + scene_key;
}

// The scene's refusal without its own file and key (the study names them): "<source>: <key>: why".
inline std::string refusal_text(const InputError& e, const std::string& scene_source) {
  const std::string what = e.what();
  const std::string prefix = scene_source + (e.field().empty() ? "" : ": " + e.field()) + ": ";
  return what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what;
}

// Checks every (variant, motion, level) scene's run start; with a start-time perturbation, also the
// latest window a realisation can draw. A motion already checked (the same ground motion, duration
// and dt) is not read again, and a scene is copied only for a motion not yet checked.
inline void check_study_run_starts(const StudySpec& s, const json_io::ObjectReader& r) {
  std::set<std::string> checked;
  RunOptions opt;  // as run_realisation runs: the scene's duration and the default output interval
  for (int v = 0; v < s.num_variants(); ++v)
    for (int m = 0; m < s.num_motions(); ++m) {
      const nlohmann::json base = study_scene_json(s, v, m);
      const nlohmann::json length = {base.value("duration", nlohmann::json()), base.value("dt", nlohmann::json())};
      for (int l = 0; l < s.num_levels(); ++l)
        for (const double shift : {0.0, s.perturb.start_time}) {
          nlohmann::json motion = base.value("ground_motion", nlohmann::json());
          apply_intensity(s, s.intensity.levels[l], motion);
          shift_window(motion, shift);
          if (!checked.insert(nlohmann::json{motion, length}.dump()).second) continue;
          nlohmann::json scene = base;
          scene["ground_motion"] = std::move(motion);
          const std::string what = "variant '" + s.variant_name(v) + "', motion '" + s.motion_name(m) + "', level " +
                                   fmt(s.intensity.levels[l]);
          const SceneSpec spec = study_scene(s, scene, what);
          try {
            check_run_start(spec, opt);
          } catch (const InputError& e) {
            const std::string key = study_key_of(s, v, m, l, e.field()), why = refusal_text(e, spec.source);
            if (shift > 0)
              r.fail("perturbations.start_time", what + ": a realisation's record window may start up to " + fmt(shift) +
                                                     " s later, and then " + key + ": " + why);
            r.fail(key, what + ": " + why);
          }
        }
    }
}

// Each variant's scene built as its runs build it (check_scene_model: an obstacle through an item at
// t = 0, a dt too long for the explicit contact), with the first motion: neither depends on the motion
// or the level. A realisation its perturbations push over (an item moved into an obstacle) is refused
// at its own run.
inline void check_study_models(const StudySpec& s, const json_io::ObjectReader& r) {
  for (int v = 0; v < s.num_variants(); ++v) {
    const std::string what = "variant '" + s.variant_name(v) + "'";
    const SceneSpec spec = study_scene(s, study_scene_json(s, v, 0), what);
    try {
      check_scene_model(spec);
    } catch (const InputError& e) {
      r.fail(study_key_of(s, v, 0, 0, e.field()), what + ": " + refusal_text(e, spec.source));
    }
  }
}

}  // namespace detail
}  // namespace furniture_fem
