#pragma once
// Internal: the scene's "exits" (ExitSpec) read, written and checked, and the room their cross-sections
// are cut by (harm/exit_path.hpp, docs/harm/harm.md). Shared by the reader, the writer, validate() and
// the exit observers. Users include furniture_fem/scene/scene.hpp.
#ifndef FURNITURE_FEM_SCENE_INTERNAL
#error "furniture_fem/scene/detail/scene_exits.hpp is internal: include <furniture_fem/scene/scene.hpp>"
#endif
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "../../core/errors.hpp"
#include "../../harm/exit_path.hpp"
#include "../json_reader.hpp"
#include "../spec.hpp"

namespace furniture_fem::detail {

// The first problem of an exit, as (key, message), or none: the reader and validate() give SceneSpecs
// made in code the same checks. A path point off the table, a segment of zero length, a width or
// reach that is not positive.
inline std::optional<std::pair<std::string, std::string>> exit_problem(const ExitSpec& e, const SceneSpec& s) {
  using P = std::pair<std::string, std::string>;
  if (e.path.size() < 2)
    return P{"path", "needs two or more points [x, y] on the floor (got " + std::to_string(e.path.size()) + ")"};
  const double hx = 0.5 * s.table.size_x, hy = 0.5 * s.table.size_y;
  for (std::size_t i = 0; i < e.path.size(); ++i) {
    const Eigen::Vector2d& p = e.path[i];
    const std::string key = "path[" + std::to_string(i) + "]";
    const std::string at = "[" + fmt(p.x()) + ", " + fmt(p.y()) + "]";
    if (!(std::abs(p.x()) <= hx && std::abs(p.y()) <= hy))
      return P{key, "the point " + at + " is off the table (x within +-" + fmt(hx) + " m, y within +-" + fmt(hy) + " m)"};
    if (i > 0 && (p - e.path[i - 1]).norm() < 1e-9)
      return P{key, "the point " + at + " repeats the one before it: a segment of zero length"};
  }
  if (!(e.width > 0 && e.width <= scene_reach)) return P{"width", "must be positive (m; got " + fmt(e.width) + ")"};
  if (e.side_reach && !(*e.side_reach > 0 && *e.side_reach <= scene_reach))
    return P{"side_reach", "must be positive (m; got " + fmt(*e.side_reach) + ")"};
  return std::nullopt;
}

inline ExitSpec read_exit(const nlohmann::json& v, const std::string& path, const std::string& source, std::size_t index) {
  const json_io::ObjectReader o(v, path, source);
  o.allow_only({"name", "path", "width", "side_reach"}, "key of an exit");
  ExitSpec e;
  e.name = o.string("name", "exit_" + std::to_string(index + 1));
  if (!o.has("path")) o.fail(o.path("path"), "required: two or more points [x, y] on the floor (m)");
  o.array("path", [&](const nlohmann::json& p, const std::string& at) {
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      o.fail(at, "expected a point [x, y] (m), got " + json_io::ObjectReader::describe(p));
    e.path.emplace_back(p[0].get<double>(), p[1].get<double>());
  });
  e.width = o.number("width", e.width);
  if (o.has("side_reach")) e.side_reach = o.number("side_reach", 0);
  return e;
}

inline nlohmann::json exit_json(const ExitSpec& e) {
  nlohmann::json path = nlohmann::json::array();
  for (const auto& p : e.path) path.push_back({p.x(), p.y()});
  nlohmann::json j = {{"name", e.name}, {"path", path}, {"width", e.width}};
  if (e.side_reach) j["side_reach"] = *e.side_reach;
  return j;
}

// What bounds the exit's cross-sections: the table, every wall's trace on the floor, its side reach.
inline ExitRoom exit_room(const SceneSpec& s, const ExitSpec& e) {
  ExitRoom room;
  room.table_min = Vec2(-0.5 * s.table.size_x, -0.5 * s.table.size_y);
  room.table_max = -room.table_min;
  for (const WallSpec& w : s.walls) {
    const Vec3 n = w.normal.normalized();
    const Vec2 half = 0.5 * w.width * Vec2(-n.y(), n.x());
    const Vec2 centre(w.point.x(), w.point.y());
    room.walls.push_back({w.name, centre - half, centre + half});
  }
  room.side_reach = e.side_reach;
  return room;
}

}  // namespace furniture_fem::detail
