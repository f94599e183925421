#pragma once
// furniture_fem/contact/room_contact.hpp: the contact policy of a furnished room on a shake table.
//
//   RoomContact  plugs into Simulation<..., Contact = RoomContact>, with any contact law (its kernel)
//
// It applies a contact law (contact_laws.hpp) to three kinds of pairs, all in the table frame:
//  - node against the floor (z = 0), the walls (planes, bounded) and a ceiling: l is the node's distance
//    to the plane and L half the width of the node's widest member (the paper judges floor and wall
//    contact from nodal coordinates);
//  - element against element of two different bodies: capsules around the centre lines, l the
//    distance of the closest points and L the mean member width; candidate pairs come from the CGAL
//    broad phase (contact.hpp), re-run whenever a node has moved more than half the boxes' margin
//  - element against rigid triangle-mesh obstacles.
// With set_rigid_pair_hulls, two rigid bodies meet by their hulls instead of their members: the
// incident face of one clipped to the reference face of the other, a few points per pair
// (detail/hull_pair.hpp; docs/contact/contact.md, "Rigid pairs by their hulls").
// A rigid body (set_rigid, which Simulation::set_rigid calls) is tested against the planes with the
// vertices of its nodes' convex hull only, its support points (a box's eight corners), not its mesh:
// the vertices of the hull face turned towards a plane each stand for an equal share of the nodes on
// that face, so a body resting on a face is held as with every node (docs/contact/contact.md).
// With set_surface, contact acts at the members' surfaces: a rigid body's support points are the
// hull's vertices of cubes of half a member's width around its nodes (its outer envelope: a cabinet
// tips about its outer edge), a flexible body's the corners of such a cube around each node; each
// force is put at its point with the moment that carries it to the node (docs/contact/contact.md,
// "At the surface").
// Each body carries its own parameters (alpha, Dc, mu on the floor along its longer and shorter edge,
// mu against walls); between two items the paper's mu between furniture applies, with alpha and Dc
// the mean of the two items' values (the paper leaves this open; docs/contact/contact.md).
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "cgal_adapter.hpp"
#include "contact_law_kernel.hpp"
#include "contact_laws.hpp"
#include "pair_force.hpp"
#include "../core/simulation.hpp"
#include "../restraints/restraint_set.hpp"

#define FURNITURE_FEM_CONTACT_INTERNAL
#include "detail/hull_pair.hpp"
#include "detail/pair_history.hpp"
#include "detail/support_points.hpp"
#undef FURNITURE_FEM_CONTACT_INTERNAL

namespace furniture_fem {

// Contact parameters of one body (an item of furniture), in SI units.
struct BodyContact {
  ContactParams floor;      // alpha, q, Dc, mu (mu_long / mu_short for anisotropic laws)
  ContactParams wall;
  ContactParams item;       // its share of item-item contact (alpha, Dc averaged with the other item)
  int long_axis_node_a = -1, long_axis_node_b = -1;  // two nodes along the item's longer edge
  std::vector<int> caster_nodes;                     // nodes with their own (low) floor friction
  double caster_mu = -1;                             // < 0: the body's floor mu
  bool implicit = true;  // its floor and wall contact inside the implicit step (with RoomContact::implicit)
  bool at_nodes = false;  // floor and walls at its nodes even with set_surface (its nodes are placed for it)
};

// A rigid plane: points with (x - point) . normal >= 0 are outside. Bounded by half extents along
// two in-plane axes (infinite when the extents are not positive). A floor unless it is a wall or the
// ceiling: a wall and the ceiling take each body's wall parameters (BodyContact::wall), the floor its
// floor parameters (and the casters' friction); each kind is reported as its own partner (pair_id).
struct RigidPlane {
  Vec3 point = Vec3::Zero(), normal = Vec3::UnitZ();
  Vec3 axis_u = Vec3::UnitX(), axis_v = Vec3::UnitY();
  double half_u = 0, half_v = 0;
  bool is_wall = false;
  bool is_ceiling = false;
  bool is_floor() const { return !is_wall && !is_ceiling; }
  bool contains_projection(const Vec3& x) const {
    if (half_u <= 0 || half_v <= 0) return true;
    const Vec3 r = x - point;
    return std::abs(r.dot(axis_u)) <= half_u && std::abs(r.dot(axis_v)) <= half_v;
  }
};

// Each node's contact distance against a plane: half the width of its narrowest member (a corner of
// 50 mm tubes: 25 mm; a caster node joined to a wide side-table beam: the caster's); infinite for a
// node on no member.
inline std::vector<double> plane_contact_distances(const Model& model) {
  std::vector<double> half(model.num_nodes(), std::numeric_limits<double>::infinity());
  for (int e = 0; e < model.num_elements(); ++e)
    for (int n : {model.elements()[e].n1, model.elements()[e].n2})
      half[n] = std::min(half[n], 0.5 * model.section_of(e).contact_width());
  return half;
}

// The contact law enters through its kernel (contact_law_kernel.hpp): RoomContact, and the Simulation
// that holds it, are one type whatever the law.
class RoomContact {
 public:
  // The partners of a body's pair forces that are not bodies (PairForce::body_b).
  static constexpr int floor_id = PairForce::floor_id, wall_id = PairForce::wall_id,
                       obstacle_id = PairForce::obstacle_id, ceiling_id = PairForce::ceiling_id;
  static int pair_id(const RigidPlane& pl) { return pl.is_ceiling ? ceiling_id : pl.is_wall ? wall_id : floor_id; }
  // Candidate pairs come from boxes inflated by `margin`; the broad phase runs again as soon as any
  // node has moved more than margin / 2 since the last run (two capsules can then have approached by
  // at most the margin, so no contact is missed), checked at every evaluation in O(nodes).
  double margin = 0.01;  // m
  bool item_contact = true;
  // Floor and wall contacts inside the implicit step (their tangents in each body's solve, the forces
  // re-evaluated at the end of a carried-over step). false: every contact force is a load evaluated
  // at the step's predictor, as the paper's code does (docs/contact/implicit_contact.md).
  bool implicit = true;
  // Item-item pairs between two flexible implicit items inside the step too (the simulation solves the
  // two items together: docs/contact/implicit_contact.md, "Flexible groups"). Off by default: exact on
  // the closed forms, but a group's dense system has three unknowns per pair node, and two panel grids
  // on each other (configuration 3's stacked cabinets) cost about half a second of CPU a step
  // (measured; open, issue 52).
  bool flexible_pairs_implicit = false;

