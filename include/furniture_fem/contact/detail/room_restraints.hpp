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
  }
  restraint_status_.assign(restraints_.size(), 0);
  for (std::size_t i = 0; i < restraints_.size(); ++i)
    restraint_status_[i] = static_cast<char>(restraints_.states()[i].regime);
  ++nodes_read_revision_;
}

// A restraint's regime as NodalContactTangent::status counts it: above the contacts' codes
// (contact_status_code), so that a node's sum still changes with any term's regime.
inline NodalContactTangent RoomContact::restraint_tangent(const ContactView& view, int i, const RestraintResponse& r) const {
  const int n = restraints_[i].node;
  const int code = (static_cast<int>(r.state.regime) + 1) << 24;
  return {n, code, r.K, r.C, view.x[n], Vec3(view.v.template segment<3>(6 * n))};
}

inline RestraintResponse RoomContact::restraint_now(const ContactView& view, int i) const {
  const int n = restraints_[i].node;
  return restraints_.response(i, view.x[n], view.v.template segment<3>(6 * n));
}

inline void RoomContact::restraint_forces(const ContactView& view, Eigen::VectorXd& f, bool only_implicit) {
  evaluated_at_ = view.time;
  restraints_applied_ = 0;
  for (std::size_t i = 0; i < restraints_.size(); ++i) {
    const Restraint& rs = restraints_[i];
    const bool inside_step = implicit && bodies_[rs.body].implicit;
    if (only_implicit && !inside_step) continue;
    const RestraintResponse r = restraints_.evaluate(i, view.x[rs.node], view.v.template segment<3>(6 * rs.node));  // kept
    restraint_status_[i] = static_cast<char>(r.state.regime);
    if (r.state.regime == RestraintRegime::idle || r.state.broken()) continue;
    f.template segment<3>(6 * rs.node) += r.on_item;
    if (!inside_step) continue;
    plane_applied_.emplace_back(rs.node, wrench(r.on_item));
    tangents_.push_back(restraint_tangent(view, static_cast<int>(i), r));
    ++restraints_applied_;
  }
}

}  // namespace furniture_fem
