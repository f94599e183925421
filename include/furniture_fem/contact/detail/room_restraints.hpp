#pragma once
// furniture_fem/contact/detail/room_restraints.hpp: RoomContact's restraints (restraints/): their forces
// at their nodes, beside the floor and wall contacts, and their slopes inside the implicit step.
// Included by contact/room_contact.hpp right after the class: member functions of RoomContact defined out of
// the class (declared, with what they do, in it); not a header of its own.
#ifndef FURNITURE_FEM_CONTACT_INTERNAL
#error "furniture_fem/contact/detail/room_restraints.hpp is internal: include <furniture_fem/contact/room_contact.hpp>"
#endif

namespace furniture_fem {

inline void RoomContact::set_restraints(RestraintSet restraints) {
  restraints_ = std::move(restraints);
  restraints_of_.assign(bodies_.size(), {});
  for (std::size_t i = 0; i < restraints_.size(); ++i) {
    const int body = restraints_[i].body;
    if (body < 0 || body >= static_cast<int>(bodies_.size()))
      throw ModelError("restraint '" + restraints_[i].name + "': body " + std::to_string(body) + " is not in the room");
    restraints_of_[body].push_back(static_cast<int>(i));
    if (const int other = restraints_[i].anchor_body; other >= 0) {
      if (other >= static_cast<int>(bodies_.size()) || other == body)
        throw ModelError("restraint '" + restraints_[i].name + "': its anchor body " + std::to_string(other) + " is not another body of the room");
      restraints_of_[other].push_back(static_cast<int>(i));
    }
  }
  restraint_status_.assign(restraints_.size(), 0);
  for (std::size_t i = 0; i < restraints_.size(); ++i)
    restraint_status_[i] = static_cast<char>(restraints_.states()[i].regime);
  ++nodes_read_revision_;
}

// A restraint's regime as NodalContactTangent::status counts it: above the contacts' codes
// (contact_status_code), so that a node's sum still changes with any term's regime.
inline NodalContactTangent RoomContact::restraint_tangent(const ContactView& view, int i, const RestraintResponse& r) const {
  const int node = restraints_[i].node;
  const int code = (static_cast<int>(r.state.regime) + 1) << 24;
  return {node, code, r.K, r.C, view.x[node], Vec3(view.v.template segment<3>(6 * node))};
}

// The place and speed restraint i's law sees: its node's, or between items relative to the anchor node.
inline std::pair<Vec3, Vec3> RoomContact::restraint_input(const ContactView& view, int i) const {
  const Restraint& rs = restraints_[i];
  const int n = rs.node, a = rs.between_items() ? rs.anchor_node : n;
  const Vec3 v = view.v.template segment<3>(6 * n);
  return {rs.item_place(view.x[n], view.x[a]), rs.between_items() ? Vec3(v - view.v.template segment<3>(6 * a)) : v};
}

inline RestraintResponse RoomContact::restraint_now(const ContactView& view, int i) const {
  const auto [x, v] = restraint_input(view, i);
  return restraints_.response(i, x, v);
}

inline void RoomContact::restraint_forces(const ContactView& view, Eigen::VectorXd& f, bool only_implicit) {
  evaluated_at_ = view.time;
  restraints_applied_ = 0;
  for (std::size_t i = 0; i < restraints_.size(); ++i) {
    const Restraint& rs = restraints_[i];
    if (rs.between_items()) {  // a joint: at the step's start only (joint_force)
      if (!only_implicit) joint_force(view, static_cast<int>(i), f);
      continue;
    }
    const bool inside_step = implicit && bodies_[rs.body].implicit;
    if (only_implicit && !inside_step) continue;
    const auto [x, v] = restraint_input(view, static_cast<int>(i));
    const RestraintResponse r = restraints_.evaluate(i, x, v);  // kept: the trial the step's commit keeps
    restraint_status_[i] = static_cast<char>(r.state.regime);
    if (r.state.regime == RestraintRegime::idle || r.state.broken()) continue;
    f.template segment<3>(6 * rs.node) += r.on_item;
    if (!inside_step) continue;
    plane_applied_.emplace_back(rs.node, wrench(r.on_item));
    tangents_.push_back(restraint_tangent(view, static_cast<int>(i), r));
    ++restraints_applied_;
  }
}

// A joint between items (i) at the step's start: its force on its node and, opposite, on the anchor
// node, and (both items inside the step) its linearisation as an item pair's, so that the simulation
// solves the two items together, as rigid pairs in contact are, and carries the linearised force to the
// step's end. Each item's own solve with the other's node held where it was fed the pair energy
// (docs/restraints/restraints.md, "Between items"). The pair's point is the item's node: the anchor
// item takes the force's moment about its own node, so that the joint keeps the angular momentum.
inline void RoomContact::joint_force(const ContactView& view, int i, Eigen::VectorXd& f) {
  const Restraint& rs = restraints_[i];
  const auto [x, v] = restraint_input(view, i);
  const RestraintResponse r = restraints_.evaluate(i, x, v);  // kept: the trial the step's commit keeps
  restraint_status_[i] = static_cast<char>(r.state.regime);
  if (r.state.regime == RestraintRegime::idle || r.state.broken()) return;
  f.template segment<3>(6 * rs.node) += r.on_item;
  f.template segment<3>(6 * rs.anchor_node) -= r.on_item;
  const Vec3 arm = view.x[rs.node] - view.x[rs.anchor_node];
  f.template segment<3>(6 * rs.anchor_node + 3) -= arm.cross(r.on_item);
  if (!implicit || !bodies_[rs.body].implicit || !bodies_[rs.anchor_body].implicit) return;
  PairContactTangent t;
  t.body_a = rs.body, t.body_b = rs.anchor_body;
  t.a0 = t.a1 = rs.node, t.b0 = t.b1 = rs.anchor_node;
  t.point = view.x[rs.node], t.K = r.K, t.C = r.C;
  t.x = arm, t.v = Vec3(view.v.template segment<3>(6 * rs.node) - view.v.template segment<3>(6 * rs.anchor_node));
  pair_tangents_.push_back(t);
}

// The joints inside the step evaluated again at its end for their history and regime only: their end
// forces are the simulation's (the linearised pair force carried through the step).
inline void RoomContact::joint_history(const ContactView& view) {
  for (std::size_t i = 0; i < restraints_.size(); ++i) {
    const Restraint& rs = restraints_[i];
    if (!rs.between_items() || !bodies_[rs.body].implicit || !bodies_[rs.anchor_body].implicit) continue;
    const auto [x, v] = restraint_input(view, static_cast<int>(i));
    restraint_status_[i] = static_cast<char>(restraints_.evaluate(i, x, v).state.regime);
  }
}

}  // namespace furniture_fem
