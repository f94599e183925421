#pragma once
// furniture_fem/contact/detail/room_contact_pairs.hpp: RoomContact's item-item contact: element pairs by the broad phase, mesh and capsule obstacles, rigid pairs by their hulls.
// Included by contact/room_contact.hpp right after the class: member functions of RoomContact defined out of
// the class (declared, with what they do, in it); not a header of its own.
#ifndef FURNITURE_FEM_CONTACT_INTERNAL
#error "furniture_fem/contact/detail/room_contact_pairs.hpp is internal: include <furniture_fem/contact/room_contact.hpp>"
#endif

namespace furniture_fem {

inline void RoomContact::end_of_step(const ContactView& view, Eigen::VectorXd& f) {
  if (!implicit) return;
  if (!plane_applied_.empty()) {
    for (const auto& [n, w] : plane_applied_) f.template segment<6>(6 * n) -= w;
    std::erase_if(pair_forces_, [&](const PairForce& pf) {
      const bool plane = pf.body_b == floor_id || pf.body_b == wall_id || pf.body_b == ceiling_id;
      return plane && bodies_[pf.body_a].implicit;
    });
    active_ -= static_cast<int>(plane_applied_.size()) - restraints_applied_;  // restraints are not contacts
    plane_contacts(view, f, true);
  }
  joint_history(view);
  for (const auto& ip : implicit_pairs_) {
    const auto& A = view.model.elements()[ip.ea];
    const auto& B = view.model.elements()[ip.eb];
    add_pair_force(std::min(A.body, B.body), std::max(A.body, B.body), -ip.reported);
    ContactState st = committed_pair_state(ip.ea, ip.eb);
    const auto nf = evaluate_segment_pair(*law_, segment_pair(view, ip.ea, ip.eb), pair_params(view.model, ip.ea, ip.eb), st);
    if (pair_history_) {
      if (nf.in_contact) pair_trial_.set(key(ip.ea, ip.eb), st);
      else pair_trial_.erase(key(ip.ea, ip.eb));
    }
    add_pair_force(std::min(A.body, B.body), std::max(A.body, B.body), reported_pair_force(A.body, B.body, nf));
  }
  for (auto& hc : hull_contacts_) {
    if (!hc.implicit) continue;
    add_pair_force(std::min(hc.body_a, hc.body_b), std::max(hc.body_a, hc.body_b), -hc.reported);
    ContactState st = committed_hull_state(hc);
    const ContactForce cf = hull_contact_force(view, hc, st);
    if (pair_history_ && hc.key >= 0) {
      if (cf.in_contact) pair_trial_.set(hc.key, st);
      else pair_trial_.erase(hc.key);
    }
    hc.reported = hc.body_a < hc.body_b ? cf.on_a : Vec3(-cf.on_a);
    add_pair_force(std::min(hc.body_a, hc.body_b), std::max(hc.body_a, hc.body_b), hc.reported);
  }
}

inline void RoomContact::element_contacts(const ContactView& view, Eigen::VectorXd& f) {
  const Model& model = view.model;
  bool rerun = x_broad_.size() != view.x.size();
  if (!rerun) {
    const double limit2 = 0.25 * margin * margin;
    for (size_t n = 0; n < view.x.size() && !rerun; ++n) rerun = (view.x[n] - x_broad_[n]).squaredNorm() > limit2;
  }
  const auto t_broad = std::chrono::steady_clock::now();
  if (rerun) {
    x_broad_ = view.x;
    std::vector<ElementBox> boxes;
    boxes.reserve(model.num_elements());
    for (int e = 0; e < model.num_elements(); ++e) {
      const auto& el = model.elements()[e];
      boxes.push_back(ElementBox::around(view.x[el.n1], view.x[el.n2],
                                         0.5 * model.section_of(e).contact_width() + margin, e, el.body));
    }
    broad_phase_.pairs(boxes, candidates_);
    ++broad_runs_;
  }
  const auto t_pairs = std::chrono::steady_clock::now();
  timings_.broad += std::chrono::duration<double>(t_pairs - t_broad).count();
  struct AddPairs {  // on every way out of the loop
    Timings& t;
    std::chrono::steady_clock::time_point t0;
    ~AddPairs() { t.pairs += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); }
  } add_pairs{timings_, t_pairs};
  for (const auto& [ea, eb] : candidates_) {
    const auto& A = model.elements()[ea];
    const auto& B = model.elements()[eb];
    if (hulls_on_ && hull_pair(A.body, B.body)) continue;  // hull_contacts
    // Most candidates are apart (the broad phase's boxes are `margin` larger): their boxes show it
    // before the closest points, the history lookup and the law. Apart, evaluate_segment_pair
    // gives no force and no history, and the loop goes on, as here.
    const double L = pair_contact_distance(model, ea, eb);
    if (segments_apart_beyond(view.x[A.n1], view.x[A.n2], view.x[B.n1], view.x[B.n2], L)) continue;
    ContactState st = committed_pair_state(ea, eb);
    const auto nf = evaluate_segment_pair(*law_, segment_pair(view, ea, eb), pair_params(model, ea, eb), st);
    if (pair_history_ && nf.in_contact) pair_trial_.set(key(ea, eb), st);
    if (!nf.in_contact) continue;
    // Two rigid (or, when asked, two flexible) implicit bodies: the simulation solves them together with
    // the pair's linearisation (a rigid and a flexible one: the pair stays explicit).
    const bool both_rigid = rigid_[A.body] && rigid_[B.body];
    const bool both_flexible = flexible_pairs_implicit && !rigid_[A.body] && !rigid_[B.body];
    if (implicit && (both_rigid || both_flexible) && bodies_[A.body].implicit && bodies_[B.body].implicit) {
      const auto& c = nf.closest;
      pair_tangents_.push_back({A.body, B.body, A.n1, A.n2, B.n1, B.n2, c.s, c.t, 0.5 * (c.p_WA + c.p_WB),
                                nf.force.K, nf.force.C, c.p_WA - c.p_WB, nf.kinematics.v});
      implicit_pairs_.push_back({ea, eb, reported_pair_force(A.body, B.body, nf)});
    }
    f.template segment<3>(6 * A.n1) += nf.on_a0;
    f.template segment<3>(6 * A.n2) += nf.on_a1;
    f.template segment<3>(6 * B.n1) += nf.on_b0;
    f.template segment<3>(6 * B.n2) += nf.on_b1;
    // The moments carrying the tangential force from the contact point to the centre lines make
    // each pair exactly torque-free.
    f.template segment<3>(6 * A.n1 + 3) += nf.moment_a0;
    f.template segment<3>(6 * A.n2 + 3) += nf.moment_a1;
    f.template segment<3>(6 * B.n1 + 3) += nf.moment_b0;
    f.template segment<3>(6 * B.n2 + 3) += nf.moment_b1;
    add_pair_force(std::min(A.body, B.body), std::max(A.body, B.body), reported_pair_force(A.body, B.body, nf));
    ++active_;
  }
}