  RoomContact() = default;
  // With a law object (any ContactLawPolicy; the paper's law by default) or a kernel already made.
  template <class Law = PaperLaw>
    requires(!std::is_convertible_v<Law, std::shared_ptr<const ContactLawKernel>>)
  RoomContact(const Model& model, std::vector<BodyContact> bodies, std::vector<RigidPlane> planes, Law law = {})
      : RoomContact(model, std::move(bodies), std::move(planes), make_contact_law_kernel(std::move(law))) {}
  RoomContact(const Model& model, std::vector<BodyContact> bodies, std::vector<RigidPlane> planes,
              std::shared_ptr<const ContactLawKernel> law)
      : law_(std::move(law)), bodies_(std::move(bodies)), planes_(std::move(planes)) {
    if (!law_) throw ModelError("RoomContact: no contact law (a null kernel)");
    per_node_mask_ = law_->per_node_mask();
    if (static_cast<int>(bodies_.size()) != model.num_bodies())
      throw ModelError("RoomContact: " + std::to_string(bodies_.size()) + " body contact records for " +
                       std::to_string(model.num_bodies()) + " bodies");
    for (const auto& b : bodies_) {
      law_->validate(b.floor);
      law_->validate(b.wall);
      law_->validate(b.item);
    }
    half_width_ = plane_contact_distances(model);
    caster_.assign(model.num_nodes(), 0);
    for (const auto& b : bodies_)
      for (int n : b.caster_nodes) caster_.at(n) = 1;
    plane_node_.assign(model.num_nodes(), 1);
    restraints_of_.resize(bodies_.size());
    select_plane_nodes();
    support_.resize(bodies_.size());
    rigid_.assign(bodies_.size(), 0);
    share_.assign(static_cast<size_t>(model.num_nodes()) * planes_.size(), 1.0);
    node_state_.assign(static_cast<size_t>(model.num_nodes()) * planes_.size(), ContactState{});
    node_trial_ = node_state_;
    // Item-item pairs keep a history when the law has one, or when any friction sticks by return mapping.
    const bool law_has_history = law_->has_history();
    pair_history_ = law_has_history;
    for (const auto& b : bodies_) pair_history_ = pair_history_ || b.item.stick_length > 0;
    // A body's floor and wall contacts keep a history on the same terms. Without one the surface
    // points' states are written by the law and never read: they are neither copied nor committed.
    for (const auto& b : bodies_)
      plane_history_.push_back(law_has_history || b.floor.stick_length > 0 || b.wall.stick_length > 0);
  }
  void add_obstacle(MeshObstacle obstacle) {
    obstacles_.push_back(std::move(obstacle));
    ++nodes_read_revision_;
  }
  // A rigid capsule fixed to the table (a person as an obstacle, harm/occupant.hpp): every node within
  // its member's half width of the surface is pushed out, as by a mesh obstacle (the body's wall
  // parameters, explicit); its forces are reported per body as PairForce::capsule_id(id).
  void add_capsule(const Capsule& capsule, int id);
  // Fastening devices (restraints/): each one's force at its node, in f and (implicit) inside the step as
  // a floor contact's, its regime compared within the step as a contact's status. Before the first step.
  void set_restraints(RestraintSet restraints);
  const RestraintSet& restraints() const { return restraints_; }

  // A body whose nodes keep their places relative to each other (Simulation::set_rigid calls this):
  // only the vertices of its nodes' convex hull are tested against the floor and walls, those of the
  // face turned towards a plane each with the penalty of its share of that face's nodes
  // (docs/contact/contact.md, "Rigid bodies"). rigid = false: every node again.
  void set_rigid(const Model& model, int body, bool rigid = true) { set_rigid(model, std::vector<int>{body}, rigid); }
  // Several bodies at once: the room's geometry (surface points, plane nodes, hull pairs) is made again
  // once, not once per body (a room of n items set up in n^2 or worse).
  void set_rigid(const Model& model, const std::vector<int>& bodies, bool rigid = true) {
    if (support_.empty()) return;  // default-constructed: no bodies, nothing to test
    for (int body : bodies) rigid_.at(body) = rigid;
    for (int body : bodies) set_centre_line_geometry(model, body);
    if (surface_on_) rebuild_surface_points(model);
    select_plane_nodes();
    update_hull_pairs(model);
    ++nodes_read_revision_;
  }
  // Floor and wall contact at the members' surfaces (true) or their centre lines (false, the paper's),
  // for every body: a rigid body's support points become the hull of cubes of half a member's width
  // around its nodes, a flexible body's nodes the corners of such a cube each (docs/contact/contact.md,
  // "At the surface"). Before the first step (the contacts' history starts again).
  void set_surface(const Model& model, bool on = true) {
    surface_on_ = on;
    if (support_.empty()) return;
    for (int b = 0; b < static_cast<int>(bodies_.size()); ++b) set_centre_line_geometry(model, b);
    rebuild_surface_points(model);
    select_plane_nodes();
    update_hull_pairs(model);
    ++nodes_read_revision_;
  }
  bool surface() const { return surface_on_; }
  // Item-item contact of two rigid bodies by their hulls (true) or by their members' element pairs
  // (false, the default): a few points where one hull's face meets the other's, instead of hundreds of
  // element pairs. A pair whose hulls overlap at rest (a chair under a desk: the desk's hull holds
  // its knee space) and a flat body (no hull) keep their element pairs. Before the first step.
  void set_rigid_pair_hulls(const Model& model, bool on = true) {
    hulls_on_ = on;
    update_hull_pairs(model);
    ++nodes_read_revision_;
  }
  bool rigid_pair_hulls() const { return hulls_on_; }
  // Whether bodies a and b meet by their hulls (set_rigid_pair_hulls).
  bool hull_pair(int a, int b) const {
    if (has_hull_.empty() || a == b || !has_hull_[a] || !has_hull_[b]) return false;
    const std::pair<int, int> ab(std::min(a, b), std::max(a, b));
    return !std::binary_search(nested_pairs_.begin(), nested_pairs_.end(), ab);
  }
  // The nodes of `body` an evaluation reads (positions, rotations, velocities) and puts forces on,
  // ascending: its nodes against planes, its surface points' nodes and its long axis. False when any
  // node may be read: item pairs by their members (the broad phase watches every node) or mesh
  // obstacles. A simulation places a rigid body's other nodes only when they are read from outside
  // (Simulation::RigidFields); nodes_read_revision() changes whenever the answer may.
  bool nodes_read(const Model& model, int body, std::vector<int>& out) const {
    out.clear();
    if (!obstacles_.empty() || !capsules_.empty() || (model.num_bodies() > 1 && (!hulls_on_ || any_element_pairs_))) return false;
    for (int n : model.body(body).nodes)
      if (plane_node_[n]) out.push_back(n);
    if (body < static_cast<int>(surface_groups_.size()))
      for (const SurfaceGroup& g : surface_groups_[body]) {
        if (g.node >= 0) out.push_back(g.node);
        for (int sp : g.points) out.push_back(surface_points_[sp].node);
      }
    for (int n : {bodies_[body].long_axis_node_a, bodies_[body].long_axis_node_b})
      if (n >= 0) out.push_back(n);
    for (int i : restraints_of_[body]) out.push_back(restraints_[i].node_on(body));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return true;
  }
  long nodes_read_revision() const { return nodes_read_revision_; }
  // The support points at the members' surfaces (all bodies, in body order).
  const std::vector<detail::SurfacePoint>& surface_points() const { return surface_points_; }
  // The nodes tested against the floor and walls (all but rigid bodies' inner nodes), ascending.
  const std::vector<int>& plane_nodes() const { return plane_nodes_; }

