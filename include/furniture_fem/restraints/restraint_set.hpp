#pragma once
// furniture_fem/restraints/restraint_set.hpp: a room's restraints and their history, as a contact policy
// evaluates them (contact/room_contact.hpp holds one).
//
//   RestraintSet   evaluate (a trial from the committed state), commit, energies, checkpoint
//
// A restraint's force acts on its node like a floor contact's: into the force vector, with its slope in
// the implicit step and its regime compared within a step (a restraint that yields or breaks inside a
// step has its body solved again). Its work on the item is summed at each commit (trapezoidal, as the
// energy ledger's contact work), so what it stored and what it dissipated are known at every step.
#include <Eigen/Core>
#include <string>
#include <type_traits>
#include <vector>

#include "../core/errors.hpp"
#include "restraint.hpp"

namespace furniture_fem {

class RestraintSet {
 public:
  RestraintSet() = default;
  explicit RestraintSet(std::vector<Restraint> restraints) : restraints_(std::move(restraints)) {
    for (const Restraint& r : restraints_) check(r);
    for (const Restraint& r : restraints_) committed_.push_back(initial_restraint_state(r));
    trial_ = committed_;
    initial_stored_ = stored_energy();
  }

  bool empty() const { return restraints_.empty(); }
  std::size_t size() const { return restraints_.size(); }
  const std::vector<Restraint>& restraints() const { return restraints_; }
  const Restraint& operator[](std::size_t i) const { return restraints_[i]; }
  // The committed state of each (its force, regime, peak, break time ... at the last step).
  const std::vector<RestraintState>& states() const { return committed_; }

  // Restraint i with its node at x moving at v, from its committed state; nothing recorded.
  RestraintResponse response(std::size_t i, const Vec3& x, const Vec3& v = Vec3::Zero()) const {
    return restraint_response(restraints_[i], committed_[i], x, v);
  }
  // The same, its state kept as the trial the next commit keeps.
  RestraintResponse evaluate(std::size_t i, const Vec3& x, const Vec3& v = Vec3::Zero()) {
    RestraintResponse out = response(i, x, v);
    trial_[i] = out.state;
    return out;
  }

  // The step is over at time t: each restraint keeps its last trial; its work, peak force and break time
  // follow from the committed and the new state.
  void commit(double t) {
    for (std::size_t i = 0; i < restraints_.size(); ++i) {
      RestraintState& now = trial_[i];
      const RestraintState& before = committed_[i];
      now.work = before.work + 0.5 * (before.on_item + now.on_item).dot(now.x - before.x);
      now.peak_force = std::max(before.peak_force, now.force);  // pushing (a bent bracket bearing) is not loading
      if (now.broken() && !before.broken()) now.broke_at = t;
    }
    committed_ = trial_;
  }

  // J: the elastic energy the restraints hold now; the work they have done on the items; what they have
  // dissipated (yielding, slipping, breaking: what went in and is no longer stored).
  double stored_energy() const {
    double e = 0;
    for (const auto& s : committed_) e += s.stored;
    return e;
  }
  double work() const {
    double w = 0;
    for (const auto& s : committed_) w += s.work;
    return w;
  }
  double dissipated_energy() const { return -work() - (stored_energy() - initial_stored_); }
  double dissipated_energy(std::size_t i) const {
    const RestraintState& s = committed_[i];
    return -s.work - (s.stored - initial_restraint_state(restraints_[i]).stored);
  }

  template <class Self, class Archive>
    requires std::is_same_v<std::remove_const_t<Self>, RestraintSet>
  friend void transfer_state(Self& set, Archive& ar) {
    ar(set.committed_, set.trial_);
  }

 private:
  static void check(const Restraint& r) {
    const auto fail = [&](const std::string& what) { throw ModelError("restraint '" + r.name + "': " + what); };
    if (r.node < 0 || r.body < 0) fail("no node of an item");
    if (r.between_items() && (r.anchor_body < 0 || r.anchor_body == r.body)) fail("its anchor must be a node of another item");
    if (r.between_items() && r.kind != RestraintKind::l_bracket && r.kind != RestraintKind::strap)
      fail("only a bracket or a strap joins two items");
    if (!r.rest.allFinite() || !r.anchor.allFinite() || !(std::abs(r.normal.norm() - 1) < 1e-9))
      fail("its rest point, anchor and unit normal must be finite");
    for (const RestraintParameter& d : restraint_parameters(r.kind)) {
      const double v = r.p.*(d.field);
      if (!d.accepts(v))
        fail(std::string(d.key) + " = " + detail::fmt(v) + " is outside " + d.range_text() + " " + std::string(d.unit));
    }
    // Softening steeper than the bracket's elastic slope would snap back: no force matches the pull.
    if (r.kind == RestraintKind::l_bracket && !(r.p.softening > r.p.strength / r.p.stiffness))
      fail("softening = " + detail::fmt(r.p.softening) + " m must exceed strength / stiffness = " +
           detail::fmt(r.p.strength / r.p.stiffness) + " m (a steeper fall than the elastic slope has no solution)");
    if (r.kind == RestraintKind::pole && !(r.p.preload < std::min(r.p.slip_strength, r.p.board_strength)))
      fail("preload = " + detail::fmt(r.p.preload) + " N must be below slip_strength and board_strength");
  }

  std::vector<Restraint> restraints_;
  std::vector<RestraintState> committed_, trial_;
  double initial_stored_ = 0;
};

}  // namespace furniture_fem