inline SegmentPair RoomContact::segment_pair(const ContactView& view, int ea, int eb) {
  const Model& model = view.model;
  const auto& A = model.elements()[ea];
  const auto& B = model.elements()[eb];
  SegmentPair sp;
  sp.a0 = view.x[A.n1];
  sp.a1 = view.x[A.n2];
  sp.b0 = view.x[B.n1];
  sp.b1 = view.x[B.n2];
  sp.va0 = view.v.template segment<3>(6 * A.n1);
  sp.va1 = view.v.template segment<3>(6 * A.n2);
  sp.vb0 = view.v.template segment<3>(6 * B.n1);
  sp.vb1 = view.v.template segment<3>(6 * B.n2);
  sp.L = pair_contact_distance(model, ea, eb);
  sp.dt = view.dt;
  return sp;
}

inline double RoomContact::pair_contact_distance(const Model& model, int ea, int eb) {
  return 0.5 * (model.section_of(ea).contact_width() + model.section_of(eb).contact_width());
}

inline ContactParams RoomContact::pair_params(const Model& model, int ea, int eb) const {
  return ContactParams::pair(bodies_[model.elements()[ea].body].item, bodies_[model.elements()[eb].body].item);
}

inline ContactState RoomContact::committed_pair_state(int ea, int eb) const {
  if (!pair_history_) return {};
  const ContactState* st = pair_state_.find(key(ea, eb));
  return st ? *st : ContactState{};
}