  // Seconds spent, accumulated over every evaluation: nodes against planes, the broad phase (boxes
  // and candidate pairs, when it re-runs), the narrow phase with the law on the candidates, and
  // nodes against mesh obstacles.
  struct Timings {
    double planes = 0, broad = 0, pairs = 0, obstacles = 0;
  };
  const Timings& timings() const { return timings_; }

  void add_forces(const ContactView& view, Eigen::VectorXd& f) {
    using clock = std::chrono::steady_clock;
    const auto seconds_since = [](clock::time_point t0) {
      return std::chrono::duration<double>(clock::now() - t0).count();
    };
    const auto t_planes = clock::now();
    const Model& model = view.model;
    pair_forces_.clear();
    pair_trial_.clear();
    pair_tangents_.clear();
    implicit_pairs_.clear();
    hull_contacts_.clear();
    active_ = 0;
    plane_contacts(view, f);
    timings_.planes += seconds_since(t_planes);
    if (item_contact && model.num_bodies() > 1) {
      if (!hulls_on_ || any_element_pairs_) element_contacts(view, f);
      if (hulls_on_) hull_contacts(view, f);
    }
    if (!obstacles_.empty() || !capsules_.empty()) {
      const auto t_obstacles = clock::now();
      if (!obstacles_.empty()) obstacle_contacts(view, f);
      if (!capsules_.empty()) capsule_contacts(view, f);
      timings_.obstacles += seconds_since(t_obstacles);
    }
  }

  // The fastest speed (m/s) at which a node or a support point closes on a floor or wall that it
  // touches, or would reach within view.dt at that speed: what the simulation's impact sub-steps
  // resolve (SimulationOptions::max_impact_substeps). Item-item contacts are not looked at.
  double fastest_closing(const ContactView& view) const {
    double fastest = 0;
    const auto closing = [&](const Vec3& x, const Vec3& v, double gap_offset) {
      for (const RigidPlane& pl : planes_) {
        const double speed = -v.dot(pl.normal);
        if (speed > fastest && (x - pl.point).dot(pl.normal) - gap_offset <= speed * view.dt &&
            pl.contains_projection(x))
          fastest = speed;
      }
    };
    for (int n : plane_nodes_) closing(view.x[n], view.v.template segment<3>(6 * n), half_width_[n]);
    for (const auto& pt : surface_points_)
      closing(point_now(view, point_index(pt)), point_velocity(view, pt.node, (*view.rotations)[pt.node] * pt.arm0), 0);
    return fastest;
  }

  // The linearisations of the floor and wall forces of the last add_forces (none unless implicit).
  const std::vector<NodalContactTangent>& nodal_tangents() const { return tangents_; }
  // The linearisations of the item-item pairs between two implicit bodies, both rigid or (with
  // flexible_pairs_implicit) both flexible (the simulation solves such bodies together), of the last
  // add_forces.
  const std::vector<PairContactTangent>& pair_tangents() const { return pair_tangents_; }
  // The floor and wall forces of the last add_forces on implicit bodies' nodes (node, force; a node
  // against two planes appears twice).
  const std::vector<std::pair<int, Vec6>>& plane_forces() const { return plane_applied_; }

  // One implicit body's floor and wall contacts at another state of the step (a trial of its solve),
  // from the committed history, nothing recorded: each contact's force and linearisation, and the
  // status (status_of) of every (node, plane) of the body. A body whose contact is not implicit has
  // none (empty status). last_status(body) gives the statuses of the last add_forces, in the same order.
  struct BodyPlaneContacts {
    std::vector<NodalContactTangent> tangents;  // per contact (a node against two planes: twice)
    std::vector<Vec6> forces;                   // the force and moment of each on its node
    std::vector<char> status;
  };
  BodyPlaneContacts body_plane_contacts(const ContactView& view, int body) const {
    BodyPlaneContacts out;
    if (!implicit || !bodies_[body].implicit) return out;
    any_body_plane_force(view, body, [&](int n, std::size_t, const ContactForce& cf) {
      out.status.push_back(status_of(cf));
      if (cf.in_contact) {
        out.tangents.push_back({n, regime_of(cf), cf.K, cf.C, view.x[n], Vec3(view.v.template segment<3>(6 * n))});
        out.forces.push_back(wrench(cf.on_a));
      }
      return false;
    }, [&](const detail::SurfacePoint& pt, std::size_t, const PointContact& pc) {
      out.status.push_back(status_of(pc.force));
      if (pc.force.in_contact) {
        out.tangents.push_back({pt.node, regime_of(pc.force), pc.force.K, pc.force.C, pc.x, pc.v, pt.arm0});
        out.forces.push_back(wrench(pc.force.on_a, pc.arm));
      }
      return false;
    });
    for (int i : restraints_of_[body]) {
      if (restraints_[i].between_items()) continue;  // a joint: an item pair's (joint_force)
      const RestraintResponse r = restraint_now(view, i);
      out.status.push_back(static_cast<char>(r.state.regime));
      if (r.state.regime == RestraintRegime::idle || r.state.broken()) continue;
      out.tangents.push_back(restraint_tangent(view, i, r));
      out.forces.push_back(wrench(r.on_item));
    }
    return out;
  }
  // Whether any of the body's (node, plane) statuses at the view's state differs from the last
  // add_forces' (no allocation: called for every implicit body at every step).
  bool body_plane_status_changed(const ContactView& view, int body) const {
    if (!implicit || !bodies_[body].implicit || plane_status_.empty()) return false;
    const bool planes_changed = any_body_plane_force(view, body, [&](int n, std::size_t p, const ContactForce& cf) {
      return status_of(cf) != plane_status_[n * planes_.size() + p];
    }, [&](const detail::SurfacePoint& pt, std::size_t p, const PointContact& pc) {
      return status_of(pc.force) != point_status_[point_index(pt) * planes_.size() + p];
    });
    return planes_changed || std::any_of(restraints_of_[body].begin(), restraints_of_[body].end(), [&](int i) {
      return !restraints_[i].between_items() && static_cast<char>(restraint_now(view, i).state.regime) != restraint_status_[i];
    });
  }
  std::vector<char> last_status(const Model& model, int body) const {
    std::vector<char> status;
    if (!implicit || !bodies_[body].implicit || plane_status_.empty()) return status;
    for (size_t p = 0; p < planes_.size(); ++p) {
      for (int n : model.body(body).nodes)
        if (plane_node_[n]) status.push_back(plane_status_[n * planes_.size() + p]);
      if (!surface_groups_.empty())
        for (const auto& group : surface_groups_[body])
          for (int sp : group.points) status.push_back(point_status_[sp * planes_.size() + p]);
    }
    for (int i : restraints_of_[body]) if (!restraints_[i].between_items()) status.push_back(restraint_status_[i]);
    return status;
  }

