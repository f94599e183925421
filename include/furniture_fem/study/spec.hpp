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

#include "../scene/json_reader.hpp"
#include "../scene/reader.hpp"
#include "../scene/validation.hpp"

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

namespace detail {

inline const json_io::EnumNames<IntensityMeasure, 3> measure_names{
    {{IntensityMeasure::scale, "scale"}, {IntensityMeasure::pga, "pga"}, {IntensityMeasure::pgv, "pgv"}}};

// A study may be large, but not absurd: the runner keeps one record per run in memory.
inline constexpr long study_max_runs = 10'000'000;

inline std::string study_name_problem(const std::string& name) {
  if (name.empty()) return "must not be empty";
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
      return "may hold letters, digits, '_', '-' and '.' only (it names columns and files), got \"" + name + "\"";
  return {};
}

inline void read_intensity(const json_io::ObjectReader& r, IntensitySpec& in) {
  r.allow_only({"measure", "levels"});
  in.measure = r.enumeration("measure", measure_names, in.measure, "intensity measure");
  if (!r.has("levels")) r.fail(r.path("levels"), "required: a list of intensity levels, e.g. [0.5, 1.0]");
  in.levels.clear();
  r.array("levels", [&](const nlohmann::json& v, const std::string& path) {
    if (!v.is_number() || !std::isfinite(v.get<double>()) || !(v.get<double>() > 0))
      r.fail(path, "expected a positive finite number, got " + json_io::ObjectReader::describe(v));
    in.levels.push_back(v.get<double>());
  });
  if (in.levels.empty()) r.fail(r.path("levels"), "needs at least one level");
}

inline void read_perturbations(const json_io::ObjectReader& r, PerturbationSpec& p) {
  r.allow_only({"x", "y", "yaw_deg", "friction", "alpha", "mass", "start_time", "items"});
  const auto read = [&](const char* key, double hi, double& out) {
    out = r.number(key, out);
    r.in_range(key, 0.0, hi);
  };
  read("x", 1.0, p.x);
  read("y", 1.0, p.y);
  read("yaw_deg", 180.0, p.yaw_deg);
  read("friction", 0.99, p.friction);
  read("alpha", 0.99, p.alpha);
  read("mass", 0.99, p.mass);
  read("start_time", 1000.0, p.start_time);
  r.array("items", [&](const nlohmann::json& v, const std::string& path) {
    if (!v.is_string()) r.fail(path, "expected an item name, got " + json_io::ObjectReader::describe(v));
    p.items.push_back(v.get<std::string>());
  });
}

}  // namespace detail

// Reads a study from JSON. The base scene (`scene`: a file name relative to `base_dir`, or an object)
// is read and validated here, so that a bad scene fails before anything runs; the variants and the
// motions are checked by applying each to it (a bad patch names its key path in the study).
inline StudySpec parse_study_json(const nlohmann::json& j, const std::string& source, const std::string& base_dir = {});

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

// A scene of the study as a SceneSpec (reading errors name the study and what was applied).
inline SceneSpec study_scene(const StudySpec& s, const nlohmann::json& scene_json, const std::string& what) {
  SceneSpec spec = parse_scene_json(scene_json, s.source + " (" + what + ")");
  spec.base_dir = detail::study_scene_dir(s);
  return spec;
}

}  // namespace furniture_fem

#define FURNITURE_FEM_STUDY_INTERNAL
#include "detail/run_start_checks.hpp"
#undef FURNITURE_FEM_STUDY_INTERNAL

