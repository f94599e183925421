#pragma once
// furniture_fem/harm/strike.hpp: an item striking an occupant (docs/harm/occupants.md, "Strikes"), and the
// verdict on it against stated thresholds.
//
//   Strike            who, what, when, how fast, with what energy, and the impact form's measures
//   StrikeThresholds  the thresholds and where they come from
//   strike_sentence   a strike in words, for a final print
//   StrikeWatch       one occupant's zone against one item over a run: finds each strike's onset
//                     between two steps, drives the zone's impact form through it, closes it
#include <cstdio>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "impact_form.hpp"
#include "occupant.hpp"

namespace furniture_fem {

struct Strike {
  std::string occupant, item;
  OccupantZone zone = OccupantZone::head;
  double time = 0;              // s, the onset (interpolated between the run's steps)
  double duration = 0;          // s, onset to the form's separation
  double relative_speed = 0;    // m/s, the item's intrusion rate at the onset (the floor is the occupant's frame)
  double kinetic_energy = 0;    // J, the whole item's at the onset
  double peak_force = 0;        // N, on the zone's impact form
  double impulse = 0;           // N s, given to the form
  double hic15 = 0;             // the head form's HIC15 (head strikes; 0 for the body)
  std::vector<std::string> exceeded;  // the thresholds it reached, by name ("hic15", "head_force", "energy")
  bool serious() const { return !exceeded.empty(); }

  template <class Self, class Archive>
    requires std::is_same_v<std::remove_const_t<Self>, Strike>
  friend void transfer_state(Self& s, Archive& ar) {
    ar(s.occupant, s.item, s.zone, s.time, s.duration, s.relative_speed, s.kinetic_energy, s.peak_force, s.impulse,
       s.hic15, s.exceeded);
  }
};

// The thresholds a strike is judged against (docs/harm/occupants.md gives the sources and what each means).
struct StrikeThresholds {
  double hic15 = 700.0;       // 49 CFR 571.208 S6.2(b): HIC15 at most 700 (about a 5 % risk of AIS 4+, Mertz 1997)
  double head_force = 4500.0; // N: the lowest skull fracture load of Yoganandan et al. 1995 (4.5 to 14.1 kN)
  double energy = 79.0;       // J: the DDESB's hazardous-fragment energy, 58 ft-lbf (TP-12), head or body
};

// The names of the thresholds a strike reaches.
inline std::vector<std::string> exceeded_thresholds(const Strike& s, const StrikeThresholds& t) {
  std::vector<std::string> out;
  if (s.zone == OccupantZone::head && s.hic15 >= t.hic15) out.push_back("hic15");
  if (s.zone == OccupantZone::head && s.peak_force >= t.head_force) out.push_back("head_force");
  if (s.kinetic_energy >= t.energy) out.push_back("energy");
  return out;
}

// A sentence for the final print: "struck on the head by tall_cabinet at 4.600 s (3.13 m/s, 98.1 J,
// 6.64 kN, HIC15 812: above hic15, head_force, energy)".
inline std::string strike_sentence(const Strike& s) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "struck on the %s by %s at %.3f s (%.2f m/s, %.1f J, %.2f kN", std::string(to_string(s.zone)).c_str(),
                s.item.c_str(), s.time, s.relative_speed, s.kinetic_energy, s.peak_force / 1000.0);
  std::string text = buf;
  if (s.zone == OccupantZone::head) {
    std::snprintf(buf, sizeof buf, ", HIC15 %.0f", s.hic15);
    text += buf;
  }
  if (s.exceeded.empty()) return text + ": below every threshold)";
  text += ": above ";
  for (std::size_t i = 0; i < s.exceeded.size(); ++i) text += (i ? ", " : "") + s.exceeded[i];
  return text + ")";
}