  // Floor and wall forces again at the end state of a carried-over step: their forces of the last
  // evaluation are taken out of f and the new ones put in; the history to commit is the new one.
  // Bodies whose contact is explicit keep their predictor evaluation (forces, history, reported pairs).
  // Item-item pairs solved inside the step are evaluated again too, for their history and the
  // reported pair forces (their forces in f are not changed: the simulation carries their linearisation).
  void end_of_step(const ContactView& view, Eigen::VectorXd& f);

  void commit() {
    ++steps_;
    restraints_.commit(evaluated_at_);
    // No copy back into node_trial_: add_forces overwrites every entry of it (reset out of contact,
    // the committed state in contact) before the law reads it.
    node_state_.swap(node_trial_);
    commit_point_states();
    pair_state_.swap(pair_trial_);  // pairs out of contact forget their history
    pair_trial_.clear();
  }

  // Its history for a checkpoint (core/checkpoint.hpp): the committed and trial contact states, the
  // broad phase's candidates and the positions it ran at, and the last evaluation's forces, slopes and
  // statuses (the step that follows reads them).
  template <class Self, class Archive>
    requires std::is_same_v<std::remove_const_t<Self>, RoomContact>
  friend void transfer_state(Self& c, Archive& ar) {
    ar(c.node_state_, c.node_trial_, c.pair_state_, c.pair_trial_, c.candidates_, c.x_broad_);
    ar(c.pair_forces_, c.tangents_, c.pair_tangents_, c.implicit_pairs_, c.hull_contacts_, c.plane_applied_,
       c.plane_status_, c.share_);
    ar(c.point_state_, c.point_trial_, c.point_status_, c.point_share_, c.group_near_, c.group_state_live_);
    ar(c.steps_, c.broad_runs_, c.active_);
    ar(c.restraints_, c.restraint_status_, c.restraints_applied_, c.evaluated_at_);
    if constexpr (!Archive::saving) c.pair_force_index_.clear();  // of the pairs before the load
  }

  const std::vector<PairForce>& pair_forces() const { return pair_forces_; }
  int active_contacts() const { return active_; }
  long broad_phase_runs() const { return broad_runs_; }
  std::size_t candidate_pairs() const { return candidates_.size(); }
  const ContactLawKernel& law() const { return *law_; }

 private:
  struct SurfaceGroup {
    detail::SupportGeometry geometry;  // a rigid body's envelope, or one node's cube
    std::vector<int> points;           // indices into surface_points_
    int node = -1;                     // a flexible body's cube: its node
    int id = 0;                        // its place among every body's groups
    std::vector<Vec3> rest_normals;    // a node's cube: its faces' unit outward normals at rest
  };

  // Nodes against planes (floor, walls): forces into f, and (implicit) their tangents; only the
  // implicit bodies' nodes when only_implicit.
  void plane_contacts(const ContactView& view, Eigen::VectorXd& f, bool only_implicit = false) {
    const Model& model = view.model;
    tangents_.clear();
    plane_applied_.clear();
    update_reach(view, only_implicit);
    update_support_shares(view, only_implicit);
    plane_status_.resize(share_.size());
    for (int n : plane_nodes_) {
      const int body = model.node(n).body;
      if (only_implicit && !bodies_[body].implicit) continue;
      for (size_t p = 0; p < planes_.size(); ++p) {
        const size_t si = n * planes_.size() + p;
        // Laws with history (stick-slip) start every evaluation from the committed state; commit()
        // keeps the trial of the last evaluation, so Newton iterations do not advance the history.
        node_trial_[si] = node_state_[si];  // out of contact: reset (history forgotten) by the law
        const ContactForce cf = node_plane_force(view, n, p, share_[si], node_trial_[si]);
        plane_status_[si] = status_of(cf);
        if (!cf.in_contact) continue;
        const Vec3& x = view.x[n];
        f.template segment<3>(6 * n) += cf.on_a;
        add_pair_force(body, pair_id(planes_[p]), cf.on_a);
        ++active_;
        if (!implicit || !bodies_[body].implicit) continue;
        plane_applied_.emplace_back(n, wrench(cf.on_a));
        const Vec3 v = view.v.template segment<3>(6 * n);
        if (!tangents_.empty() && tangents_.back().node == n && tangents_.back().at_node()) {
          tangents_.back().K += cf.K;
          tangents_.back().C += cf.C;
          tangents_.back().status += regime_of(cf);
        } else {
          tangents_.push_back({n, regime_of(cf), cf.K, cf.C, x, v});
        }
      }
    }
    surface_point_contacts(view, f, only_implicit);
    restraint_forces(view, f, only_implicit);
  }