inline Vec3 RoomContact::reported_pair_force(int body_a, int body_b, const SegmentPairForces& nf) {
  return body_a < body_b ? Vec3(nf.on_a0 + nf.on_a1) : Vec3(nf.on_b0 + nf.on_b1);
}

inline void RoomContact::obstacle_contacts(const ContactView& view, Eigen::VectorXd& f) {
  const Model& model = view.model;
  for (int n = 0; n < model.num_nodes(); ++n) {
    for (const auto& ob : obstacles_) {
      const double L = half_width_[n];
      // Only nodes within L of the mesh get a closest-point search (one per node and step made a
      // 20 000-vertex obstacle far from every item cost 5 to 23 s per 50 steps; issue 13).
      const auto cp = ob.closest_within(view.x[n], L);
      if (!cp) continue;
      const Vec3 d = view.x[n] - cp->p_WM;
      const double l = d.norm();
      if (l > L || l < 1e-12) continue;
      push_off_obstacle(view, n, l, Vec3(d / l), obstacle_id, f);  // the closest point as a plane through it
    }
  }
}

inline void RoomContact::push_off_obstacle(const ContactView& view, int n, double distance, const Vec3& normal, int pair_id,
                                           Eigen::VectorXd& f) {
  const int body = view.model.node(n).body;
  const NodeOnPlane node{view.x[n], view.v.template segment<3>(6 * n), half_width_[n], view.dt, Vec3::Zero(), Vec3::Zero()};
  ContactState st;
  const ContactForce cf = detail::node_force(*law_, node, distance, normal, bodies_[body].wall, st);
  f.template segment<3>(6 * n) += cf.on_a;
  add_pair_force(body, pair_id, cf.on_a);
  ++active_;
}

inline void RoomContact::add_capsule(const Capsule& capsule, int id) {
  if (!(capsule.radius > 0) || !capsule.a.allFinite() || !capsule.b.allFinite())
    throw ModelError("RoomContact: capsule obstacle " + std::to_string(id) + " needs a positive radius and finite ends (radius " +
                     std::to_string(capsule.radius) + ")");
  capsules_.push_back({capsule, PairForce::capsule_id(id)});
  ++nodes_read_revision_;
}

inline void RoomContact::capsule_contacts(const ContactView& view, Eigen::VectorXd& f) {
  const Model& model = view.model;
  for (const auto& [shape, pair_id] : capsules_) {
    // A node farther than the capsule's radius and its own half width from the capsule's box is skipped
    // before the distance (most nodes of a room are).
    const Vec3 lo = shape.a.cwiseMin(shape.b), hi = shape.a.cwiseMax(shape.b);
    for (int n = 0; n < model.num_nodes(); ++n) {
      const double L = half_width_[n], reach = shape.radius + L;
      const Vec3& x = view.x[n];
      if (((x - hi).array() > reach).any() || ((lo - x).array() > reach).any()) continue;
      const auto d = point_capsule(x, shape);
      if (!d || d->signed_distance > L) continue;
      push_off_obstacle(view, n, d->signed_distance, d->n_W, pair_id, f);
    }
  }
}

inline const detail::SupportGeometry& RoomContact::hull_of(int body) const {
  return surface_at(body) ? surface_groups_[body].front().geometry : support_[body];
}

inline std::pair<int, Vec3> RoomContact::hull_point(int body, int i) const {
  if (!surface_at(body)) return {i, Vec3::Zero()};
  return {surface_points_[i].node, surface_points_[i].arm0};
}

inline double RoomContact::hull_distance(int a, int b) const {
  return (surface_at(a) ? 0.0 : hull_half_width_[a]) + (surface_at(b) ? 0.0 : hull_half_width_[b]);
}

inline double RoomContact::hull_L(int a, int b) const {
  return hull_half_width_[a] + hull_half_width_[b];
}

