#pragma once
// furniture_fem/harm/impact_form.hpp: what an item's strike does to a person's head or body, measured on
// an impact form (docs/harm/occupants.md, "Strikes"): a free mass m (a head form: 4.5 kg, the Hybrid III
// head) at rest, pushed along the strike's normal by a contact spring k as the item intrudes into the
// zone. The item's intrusion d(t) comes from the run; the form does not push back (an occupant is a
// sensor), so the item moves as if unobstructed: for an item of effective mass M at the contact the
// form's peak force is an upper bound by sqrt(1 + m / M).
//
//   ImpactForm        mass, stiffness, the contact's natural period
//   FormStrike        the form driven by an intrusion history, step by step: force, impulse, peak,
//                     and the acceleration history a head injury criterion is taken on
//   ForceStrike       a person standing as a rigid obstacle: the contact force it carries, as the force on the form
//   head_injury_criterion   HIC over windows up to a length (15 ms: HIC15, 49 CFR 571.208 S6.2)
#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>
#include <vector>

#include "../core/model.hpp"  // standard_gravity

namespace furniture_fem {

struct ImpactForm {
  double mass = 4.5;         // kg
  double stiffness = 1.0e6;  // N/m
  // The half period of the form on its spring: how long a strike by an item at constant speed lasts.
  double contact_duration() const { return std::numbers::pi * std::sqrt(mass / stiffness); }
};

// The head injury criterion of an acceleration history (times t in s, accelerations a in g): the largest
// (t2 - t1) (mean of a over [t1, t2])^2.5 over pairs of samples no further apart than `window`
// (trapezoidal integral; every pair: a strike has a few hundred samples).
inline double head_injury_criterion(const std::vector<double>& t, const std::vector<double>& a_g, double window = 0.015) {
  std::vector<double> integral(a_g.size(), 0.0);
  for (std::size_t i = 1; i < a_g.size(); ++i) integral[i] = integral[i - 1] + 0.5 * (t[i] - t[i - 1]) * (a_g[i - 1] + a_g[i]);
  double hic = 0.0;
  for (std::size_t i = 0; i < a_g.size(); ++i)
    for (std::size_t j = i + 1; j < a_g.size() && t[j] - t[i] <= window * (1 + 1e-12); ++j) {
      const double T = t[j] - t[i], mean = (integral[j] - integral[i]) / T;
      if (mean > 0) hic = std::max(hic, T * std::pow(mean, 2.5));
    }
  return hic;
}

// The form through one strike: at rest at the onset (intrusion 0), then pushed while the item's
// intrusion d exceeds the form's own travel x: force k (d - x). Integrated by velocity Verlet in
// sub-steps of at most a 200th of the contact duration, the intrusion linear between the run's steps.
class FormStrike {
 public:
  explicit FormStrike(const ImpactForm& form) : form_(form), h_max_(form.contact_duration() / 200.0) {
    t_.push_back(0.0);
    a_g_.push_back(0.0);
  }

  // Advances from the intrusion d0 to d1 over dt seconds (d0 = 0 at the onset).
  void advance(double d0, double d1, double dt) {
    if (!(dt > 0)) return;
    const int n = std::max(1, static_cast<int>(std::ceil(dt / h_max_)));
    const double h = dt / n;
    for (int i = 0; i < n; ++i) {
      const double f0 = force(d0 + (d1 - d0) * double(i) / n);
      v_ += 0.5 * h * f0 / form_.mass;
      x_ += h * v_;
      const double f1 = force(d0 + (d1 - d0) * double(i + 1) / n);
      v_ += 0.5 * h * f1 / form_.mass;
      impulse_ += 0.5 * h * (f0 + f1);
      peak_ = std::max(peak_, f1);
      if (f0 > 0 || f1 > 0) contact_end_ = t_.back() + h;
      t_.push_back(t_.back() + h);
      a_g_.push_back(f1 / form_.mass / standard_gravity);
    }
    intrusion_ = d1;
  }
  double force_now() const { return force(intrusion_); }
  // The strike is over once the form is out of contact and moving away at least as fast as the item
  // intrudes (m/s).
  bool separated(double intrusion_rate) const { return impulse_ > 0 && force_now() <= 0 && v_ >= intrusion_rate; }
  double peak_force() const { return peak_; }  // N
  double impulse() const { return impulse_; }  // N s: the form's momentum
  double form_speed() const { return v_; }     // m/s
  double duration() const { return contact_end_; }  // s from the onset to the last sub-step in contact
  // HIC over windows up to `window` of the form's acceleration (in g).
  double hic(double window = 0.015) const { return head_injury_criterion(t_, a_g_, window); }

  // Checkpoints (core/checkpoint.hpp): a run resumed mid-strike carries on with the same form.
  template <class Self, class Archive>
    requires std::is_same_v<std::remove_const_t<Self>, FormStrike>
  friend void transfer_state(Self& f, Archive& ar) {
    ar(f.form_.mass, f.form_.stiffness, f.h_max_, f.x_, f.v_, f.impulse_, f.peak_, f.intrusion_, f.contact_end_, f.t_, f.a_g_);
  }

 private:
  ImpactForm form_;
  double h_max_;
  double x_ = 0, v_ = 0, impulse_ = 0, peak_ = 0, intrusion_ = 0, contact_end_ = 0;
  std::vector<double> t_, a_g_;  // the form's acceleration (g) at the sub-steps' ends, from the onset

  double force(double d) const { return form_.stiffness * std::max(0.0, d - x_); }
};

// A strike on a person standing as a rigid obstacle (Occupant::obstacle): the contact force the zone
// carries, sampled at the run's steps and linear between them, is the force on the zone's form: its
// impulse and peak, and HIC of the acceleration F / m the form would have under it (the obstacle does not
// move; a free head form of mass m under the same force would).
class ForceStrike {
 public:
  explicit ForceStrike(const ImpactForm& form) : mass_(form.mass) {
    t_.push_back(0.0);
    a_g_.push_back(0.0);
  }
  // The force F (N) at t seconds after the onset (t after the last sample).
  void add(double t, double F) {
    if (!(t > t_.back())) return;
    impulse_ += 0.5 * (t - t_.back()) * (f_last_ + F);
    f_last_ = F;
    peak_ = std::max(peak_, F);
    if (F > 0) contact_end_ = t;
    t_.push_back(t);
    a_g_.push_back(F / mass_ / standard_gravity);
  }
  double peak_force() const { return peak_; }       // N
  double impulse() const { return impulse_; }       // N s
  double duration() const { return contact_end_; }  // s from the onset to the last sample with a force
  double hic(double window = 0.015) const { return head_injury_criterion(t_, a_g_, window); }

  template <class Self, class Archive>
    requires std::is_same_v<std::remove_const_t<Self>, ForceStrike>
  friend void transfer_state(Self& f, Archive& ar) {
    ar(f.mass_, f.impulse_, f.peak_, f.contact_end_, f.f_last_, f.t_, f.a_g_);
  }

 private:
  double mass_;
  double impulse_ = 0, peak_ = 0, contact_end_ = 0, f_last_ = 0;
  std::vector<double> t_, a_g_;  // the samples: time from the onset, F / m in g
};

}  // namespace furniture_fem