  // Surface points against planes (set_surface): as plane_contacts, each force at its point. A flexible
  // body's node far from a plane (its cube cannot reach it) skips its corners.
  void surface_point_contacts(const ContactView& view, Eigen::VectorXd& f, bool only_implicit) {
    const size_t np = planes_.size();
    for (std::size_t body = 0; body < surface_groups_.size(); ++body) {
      if (only_implicit && !bodies_[body].implicit) continue;
      for (int g : reach_[body].groups) {
        const SurfaceGroup& group = surface_groups_[body][g];
        const char* near = &group_near_[group.id * np];
        for (int sp : group.points)
          for (size_t p = 0; p < np; ++p)
            if (near[p]) surface_point_contact(view, f, sp, p);
      }
    }
  }
  // Which cubes are within reach of each plane now (group_near_), for the bodies evaluated: those of a
  // body's list (cubes_in_reach) tested, the others out of reach. Out of reach now: the cube's points'
  // statuses go to 0 (once); their trial states are not read (commit_point_states empties their
  // committed states instead).
  void update_reach(const ContactView& view, bool only_implicit) {
    const size_t np = planes_.size();
    for (std::size_t body = 0; body < surface_groups_.size(); ++body) {
      if (only_implicit && !bodies_[body].implicit) continue;
      for (int g : cubes_in_reach(view, body)) {
        const SurfaceGroup& group = surface_groups_[body][g];
        for (size_t p = 0; p < np; ++p) set_near(group, p, !beyond_reach(view, group, p));
      }
    }
  }
  void set_near(const SurfaceGroup& group, size_t p, bool now) {
    const size_t np = planes_.size();
    char& near = group_near_[group.id * np + p];
    if (!now && near)
      for (int sp : group.points) point_status_[sp * np + p] = 0;
    near = now;
  }
  // A body's cubes that may reach a plane: those whose node was within 1.75 c + margin of one when the
  // list was made, made again as soon as one of the body's nodes has moved more than `margin` since
  // (the others cannot have come within 1.75 c). A rigid body's one hull is always on it.
  const std::vector<int>& cubes_in_reach(const ContactView& view, std::size_t body) {
    ReachList& r = reach_[body];
    const auto& groups = surface_groups_[body];
    if (groups.size() == 1 && groups[0].node < 0) return r.groups;  // set by rebuild_surface_points
    bool moved = r.x.size() != groups.size();
    for (std::size_t i = 0; i < groups.size() && !moved; ++i)
      moved = (view.x[groups[i].node] - r.x[i]).squaredNorm() > r.margin * r.margin;
    if (!moved) return r.groups;
    r.margin = margin;  // the list's own: `margin` may be changed between two evaluations
    r.x.resize(groups.size());
    r.groups.clear();
    for (std::size_t i = 0; i < groups.size(); ++i) {
      const SurfaceGroup& group = groups[i];
      const Vec3& x = view.x[group.node];
      r.x[i] = x;
      bool can_reach = false;
      for (const RigidPlane& pl : planes_)
        can_reach = can_reach || (x - pl.point).dot(pl.normal) <= 1.75 * half_width_[group.node] + r.margin + 1e-9;
      if (can_reach) {
        r.groups.push_back(static_cast<int>(i));
        continue;
      }
      const char* live = &group_state_live_[group.id * planes_.size()];
      for (size_t p = 0; p < planes_.size(); ++p) set_near(group, p, false);
      if (std::any_of(live, live + planes_.size(), [](char c) { return c != 0; }))
        left_reach_.emplace_back(static_cast<int>(body), static_cast<int>(i));  // its history: emptied at commit
    }
    return r.groups;
  }
  void surface_point_contact(const ContactView& view, Eigen::VectorXd& f, int sp, size_t p) {
    const auto& pt = surface_points_[sp];
    const int n = pt.node, body = view.model.node(n).body;
    const size_t si = sp * planes_.size() + p;
    ContactState scratch;
    ContactState& state = plane_history_[body] ? point_trial_[si] : scratch;
    if (plane_history_[body]) state = point_state_[si];
    const PointContact pc = point_plane_force(view, pt, p, point_share_[si], state);
    const ContactForce& cf = pc.force;
    point_status_[si] = status_of(cf);
    if (!cf.in_contact) return;
    const Vec3 moment = pc.arm.cross(cf.on_a);
    f.template segment<3>(6 * n) += cf.on_a;
    f.template segment<3>(6 * n + 3) += moment;
    add_pair_force(body, pair_id(planes_[p]), cf.on_a);
    ++active_;
    if (!implicit || !bodies_[body].implicit) return;
    Vec6 w;
    w << cf.on_a, moment;
    plane_applied_.emplace_back(n, w);
    tangents_.push_back({n, regime_of(cf), cf.K, cf.C, pc.x, pc.v, pt.arm0});
  }
  // Whether a flexible body's node is so far from plane p that no corner of its cube reaches it (its
  // half diagonal is sqrt(3) half widths).
  bool beyond_reach(const ContactView& view, const SurfaceGroup& group, size_t p) const {
    if (group.node < 0) return false;
    const RigidPlane& pl = planes_[p];
    return (view.x[group.node] - pl.point).dot(pl.normal) > 1.75 * half_width_[group.node];
  }
  // The surface points' committed states: a cube's last evaluated trials where it was within reach of
  // the plane, no history where not. Only states that may hold a history are written: those of the
  // cubes in reach lists, and of cubes that left them since the last commit.
  void commit_point_states() {
    for (std::size_t body = 0; body < surface_groups_.size(); ++body)
      if (plane_history_[body])
        for (int g : reach_[body].groups) commit_point_states(surface_groups_[body][g]);
    for (const auto& [body, g] : left_reach_) commit_point_states(surface_groups_[body][g]);
    left_reach_.clear();
  }
  void commit_point_states(const SurfaceGroup& group) {
    const size_t np = planes_.size();
    for (size_t p = 0; p < np; ++p) {
      const size_t gp = group.id * np + p;
      if (group_near_[gp]) {
        for (int sp : group.points) point_state_[sp * np + p] = point_trial_[sp * np + p];
        group_state_live_[gp] = 1;
      } else if (group_state_live_[gp]) {
        for (int sp : group.points) point_state_[sp * np + p] = ContactState{};
        group_state_live_[gp] = 0;
      }
    }
  }

  // A surface point against a plane: its position and velocity now (its offset turned with its node),
  // the offset, and the law's force, the point standing for `share` nodes.
  struct PointContact {
    Vec3 x, v, arm;
    ContactForce force;
  };
  PointContact point_plane_force(const ContactView& view, const detail::SurfacePoint& pt, size_t p, double share,
                                 ContactState& state) const {
    if (!view.rotations)
      throw ModelError("RoomContact: contact at the members' surfaces needs the nodes' rotations in the ContactView");
    const int n = pt.node;
    PointContact pc;
    pc.arm = (*view.rotations)[n] * pt.arm0;
    pc.x = view.x[n] + pc.arm;
    pc.v = view.v.template segment<3>(6 * n) + Vec3(view.v.template segment<3>(6 * n + 3)).cross(pc.arm);
    const RigidPlane& pl = planes_[p];
    // The law sees the node's distance as if the point were its contact surface: the point's distance
    // to the plane plus the contact distance, so that contact starts when the point reaches the plane.
    const double L = half_width_[n], l = (pc.x - pl.point).dot(pl.normal) + L;
    if (l > L || !pl.contains_projection(pc.x)) {
      state = ContactState{};
      return pc;
    }
    const NodeOnPlane node{pc.x, pc.v, L, view.dt, long_axis(view.model.node(n).body, view), Vec3::Zero()};
    pc.force = detail::node_force(*law_, node, l, pl.normal, plane_params(view.model, n, p, share), state);
    return pc;
  }

  // One node against one plane, standing for `share` nodes, from the history in `state` (advanced
  // in place; reset when apart).
  ContactForce node_plane_force(const ContactView& view, int n, size_t p, double share, ContactState& state) const {
    const RigidPlane& pl = planes_[p];
    const Vec3& x = view.x[n];
    const double l = (x - pl.point).dot(pl.normal);
    if (l > half_width_[n] || !pl.contains_projection(x)) {
      state = ContactState{};
      return {};
    }
    const int body = view.model.node(n).body;
    // The tested node-against-plane evaluation (contact_laws.hpp), on this plane's distance; the
    // plane's own extent test above decides whether a wall panel is reached.
    const NodeOnPlane node{x, view.v.template segment<3>(6 * n), half_width_[n], view.dt, long_axis(body, view),
                           Vec3::Zero()};
    return detail::node_force(*law_, node, l, pl.normal, plane_params(view.model, n, p, share), state);
  }
  // The parameters of node n's contact with plane p, standing for `share` nodes.
  ContactParams plane_params(const Model& model, int n, size_t p, double share) const {
    const RigidPlane& pl = planes_[p];
    const int body = model.node(n).body;
    // The ceiling is met as a wall is: a body's top is no footing (neither its floor friction nor its
    // casters' applies).
    ContactParams prm = pl.is_floor() ? bodies_[body].floor : bodies_[body].wall;
    if (pl.is_floor() && caster_[n] && bodies_[body].caster_mu >= 0) {
      prm.mu = prm.mu_long = prm.mu_short = bodies_[body].caster_mu;
    }
    // Standing for `share` nodes: every force coefficient the law declares per_node `share` times one node's.
    if (share != 1.0) prm.scale_per_node(share, per_node_mask_);
    return prm;
  }