inline void RoomContact::update_hull_pairs(const Model& model) {
  const std::size_t nb = bodies_.size();
  has_hull_.assign(hulls_on_ ? nb : 0, 0);
  nested_pairs_.clear();
  hull_half_width_.assign(nb, 0.0);
  if (!hulls_on_) return;
  const auto points = std::max<long long>(model.num_nodes(), static_cast<long long>(surface_points_.size()));
  if (points >= hull_id_limit || static_cast<long long>(nb) >= hull_id_limit)
    throw ModelError("RoomContact: rigid pairs by their hulls (scene key contact.rigid_pairs, \"hulls\") number "
                     "their points and bodies below 2^20 = 1048576; this model has " + std::to_string(points) +
                     " points in " + std::to_string(nb) + " bodies: use contact.rigid_pairs \"members\", or fewer "
                     "or coarser items");
  for (std::size_t b = 0; b < nb; ++b)
    for (int n : model.body(static_cast<int>(b)).nodes)
      if (std::isfinite(half_width_[n])) hull_half_width_[b] = std::max(hull_half_width_[b], half_width_[n]);
  const auto has_hull = [&](int b) {
    if (!rigid_[b]) return false;
    if (surface_at(b)) return !surface_groups_[b].empty() && !surface_groups_[b].front().geometry.faces.empty();
    return !support_[b].faces.empty();
  };
  const auto rest = [&](int body) {
    return [this, &model, body](int i) -> Vec3 {
      const auto [n, arm] = hull_point(body, i);
      return model.node(n).X + arm;
    };
  };
  // Every two bodies with hulls meet by them, unless their hulls overlap at rest (nested: element pairs).
  // Only bodies whose rest boxes, each grown by its half width, overlap can: they are found by sweeping
  // the boxes along x (sorted by their lower x), so a room of n items is set up in about n log n, not n^2.
  std::vector<int> hull_bodies;
  std::vector<Vec3> lo(nb), hi(nb);
  for (int b = 0; b < static_cast<int>(nb); ++b) {
    if (!has_hull(b)) continue;
    hull_bodies.push_back(b);
    lo[b] = Vec3::Constant(std::numeric_limits<double>::infinity());
    hi[b] = -lo[b];
    for (int v : hull_of(b).vertices) {
      const Vec3 x = rest(b)(v);
      lo[b] = lo[b].cwiseMin(x), hi[b] = hi[b].cwiseMax(x);
    }
    lo[b].array() -= hull_half_width_[b];
    hi[b].array() += hull_half_width_[b];
  }
  for (int b : hull_bodies) has_hull_[b] = 1;
  std::vector<int> by_x = hull_bodies;
  std::sort(by_x.begin(), by_x.end(), [&](int a, int b) { return lo[a].x() != lo[b].x() ? lo[a].x() < lo[b].x() : a < b; });
  std::vector<int> nested_partners(nb, 0);
  bool any_nested = false;
  for (std::size_t i = 0; i < by_x.size(); ++i)
    for (std::size_t j = i + 1; j < by_x.size() && lo[by_x[j]].x() <= hi[by_x[i]].x(); ++j) {
      const int a = std::min(by_x[i], by_x[j]), b = std::max(by_x[i], by_x[j]);
      if ((lo[a].array() > hi[b].array()).any() || (lo[b].array() > hi[a].array()).any()) continue;
      // Overlapping hulls at rest (deeper than the contact distance allows): nested, element pairs.
      if (detail::hull_separation(hull_of(a), rest(a), hull_of(b), rest(b), hull_distance(a, b)) < -nested_overlap) {
        nested_pairs_.emplace_back(a, b);
        ++nested_partners[a], ++nested_partners[b];
        any_nested = true;
      }
    }
  std::sort(nested_pairs_.begin(), nested_pairs_.end());
  // A body is in a hull pair when some other hull body is not nested with it; element pairs are left
  // when a body has no hull or some pair is nested.
  hull_body_.assign(nb, 0);
  for (int b : hull_bodies) hull_body_[b] = nested_partners[b] < static_cast<int>(hull_bodies.size()) - 1;
  any_element_pairs_ = any_nested || (nb > 1 && hull_bodies.size() < nb);
}

inline long long RoomContact::hull_key(detail::HullPointKind kind, long long p, long long q, long long r) {
  return (1LL << 62) | (static_cast<long long>(kind) << 60) | (p << 40) | (q << 20) | r;
}

inline long long RoomContact::hull_key(const detail::HullContactPoint& pt, int inc, int ref) {
  using K = detail::HullPointKind;
  switch (pt.kind) {
    case K::corner: return hull_key(pt.kind, pt.id, 0, ref);
    case K::entering:
    case K::leaving: return hull_key(pt.kind, pt.id, pt.id2, 0);
    case K::reference: return hull_key(pt.kind, pt.id, 0, inc);
  }
  return -1;
}

