#pragma once
// furniture_fem/scene/occupant_observers.hpp: what the run records of its occupants (harm/,
// docs/harm/occupants.md). A built-in observer of observers.hpp, only for a scene with occupants.
//
//   OccupantStrikes   every item's box against every occupant's head and body after each step (or, for a
//                     person standing as an obstacle, the contact force each zone carries): each
//                     strike with its measures and verdict, and the items in contact with someone at the end
//                     -> RunSummary::occupants (summary.json, the final print), strikes.csv
#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../core/errors.hpp"
#include "../harm/strike.hpp"
#include "observer.hpp"

namespace furniture_fem {

// One strike as summary.json and strikes.csv write it (one set of keys).
inline nlohmann::json strike_json(const Strike& s) {
  return {{"item", s.item},
          {"zone", std::string(to_string(s.zone))},
          {"time_s", s.time},
          {"duration_s", s.duration},
          {"relative_speed_m_s", s.relative_speed},
          {"kinetic_energy_j", s.kinetic_energy},
          {"peak_force_n", s.peak_force},
          {"impulse_n_s", s.impulse},
          {"hic15", s.hic15},
          {"exceeded", s.exceeded}};
}
inline Strike strike_from_json(const std::string& occupant, const nlohmann::json& j) {
  Strike s;
  s.occupant = occupant;
  s.item = j.at("item").get<std::string>();
  s.zone = j.at("zone").get<std::string>() == "head" ? OccupantZone::head : OccupantZone::body;
  s.time = j.at("time_s").get<double>();
  s.duration = j.at("duration_s").get<double>();
  s.relative_speed = j.at("relative_speed_m_s").get<double>();
  s.kinetic_energy = j.at("kinetic_energy_j").get<double>();
  s.peak_force = j.at("peak_force_n").get<double>();
  s.impulse = j.at("impulse_n_s").get<double>();
  s.hic15 = j.at("hic15").get<double>();
  s.exceeded = j.at("exceeded").get<std::vector<std::string>>();
  return s;
}
// Each occupant's outcome as summary.json and a study's run records write it (one set of keys), and back.
inline nlohmann::json occupant_outcomes_json(const std::vector<OccupantOutcome>& list) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& o : list) {
    nlohmann::json strikes = nlohmann::json::array();
    for (const Strike& s : o.strikes) strikes.push_back(strike_json(s));
    out.push_back({{"name", o.name}, {"struck", !o.strikes.empty()}, {"seriously", o.seriously_struck()},
                   {"strikes", strikes}, {"in_contact_at_end", o.in_contact_at_end}});
  }
  return out;
}
inline std::vector<OccupantOutcome> occupant_outcomes_from_json(const nlohmann::json& list) {
  std::vector<OccupantOutcome> out;
  for (const auto& j : list) {
    OccupantOutcome o;
    o.name = j.at("name").get<std::string>();
    for (const auto& s : j.at("strikes")) o.strikes.push_back(strike_from_json(o.name, s));
    o.in_contact_at_end = j.at("in_contact_at_end").get<std::vector<std::string>>();
    out.push_back(std::move(o));
  }
  return out;
}

class OccupantStrikes : public RunObserver {
 public:
  void begin(const RunView& run) override {
    corner_nodes_.clear();
    for (const ItemInfo& item : run.items) corner_nodes_.push_back(box_corner_nodes(run.model, item));
    watches_.clear();
    for (const Occupant& o : run.spec.occupants)
      for (std::size_t i = 0; i < run.items.size(); ++i)
        for (OccupantZone z : {OccupantZone::head, OccupantZone::body})
          watches_.push_back({o.name, i, o.obstacle, StrikeWatch(o, z, run.items[i].name, run.spec.strike_thresholds)});
    item_of_body_.assign(run.model.num_bodies(), -1);
    for (std::size_t i = 0; i < run.items.size(); ++i) item_of_body_[run.items[i].body] = static_cast<int>(i);
    observe(run);
  }
  void after_step(const RunView& run, const StepInfo&) override { observe(run); }
  void end(const RunView& run, RunSummary& summary) override {
    for (Watch& w : watches_)
      if (auto s = w.watch.finish()) strikes_.push_back(*s);
    // By onset (a head's strike lasts milliseconds, a body's tens: they end in another order).
    std::stable_sort(strikes_.begin(), strikes_.end(), [](const Strike& a, const Strike& b) { return a.time < b.time; });
    summary.occupants.clear();
    for (const Occupant& o : run.spec.occupants) {
      OccupantOutcome out;
      out.name = o.name;
      for (const Strike& s : strikes_)
        if (s.occupant == o.name) out.strikes.push_back(s);
      for (const Watch& w : watches_)
        if (w.occupant == o.name && w.watch.touching() &&
            std::find(out.in_contact_at_end.begin(), out.in_contact_at_end.end(), run.items[w.item].name) == out.in_contact_at_end.end())
          out.in_contact_at_end.push_back(run.items[w.item].name);
      summary.occupants.push_back(out);
    }
    if (!run.out_dir.empty()) write_csv(run.out_dir + "/strikes.csv");
  }
  void save(StateWriter& w) override {
    w(strikes_);
    for (const Watch& x : watches_) w(x.watch);
  }
  void resume(const RunView& run, StateReader& r) override {
    begin(run);
    r(strikes_);
    for (Watch& x : watches_) r(x.watch);
  }

