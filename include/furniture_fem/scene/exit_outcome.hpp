#pragma once
// furniture_fem/scene/exit_outcome.hpp: an exit's outcome (RunSummary::exits; scene/exit_observers.hpp) as
// summary.json and a study's run records write it, and in words for the final print.
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "run_summary.hpp"

namespace furniture_fem {

// One exit's outcome as summary.json and a study's run records write it (one set of keys), and back.
inline nlohmann::json exit_section_json(const ExitSection& s) {
  return {{"t_s", s.t}, {"clear_width_m", s.clear_width}, {"s_m", s.s}, {"x_m", s.x}, {"y_m", s.y}, {"by", s.by}};
}
inline ExitSection exit_section_from_json(const nlohmann::json& j) {
  return {j.at("t_s").get<double>(),  j.at("clear_width_m").get<double>(), j.at("s_m").get<double>(),
          j.at("x_m").get<double>(),  j.at("y_m").get<double>(),           j.at("by").get<std::vector<std::string>>()};
}
inline nlohmann::json exit_outcome_json(const ExitOutcome& o) {
  return {{"name", o.name},
          {"required_width_m", o.required_width},
          {"blocked", o.blocked},
          {"first_blocked_at_s", o.first_blocked ? nlohmann::json(o.first_blocked->t) : nlohmann::json()},
          {"first_blocked", o.first_blocked ? exit_section_json(*o.first_blocked) : nlohmann::json()},
          {"narrowest", exit_section_json(o.narrowest)},
          {"at_end", exit_section_json(o.at_end)}};
}
inline ExitOutcome exit_outcome_from_json(const nlohmann::json& j) {
  ExitOutcome o;
  o.name = j.at("name").get<std::string>();
  o.required_width = j.at("required_width_m").get<double>();
  o.blocked = j.at("blocked").get<bool>();
  if (!j.at("first_blocked").is_null()) o.first_blocked = exit_section_from_json(j.at("first_blocked"));
  o.narrowest = exit_section_from_json(j.at("narrowest"));
  o.at_end = exit_section_from_json(j.at("at_end"));
  return o;
}
inline nlohmann::json exit_outcomes_json(const std::vector<ExitOutcome>& list) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& o : list) out.push_back(exit_outcome_json(o));
  return out;
}

// "exit corridor blocked at 4.60 s by tall_cabinet; clear width 0.31 m at x = 1.20 m, y = 0.40 m" (the end's
// narrowest section), or "exit corridor clear: 0.92 m at its narrowest ...": the final print's line.
inline std::string exit_outcome_text(const ExitOutcome& o) {
  const auto by = [](const ExitSection& s) {
    std::string names;
    for (const auto& n : s.by) names += (names.empty() ? "" : " and ") + n;
    return names.empty() ? std::string("the room") : names;
  };
  char where[160];
  std::snprintf(where, sizeof where, "clear width %.2f m (needs %.2f m) at x = %.2f m, y = %.2f m", o.at_end.clear_width,
                o.required_width, o.at_end.x, o.at_end.y);
  std::string text = "exit " + o.name;
  if (o.blocked) {
    char at[48];
    std::snprintf(at, sizeof at, "%.2f", o.first_blocked->t);
    text += " blocked at " + std::string(at) + " s by " + by(*o.first_blocked) + "; at the end " + where + ", by " + by(o.at_end);
  } else {
    text += " clear at the end: " + std::string(where);
    if (o.first_blocked) {
      char at[48];
      std::snprintf(at, sizeof at, "%.2f", o.first_blocked->t);
      text += " (blocked for a while from " + std::string(at) + " s by " + by(*o.first_blocked) + ")";
    }
  }
  return text;
}

}  // namespace furniture_fem