// One zone of one occupant against one item: call observe() after every step with the item's box and
// kinetic energy; finished strikes are returned by it as they end. A strike lasting longer than
// `longest` (the form never separated: the item keeps pushing) is closed there.
//
// An item still in the zone when its strike ends (a cabinet leaning on the person) strikes again only
// once it has slowed below `rearm_speed` (it rests or leans there) and then goes deeper than it has
// been since, faster than that: the person is taken to stand against it at that depth (a fresh form at
// rest there). An item passing through at speed is one strike; rocking against a person at the same
// depth is one; a leaning cabinet that then falls through the person is a second one, at its falling
// speed (the sensor does not stop it: without the second strike it was counted at its leaning speed).
class StrikeWatch {
 public:
  StrikeWatch(const Occupant& o, OccupantZone z, std::string item, StrikeThresholds t = {})
      : occupant_(o), zone_(z), item_(std::move(item)), thresholds_(t) {}

  std::optional<Strike> observe(double t, const OrientedBox& box, double item_kinetic_energy) {
    return observe(t, intrusion_of(box), item_kinetic_energy);
  }
  // The same with the item's intrusion into the zone already measured (intrusion_of).
  std::optional<Strike> observe(double t, double d, double item_kinetic_energy) {
    std::optional<Strike> done;
    const double rate = t > t_prev_ ? (d - d_prev_) / (t - t_prev_) : 0.0;
    if (form_) {
      form_->advance(d_prev_ - base_, d - base_, t - t_prev_);
      if (form_->separated(rate) || t - strike_.time > longest) done = close(), armed_at_ = std::max(0.0, d), armed_ = false;
    } else if (armed_ && d > armed_at_ && d_prev_ <= armed_at_ && t_prev_ >= 0 && t > t_prev_ &&
               (armed_at_ == 0 || rate >= rearm_speed)) {
      open(t, d, item_kinetic_energy);
    } else if (d <= 0) {
      armed_at_ = 0, armed_ = true;  // out of the zone: armed at its surface again
    } else {
      armed_at_ = std::max(armed_at_, d);
      armed_ = armed_ || rate < rearm_speed;
    }
    d_prev_ = d, t_prev_ = t, ke_prev_ = item_kinetic_energy;
    return done;
  }
  // A person standing as a rigid obstacle (Occupant::obstacle): the strike is the contact force F (N)
  // the item carries against the zone this step, with its intrusion d and energy as for observe(). It
  // opens when the force appears (its onset, speed and energy half a step before this one: the contact
  // began between the steps), at the item's first contact or at a later one while it approaches at
  // rearm_speed or faster (a resting contact lost for a step and found again is not a new strike); it
  // closes when the force is gone, or after `longest` (then not again before the force is gone).
  std::optional<Strike> observe_contact(double t, double d, double item_kinetic_energy, double F) {
    std::optional<Strike> done;
    const double rate = t > t_prev_ ? (d - d_prev_) / (t - t_prev_) : 0.0;
    if (pushed_) {
      if (F > 0 && t - strike_.time <= longest) {
        pushed_->add(t - strike_.time, F);
      } else {
        if (!(F > 0)) pushed_->add(t - strike_.time, 0.0);  // gone between the steps, linearly
        done = close(), armed_ = !(F > 0);
      }
    } else if (F > 0 && armed_ && t_prev_ > 0 && t > t_prev_ && (!struck_ || rate >= rearm_speed)) {
      begin_strike(0.5, t, d, item_kinetic_energy);  // the contact began between the steps
      pushed_.emplace(occupant_.form(zone_));
      pushed_->add(t - strike_.time, F);
      struck_ = true;
    } else {
      // Touching at the start is no strike: the contact forces are known from the first step on (at t =
      // 0 none has been evaluated), so a force at the first step was there from the start.
      armed_ = t_prev_ > 0 ? armed_ || !(F > 0) : !(F > 0);
    }
    d_prev_ = d, t_prev_ = t, ke_prev_ = item_kinetic_energy, f_prev_ = F;
    return done;
  }
  // The strike under way when the run ends, closed there; none if there is none.
  std::optional<Strike> finish() { return form_ || pushed_ ? std::optional<Strike>(close()) : std::nullopt; }
  double intrusion_of(const OrientedBox& box) const { return zone_intrusion(occupant_, zone_, box); }
  // The item is in the zone after the last step (as an obstacle: pushes on it).
  bool touching() const { return occupant_.obstacle ? f_prev_ > 0 : d_prev_ > 0; }
  double intrusion() const { return d_prev_; }   // m

