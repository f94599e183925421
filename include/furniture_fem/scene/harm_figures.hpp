#pragma once
// furniture_fem/scene/harm_figures.hpp: the figures of a scene with occupants or exits (docs/harm/):
//   plan.png      the room from above at the end (plan_view.hpp): the items, each exit's band (red where
//                 blocked), each occupant (a circle of its body, a dot of its head; red when struck
//                 seriously)
//   timeline.png  what happened when: a panel per occupant with each strike as a stem of the item's
//                 kinetic energy at its onset (the energy threshold dashed), and a panel of the exits'
//                 clear width over time against the widths they need
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "../figures/plot.hpp"
#include "exit_observers.hpp"
#include "observer.hpp"
#include "occupant_observers.hpp"
#include "plan_view.hpp"

namespace furniture_fem {

namespace detail {
// A circle as a closed series of 48 points.
inline Series circle_series(const Vec2& c, double r, std::string label, RGB colour, double width, double fill) {
  std::vector<Vec2> pts;
  for (int i = 0; i < 48; ++i) {
    const double a = 2 * std::numbers::pi * i / 48;
    pts.emplace_back(c.x() + r * std::cos(a), c.y() + r * std::sin(a));
  }
  return closed_series(pts, std::move(label), colour, width, fill);
}
}  // namespace detail

// Each occupant on the plan: its body's circle and its head's, filled red when it was struck seriously,
// orange when struck, blue when not.
inline void add_occupants_to_plan(LinePlot& p, const std::vector<Occupant>& people, const std::vector<OccupantOutcome>& outcomes) {
  for (std::size_t i = 0; i < people.size(); ++i) {
    const Occupant& o = people[i];
    const OccupantOutcome* out = i < outcomes.size() ? &outcomes[i] : nullptr;
    const bool serious = out && out->seriously_struck(), struck = out && !out->strikes.empty();
    const RGB colour = serious ? RGB{200, 30, 30} : struck ? RGB{230, 140, 20} : RGB{40, 90, 200};
    const std::string verdict = serious ? "struck seriously" : struck ? "struck" : "not struck";
    p.add(detail::circle_series(o.position, o.body_radius, o.name + " (" + verdict + ")", colour, 2.0, 0.25));
    p.add(detail::circle_series(o.position, o.head_radius, "", colour, 1.5, 0.6));
  }
}

namespace detail {
// exits.csv read back (its own writer's columns: t, then <exit>_clear_width, <exit>_s per exit): the
// times and each exit's clear width at them.
inline std::pair<std::vector<double>, std::vector<std::vector<double>>> read_exit_widths(const std::string& path, std::size_t exits) {
  std::pair<std::vector<double>, std::vector<std::vector<double>>> out;
  out.second.resize(exits);
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);  // the header
  while (std::getline(f, line)) {
    std::vector<double> v;
    std::size_t at = 0;
    while (at <= line.size()) {
      const std::size_t comma = std::min(line.find(',', at), line.size());
      v.push_back(std::strtod(line.c_str() + at, nullptr));
      at = comma + 1;
    }
    if (v.size() < 1 + 2 * exits) continue;
    out.first.push_back(v[0]);
    for (std::size_t e = 0; e < exits; ++e) out.second[e].push_back(v[1 + 2 * e]);
  }
  return out;
}
}  // namespace detail

// timeline.png: a panel per occupant (each strike a stem of the item's kinetic energy at its onset, the
// item and zone in the legend, the energy threshold dashed) and, with exits, a panel of their clear
// widths over time against the widths they need.
inline void draw_harm_timeline(const RunView& run, const RunSummary& summary, const std::string& path) {
  const int people = static_cast<int>(summary.occupants.size());
  const bool exits = !run.spec.exits.empty();
  const int panels = people + (exits ? 1 : 0);
  if (panels == 0) return;
  const double t_end = std::max(run.sim.time(), 1e-3);
  LinePlot p;
  p.title(run.spec.name + ": strikes and exits over time").xlabel("time (s)").panels(panels).xlim(0.0, t_end);
  for (int i = 0; i < people; ++i) {
    const OccupantOutcome& o = summary.occupants[i];
    p.panel_title(o.name + (o.strikes.empty() ? ": not struck" : o.seriously_struck() ? ": struck seriously" : ": struck"), i);
    p.ylabel("item's energy (J)", i);
    std::vector<std::string> named;
    for (const Strike& s : o.strikes) {
      const std::string key = s.item + " (" + std::string(to_string(s.zone)) + ")";
      const bool first = std::find(named.begin(), named.end(), key) == named.end();
      if (first) named.push_back(key);
      Series stem;
      stem.x = {s.time, s.time};
      stem.y = {0.0, s.kinetic_energy};
      stem.label = first ? key : "";
      stem.color = palette_color(static_cast<std::size_t>(std::find(named.begin(), named.end(), key) - named.begin()));
      stem.marker = 3.5;
      p.add(std::move(stem), i);
    }
    const double e = run.spec.strike_thresholds.energy;
    p.add_reference({0.0, t_end}, {e, e}, "energy threshold " + detail::fmt(e) + " J", i);
  }
  if (exits) {
    const int k = people;
    const auto [t, widths] = detail::read_exit_widths(run.out_dir + "/exits.csv", run.spec.exits.size());
    p.panel_title("exits: clear width at the narrowest station", k).ylabel("m", k);
    for (std::size_t e = 0; e < run.spec.exits.size(); ++e) {
      const ExitSpec& x = run.spec.exits[e];
      p.add(t, widths[e], x.name, k);
      p.add_reference({0.0, t_end}, {x.width, x.width}, x.name + " needs " + detail::fmt(x.width) + " m", k);
    }
  }
  p.save_png(path, 1000, 250 + 220 * panels);
}

// plan.png and timeline.png, at the end, for a scene with occupants or exits (after ExitHistory wrote
// exits.csv and the outcomes filled the summary).
class HarmFigures : public RunObserver {
 public:
  void end(const RunView& run, RunSummary& summary) override {
    char title[200];
    std::snprintf(title, sizeof title, "%s: plan at t = %.2f s (grey: initial; filled: fell)", run.spec.name.c_str(), run.sim.time());
    LinePlot p = plan_view(run.spec, plan_item_outlines(run, summary.items), title);
    if (!run.spec.exits.empty()) add_exits_to_plan(p, run.spec, measure_exits(run));
    add_occupants_to_plan(p, run.spec.occupants, summary.occupants);
    p.save_png(run.out_dir + "/plan.png", 1000, plan_height(run.spec));
    draw_harm_timeline(run, summary, run.out_dir + "/timeline.png");
  }
};

}  // namespace furniture_fem
