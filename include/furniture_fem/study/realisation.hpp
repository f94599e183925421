#pragma once
// furniture_fem/study/realisation.hpp: which values a realisation of a study gets, and its scene.
//
//   RealisationParameters realisation_parameters(study, index)     from the seed and the index alone
//   nlohmann::json realisation_scene_json(study, parameters, variant)  the scene it runs, as a file takes it
//
// Realisations are numbered level-major: index = (level * motions + motion) * realisations + replicate.
// The perturbations are drawn from streams keyed by (motion name, replicate, item name, factor), not
// by the level: replicate r of a motion is the same room at every intensity level, as in incremental dynamic
// analysis, so a fragility curve compares levels on the same rooms; and a variant runs the same room
// as every other variant (paired comparisons). Each factor has its own stream: turning one
// perturbation on or off leaves the others' values unchanged.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "random.hpp"
#include "spec.hpp"

#define FURNITURE_FEM_STUDY_INTERNAL
#include "detail/run_start_checks.hpp"  // how a level and a start shift set the ground motion
#undef FURNITURE_FEM_STUDY_INTERNAL

namespace furniture_fem {

struct ItemPerturbation {
  std::string item;
  double dx = 0, dy = 0, dyaw_deg = 0;                    // m, m, deg
  double friction_factor = 1, alpha_factor = 1, mass_factor = 1;
};

struct RealisationParameters {
  long index = 0;
  int level_index = 0, motion_index = 0, replicate = 0;
  double level = 1;          // the intensity level's value (the study's measure)
  double start_shift = 0;    // s: the record window starts this much later
  std::vector<ItemPerturbation> items;  // the perturbed items, in scene order
};

namespace detail {
// Stream keys of the factors (fixed: they decide every perturbed value of every study).
enum PerturbationFactor : std::uint64_t { f_x = 1, f_y, f_yaw, f_friction, f_alpha, f_mass, f_start };
inline constexpr std::uint64_t motion_wide = 0xffffffffULL;  // the item key of a draw that is not per item

// A stream key from a name (an item's, a motion's): the same name, the same stream, wherever it stands
// in its list, so adding or reordering motions or items leaves the others' values unchanged.
inline std::uint64_t name_key(const std::string& name) {
  std::uint64_t key = 0;
  for (unsigned char c : name) key = mix64(key ^ c);
  return key;
}

inline double symmetric_draw(const StudySpec& s, std::uint64_t motion, int replicate, std::uint64_t item,
                             std::uint64_t factor, double half_width) {
  if (!(half_width > 0)) return 0;
  RandomStream r(s.seed, {motion, std::uint64_t(replicate), item, factor});
  return r.uniform(-half_width, half_width);
}

inline std::vector<std::string> perturbed_items(const StudySpec& s) {
  if (!s.perturb.items.empty()) return s.perturb.items;
  std::vector<std::string> names;
  for (const auto& it : s.scene.value("items", nlohmann::json::array()))
    if (it.is_object() && it.contains("name") && it["name"].is_string()) names.push_back(it["name"].get<std::string>());
  return names;
}
}  // namespace detail

inline RealisationParameters realisation_parameters(const StudySpec& s, long index) {
  if (index < 0 || index >= s.num_realisations())
    throw std::out_of_range("realisation " + std::to_string(index) + " of study '" + s.name + "', which has " +
                            std::to_string(s.num_realisations()));
  RealisationParameters p;
  p.index = index;
  p.replicate = static_cast<int>(index % s.realisations);
  p.motion_index = static_cast<int>((index / s.realisations) % s.num_motions());
  p.level_index = static_cast<int>(index / (long(s.realisations) * s.num_motions()));
  p.level = s.intensity.levels[p.level_index];
  const std::uint64_t m = detail::name_key(s.motion_name(p.motion_index));
  const int r = p.replicate;
  if (s.perturb.start_time > 0) {
    RandomStream st(s.seed, {m, std::uint64_t(r), detail::motion_wide, detail::f_start});
    p.start_shift = st.uniform(0.0, s.perturb.start_time);
  }
  if (!s.perturb.any()) return p;
  const auto names = detail::perturbed_items(s);
  for (const auto& name : names) {
    const std::uint64_t key = detail::name_key(name);
    ItemPerturbation ip;
    ip.item = name;
    const auto draw = [&](detail::PerturbationFactor f, double half) { return detail::symmetric_draw(s, m, r, key, f, half); };
    ip.dx = draw(detail::f_x, s.perturb.x);
    ip.dy = draw(detail::f_y, s.perturb.y);
    ip.dyaw_deg = draw(detail::f_yaw, s.perturb.yaw_deg);
    ip.friction_factor = 1 + draw(detail::f_friction, s.perturb.friction);
    ip.alpha_factor = 1 + draw(detail::f_alpha, s.perturb.alpha);
    ip.mass_factor = 1 + draw(detail::f_mass, s.perturb.mass);
    p.items.push_back(ip);
  }
  return p;
}

namespace detail {
// A factor on an item parameter that may already be given: multiplies it.
inline void scale_param(nlohmann::json& item, const char* key, double factor, bool applies) {
  if (!applies) return;
  nlohmann::json& params = item["params"];
  if (!params.is_object()) params = nlohmann::json::object();
  params[key] = params.value(key, 1.0) * factor;
}
}  // namespace detail

// The scene realisation `p` runs under `variant`, as JSON (furniture_quake can run it by itself).
inline nlohmann::json realisation_scene_json(const StudySpec& s, const RealisationParameters& p, int variant) {
  nlohmann::json scene = detail::study_scene_json(s, variant, p.motion_index);
  detail::apply_intensity(s, p.level, scene["ground_motion"]);
  detail::shift_window(scene["ground_motion"], p.start_shift);
  for (const auto& ip : p.items)
    for (auto& item : scene["items"])
      if (item.value("name", "") == ip.item) {
        item["x"] = item.value("x", 0.0) + ip.dx;
        item["y"] = item.value("y", 0.0) + ip.dy;
        item["yaw_deg"] = item.value("yaw_deg", 0.0) + ip.dyaw_deg;
        detail::scale_param(item, "friction_scale", ip.friction_factor, s.perturb.friction > 0);
        detail::scale_param(item, "alpha_scale", ip.alpha_factor, s.perturb.alpha > 0);
        detail::scale_param(item, "mass_scale", ip.mass_factor, s.perturb.mass > 0);
      }
  scene["name"] = s.name + " realisation " + std::to_string(p.index) + " (" + s.variant_name(variant) + ")";
  return scene;
}

// The parameters as named columns (realisations.csv): the level, the motion, then each perturbed
// value that the study varies.
inline std::vector<std::pair<std::string, double>> parameter_columns(const StudySpec& s, const RealisationParameters& p) {
  std::vector<std::pair<std::string, double>> c{{"level", p.level}};
  if (s.perturb.start_time > 0) c.emplace_back("start_shift_s", p.start_shift);
  for (const auto& ip : p.items) {
    if (s.perturb.x > 0) c.emplace_back(ip.item + ".dx_m", ip.dx);
    if (s.perturb.y > 0) c.emplace_back(ip.item + ".dy_m", ip.dy);
    if (s.perturb.yaw_deg > 0) c.emplace_back(ip.item + ".dyaw_deg", ip.dyaw_deg);
    if (s.perturb.friction > 0) c.emplace_back(ip.item + ".friction_factor", ip.friction_factor);
    if (s.perturb.alpha > 0) c.emplace_back(ip.item + ".alpha_factor", ip.alpha_factor);
    if (s.perturb.mass > 0) c.emplace_back(ip.item + ".mass_factor", ip.mass_factor);
  }
  return c;
}

}  // namespace furniture_fem