  static constexpr double longest = 0.5;       // s
  static constexpr double rearm_speed = 0.05;  // m/s: slower, an item in the zone creeps, it does not strike

  // Checkpoints: the last step's intrusion and energy, and the strike under way with its form.
  template <class Self, class Archive>
    requires std::is_same_v<std::remove_const_t<Self>, StrikeWatch>
  friend void transfer_state(Self& w, Archive& ar) {
    ar(w.d_prev_, w.t_prev_, w.ke_prev_, w.f_prev_, w.armed_at_, w.base_, w.armed_, w.struck_, w.strike_);
    transfer_optional(w.form_, w.occupant_.form(w.zone_), ar);
    transfer_optional(w.pushed_, w.occupant_.form(w.zone_), ar);
  }

 private:
  Occupant occupant_;
  OccupantZone zone_;
  std::string item_;
  StrikeThresholds thresholds_;
  double d_prev_ = 0, t_prev_ = -1, ke_prev_ = 0, f_prev_ = 0;
  double armed_at_ = 0;  // the intrusion a strike starts at: 0, or the depth an item in the zone reached
  double base_ = 0;      // the strike under way's armed_at_: its form sees the intrusion beyond it
  bool armed_ = true;    // after a strike, false until the item slows below rearm_speed or leaves
  bool struck_ = false;   // as an obstacle: this item has struck this zone before
  std::optional<FormStrike> form_;     // a sensor's strike under way
  std::optional<ForceStrike> pushed_;  // an obstacle's strike under way
  Strike strike_;

  // An optional strike record through a checkpoint: whether there is one, then it.
  template <class T, class Archive>
  static void transfer_optional(std::optional<T>& x, const ImpactForm& form, Archive& ar) {
    bool present = x.has_value();
    ar(present);
    if (present && !x) x.emplace(form);
    if (!present) x.reset();
    if (present) ar(*x);
  }
  template <class T, class Archive>
  static void transfer_optional(const std::optional<T>& x, const ImpactForm&, Archive& ar) {
    bool present = x.has_value();
    ar(present);
    if (present) ar(*x);
  }

  // A new strike's record, the item reaching the zone at `frac` of the way from the last step to this
  // one: its time, its speed into the zone and its energy there.
  void begin_strike(double frac, double t, double d, double ke) {
    strike_ = Strike{};
    strike_.occupant = occupant_.name;
    strike_.item = item_;
    strike_.zone = zone_;
    strike_.time = t_prev_ + frac * (t - t_prev_);
    strike_.relative_speed = (d - d_prev_) / (t - t_prev_);
    strike_.kinetic_energy = ke_prev_ + frac * (ke - ke_prev_);
  }
  void open(double t, double d, double ke) {
    base_ = armed_at_;
    begin_strike((base_ - d_prev_) / (d - d_prev_), t, d, ke);  // where between the steps it crossed base_
    form_.emplace(occupant_.form(zone_));
    form_->advance(0.0, d - base_, t - strike_.time);
  }
  Strike close() {
    const auto take = [&](const auto& record) {
      strike_.duration = record.duration();
      strike_.peak_force = record.peak_force();
      strike_.impulse = record.impulse();
      if (zone_ == OccupantZone::head) strike_.hic15 = record.hic(0.015);
    };
    if (form_) take(*form_);
    else take(*pushed_);
    strike_.exceeded = exceeded_thresholds(strike_, thresholds_);
    form_.reset(), pushed_.reset();
    return strike_;
  }
};

}  // namespace furniture_fem