  // A contact's status: 0 apart, 1 pushing (or any force, for a law that may pull), 2 touching with
  // its force clamped at zero (a dashpot pulling harder than its spring pushes).
  char status_of(const ContactForce& cf) const {
    if (!cf.in_contact) return 0;
    return cf.normal > 0 || !clamps_tensile() ? 1 : 2;
  }
  // Its regime for a reused factorisation (NodalContactTangent::status): stick, slip or clamped.
  int regime_of(const ContactForce& cf) const { return contact_status_code(cf.sticking, status_of(cf) == 2); }
  bool clamps_tensile() const { return law_->clamps_tensile(); }

  // Each rigid body's support points against each plane: those of the hull face turned towards the
  // plane take that face's share, the others their own node's (a corner the body tips onto).
  void update_support_shares(const ContactView& view, bool only_implicit) {
    const size_t np = planes_.size();
    for (const auto& sg : support_) {
      if (sg.faces.empty()) continue;
      for (size_t p = 0; p < np; ++p) {
        for (int n : sg.vertices) share_[n * np + p] = 1.0;
        if (const auto* face = sg.face_towards([&](int n) -> const Vec3& { return view.x[n]; }, planes_[p].normal))
          for (int n : face->vertices) share_[n * np + p] = face->share;
      }
    }
    for (std::size_t body = 0; body < surface_groups_.size(); ++body) {
      if (only_implicit && !bodies_[body].implicit) continue;
      for (int g : reach_[body].groups) {
        const SurfaceGroup& group = surface_groups_[body][g];
        if (group.geometry.faces.empty()) continue;
        for (size_t p = 0; p < np; ++p) {
          if (!group_near_[group.id * np + p]) continue;
          for (int sp : group.points) point_share_[sp * np + p] = 1.0;
          if (const auto* face = face_towards(view, group, planes_[p].normal))
            for (int sp : face->vertices) point_share_[sp * np + p] = face->share;
        }
      }
    }
  }
  // The group's face that looks most directly into a plane of unit normal n. A node's cube turns with
  // its node, so its faces' normals are their rest normals turned: compare those with n turned back
  // (one product instead of three corner positions per face).
  const detail::SupportFace* face_towards(const ContactView& view, const SurfaceGroup& group, const Vec3& n) const {
    if (group.node < 0) return group.geometry.face_towards([&](int sp) { return point_now(view, sp); }, n);
    const Vec3 m = (*view.rotations)[group.node].transpose() * n;
    const detail::SupportFace* best = nullptr;
    double best_cos = -2;
    for (std::size_t i = 0; i < group.geometry.faces.size(); ++i) {
      const double c = -group.rest_normals[i].dot(m);
      if (c > best_cos) best_cos = c, best = &group.geometry.faces[i];
    }
    return best;
  }
  // A surface point's position now.
  Vec3 point_now(const ContactView& view, int sp) const {
    const auto& pt = surface_points_[sp];
    return view.x[pt.node] + (*view.rotations)[pt.node] * pt.arm0;
  }
  int point_index(const detail::SurfacePoint& pt) const { return static_cast<int>(&pt - surface_points_.data()); }
  static Vec6 wrench(const Vec3& force, const Vec3& arm = Vec3::Zero()) {
    Vec6 w;
    w << force, arm.cross(force);
    return w;
  }

  bool surface_at(int body) const { return surface_on_ && !bodies_[body].at_nodes; }
  // A body's contact at the centre lines: a rigid body's hull vertices, a flexible body's every node;
  // none with set_surface (its surface points instead) unless the body asks for its nodes.
  void set_centre_line_geometry(const Model& model, int body) {
    const auto& nodes = model.body(body).nodes;
    const bool rigid = rigid_[body];
    const bool surface = surface_at(body);
    support_.at(body) = rigid && !surface ? detail::support_geometry(model, nodes) : detail::SupportGeometry{};
    for (int n : nodes) plane_node_[n] = !rigid && !surface;
    for (int n : support_[body].vertices) plane_node_[n] = 1;
  }

  // Every body's surface geometry again (set_rigid, set_surface; before the first step, so no history
  // is lost): a rigid body's one hull, a flexible body's cube per node.
  void rebuild_surface_points(const Model& model) {
    surface_points_.clear();
    surface_groups_.assign(bodies_.size(), {});
    group_count_ = 0;
    if (surface_on_) {
      const std::vector<Mat3> axes = detail::cube_axes(model);
      for (std::size_t b = 0; b < bodies_.size(); ++b) {
        const auto& nodes = model.body(static_cast<int>(b)).nodes;
        if (!surface_at(static_cast<int>(b))) continue;
        if (rigid_[b]) surface_groups_[b].push_back(surface_group(model, nodes, axes, -1));
        else
          for (int n : nodes) surface_groups_[b].push_back(surface_group(model, {n}, axes, n));
      }
    }
    const std::size_t m = surface_points_.size() * planes_.size();
    point_state_.assign(m, ContactState{});
    point_trial_ = point_state_;
    point_status_.assign(m, 0);
    point_share_.assign(m, 1.0);
    // Per group and plane: within reach at its last evaluation; whether its points' committed states
    // may hold a history (commit_point_states).
    group_near_.assign(group_count_ * planes_.size(), 0);
    group_state_live_ = group_near_;
    reach_.assign(bodies_.size(), ReachList{});
    left_reach_.clear();
    for (std::size_t b = 0; b < bodies_.size(); ++b)
      if (surface_groups_[b].size() == 1 && surface_groups_[b][0].node < 0) reach_[b].groups = {0};
  }
  SurfaceGroup surface_group(const Model& model, const std::vector<int>& nodes, const std::vector<Mat3>& axes, int node) {
    SurfaceGroup group;
    group.node = node;
    group.id = group_count_++;
    const std::size_t first = surface_points_.size();
    // The geometry names the points by their place in the whole list.
    group.geometry = detail::surface_support_geometry(model, nodes, half_width_, axes, surface_points_);
    for (std::size_t i = first; i < surface_points_.size(); ++i) group.points.push_back(static_cast<int>(i));
    if (node >= 0)
      for (const auto& face : group.geometry.faces) {
        const auto arm = [&](int k) -> const Vec3& { return surface_points_[face.frame[k]].arm0; };
        group.rest_normals.push_back((arm(1) - arm(0)).cross(arm(2) - arm(0)).normalized());
      }
    return group;
  }

  void select_plane_nodes() {
    plane_nodes_.clear();
    for (size_t n = 0; n < plane_node_.size(); ++n)
      if (plane_node_[n]) plane_nodes_.push_back(static_cast<int>(n));
  }