inline ContactState RoomContact::committed_hull_state(const HullContact& hc) const {
  if (!pair_history_ || hc.key < 0) return {};
  const ContactState* st = pair_state_.find(hc.key);
  return st ? *st : ContactState{};
}

inline void RoomContact::hull_contacts(const ContactView& view, Eigen::VectorXd& f) {
  if (!view.rotations)
    throw ModelError("RoomContact: rigid pairs by their hulls need the nodes' rotations in the ContactView");
  const std::size_t nb = bodies_.size();
  // Each hull body's vertices placed once (the separating axes read each many times), and its box.
  hull_box_lo_.assign(nb, Vec3::Constant(std::numeric_limits<double>::infinity()));
  hull_box_hi_.assign(nb, Vec3::Constant(-std::numeric_limits<double>::infinity()));
  for (std::size_t b = 0; b < nb; ++b) {
    if (!hull_body_[b]) continue;
    for (int v : hull_of(static_cast<int>(b)).vertices) {
      const auto [n, arm] = hull_point(static_cast<int>(b), v);
      const Vec3 x = view.x[n] + (*view.rotations)[n] * arm;
      if (static_cast<std::size_t>(v) >= hull_x_.size()) hull_x_.resize(static_cast<std::size_t>(v) + 1);
      hull_x_[v] = x;
      hull_box_lo_[b] = hull_box_lo_[b].cwiseMin(x);
      hull_box_hi_[b] = hull_box_hi_[b].cwiseMax(x);
    }
  }
  const auto at = [this](int i) -> const Vec3& { return hull_x_[i]; };
  detail::HullPairContact hc;
  for (const auto& [a, b] : near_hull_pairs()) {
    if (!hull_pair(a, b)) continue;
    // Boxes apart by more than the contact distance: no face can touch.
    const double d = hull_distance(a, b);
    if (((hull_box_lo_[a] - hull_box_hi_[b]).array() > d).any() || ((hull_box_lo_[b] - hull_box_hi_[a]).array() > d).any())
      continue;
    if (!detail::hull_pair_contact(hull_of(a), at, hull_of(b), at, d, 0.0, hull_bias, hc))
      continue;
    const int inc = hc.reference_on_a ? b : a, ref = hc.reference_on_a ? a : b;
    const int ref_node = hull_point(ref, hc.reference->frame[0]).first;
    const int inc_face_node = hull_point(inc, hc.incident->frame[0]).first;
    for (const auto& pt : hc.points) {
      HullContact c;
      c.body_a = inc, c.body_b = ref;
      // A corner of the incident face is a hull point of its body; any other point is held by the
      // incident face's first node.
      const bool corner = pt.kind == detail::HullPointKind::corner;
      const Vec3& x_inc = pt.x;
      c.node_a = corner ? hull_point(inc, pt.id).first : inc_face_node;
      c.node_b = ref_node;
      const Mat3& Ra = (*view.rotations)[c.node_a];
      const Mat3& Rb = (*view.rotations)[c.node_b];
      c.arm_a0 = Ra.transpose() * (x_inc - view.x[c.node_a]);
      c.arm_b0 = Rb.transpose() * (x_inc - view.x[c.node_b]);
      c.normal0 = Rb.transpose() * hc.normal;
      c.gap0 = pt.gap;
      c.L = hull_L(a, b);
      c.share = hc.incident->share;
      c.key = hull_key(pt, inc, ref);
      c.implicit = implicit && bodies_[a].implicit && bodies_[b].implicit;
      ContactState st = committed_hull_state(c);
      const ContactForce cf = hull_contact_force(view, c, st);
      if (pair_history_ && c.key >= 0 && cf.in_contact) pair_trial_.set(c.key, st);
      if (!cf.in_contact) continue;
      apply_hull_force(view, c, cf.on_a, f);
      c.reported = c.body_a < c.body_b ? cf.on_a : Vec3(-cf.on_a);
      add_pair_force(std::min(a, b), std::max(a, b), c.reported);
      ++active_;
      if (c.implicit) {
        const Vec3 arm_a = Ra * c.arm_a0, arm_b = Rb * c.arm_b0;
        PairContactTangent t{c.body_a, c.body_b, c.node_a, c.node_a, c.node_b, c.node_b, 0, 0, x_inc, cf.K, cf.C,
                             view.x[c.node_a] + arm_a - (view.x[c.node_b] + arm_b),
                             point_velocity(view, c.node_a, arm_a) - point_velocity(view, c.node_b, arm_b),
                             c.arm_a0, c.arm_b0};
        pair_tangents_.push_back(t);
      }
      hull_contacts_.push_back(c);
    }
  }
}

