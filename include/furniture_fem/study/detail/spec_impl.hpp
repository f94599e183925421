#pragma once
// Internal: the study file's reading and writing (study/spec.hpp's entry points), defined inline when the
// study is used header-only and once in the compiled study (src/study/study_spec.cpp).
#ifndef FURNITURE_FEM_STUDY_INTERNAL
#error "furniture_fem/study/detail/spec_impl.hpp is internal: include <furniture_fem/study/spec.hpp>"
#endif
#include <nlohmann/json.hpp>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>

#include "../../scene/json_reader.hpp"
#include "../../scene/reader.hpp"
#include "../../scene/validation.hpp"
#include "../spec.hpp"

#define FURNITURE_FEM_STUDY_INTERNAL
#include "measure_names.hpp"
#undef FURNITURE_FEM_STUDY_INTERNAL

namespace furniture_fem {

namespace detail {

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

FFEM_STUDY_ENTRY SceneSpec study_scene(const StudySpec& s, const nlohmann::json& scene_json, const std::string& what) {
  SceneSpec spec = parse_scene_json(scene_json, s.source + " (" + what + ")");
  spec.base_dir = detail::study_scene_dir(s);
  return spec;
}

}  // namespace furniture_fem

#define FURNITURE_FEM_STUDY_INTERNAL
#include "run_start_checks.hpp"
#undef FURNITURE_FEM_STUDY_INTERNAL

namespace furniture_fem {

FFEM_STUDY_ENTRY StudySpec parse_study_json(const nlohmann::json& j, const std::string& source, const std::string& base_dir) {
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

FFEM_STUDY_ENTRY StudySpec parse_study(const std::string& path) {
  return parse_study_json(read_json_file(path, "study"), path, std::filesystem::path(path).parent_path().string());
}

FFEM_STUDY_ENTRY nlohmann::json to_json(const StudySpec& s) {
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