  Vec3 long_axis(int body, const ContactView& view) const {
    const auto& b = bodies_[body];
    if (b.long_axis_node_a < 0 || b.long_axis_node_b < 0) return Vec3::Zero();
    Vec3 a = view.x[b.long_axis_node_b] - view.x[b.long_axis_node_a];
    a.z() = 0;
    const double n = a.norm();
    return n > 1e-9 ? Vec3(a / n) : Vec3::Zero();
  }

  void add_pair_force(int a, int b, const Vec3& f) {
    if (PairForce* pf = find_pair_force(a, b)) {
      pf->force_on_a += f;
      return;
    }
    pair_forces_.push_back({a, b, f});
    if (!pair_force_index_.empty()) pair_force_index_.emplace(pair_force_key(a, b), pair_forces_.size() - 1);
  }
  // A handful of pairs is scanned; a room of thousands of items on the floor has thousands, found by
  // a hash index (a scan made each step quadratic in the items). The index is made again whenever
  // pair_forces_ was changed otherwise (cleared, filtered, loaded: its size then differs).
  PairForce* find_pair_force(int a, int b) {
    constexpr std::size_t scan_limit = 32;
    if (pair_forces_.size() <= scan_limit) {
      if (!pair_force_index_.empty()) pair_force_index_.clear();
      for (auto& pf : pair_forces_)
        if (pf.body_a == a && pf.body_b == b) return &pf;
      return nullptr;
    }
    if (pair_force_index_.size() != pair_forces_.size()) {
      pair_force_index_.clear();
      for (std::size_t i = 0; i < pair_forces_.size(); ++i)
        pair_force_index_.emplace(pair_force_key(pair_forces_[i].body_a, pair_forces_[i].body_b), i);
    }
    const auto it = pair_force_index_.find(pair_force_key(a, b));
    return it == pair_force_index_.end() ? nullptr : &pair_forces_[it->second];
  }
  static std::uint64_t pair_force_key(int a, int b) {
    return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
  }

  // f(node, plane, force) for each of a body's (node, plane) contacts, evaluated at the view's state
  // from the committed history, plane by plane and node by node; true as soon as f returns true.
  // g(point, plane, contact) likewise for its surface points, after its nodes on each plane.
  template <class F, class G>
  bool any_body_plane_force(const ContactView& view, int body, F&& f, G&& g) const {
    const auto& sg = support_[body];
    const auto share_on = [](const detail::SupportFace* face, int i) {
      return face && std::find(face->vertices.begin(), face->vertices.end(), i) != face->vertices.end() ? face->share : 1.0;
    };
    for (size_t p = 0; p < planes_.size(); ++p) {
      const detail::SupportFace* face =
          sg.faces.empty() ? nullptr : sg.face_towards([&](int n) -> const Vec3& { return view.x[n]; }, planes_[p].normal);
      for (int n : view.model.body(body).nodes) {
        if (!plane_node_[n]) continue;
        ContactState st = node_state_[n * planes_.size() + p];
        if (f(n, p, node_plane_force(view, n, p, share_on(face, n), st))) return true;
      }
      if (surface_groups_.empty()) continue;
      for (const auto& group : surface_groups_[body]) {
        if (beyond_reach(view, group, p)) {
          for (int sp : group.points)
            if (g(surface_points_[sp], p, PointContact{})) return true;
          continue;
        }
        const detail::SupportFace* point_face =
            group.geometry.faces.empty() ? nullptr : face_towards(view, group, planes_[p].normal);
        for (int sp : group.points) {
          ContactState st = point_state_[sp * planes_.size() + p];
          if (g(surface_points_[sp], p, point_plane_force(view, surface_points_[sp], p, share_on(point_face, sp), st)))
            return true;
        }
      }
    }
    return false;
  }

  void element_contacts(const ContactView& view, Eigen::VectorXd& f);
  // The restraints' forces (of the implicit bodies only when only_implicit), as plane_contacts' (not
  // counted as contacts, not reported as wall or floor forces); a restraint's slope as a contact's.
  void restraint_forces(const ContactView& view, Eigen::VectorXd& f, bool only_implicit);
  NodalContactTangent restraint_tangent(const ContactView& view, int i, const RestraintResponse& r) const;
  void joint_force(const ContactView& view, int i, Eigen::VectorXd& f);  // a joint between items (room_restraints.hpp)
  void joint_history(const ContactView& view);
  std::pair<Vec3, Vec3> restraint_input(const ContactView& view, int i) const;
  // The segment pair of elements ea (A) and eb (B) in the view's state; L is the mean member width.
  static SegmentPair segment_pair(const ContactView& view, int ea, int eb);
  // The centre lines' distance at which two elements touch: half the sum of their widths.
  static double pair_contact_distance(const Model& model, int ea, int eb);
  ContactParams pair_params(const Model& model, int ea, int eb) const;
  // Only laws with a history (a tangential spring) keep per-pair state across steps.
  ContactState committed_pair_state(int ea, int eb) const;
  // The force a pair puts on the lower-numbered of its two bodies.
  static Vec3 reported_pair_force(int body_a, int body_b, const SegmentPairForces& nf);

  void obstacle_contacts(const ContactView& view, Eigen::VectorXd& f);
  void capsule_contacts(const ContactView& view, Eigen::VectorXd& f);
  // Node n `distance` in front of a fixed obstacle's surface (normal toward it): the law's force, explicit.
  void push_off_obstacle(const ContactView& view, int n, double distance, const Vec3& normal, int pair_id, Eigen::VectorXd& f);
  RestraintResponse restraint_now(const ContactView& view, int i) const;  // at its node's place and speed, nothing kept

  // ---- Rigid pairs by their hulls (set_rigid_pair_hulls) ----

  // One contact point of two hulls: the force acts on body_a (the incident face's) at the point and
  // -F on body_b (the reference face's); each side holds it at an offset from one of its nodes, turned
  // with the node, so that the point moves with its body. gap0: the gap at the evaluation that found
  // it; the gap at another state adds the points' relative displacement along the normal.
  struct HullContact {
    static constexpr bool checkpoint_as_bytes = true;  // core/checkpoint.hpp (no padding: 8-byte fields)
    int body_a = -1, body_b = -1, node_a = -1, node_b = -1;
    Vec3 arm_a0 = Vec3::Zero(), arm_b0 = Vec3::Zero();  // in the nodes' initial frames
    Vec3 normal0 = Vec3::UnitZ();                        // out of body_b, in node_b's initial frame
    double gap0 = 0, L = 0, share = 1;
    long long key = -1;  // its history's key (hull_key)
    long long implicit = 0;
    Vec3 reported = Vec3::Zero();  // its share of pair_forces_
  };