namespace furniture_fem {

inline StudySpec parse_study_json(const nlohmann::json& j, const std::string& source, const std::string& base_dir) {
  using json_io::ObjectReader;
  StudySpec s;
  s.source = source;
  s.base_dir = base_dir;
  const ObjectReader r(j, "", s.source);
  r.allow_only({"name", "seed", "scene", "intensity", "ground_motions", "perturbations", "realisations", "compare",
                "outcomes", "duration"});
  s.name = r.string("name", s.name);
  if (const auto why = detail::study_name_problem(s.name); !why.empty()) r.fail(r.path("name"), why);
  if (const auto seed = r.optional_integer("seed")) {
    r.require(*seed >= 0, "seed", "must not be negative");
    s.seed = static_cast<std::uint64_t>(*seed);
  }

  if (!r.has("scene")) r.fail(r.path("scene"), "required: a scene file (relative to the study file) or a scene object");
  if (r.raw("scene").is_string()) {
    const std::string file = r.raw("scene").get<std::string>();
    const std::string path = file.empty() || std::filesystem::path(file).is_absolute() || base_dir.empty()
                                 ? file
                                 : (std::filesystem::path(base_dir) / file).lexically_normal().string();
    try {
      s.scene = read_json_file(path, "scene");
    } catch (const InputError& e) {
      r.fail(r.path("scene"), std::string("the scene file cannot be used: ") + e.what());
    }
    s.scene_file = path;
  } else if (r.raw("scene").is_object()) {
    s.scene = r.raw("scene");
  } else {
    r.fail(r.path("scene"), "expected a file name or a scene object, got " + ObjectReader::describe(r.raw("scene")));
  }

  if (r.has("intensity")) detail::read_intensity(r.object("intensity"), s.intensity);
  // An empty suite would silently run the scene's own motion instead.
  if (r.has("ground_motions") && r.raw("ground_motions").is_array() && r.raw("ground_motions").empty())
    r.fail(r.path("ground_motions"), "is empty: list at least one {\"name\", \"ground_motion\"}, or leave the key out "
                                     "to run the scene's own ground_motion");
  r.array("ground_motions", [&](const nlohmann::json& v, const std::string& path) {
    const ObjectReader m(v, path, s.source);
    m.allow_only({"name", "ground_motion"});
    StudyMotion motion;
    // Required: the name labels the results and keys the realisations' random streams (a default by
    // position would change the draws when the suite is reordered).
    if (!m.has("name"))
      m.fail(m.path("name"), "required: a name for the motion, e.g. \"kobe_ns\" (it labels the results and keys "
                             "the realisations' random draws)");
    motion.name = m.string("name", "");
    if (const auto why = detail::study_name_problem(motion.name); !why.empty()) m.fail(m.path("name"), why);
    if (!m.has("ground_motion") || !m.raw("ground_motion").is_object())
      m.fail(m.path("ground_motion"), "required: a ground_motion object as a scene file takes it");
    motion.ground_motion = m.raw("ground_motion");
    for (const auto& other : s.motions)
      if (other.name == motion.name) m.fail(m.path("name"), "duplicate motion name \"" + motion.name + "\"");
    s.motions.push_back(std::move(motion));
  });
  if (r.has("perturbations")) detail::read_perturbations(r.object("perturbations"), s.perturb);
  if (const auto n = r.optional_integer("realisations")) {
    r.require(*n >= 1 && *n <= 1'000'000, "realisations", "must lie in [1, 1000000] (per level and motion)");
    s.realisations = static_cast<int>(*n);
  }
  r.array("compare", [&](const nlohmann::json& v, const std::string& path) {
    const ObjectReader c(v, path, s.source);
    c.allow_only({"name", "scene", "fidelity"});
    StudyVariant variant;
    variant.name = c.string("name", "variant_" + std::to_string(s.variants.size() + 1));
    if (const auto why = detail::study_name_problem(variant.name); !why.empty()) c.fail(c.path("name"), why);
    if (c.has("scene") && !c.raw("scene").is_object())
      c.fail(c.path("scene"), "expected a merge patch of the base scene, e.g. {\"contact\": {\"law\": \"stiff\"}}");
    if (c.has("scene")) variant.patch = c.raw("scene");
    variant.fidelity = c.string("fidelity", "");
    if (!variant.fidelity.empty() && variant.fidelity != "full" && variant.fidelity != "coarse" &&
        variant.fidelity != "rigid" && variant.fidelity != "auto")
      c.fail(c.path("fidelity"), "unknown fidelity \"" + variant.fidelity + "\"; expected one of: full, coarse, rigid, auto");
    for (const auto& other : s.variants)
      if (other.name == variant.name) c.fail(c.path("name"), "duplicate variant name \"" + variant.name + "\"");
    s.variants.push_back(std::move(variant));
  });
  if (r.has("outcomes")) {
    const ObjectReader o = r.object("outcomes");
    o.allow_only({"slide_threshold", "tilt_threshold_deg"});
    s.outcomes.slide_threshold = o.number("slide_threshold", s.outcomes.slide_threshold);
    o.positive("slide_threshold");
    s.outcomes.tilt_threshold_deg = o.number("tilt_threshold_deg", s.outcomes.tilt_threshold_deg);
    o.in_range("tilt_threshold_deg", 0.1, 89.0);
  }
  s.duration = r.optional_number("duration");
  r.positive("duration");
  if (s.num_runs() > detail::study_max_runs)
    r.fail(r.path("realisations"), "the study has " + std::to_string(s.num_runs()) + " runs (levels x motions x "
                                   "realisations x variants); at most " + std::to_string(detail::study_max_runs));

  // Every (variant, motion) scene must read and validate; the perturbations must name items it has
  // and apply to its motion. Checked here, before any run.
  for (int v = 0; v < s.num_variants(); ++v)
    for (int m = 0; m < s.num_motions(); ++m) {
      const std::string what = "variant '" + s.variant_name(v) + "', motion '" + s.motion_name(m) + "'";
      const SceneSpec scene = study_scene(s, detail::study_scene_json(s, v, m), what);
      validate(scene);
      for (std::size_t i = 0; i < s.perturb.items.size(); ++i) {
        bool found = false;
        for (const auto& it : scene.items) found = found || it.name == s.perturb.items[i];
        if (!found)
          r.fail("perturbations.items[" + std::to_string(i) + "]",
                 "no item named \"" + s.perturb.items[i] + "\" in the scene (" + what + ")");
      }
      const MotionSource src = scene.ground_motion.source;
      if (s.perturb.start_time > 0 && src != MotionSource::file)
        r.fail("perturbations.start_time", "applies to record files only (" + what + " has a " +
                                               (src == MotionSource::synthetic ? "synthetic" : "points") + " motion)");
      if (s.intensity.measure == IntensityMeasure::pgv && src != MotionSource::file)
        r.fail("intensity.measure", "\"pgv\" scales record files only (" + what + " has another source)");
      if (s.intensity.measure == IntensityMeasure::pga && src == MotionSource::points)
        r.fail("intensity.measure", "\"pga\" scales record files and synthetic motions, not \"points\" (" + what + ")");
    }
  // Then each scene as its runs will start, at every level: what a run would refuse fails here.
  detail::check_study_run_starts(s, r);
  detail::check_study_models(s, r);
  return s;
}

// Reads a study file (read_json_file's checks); relative paths in it (the scene file) are taken from its folder.
inline StudySpec parse_study(const std::string& path) {
  return parse_study_json(read_json_file(path, "study"), path, std::filesystem::path(path).parent_path().string());
}

// The study as JSON: parse_study_json(to_json(s)) gives the same study (the scene written inline).
inline nlohmann::json to_json(const StudySpec& s) {
  using nlohmann::json;
  json j = {{"name", s.name},
            {"seed", s.seed},
            {"scene", s.scene},
            {"intensity",
             {{"measure", json_io::enum_name(detail::measure_names, s.intensity.measure)}, {"levels", s.intensity.levels}}},
            {"perturbations",
             {{"x", s.perturb.x},
              {"y", s.perturb.y},
              {"yaw_deg", s.perturb.yaw_deg},
              {"friction", s.perturb.friction},
              {"alpha", s.perturb.alpha},
              {"mass", s.perturb.mass},
              {"start_time", s.perturb.start_time},
              {"items", s.perturb.items}}},
            {"realisations", s.realisations},
            {"outcomes", {{"slide_threshold", s.outcomes.slide_threshold}, {"tilt_threshold_deg", s.outcomes.tilt_threshold_deg}}}};
  json motions = json::array();
  for (const auto& m : s.motions) motions.push_back({{"name", m.name}, {"ground_motion", m.ground_motion}});
  if (!s.motions.empty()) j["ground_motions"] = motions;
  json variants = json::array();
  for (const auto& v : s.variants) {
    variants.push_back({{"name", v.name}, {"scene", v.patch}});
    if (!v.fidelity.empty()) variants.back()["fidelity"] = v.fidelity;
  }
  if (!s.variants.empty()) j["compare"] = variants;
  if (s.duration) j["duration"] = *s.duration;
  return j;
}

}  // namespace furniture_fem
