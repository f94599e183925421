#pragma once
// furniture_fem/scene/plan_view.hpp: the room seen from above (plan.png; docs/io/output.md): the table's
// outline, the walls, every item's outline at the start (light grey) and now (its colour, filled when it
// fell). plan_view() returns the figure unsaved: each layer (exits: exit_observers.hpp) adds its series.
#include <algorithm>
#include <string>
#include <vector>

#include "../figures/plot.hpp"
#include "../harm/item_box.hpp"
#include "observer.hpp"

namespace furniture_fem {

struct PlanItemOutline {
  std::string name;
  std::vector<Vec2> start, now;  // plan outlines, counter-clockwise (harm/item_box.hpp)
  RGB colour;
  bool fallen = false;           // filled
};

// Every item's outline as placed and where its body is now; fallen: its final state (RunSummary::items)
// is "fell" or "overturned".
inline std::vector<PlanItemOutline> plan_item_outlines(const RunView& run, const std::vector<ItemFinalState>& states) {
  std::vector<PlanItemOutline> out;
  for (const ItemInfo& it : run.items) {
    const auto s = std::find_if(states.begin(), states.end(), [&](const ItemFinalState& f) { return f.name == it.name; });
    const bool fallen = s != states.end() && (s->state == "fell" || s->state == "overturned");
    out.push_back({it.name, plan_outline(placed_box(it)), plan_outline(current_item_box(run.sim, run.model, it)),
                   palette_color(static_cast<std::size_t>(it.body)), fallen});
  }
  return out;
}

namespace detail {
// A closed polygon's points as a series (the first repeated at the end).
inline Series closed_series(const std::vector<Vec2>& pts, std::string label, RGB colour, double width, double fill = 0) {
  Series s;
  for (std::size_t i = 0; i <= pts.size() && !pts.empty(); ++i) {
    s.x.push_back(pts[i % pts.size()].x());
    s.y.push_back(pts[i % pts.size()].y());
  }
  s.label = std::move(label);
  s.color = colour;
  s.width = width;
  s.fill = fill;
  return s;
}
}  // namespace detail

// The plan at `title`: axes in m, the table plus 0.3 m, and every outline that reaches beyond it.
inline LinePlot plan_view(const SceneSpec& spec, const std::vector<PlanItemOutline>& items, const std::string& title) {
  const double hx = 0.5 * spec.table.size_x, hy = 0.5 * spec.table.size_y;
  Vec2 lo(-hx, -hy), hi(hx, hy);
  for (const auto& it : items)
    for (const Vec2& p : it.now) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  lo.array() -= 0.3, hi.array() += 0.3;
  LinePlot p;
  p.title(title).xlabel("x (m)").ylabel("y (m)").xlim(lo.x(), hi.x()).ylim(lo.y(), hi.y());
  p.add(detail::closed_series({Vec2(-hx, -hy), Vec2(hx, -hy), Vec2(hx, hy), Vec2(-hx, hy)}, "table", colors::black, 1.0));
  for (const WallSpec& w : spec.walls) {
    const Vec3 n = w.normal.normalized();
    const Vec2 c(w.point.x(), w.point.y()), half = 0.5 * w.width * Vec2(-n.y(), n.x());
    Series s;
    s.x = {c.x() - half.x(), c.x() + half.x()};
    s.y = {c.y() - half.y(), c.y() + half.y()};
    s.color = RGB{90, 90, 90};
    s.width = 4.0;
    s.label = &w == &spec.walls.front() ? "walls" : "";
    p.add(std::move(s));
  }
  for (const auto& it : items) p.add(detail::closed_series(it.start, "", RGB{195, 195, 195}, 1.5));
  for (const auto& it : items)
    p.add(detail::closed_series(it.now, it.name + (it.fallen ? " (fell)" : ""), it.colour, 2.0, it.fallen ? 0.45 : 0.0));
  return p;
}

// The size plan.png is saved at: 1000 px wide, as tall as the plan's aspect asks (within 500 to 1400).
inline int plan_height(const SceneSpec& spec) {
  return std::clamp(static_cast<int>(100 + 900 * spec.table.size_y / spec.table.size_x), 500, 1400);
}

}  // namespace furniture_fem