  // A body's hull for item-item contact: its surface points' hull at surfaces, its nodes' at centre lines.
  const detail::SupportGeometry& hull_of(int body) const;
  // A hull point's node and its offset from the node in the node's initial frame.
  std::pair<int, Vec3> hull_point(int body, int i) const;
  // The contact distance of two hulls' surfaces (at centre lines: the members' half widths) and the
  // law's L (the mean member width, as for element pairs; each body's widest member).
  double hull_distance(int a, int b) const;
  double hull_L(int a, int b) const;

  // Which body pairs meet by their hulls: both rigid with a hull (not flat), and their hulls apart at
  // the initial positions (the model's: the same on a resumed run).
  void update_hull_pairs(const Model& model);
  static constexpr double nested_overlap = 0.005;  // m: hulls overlapping more at rest are nested

  // The key of a hull contact point's history, from its kind and the hull points (or bodies) that name
  // it, each below 2^20 (update_hull_pairs checks): above every element pair's key.
  static constexpr long long hull_id_limit = 1LL << 20;
  static long long hull_key(detail::HullPointKind kind, long long p, long long q, long long r);
  static long long hull_key(const detail::HullContactPoint& pt, int inc, int ref);
  ContactState committed_hull_state(const HullContact& hc) const;

  // Every hull pair's contact points at the view's state: forces into f, their tangents (both bodies
  // implicit) for the rigid groups.
  void hull_contacts(const ContactView& view, Eigen::VectorXd& f);
  const std::vector<std::pair<int, int>>& near_hull_pairs();
  static constexpr double hull_bias = 1e-3;  // m: a's faces win ties up to this (hull_pair_contact)

  static Vec3 point_velocity(const ContactView& view, int n, const Vec3& arm);
  // A hull contact's force on body_a at the view's state, from the history in `state`.
  ContactForce hull_contact_force(const ContactView& view, const HullContact& c, ContactState& state) const;
  // F on body_a at the contact point, -F on body_b: each at its node with the moment that puts it there.
  static void apply_hull_force(const ContactView& view, const HullContact& c, const Vec3& F, Eigen::VectorXd& f);

  static long long key(int a, int b) { return (static_cast<long long>(a) << 32) | static_cast<unsigned>(b); }

  std::shared_ptr<const ContactLawKernel> law_;
  unsigned per_node_mask_ = 0;  // the law's per_node parameters (ContactParams::per_node_mask)
  std::vector<BodyContact> bodies_;
  std::vector<RigidPlane> planes_;
  std::vector<MeshObstacle> obstacles_;
  std::vector<std::pair<Capsule, int>> capsules_;  // each with its pair id (PairForce::capsule_id)
  std::vector<double> half_width_;
  std::vector<char> plane_node_;  // whether plane_contacts tests the node (a rigid body: its hull vertices)
  std::vector<int> plane_nodes_;  // those nodes, ascending
  std::vector<detail::SupportGeometry> support_;  // per body; empty unless rigid
  std::vector<double> share_;     // per node and plane: how many nodes the contact stands for
  std::vector<char> caster_;
  std::vector<ContactState> node_state_, node_trial_;
  detail::PairHistory pair_state_, pair_trial_;  // per element pair in contact
  BroadPhase broad_phase_;
  std::vector<std::pair<int, int>> candidates_;
  std::vector<PairForce> pair_forces_;
  std::unordered_map<std::uint64_t, std::size_t> pair_force_index_;  // find_pair_force: (a, b) -> index
  std::vector<NodalContactTangent> tangents_;
  std::vector<PairContactTangent> pair_tangents_;
  struct ImplicitPair {
    static constexpr bool checkpoint_as_bytes = true;  // core/checkpoint.hpp
    int ea, eb;
    Vec3 reported;  // its share of pair_forces_ at the evaluation
  };
  std::vector<ImplicitPair> implicit_pairs_;  // the pairs behind pair_tangents_
  long nodes_read_revision_ = 0;              // nodes_read: counts the changes of what it answers
  bool hulls_on_ = false;                     // set_rigid_pair_hulls
  std::vector<char> has_hull_;                // per body: rigid with a hull (empty: hulls off)
  std::vector<std::pair<int, int>> nested_pairs_;  // hull bodies (a < b, sorted) nested at rest: element pairs
  std::vector<int> hull_order_;                  // scratch of hull_contacts: hull bodies by their box's lower x
  std::vector<std::pair<int, int>> hull_candidates_;  // scratch of hull_contacts: pairs whose boxes come near
  bool any_element_pairs_ = true;             // some body pair meets by its members
  std::vector<char> hull_body_;               // per body: in a hull pair
  std::vector<Vec3> hull_x_;                  // hull vertices' positions at the evaluation, by point
  std::vector<Vec3> hull_box_lo_, hull_box_hi_;  // per hull body: its vertices' box
  std::vector<double> hull_half_width_;       // per body: its hull nodes' widest half width
  std::vector<HullContact> hull_contacts_;    // of the last add_forces
  std::vector<char> rigid_;                   // per body: set_rigid
  std::vector<std::pair<int, Vec6>> plane_applied_;  // the floor and wall forces (and moments) of the last evaluation
  // Contact at the members' surfaces (set_surface): per body its groups of points (a rigid body's hull,
  // or a flexible body's cube per node), each with its geometry over surface_points_; per point and
  // plane, as node_state_ ... for nodes.
  bool surface_on_ = false;
  std::vector<std::vector<SurfaceGroup>> surface_groups_;  // per body
  std::vector<detail::SurfacePoint> surface_points_;
  std::vector<ContactState> point_state_, point_trial_;
  std::vector<char> point_status_;
  std::vector<double> point_share_;
  std::vector<char> group_near_, group_state_live_;  // per group and plane
  struct ReachList {
    std::vector<int> groups;  // indices into the body's surface_groups_, ascending
    std::vector<Vec3> x;      // its cubes' nodes when it was made
    double margin = 0;        // the margin it was made with
  };
  std::vector<ReachList> reach_;  // per body (cubes_in_reach)
  std::vector<std::pair<int, int>> left_reach_;  // (body, group) out of a reach list since the last commit
  int group_count_ = 0;
  std::vector<char> plane_status_;  // per node and plane: status_of its contact at the last evaluation
  bool pair_history_ = false;
  std::vector<char> plane_history_;  // per body: its floor and wall contacts keep a history
  std::vector<Vec3> x_broad_;  // node positions at the last broad phase
  Timings timings_;
  RestraintSet restraints_;
  std::vector<std::vector<int>> restraints_of_;  // per body: its restraints
  std::vector<char> restraint_status_;           // per restraint: its regime at the last evaluation
  int restraints_applied_ = 0;                   // of plane_applied_'s entries, the restraints'
  double evaluated_at_ = 0;                      // the last evaluation's time (a break's time at commit)
  long steps_ = 0, broad_runs_ = 0;
  int active_ = 0;
};

}  // namespace furniture_fem

// The members defined out of the class (contact/detail/).
#define FURNITURE_FEM_CONTACT_INTERNAL
#include "detail/room_contact_pairs.hpp"
#include "detail/room_restraints.hpp"
#undef FURNITURE_FEM_CONTACT_INTERNAL
