#pragma once
// furniture_fem/scene/exit_observers.hpp: what the run writes of its exits (harm/exit_path.hpp,
// docs/harm/harm.md "Exits"). Built-in observers of observers.hpp, only for a scene with exits.
//
//   ExitOutcomes  each exit's narrowest cross-section at every history row and at the end: when it first
//                 fell below the exit's width, where and by which item, the narrowest over the run, the
//                 end -> RunSummary::exits; the floor area the fallen items cover
//                 -> RunSummary::floor_covered_by_fallen_items (summary.json, the final print)
//   ExitHistory   exits.csv (plan.png and timeline.png: harm_figures.hpp)
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../figures/plot.hpp"
#include "../harm/exit_path.hpp"
#include "exit_outcome.hpp"
#include "observer.hpp"
#include "plan_view.hpp"
#include "row_history.hpp"

#define FURNITURE_FEM_SCENE_INTERNAL
#include "detail/scene_exits.hpp"
#undef FURNITURE_FEM_SCENE_INTERNAL

namespace furniture_fem {

// Every item's outline on the plan where its body is now.
inline std::vector<PlanObstacle> current_plan_obstacles(const RunView& run) {
  std::vector<PlanObstacle> out;
  for (const ItemInfo& it : run.items) out.push_back({it.name, plan_outline(current_item_box(run.sim, run.model, it))});
  return out;
}

// Each exit of the scene measured against the items where they are now.
inline std::vector<ExitMeasure> measure_exits(const RunView& run) {
  const std::vector<PlanObstacle> obstacles = current_plan_obstacles(run);
  std::vector<ExitMeasure> out;
  for (const ExitSpec& e : run.spec.exits) out.push_back(measure_exit(e.path, e.width, detail::exit_room(run.spec, e), obstacles));
  return out;
}

inline ExitSection exit_section(double t, const CrossSection& x) {
  return {t, x.clear_width, x.station.s, x.station.at.x(), x.station.at.y(), x.narrowed_by()};
}

class ExitOutcomes : public RunObserver {
 public:
  void begin(const RunView& run) override {
    tracked_.clear();
    for (const ExitSpec& e : run.spec.exits) tracked_.push_back({e.name, e.width, false, std::nullopt, {}, {}});
    track(run);
  }
  void after_step(const RunView& run, const StepInfo&) override {
    if (run.row_due()) track(run);
  }
  void end(const RunView& run, RunSummary& summary) override {
    const std::vector<ExitMeasure> m = track(run);
    for (std::size_t i = 0; i < m.size(); ++i) {
      tracked_[i].at_end = exit_section(run.sim.time(), m[i].at_narrowest());
      tracked_[i].blocked = tracked_[i].at_end.clear_width < tracked_[i].required_width;
    }
    summary.exits = tracked_;
    std::vector<std::vector<Vec2>> fallen;
    for (const PlanItemOutline& it : plan_item_outlines(run, summary.items))
      if (it.fallen) fallen.push_back(it.now);
    summary.floor_covered_by_fallen_items = union_area(fallen);
  }
  void save(StateWriter& w) override { w(tracked_.size()), save_outcomes(w); }
  void resume(const RunView&, StateReader& r) override {
    std::size_t n = 0;
    r(n);
    tracked_.resize(n);
    for (ExitOutcome& o : tracked_) {
      bool first = false;
      r(o.name, o.required_width, first, o.narrowest);
      if (first) o.first_blocked.emplace(), r(*o.first_blocked);
    }
  }

 private:
  std::vector<ExitOutcome> tracked_;
  void save_outcomes(StateWriter& w) const {
    for (const ExitOutcome& o : tracked_) {
      w(o.name, o.required_width, o.first_blocked.has_value(), o.narrowest);
      if (o.first_blocked) w(*o.first_blocked);
    }
  }
  std::vector<ExitMeasure> track(const RunView& run) {
    std::vector<ExitMeasure> m = measure_exits(run);
    for (std::size_t i = 0; i < m.size(); ++i) {
      const ExitSection now = exit_section(run.sim.time(), m[i].at_narrowest());
      ExitOutcome& o = tracked_[i];
      if (!o.first_blocked && now.clear_width < o.required_width) o.first_blocked = now;
      if (run.sim.steps() == 0 || now.clear_width < o.narrowest.clear_width) o.narrowest = now;
    }
    return m;
  }
};

// Each exit on the plan: its path (dashed), its required width as a band (blue), red over the stations
// whose clear width is below it; `now`: the exits measured (measure_exits), in the scene's order.
inline void add_exits_to_plan(LinePlot& p, const SceneSpec& spec, const std::vector<ExitMeasure>& now) {
  const RGB band{60, 120, 220}, blocked{220, 30, 30};
  bool band_named = false, blocked_named = false;  // each named once in the legend
  for (std::size_t i = 0; i < spec.exits.size(); ++i) {
    const ExitSpec& e = spec.exits[i];
    const double h = 0.5 * e.width;
    const auto& sec = now[i].sections;
    const auto red = [&](std::size_t k) { return sec[k].clear_width < e.width || sec[k + 1].clear_width < e.width; };
    // One polygon per run of station pairs of one colour along one segment (a corner starts a new run).
    for (std::size_t k = 0; k + 1 < sec.size();) {
      std::size_t last = k;
      while (last + 2 < sec.size() && sec[last + 1].station.normal == sec[k].station.normal &&
             sec[last + 2].station.normal == sec[k].station.normal && red(last + 1) == red(k))
        ++last;
      const PathStation &a = sec[k].station, &b = sec[last + 1].station;
      const bool is_red = red(k);
      bool& named = is_red ? blocked_named : band_named;
      if (a.normal == b.normal) {
        const std::vector<Vec2> quad = {a.at - h * a.normal, b.at - h * b.normal, b.at + h * b.normal, a.at + h * a.normal};
        p.add(detail::closed_series(quad, named ? "" : is_red ? "clear width below the exit's" : "the exit's width",
                                    is_red ? blocked : band, 0.5, is_red ? 0.6 : 0.2));
        named = true;
      }
      k = last + 1;
    }
    Series line;
    for (const Vec2& q : e.path) line.x.push_back(q.x()), line.y.push_back(q.y());
    line.label = "exit " + e.name + " (" + detail::fmt(e.width) + " m)";
    line.color = band;
    line.dashed = true;
    p.add(std::move(line));
  }
}

// exits.csv: t, then per exit <name>_clear_width (m, at its narrowest station) and <name>_s (m, that
// station's arc length along the path), at each history row.
class ExitHistory : public RowHistory {
 private:
  std::string file() const override { return "exits.csv"; }
  std::vector<std::string> columns(const RunView& run) const override {
    std::vector<std::string> cols{"t"};
    for (const ExitSpec& e : run.spec.exits)
      for (const char* c : {"_clear_width", "_s"}) cols.push_back(e.name + c);
    return cols;
  }
  void write_row(const RunView& run) override {
    std::vector<double> row{run.sim.time()};
    for (const ExitMeasure& m : measure_exits(run)) row.insert(row.end(), {m.at_narrowest().clear_width, m.at_narrowest().station.s});
    csv().row(row);
  }
};

}  // namespace furniture_fem
