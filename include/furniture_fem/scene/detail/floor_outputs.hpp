#pragma once
// Internal: what the outputs add when the table is a building's storey (ground_motion.building): the
// ground's motion beside the table's in input_motion.csv and input_motion.png, and the response
// spectra of both in input_spectra.png. Users include furniture_fem/scene/scene.hpp.
#ifndef FURNITURE_FEM_SCENE_INTERNAL
#error "furniture_fem/scene/detail/floor_outputs.hpp is internal: include <furniture_fem/scene/scene.hpp>"
#endif
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "../../excitation/spectrum.hpp"
#include "../../figures/plot.hpp"
#include "../scene_motion.hpp"
#include "../spec.hpp"

namespace furniture_fem::detail {

// The ground under the table's storey (scaled as the scene says); none without a building.
inline std::optional<TableMotion> ground_under_table(const SceneSpec& s) {
  if (!s.ground_motion.building) return std::nullopt;
  return scene_ground_motion(s);
}

// input_motion.csv's columns for the ground, after the table's.
inline std::vector<std::string> ground_columns() {
  return {"ground_ax", "ground_ay", "ground_az", "ground_vx", "ground_vy",
          "ground_vz", "ground_dx", "ground_dy", "ground_dz"};
}

// The horizontal components a motion has: X, and Y in 3-D.
inline std::vector<std::pair<const Record*, std::string>> horizontal(const TableMotion& m) {
  std::vector<std::pair<const Record*, std::string>> out{{&m.x, "X"}};
  if (m.has_y) out.emplace_back(&m.y, "Y");
  return out;
}

// A record's samples up to t_end (s), as (times, accelerations), for plotting it beside the run's rows.
inline std::pair<std::vector<double>, std::vector<double>> samples_until(const Record& r, double t_end) {
  std::pair<std::vector<double>, std::vector<double>> out;
  for (std::size_t i = 0; i < r.size() && r.time(i) <= t_end; ++i) {
    out.first.push_back(r.time(i));
    out.second.push_back(r.acc[i]);
  }
  return out;
}

// input_spectra.png: the 5 % absolute-acceleration response spectra of the ground and of the table's
// floor, each horizontal component: what the building makes of the record at each period.
inline void draw_floor_spectra(const SceneSpec& s, const TableMotion& ground, const TableMotion& floor,
                               const std::string& path) {
  const BuildingSpec& b = *s.ground_motion.building;
  const std::vector<double> periods = log_periods(0.05, 10.0, 80);
  LinePlot p;
  p.title("Response spectra (5 %): ground and floor " + std::to_string(b.storey) + " of " + std::to_string(b.floors()))
      .xlabel("period (s)")
      .log_x();
  p.ylabel("absolute acceleration (m/s^2)");
  for (const auto& [motion, who] : {std::pair{&ground, std::string("ground")}, std::pair{&floor, std::string("floor")}})
    for (const auto& [rec, axis] : horizontal(*motion))
      p.add(periods, response_spectrum(*rec, periods, 0.05).sa, who + " " + axis);
  p.save_png(path, 1000, 600);
}

}  // namespace furniture_fem::detail