inline const std::vector<std::pair<int, int>>& RoomContact::near_hull_pairs() {
  // Every pair (a < b) of hull bodies whose vertex boxes, each grown by the largest contact reach and a
  // micrometre, overlap: a superset of the pairs whose boxes come within hull_distance, found by
  // sweeping the boxes along x; in ascending (a, b), the order of a loop over all pairs, so that forces
  // add up in the same order (the same results to the bit) in n log n rather than n^2 per step.
  const std::size_t nb = bodies_.size();
  double reach = 0;
  hull_order_.clear();
  for (std::size_t b = 0; b < nb; ++b)
    if (hull_body_[b]) {
      hull_order_.push_back(static_cast<int>(b));
      reach = std::max(reach, surface_at(static_cast<int>(b)) ? 0.0 : hull_half_width_[b]);
    }
  const double grow = reach + 1e-6;
  const auto lo_x = [&](int b) { return hull_box_lo_[b].x() - grow; };
  std::sort(hull_order_.begin(), hull_order_.end(), [&](int a, int b) { return lo_x(a) != lo_x(b) ? lo_x(a) < lo_x(b) : a < b; });
  hull_candidates_.clear();
  for (std::size_t i = 0; i < hull_order_.size(); ++i) {
    const int a = hull_order_[i];
    for (std::size_t j = i + 1; j < hull_order_.size() && lo_x(hull_order_[j]) <= hull_box_hi_[a].x() + grow; ++j) {
      const int b = hull_order_[j];
      if (((hull_box_lo_[a] - hull_box_hi_[b]).array() > 2 * grow).any() ||
          ((hull_box_lo_[b] - hull_box_hi_[a]).array() > 2 * grow).any())
        continue;
      hull_candidates_.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(hull_candidates_.begin(), hull_candidates_.end());
  return hull_candidates_;
}

inline Vec3 RoomContact::point_velocity(const ContactView& view, int n, const Vec3& arm) {
  return Vec3(view.v.template segment<3>(6 * n)) + Vec3(view.v.template segment<3>(6 * n + 3)).cross(arm);
}

inline ContactForce RoomContact::hull_contact_force(const ContactView& view, const HullContact& c, ContactState& state) const {
  const Mat3& Ra = (*view.rotations)[c.node_a];
  const Mat3& Rb = (*view.rotations)[c.node_b];
  const Vec3 arm_a = Ra * c.arm_a0, arm_b = Rb * c.arm_b0;
  const Vec3 pa = view.x[c.node_a] + arm_a, pb = view.x[c.node_b] + arm_b;
  const Vec3 n = Rb * c.normal0;
  const double gap = c.gap0 + n.dot(pa - pb);
  if (!(gap <= 0)) {
    state = ContactState{};
    return {};
  }
  const NodeOnPlane node{pa, point_velocity(view, c.node_a, arm_a), c.L, view.dt, Vec3::Zero(),
                         point_velocity(view, c.node_b, arm_b)};
  ContactParams prm = ContactParams::pair(bodies_[c.body_a].item, bodies_[c.body_b].item);
  if (c.share != 1.0) prm.scale_per_node(c.share, per_node_mask_);
  return detail::node_force(*law_, node, gap + c.L, n, prm, state);
}

inline void RoomContact::apply_hull_force(const ContactView& view, const HullContact& c, const Vec3& F, Eigen::VectorXd& f) {
  const Mat3& Ra = (*view.rotations)[c.node_a];
  const Mat3& Rb = (*view.rotations)[c.node_b];
  f.template segment<3>(6 * c.node_a) += F;
  f.template segment<3>(6 * c.node_a + 3) += (Ra * c.arm_a0).cross(F);
  f.template segment<3>(6 * c.node_b) -= F;
  f.template segment<3>(6 * c.node_b + 3) -= (Rb * c.arm_b0).cross(F);
}

}  // namespace furniture_fem