 private:
  struct Watch {
    std::string occupant;
    std::size_t item;
    bool obstacle;  // the occupant stands as a rigid obstacle: strikes are its contact forces
    StrikeWatch watch;
  };
  std::vector<int> item_of_body_;
  std::vector<Watch> watches_;
  std::vector<Strike> strikes_;  // finished (sorted by onset at the end)

  // Each item's box once, each watch's intrusion once, the item's kinetic energy only when it is near
  // someone (within reach_ of a zone: no item moves that far in a step), then every watch.
  void observe(const RunView& run) {
    std::vector<OrientedBox> boxes;
    for (std::size_t i = 0; i < run.items.size(); ++i) boxes.push_back(box_now(run, run.items[i], corner_nodes_[i]));
    std::vector<double> depth(watches_.size());
    std::vector<char> near(run.items.size(), 0);
    for (std::size_t k = 0; k < watches_.size(); ++k) {
      depth[k] = watches_[k].watch.intrusion_of(boxes[watches_[k].item]);
      if (depth[k] > -reach_) near[watches_[k].item] = 1;
    }
    std::vector<double> energies(run.items.size(), 0.0);
    for (std::size_t i = 0; i < run.items.size(); ++i)
      if (near[i])
        for (int n : run.model.body(run.items[i].body).nodes) energies[i] += run.sim.kinetic_energy(n);
    const std::vector<double> pushed = capsule_forces(run);
    for (std::size_t k = 0; k < watches_.size(); ++k) {
      Watch& w = watches_[k];
      const double t = run.sim.time(), ke = energies[w.item];
      if (auto s = w.obstacle ? w.watch.observe_contact(t, depth[k], ke, pushed[k]) : w.watch.observe(t, depth[k], ke))
        strikes_.push_back(*s);
    }
  }
  // Per watch, the contact force its zone carries from its item (N; 0 for a sensor's): the pair forces of
  // the occupants' capsules (occupant_capsule: 2 j for occupant j's head, 2 j + 1 its body), in the
  // watches' order (occupant, item, head then body).
  std::vector<double> capsule_forces(const RunView& run) const {
    std::vector<double> out(watches_.size(), 0.0);
    const std::size_t items = run.items.size();
    for (const PairForce& pf : run.sim.pair_forces()) {
      if (!PairForce::is_capsule(pf.body_b) || pf.body_a < 0 || pf.body_a >= static_cast<int>(item_of_body_.size()) ||
          item_of_body_[pf.body_a] < 0)
        continue;
      const int k = PairForce::capsule_index(pf.body_b);
      const std::size_t j = static_cast<std::size_t>(k / 2), i = static_cast<std::size_t>(item_of_body_[pf.body_a]);
      out[(j * items + i) * 2 + static_cast<std::size_t>(k % 2)] += pf.force_on_a.norm();
    }
    return out;
  }
  static constexpr double reach_ = 0.5;  // m
  std::vector<std::vector<int>> corner_nodes_;  // per item, its nodes nearest its box's corners

  // The item's nodes nearest its box's eight corners (distinct): its box follows their best rigid motion.
  // Exact for a rigid item, the corners' fit for a flexible one; all its nodes (current_item_box) took
  // three quarters of a rigid room's run time with two people in it.
  static std::vector<int> box_corner_nodes(const Model& model, const ItemInfo& item) {
    std::vector<int> nodes;
    for (const Vec3& corner : placed_box(item).corners()) {
      const int n = nearest_node(model, item.body, corner);
      if (std::find(nodes.begin(), nodes.end(), n) == nodes.end()) nodes.push_back(n);
    }
    return nodes;
  }
  static OrientedBox box_now(const RunView& run, const ItemInfo& item, const std::vector<int>& nodes) {
    if (nodes.size() < 3) return current_item_box(run.sim, run.model, item);
    Vec3 Xc = Vec3::Zero(), xc = Vec3::Zero();
    for (int n : nodes) Xc += run.model.node(n).X, xc += run.sim.position(n);
    Xc /= double(nodes.size()), xc /= double(nodes.size());
    const Mat3 Q = detail::best_rotation(
        static_cast<int>(nodes.size()),
        [&](int i) { return std::pair<Vec3, Vec3>(run.model.node(nodes[i]).X, run.sim.position(nodes[i])); }, Xc, xc);
    return item_box(item, Q, Xc, xc);
  }
  void write_csv(const std::string& path) const {
    std::ofstream f(path);
    if (!f) throw OutputError("cannot write " + path);
    f.precision(9);
    f << "occupant,zone,item,time_s,duration_s,relative_speed_m_s,kinetic_energy_j,peak_force_n,impulse_n_s,hic15,exceeded\n";
    for (const Strike& s : strikes_) {
      f << s.occupant << ',' << to_string(s.zone) << ',' << s.item << ',' << s.time << ',' << s.duration << ','
        << s.relative_speed << ',' << s.kinetic_energy << ',' << s.peak_force << ',' << s.impulse << ',' << s.hic15 << ',';
      for (std::size_t i = 0; i < s.exceeded.size(); ++i) f << (i ? ";" : "") << s.exceeded[i];
      f << '\n';
    }
  }
};

}  // namespace furniture_fem
