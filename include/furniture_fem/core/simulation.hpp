#pragma once
// furniture_fem/core/simulation.hpp: the ASI-Gauss beam solver, composed at compile time.
//
//   Simulation<Element, Integrator, LinearSolver, Contact>
//
// Element: an ElementPolicy (elements.hpp); Integrator: an IntegratorPolicy (integrators.hpp);
// LinearSolver: a LinearSolverPolicy (solvers.hpp); Contact: anything with
// add_forces(const ContactView&, Eigen::VectorXd&) (NoContact by default; contact.hpp provides the
// beam/floor/wall contact). Large displacements and rotations are handled by a corotational frame per
// element (detail/body_system.hpp), so element policies are small-strain kernels.
//
// Each body (furniture item) is its own block: its own sparse effective matrix and solver, evaluated
// in parallel over bodies. Between matrix refreshes a body's factorisation is reused with the body's
// rigid rotation taken out of the right-hand side and put back into the solution, which keeps the
// reuse valid while an item tumbles. Nothing allocates inside the time loop.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <chrono>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <numeric>
#include <string>
#include <span>
#include <vector>

#include "checkpoint.hpp"
#include "elements.hpp"
#include "integrators.hpp"
#include "model.hpp"
#include "node_states.hpp"
#include "solvers.hpp"
#include "statics.hpp"

#define FURNITURE_FEM_CORE_INTERNAL
#include "detail/body_system.hpp"
#include "detail/finite.hpp"
#include "detail/parallel.hpp"
#include "detail/rigid_affine.hpp"
#include "detail/rigid_pair_terms.hpp"
#include "detail/rotation.hpp"
#include "detail/static_path.hpp"
#undef FURNITURE_FEM_CORE_INTERNAL
#include "step_report.hpp"

namespace furniture_fem {

struct SimulationOptions {
  // s; at least min_dt. Below it the integrator's mass term m / (beta dt^2) swamps the stiffness in
  // double precision (a 0.1 kg node at 1e-9 s: 4e17 N/m against members' 1e6 N/m), and it overflows
  // below 1e-154 s: dt = 1e-300 ran and then "diverged; try a smaller dt" (issue 13).
  double dt = 1e-3;
  static constexpr double min_dt = 1e-9;
  Vec3 gravity = Vec3(0, 0, -9.80665);
  double mass_damping = 0;      // C = mass_damping * M (1/s); 0: no viscous damping
  // Structural damping of flexible members (s): each element's deformational force gains
  // stiffness_damping * k_e * (d - d_n) / dt in its corotated frame (k_e its tangent, d its deformations,
  // d_n at the step's start), so rigid motion is never damped and a mode at omega gets the damping ratio
  // stiffness_damping * omega / 2 (docs/core/theory.md, "Structural damping"). 0: none, the paper's code.
  double stiffness_damping = 0;
  // A flexible body's reused factorisation is refreshed when one of its members has turned away from
  // the body's rotation by more than this angle (rad) since the factorisation (FlexibleBody::frame_drift):
  // a chair's short stiff members, factorised while it landed, made the reuse create energy in the free
  // flight after (docs/core/theory.md section 8, "Members that turn on their own"). 0: never, as before.
  double frame_drift_refresh = 0;
  int max_iterations = 25;      // for EquilibriumMode::iterate
  double tolerance = 1e-7;      // residual norm relative to the force scale
  // Refresh (assemble and factorise) each body's matrix every this many steps (1: every step);
  // between refreshes the factorisation is reused with the body's rigid rotation taken out.
  int refresh_interval_steps = 1;
  bool geometric_stiffness = true;
  bool finite_rotation_update = true;  // put each free body's rigid turn of a step on the finite rotation
  bool check_finite = true;     // stop with a diagnosis on NaN / divergence
  int threads = 1;              // threads over bodies (element forces, solves); 0: all hardware threads
  // Carry-over: a body whose floor or wall contacts change status within the step (a corner that
  // touches, a face that leaves, a dashpot clamped) is solved again with its contacts at the step's
  // end, at most this many times (docs/contact/implicit_contact.md, "Contacts that change within a
  // step"). 0: the predictor's contacts for the whole step (a face arriving at 5 m/s then enters the
  // floor unopposed for a step and its spring gives back energy it never took).
  int contact_iterations = 4;
  // A rigid body (set_rigid) stepped on its fields: its nodes' translational fields are affine in their
  // material arms, so the step's sums come from the body's mass moments and its nodes are placed in one
  // pass per solve (docs/core/theory.md, "Rigid bodies on their fields"). The same scheme as node by
  // node up to rounding. A body with a point inertia, a nodal load or a spring stays node by node.
  bool rigid_fields = true;
  // A flexible body's reused factorisation: a contact term's change small against its node's diagonal
  // (below half of it: the mass term and the members) is solved by conjugate gradients preconditioned
  // by the factor instead of the Woodbury update or a refactorisation (docs/contact/implicit_contact.md,
  // "Refined, not refactorised"). Off by default until the changes a reuse leaves out are refined too
  // (a sliding full desk: -6.6 % against every step, measured); off, the same to the bit as before.
  bool contact_refinement = false;
  // Impacts (docs/contact/implicit_contact.md, "Impacts: sub-steps"): a step in which a node or support
  // point closes on a floor or wall it can reach within the step faster than impact_travel / dt is
  // divided into ceil(speed dt / impact_travel) equal sub-steps, at most max_impact_substeps. Newmark
  // moves a face that its contact stops within a step by (1 - beta / gamma) v dt regardless of the law
  // (2.3 mm at 5 m/s and 1 ms under the paper's scheme); a sub-step of impact_travel leaves 0.47 of it.
  // 1: never (the paper's code). A contact policy without fastest_closing is never sub-stepped.
  int max_impact_substeps = 1;
  double impact_travel = 5e-4;  // m per sub-step
};

// What a contact model sees: the current state of the structure, all in the table frame.
struct ContactView {
  const Model& model;
  const std::vector<Vec3>& x;      // nodal positions
  const Eigen::VectorXd& v;        // nodal velocities (6 per node, angular in world axes)
  double time;
  double dt;
  const std::vector<Mat3>* rotations = nullptr;  // nodal rotations (contact points off a node turn with it)
};

struct NoContact {
  void add_forces(const ContactView&, Eigen::VectorXd&) {}
};
template <class Self, class Archive>
  requires std::is_same_v<std::remove_const_t<Self>, NoContact>
void transfer_state(Self&, Archive&) {}  // no history

// A contact policy whose history a checkpoint can hold (core/checkpoint.hpp): transfer_state lists it.
template <class C>
concept CheckpointableContact = requires(const C& c, C& m, StateWriter& w, StateReader& r) {
  transfer_state(c, w);
  transfer_state(m, r);
};

template <class C>
concept ContactPolicy = requires(C c, const ContactView& view, Eigen::VectorXd& f) { c.add_forces(view, f); };

// The linearisation of the contact force on one node's translations, about the state (x, v) it was
// evaluated at: f(x + dx, v + dv) ~ f - K dx - C dv. A contact policy that offers these
// (nodal_tangents()) has them inside the implicit step: each body's solve adds them to its
// effective matrix as a low-rank update of its factorisation (docs/contact/implicit_contact.md).
// A contact at a point off its node (a rigid body's member surface) gives arm0, the point's offset in
// the node's initial frame: x and v are then the point's, which moves with the node's rotation too
// (dx_point = dx + dtheta x arm), and the force acts there (a moment arm x f on the node). Only
// rigid bodies' contacts may have one.
// `status` is the contact's regime (contact_status_code; a node's terms summed: counts of each), which a
// factorisation reused between refreshes compares on its own: a change of regime always enters the step.
struct NodalContactTangent {
  static constexpr bool checkpoint_as_bytes = true;  // core/checkpoint.hpp
  int node = -1;
  int status = 0;
  Mat3 K = Mat3::Zero(), C = Mat3::Zero();
  Vec3 x = Vec3::Zero(), v = Vec3::Zero();
  Vec3 arm0 = Vec3::Zero();
  bool at_node() const { return arm0.x() == 0 && arm0.y() == 0 && arm0.z() == 0; }
};

// A contact's regime as NodalContactTangent::status counts it: pushing while slipping (or without
// friction) 1, sticking 1 << 8, touching with its force clamped at zero 1 << 16. Summed over a node's
// terms the counts stay apart (fewer than 256 terms a node), so any change of any term's regime shows.
inline constexpr int contact_status_code(bool sticking, bool clamped) {
  return clamped ? 1 << 16 : sticking ? 1 << 8 : 1;
}

// The linearisation of an item-item contact force about the state it was evaluated at: the force F
// acts on body_a at `point` and -F on body_b; the contact points move with their segments' nodes
// (shares 1 - s, s on a0, a1 and 1 - t, t on b0, b1), and F(x + dx, v + dv) ~ F - K d - C d', d the
// relative displacement of a's point from b's. When both bodies are rigid the simulation solves them
// in one system with these terms (rigid groups); otherwise the force stays a load of the predictor.
struct PairContactTangent {
  static constexpr bool checkpoint_as_bytes = true;  // core/checkpoint.hpp
  int body_a = -1, body_b = -1;
  int a0 = -1, a1 = -1, b0 = -1, b1 = -1;
  double s = 0, t = 0;
  Vec3 point = Vec3::Zero();
  Mat3 K = Mat3::Zero(), C = Mat3::Zero();
  Vec3 x = Vec3::Zero(), v = Vec3::Zero();  // relative position and velocity at the evaluation
  // A point off its segment (two rigid bodies' hulls, a0 == a1 and b0 == b1): its offset from the node
  // in the node's initial frame; it turns with the node (zero for element pairs).
  Vec3 arm_a0 = Vec3::Zero(), arm_b0 = Vec3::Zero();
  bool has_arms() const { return !arm_a0.isZero(0) || !arm_b0.isZero(0); }
};

// A contact policy whose item-item pairs offer their linearisation (pair_tangents(), of its last
// add_forces). Its end_of_step must re-evaluate those pairs at the end state, as for planes.
template <class C>
concept PairTangentPolicy = requires(const C c) {
  { c.pair_tangents() } -> std::convertible_to<const std::vector<PairContactTangent>&>;
};

// A contact policy with its forces inside the implicit step: the tangents of its last add_forces, and
// end_of_step(view, f), which re-evaluates at the end of a carried-over step the forces it linearised
// (updating f), as the internal forces are.
template <class C>
concept ImplicitContactPolicy = ContactPolicy<C> && requires(C c, const ContactView& view, Eigen::VectorXd& f) {
  { c.nodal_tangents() } -> std::convertible_to<const std::vector<NodalContactTangent>&>;
  c.end_of_step(view, f);
};

// An implicit contact policy that can evaluate one body's plane contacts at a trial state of the
// step (body_plane_contacts: tangents, forces, statuses; body_plane_status_changed: only whether a
// status differs), with the statuses of its last evaluation (last_status) and the forces that
// evaluation applied (plane_forces): a body whose contacts change status within a step is then
// solved again (SimulationOptions::contact_iterations).
template <class C>
concept BodyPlaneContactPolicy = ImplicitContactPolicy<C> && requires(const C c, const ContactView& view, const Model& m) {
  { c.body_plane_contacts(view, 0).tangents } -> std::convertible_to<const std::vector<NodalContactTangent>&>;
  { c.body_plane_contacts(view, 0).forces } -> std::convertible_to<const std::vector<Vec6>&>;
  { c.body_plane_contacts(view, 0).status } -> std::convertible_to<const std::vector<char>&>;
  { c.body_plane_status_changed(view, 0) } -> std::convertible_to<bool>;
  { c.last_status(m, 0) } -> std::convertible_to<std::vector<char>>;
  { c.plane_forces() } -> std::convertible_to<const std::vector<std::pair<int, Vec6>>&>;
};

template <class Element, class Integrator = Newmark, class LinearSolver = DirectLdltSolver, class Contact = NoContact>
class Simulation {
  static_assert(check_element_policy<Element>());
  static_assert(check_integrator_policy<Integrator>());
  static_assert(check_linear_solver_policy<LinearSolver>());
  static_assert(ContactPolicy<Contact>,
                "furniture_fem: the Contact policy must provide add_forces(const ContactView&, Eigen::VectorXd&); "
                "see docs/contact/contact.md");

 public:
  using State = typename Element::State;

  Simulation(const Model& model, Integrator integrator = {}, SimulationOptions options = {}, Contact contact = {});

  // ---- loads and initial conditions ----
  // Table (base) acceleration in m/s^2; every mass gets -m a_table(t) (the table frame).
  void set_table_acceleration(std::function<Vec3(double)> a) { table_acc_ = std::move(a); }
  // A nodal load (3 forces, 3 moments), scaled by load_scale(t) in dynamics and by the load factor in
  // statics.
  void set_nodal_load(int node, const Vec6& load) {
    place_body_nodes(check_node(node));
    nodal_load_.segment<6>(6 * check_node(node)) = load;
    nodes_set_from_outside(node);
  }
  void set_load_scale(std::function<double(double)> s) { load_scale_ = std::move(s); }
  void set_velocity(int node, const Vec6& v) {
    place_body_nodes(check_node(node));
    v_.segment<6>(6 * check_node(node)) = v;
    nodes_set_from_outside(node);
  }
  // Rigid-body velocity field (v0 + w x (x - c)) for all nodes of a body.
  void set_body_velocity(int body, const Vec3& v0, const Vec3& w, const Vec3& c) {
    if (!model_.body(body).nodes.empty()) place_body_nodes(model_.body(body).nodes.front());
    for (int n : model_.body(body).nodes) {
      v_.segment<3>(6 * n) = v0 + w.cross(x_[n] - c);
      v_.segment<3>(6 * n + 3) = w;
    }
    if (!model_.body(body).nodes.empty()) nodes_set_from_outside(model_.body(body).nodes.front());
  }
  // At rest where the bodies are now: every velocity and acceleration zero, the clock, the step and
  // factorisation counts, the timings and the energy ledger back at 0; the next step starts again
  // (start()) from here. Positions, rotations, hinges and the contact's history stay. A scene's settled
  // start (contact.start) loads a settled state and calls this.
  void restart_at_rest() {
    place_unplaced_nodes();
    v_.setZero();
    a_.setZero();
    for (int b = 0; b < model_.num_bodies(); ++b)
      if (!model_.body(b).nodes.empty()) nodes_set_from_outside(model_.body(b).nodes.front());
    t_ = t_state_ = 0;
    steps_ = impact_steps_ = impact_substeps_ = 0;
    divided_ = false;
    step_start_t_ = std::numeric_limits<double>::quiet_NaN();
    ledger_ = {};
    timings_ = {};
    long made = 0;  // the factorisations count from here
    for (const auto& solver : solvers_) made += solver->factorizations();
    factorizations_offset_ = -made;
    started_ = false;
    for (auto& bs : systems_) {
      bs.needs_refresh = true;
      bs.max_reuse_error = bs.max_frame_drift = 0;
      bs.drift_refreshes = 0;
    }
  }
  Contact& contact() { return contact_; }
  const Contact& contact_model() const { return contact_; }

  // Models a body as rigid (6 DOF) with the same nodes and masses: its elements carry no forces and
  // are not evaluated; its motion is solved in the rigid subspace (Newton on the body's translation and
  // rotation, the residual reduced from the nodal one). The contact is told (it may reduce the body's
  // geometry). Call before the first step. "Model only what a scene needs": an item whose internal
  // forces nobody asked for.
  void set_rigid(int body, bool rigid = true) {
    if (started_) throw ModelError("set_rigid: call before the first step");
    if (body < 0 || body >= model_.num_bodies()) throw ModelError("set_rigid: unknown body " + std::to_string(body));
    if (rigid)
      for (int n : model_.body(body).nodes)
        if (model_.node(n).fixed)
          throw ModelError("set_rigid: body '" + model_.body(body).name + "' has supported node " + std::to_string(n) +
                           "; a rigid body must be free");
    systems_[body].rigid = rigid;
    // Forces a static solve may have left: a rigid body's stay zero (evaluate_body no longer clears them).
    if (rigid)
      for (int n : model_.body(body).nodes) fint_.segment<6>(6 * n).setZero();
    // The contact may then test a reduced geometry of the body (RoomContact: its hull's nodes).
    if constexpr (requires { contact_.set_rigid(model_, body, rigid); }) contact_.set_rigid(model_, body, rigid);
  }
  bool is_rigid(int body) const { return systems_.at(body).rigid; }
  // Whether a rigid body is stepped on its fields (SimulationOptions::rigid_fields; decided at the
  // first step: a body with a point inertia, a nodal load or a spring is stepped node by node).
  bool rigid_on_fields(int body) const { return fields_.at(body).on; }

  // A grounded spring on one DOF (0-2 translations, 3-5 rotations): force k (target - u). The target
  // is scaled like the loads (load factor in statics, load_scale(t) in dynamics), so a stiff spring
  // prescribes a displacement (displacement control of a push-over). Returns the spring's index.
  int add_support_spring(int node, int dof, double k, double target = 0) {
    check_node(node);
    if (dof < 0 || dof > 5) throw ModelError("support spring at node " + std::to_string(node) + ": dof must be 0..5");
    if (!(k > 0) || !std::isfinite(k) || !std::isfinite(target))
      throw ModelError("support spring at node " + std::to_string(node) + ": k must be positive and finite (got " +
                       detail::fmt(k) + ")");
    springs_.push_back({node, dof, k, target});
    return static_cast<int>(springs_.size()) - 1;
  }
  // Force the spring exerts on its node (the support reaction, sign of the DOF).
  double spring_force(int i) const {
    const auto& sp = springs_.at(i);
    return sp.k * (spring_scale() * sp.target - dof_value(sp.node, sp.dof));
  }

  // Places a node (position and rotation) and recomputes the internal forces: for checks such as
  // "a rigid rotation produces no internal force". Velocities are left as they are.
  void set_pose(int node, const Vec3& x, const Mat3& R) {
    place_body_nodes(check_node(node));
    x_[node] = x;
    u_[node] = x - model_.node(node).X;
    R_[node] = R;
    nodes_set_from_outside(node);
  }
  void update_internal_forces() {
    place_unplaced_nodes();
    evaluate_elements(false);
    committed_ = trial_;
  }
  Vec6 internal_force(int node) const { return fint_.segment<6>(6 * check_node(node)); }

  // The body's static tangent stiffness at the current configuration (dense; for modal analysis of
  // small models), and the lumped mass diagonal, in the body's local DOF order (see body_nodes).
  Eigen::MatrixXd stiffness_matrix(int body) {
    {
      const StaticScope statics(*this, StaticScope::keep_dynamics);
      evaluate_body(body, true);
    }
    systems_[body].needs_refresh = true;
    systems_[body].assembled = false;
    return Eigen::MatrixXd(systems_[body].K);
  }
  Eigen::VectorXd mass_diagonal(int body) const {
    const auto& bs = systems_[body];
    Eigen::VectorXd m(bs.ndof());
    for (size_t k = 0; k < bs.nodes.size(); ++k) m.segment<6>(6 * k) = mass_.segment<6>(6 * bs.nodes[k]);
    return m;
  }
  const std::vector<int>& body_nodes(int body) const { return systems_[body].nodes; }
  bool dof_fixed(int node, int dof) const { return (model_.node(node).fixed >> dof) & 1u; }

  // ---- time stepping ----
  // A step is one pass over the whole scene for what couples the bodies (the loads' time functions
  // and contact), and one sweep over the bodies for the rest: each body's residual, solve, update,
  // element forces, energy and ASI shifts are done while its data is in the core's cache. Done phase
  // by phase over the whole scene instead, every phase streamed the scene's state from memory, and the
  // cost per element grew with the size of the scene (docs/performance.md section 2).
  StepInfo step();

  // Steps until time t_end; the observer (if any) is called after every step with (sim, info).
  template <class Observer>
  void run_until(double t_end, Observer&& observer) {
    while (t_ < t_end - 0.5 * opt_.dt) {
      const StepInfo info = step();
      observer(*this, info);
    }
  }
  void run_until(double t_end) {
    run_until(t_end, [](const Simulation&, const StepInfo&) {});
  }

  // ---- statics (detail/static_path.hpp; docs/core/theory.md section 7) ----
  // None of the static solves throws when the structure cannot carry the load (a mechanism, a limit
  // point): the result says why it stopped and the simulation is left in the last converged state.
  // They throw for a model statics cannot solve (a rigid body) and for bad arguments.
  using StaticResult = furniture_fem::StaticResult;
  // Load control: the load factor ramped from 1/increments to 1, full Newton (tangent refreshed at
  // every iteration) at each increment.
  StaticResult solve_static(int increments = 1, int max_iterations = 50, double tolerance = 1e-9);
  // Displacement control: DOF `dof` (0-2 translations, 3-5 rotations) of `node` moved from where it is
  // to `target` in equal increments; the path gives the load factor of the reference load (nodal loads,
  // gravity, spring targets) at each. The state starts at load factor start_load_factor.
  StaticPath solve_static_displacement(int node, int dof, double target, int increments, int max_iterations = 50,
                                       double tolerance = 1e-9, double start_load_factor = 0);
  // Arc-length (Crisfield, cylindrical): follows the path past limit points and along mechanisms.
  StaticPath solve_static_arc_length(const ArcLengthOptions& options);
  double load_factor() const { return load_factor_; }
  void set_load_factor(double f) { load_factor_ = f; }

  // ---- results ----
  double time() const { return t_; }
  long steps() const { return steps_; }
  const Model& model() const { return model_; }
  // A node of a rigid body on its fields is placed when read (RigidFields: the step places only the
  // nodes it reads), so these give every node's state whatever the contact reads.
  const Vec3& position(int n) const { return place_node_if_unplaced(n), x_[n]; }
  const Vec3& displacement(int n) const { return place_node_if_unplaced(n), u_[n]; }
  const Mat3& rotation(int n) const { return place_node_if_unplaced(n), R_[n]; }
  Vec6 velocity(int n) const { return place_node_if_unplaced(n), v_.segment<6>(6 * n); }
  Vec6 acceleration(int n) const { return place_node_if_unplaced(n), a_.segment<6>(6 * n); }
  const std::vector<Vec3>& positions() const { return place_unplaced_nodes(), x_; }
  const std::vector<Vec3>& displacements() const { return place_unplaced_nodes(), u_; }
  const std::vector<Mat3>& rotations() const { return place_unplaced_nodes(), R_; }
  const Eigen::VectorXd& velocities() const { return place_unplaced_nodes(), v_; }
  const Eigen::VectorXd& accelerations() const { return place_unplaced_nodes(), a_; }
  // The nodes' state at the start of the last step, at step_start_time() (NaN until a step has
  // predicted): what the step keeps of it (u0_, R0_, vn_, an_; a body on its fields: its fields at
  // the start), positions X + u0. What is left of a run whose step diverged.
  // A step divided for an impact: the start of the whole step, not of its last sub-step.
  double step_start_time() const { return divided_ ? division_start_t_ : step_start_t_; }
  void copy_step_start_states(NodeStates& out) const {
    if (divided_) {
      out = division_start_;
      return;
    }
    const int nn = model_.num_nodes();
    out.u = u0_;
    out.R = R0_;
    out.v = vn_;
    out.a = an_;
    out.x.resize(nn);
    for (int n = 0; n < nn; ++n) out.x[n] = model_.node(n).X + u0_[n];
    for (int b = 0; b < model_.num_bodies(); ++b)
      if (fields_[b].on) RigidFields::start_states(*this, b, out);
  }
  // The first node whose position, rotation or velocity is not finite, -1 if none: one branch-free
  // pass over each array, the node looked for only when one is not finite. Bodies on their fields
  // with unplaced nodes are checked by their fields and the nodes their step placed.
  int first_non_finite_node() const {
    if (std::find(unplaced_.begin(), unplaced_.end(), 1) != unplaced_.end()) return first_non_finite_node_by_body();
    static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Mat3) == 9 * sizeof(double),
                  "the arrays of positions and rotations are read as flat arrays of doubles");
    const auto n = static_cast<Eigen::Index>(x_.size());
    if (n == 0 || (detail::all_finite(x_.front().data(), 3 * n) && detail::all_finite(R_.front().data(), 9 * n) &&
                   detail::all_finite(v_)))
      return -1;
    for (Eigen::Index i = 0; i < n; ++i)
      if (!(x_[i].allFinite() && R_[i].allFinite() && v_.segment<6>(6 * i).allFinite())) return static_cast<int>(i);
    return -1;
  }
  double nodal_mass(int n) const { return mass_[6 * n]; }
  double nodal_rotary_inertia(int n) const { return mass_[6 * n + 3]; }
  // A node's rotary inertia tensor (world axes) as the dynamics use it: on a rigid body the initial
  // tensor turned with the node, on a flexible one the lumped diagonal in world axes.
  Mat3 node_rotary_inertia(int n) const {
    if (!systems_[model_.node(n).body].rigid) return mass_.segment<3>(6 * n + 3).asDiagonal();
    return rigid_node_rotary_inertia(n);
  }
  // The same for a node known to be on a rigid body (no look-up of its body: the reduced system's loop).
  Mat3 rigid_node_rotary_inertia(int n) const {
    const int k = rotary_index_[n];
    if (k < 0) return mass_.segment<3>(6 * n + 3).asDiagonal();
    return R_[n] * rotary0_[k] * R_[n].transpose();
  }
  const State& element_state(int e) const { return committed_[e]; }
  // Current element frame (columns: local x, y, z in world axes).
  Mat3 element_frame(int e) const { return frames_[e]; }

  // Sectional forces (local axes of the element) at its stress evaluation point, or at any xi.
  SectionForces section_forces(int e) const {
    return Element::section_forces(props_[e], committed_[e], d_[e]);
  }
  SectionForces section_forces_at(int e, double xi) const {
    const SectionForces s = section_forces(e);
    const Vec6 v = detail::forces_at(s.as_vector(), s.xi, xi, props_[e].L0);
    return {v[0], v[1], v[2], v[3], v[4], v[5], xi};
  }

  Vec3 linear_momentum() const {
    place_unplaced_nodes();
    Vec3 p = Vec3::Zero();
    for (int n = 0; n < model_.num_nodes(); ++n) p += mass_[6 * n] * v_.segment<3>(6 * n);
    return p;
  }
  Vec3 angular_momentum(const Vec3& about = Vec3::Zero()) const {
    place_unplaced_nodes();
    Vec3 L = Vec3::Zero();
    for (int n = 0; n < model_.num_nodes(); ++n)
      L += (x_[n] - about).cross(mass_[6 * n] * v_.segment<3>(6 * n)) + rotary_momentum(n);
    return L;
  }
  EnergyLedger energy() const {
    place_unplaced_nodes();
    EnergyLedger e = ledger_;
    e.kinetic = 0;
    for (int n = 0; n < model_.num_nodes(); ++n)
      e.kinetic += 0.5 * (mass_[6 * n] * v_.segment<3>(6 * n).squaredNorm() +
                          v_.segment<3>(6 * n + 3).dot(rotary_momentum(n)));
    e.gravity_potential = 0;
    for (int n = 0; n < model_.num_nodes(); ++n) e.gravity_potential -= mass_[6 * n] * opt_.gravity.dot(x_[n]);
    e.strain = 0;
    e.plastic_work = 0;
    for (int el = 0; el < model_.num_elements(); ++el) {
      // A rigid body's elements keep their initial state and zero deformation: adding their strain
      // energy and plastic work (+0) changed nothing but cost their sectional forces at every row.
      if (systems_[model_.node(model_.elements()[el].n1).body].rigid) continue;
      e.strain += strain_energy(el);
      if constexpr (requires { committed_[el].plastic_work; }) e.plastic_work += committed_[el].plastic_work;
    }
    if (!started_) e.initial_total = e.total();  // before the first step the ledger is balanced by definition
    return e;
  }
  long factorizations() const {
    long f = factorizations_offset_;
    for (const auto& s : solvers_) f += s->factorizations();
    return f;
  }
  // The factor-reuse error: the largest change of a node's contact term, relative to the term, that a
  // flexible body's reused factorisation has left out of a solve since the start (bounded by the change
  // tolerance, 0.3; a change of contact regime is never left out). 0 when every step was refactorised.
  double factor_reuse_error() const {
    double e = 0;
    for (const auto& bs : systems_) e = std::max(e, bs.max_reuse_error);
    return e;
  }
  // Contact changes refined on reused factorisations (SimulationOptions::contact_refinement): the
  // conjugate-gradient solves since the start, and the steps whose refinement did not converge.
  long refinement_solves() const {
    long n = 0;
    for (const auto& bs : systems_) n += bs.refinement_solves;
    return n;
  }
  // Factorisations due to a member's frame drifting from its body's rotation (frame_drift_refresh), and
  // the largest drift a reused factorisation solved with.
  long drift_refreshes() const {
    long n = 0;
    for (const auto& bs : systems_) n += bs.drift_refreshes;
    return n;
  }
  double max_frame_drift() const {
    double e = 0;
    for (const auto& bs : systems_) e = std::max(e, bs.max_frame_drift);
    return e;
  }
  long refinement_fallbacks() const {
    long n = 0;
    for (const auto& bs : systems_) n += bs.refinement_fallbacks;
    return n;
  }
  // Impact sub-steps (SimulationOptions::max_impact_substeps): the steps divided since the start, and
  // the sub-steps they were divided into.
  long impact_steps() const { return impact_steps_; }
  long impact_substeps() const { return impact_substeps_; }

  // ---- checkpoint (core/checkpoint.hpp, docs/core/checkpoint.md) ----
  // Everything a step reads that an earlier step wrote: time, displacements, rotations, velocities,
  // accelerations, the forces carried over, the elements' integration points and hinges, the rigid
  // groups, the energy ledger, each body's matrix as last factorised, and the contact's history.
  // Loaded into a simulation built the same way (same model, options and policies), the next steps
  // are those of the simulation that saved it, to the bit.
  void save_state(StateWriter& w) const {
    static_assert(CheckpointableContact<Contact>, "furniture_fem: checkpoints need the contact policy's "
                                                  "transfer_state (core/checkpoint.hpp)");
    place_unplaced_nodes();  // the arrays as a run that places every node has them
    transfer_state_of(*this, w);
  }
  void load_state(StateReader& r) {
    static_assert(CheckpointableContact<Contact>, "furniture_fem: checkpoints need the contact policy's "
                                                  "transfer_state (core/checkpoint.hpp)");
    transfer_state_of(*this, r);
    std::fill(unplaced_.begin(), unplaced_.end(), 0);  // saved with every node placed
    refactorise_loaded_matrices();
    for (int b = 0; b < model_.num_bodies(); ++b)
      if (fields_[b].on) RigidFields::set_arms(*this, b);
  }
  const SimulationOptions& options() const { return opt_; }
  const StepTimings& timings() const { return timings_; }
  const Integrator& integrator() const { return integrator_; }

 private:
  friend class detail::StaticSolver<Simulation>;

  // Statics for the life of the scope: the loads at the load factor, no inertia in the matrices. Its
  // end, however reached, restores the mode. After a static solve (restart_dynamics) the next dynamic
  // step starts again (start()): it assembles the effective (dynamic) matrix in place of the static
  // tangent left flagged as assembled, and sets the initial accelerations, forces and energy from the
  // state statics left. Left by an exception, every body's matrix is refreshed too: a body solved
  // before the failure holds a static factorisation its next step would otherwise reuse.
  class StaticScope {
   public:
    enum Exit { keep_dynamics, restart_dynamics };
    StaticScope(Simulation& sim, Exit exit)
        : sim_(sim), saved_(sim.static_), exit_(exit), exceptions_(std::uncaught_exceptions()) {
      sim.place_unplaced_nodes();  // statics reads every node
      sim.static_ = true;
    }
    ~StaticScope() {
      sim_.static_ = saved_;
      if (exit_ == keep_dynamics) return;
      sim_.started_ = false;
      if (std::uncaught_exceptions() > exceptions_)
        for (auto& bs : sim_.systems_) bs.needs_refresh = true;
    }
    StaticScope(const StaticScope&) = delete;
    StaticScope& operator=(const StaticScope&) = delete;

   private:
    Simulation& sim_;
    bool saved_;
    Exit exit_;
    int exceptions_;
  };

  // What a step scheme (CarryOverScheme, IteratedScheme in integrators.hpp) drives: the sweeps over
  // the bodies of the step to t1, and the options it reads.
  class StepKernel {
   public:
    StepKernel(Simulation& sim, double t1) : sim_(sim), t1_(t1) {}
    int max_iterations() const { return sim_.opt_.max_iterations; }
    double tolerance() const { return sim_.opt_.tolerance; }
    bool check_finite() const { return sim_.opt_.check_finite; }
    double end_time() const { return t1_; }

    // Each body in one go: its residual, solve, update and commit (carry-over).
    StepInfo solve_and_commit_bodies() {
      sim_.body_sweep([&](int b) { sim_.solve_and_commit_body(b); });
      const BodyStepSums total = sim_.sum_bodies(t1_);
      StepInfo info;
      info.residual = total.residual();
      info.refreshed_bodies = total.refreshed;
      info.shifted_points = total.shifted;
      return info;
    }
    void evaluate_residuals() {
      sim_.body_sweep([&](int b) {
        BodyStepSums& s = sim_.sums_[b];
        sim_.residual_body(sim_.systems_[b], sim_.fext1_, s.residual_num, s.residual_den);
      });
    }
    double residual_norm() { return sim_.sum_bodies(t1_).residual(); }
    // Returns the number of bodies whose matrix was refreshed.
    int update_bodies(bool first_solve) {
      sim_.body_sweep([&](int b) { sim_.update_body(b, sim_.sums_[b], first_solve); });
      return sim_.sum_bodies(t1_).refreshed;
    }
    // Contact at the current iterate (its positions and velocities).
    void contact_at_trial() {
      sim_.timed(sim_.timings_.contact, [&] { sim_.contact_forces(t1_, sim_.v_, sim_.fc1_); });
    }
    // Returns the number of ASI integration points moved.
    int commit_bodies() {
      sim_.body_sweep([&](int b) { sim_.commit_body(b, sim_.sums_[b]); });
      return sim_.sum_bodies(t1_).shifted;
    }

   private:
    Simulation& sim_;
    double t1_;
  };

  // A body's whole step in carry-over mode: residual, solve, update and commit while its data is in
  // the core's cache; a failed solve or a non-finite increment leaves it uncommitted (sum_bodies
  // reports it).
  void solve_and_commit_body(int b) {
    if (const int g = group_of(b); g >= 0) {
      if (groups_[g].front() == b) solve_and_commit_group(groups_[g]);
      return;
    }
    BodyStepSums& s = sums_[b];
    timed(s.solve, [&] { residual_body(systems_[b], fext1_, s.residual_num, s.residual_den); });
    if (!update_body(b, s, true)) return;
    resolve_changed_contacts(std::span<const int>(&b, 1));
    if (s.solve_failed) return;
    if (opt_.check_finite) {
      s.not_finite = s.not_finite || !increment_finite(b);
      if (s.not_finite) return;
    }
    commit_body(b, s);
  }

  // A body's (or rigid group's) step again while its floor and wall contacts at the step's end
  // differ in status from those it was solved with: a Newton step from the end state with the
  // contacts evaluated there (forces into fc1_ in place of the ones it held, their slopes into the
  // 6 x 6 system; a group's pairs carried by their linearisation to that state). The forces a body
  // ends with are the last evaluation's carried by its linearisation to the end state, as
  // contact_at_end_of_step does for the others (which then skips the body). Statuses that stop
  // changing mean the last solve had the right contacts; a status that keeps flipping (a clamp with no
  // consistent side) is left after contact_iterations. A flexible body's Newton step goes through its
  // factorisation with the new contact terms (low-rank update, or refactorised beyond the cap).
  void resolve_changed_contacts(std::span<const int> members) {
    if constexpr (BodyPlaneContactPolicy<Contact>) {
      if (opt_.contact_iterations <= 0 || static_) return;
      const ContactView at_end{model_, x_, v_, t_state_, opt_.dt, &R_};
      if (std::none_of(members.begin(), members.end(), [&](int b) { return contact_.body_plane_status_changed(at_end, b); }))
        return;  // the usual case, checked without allocating
      const size_t n = members.size();
      std::vector<std::vector<char>> status(n);
      for (size_t i = 0; i < n; ++i) status[i] = contact_.last_status(model_, members[i]);
      std::vector<typename Contact::BodyPlaneContacts> used(n), now(n);
      bool iterated = false;
      for (int it = 0; it < opt_.contact_iterations && !sums_[members.front()].solve_failed; ++it) {
        const ContactView view{model_, x_, v_, t_state_, opt_.dt, &R_};
        bool changed = false;
        for (size_t i = 0; i < n; ++i) {
          now[i] = contact_.body_plane_contacts(view, members[i]);
          changed = changed || now[i].status != status[i];
        }
        if (!changed) break;
        for (size_t i = 0; i < n; ++i) {
          status[i] = std::move(now[i].status);
          replace_plane_contacts(members[i], used[i], std::move(now[i]), !iterated);
        }
        iterated = true;
        newton_step_from_current_state(members);
      }
      if (!iterated) return;
      for (const auto& u : used)
        for (const auto& t : u.tangents)  // the last evaluation's forces at the end state
          add_wrench(fc1_, t, plane_contact_shift(t));
    }
  }
  // Puts a body's plane contacts `now` in place of `used` (of the predictor's, the first time): their
  // forces in fc1_, their slopes in its system.
  template <class Contacts>
  void replace_plane_contacts(int b, Contacts& used, Contacts&& now, bool first) {
    if (first) remove_predictor_plane_forces(b);
    for (size_t k = 0; k < used.forces.size(); ++k) subtract_wrench(fc1_, used.tangents[k], used.forces[k]);
    for (size_t k = 0; k < now.forces.size(); ++k) add_wrench(fc1_, now.tangents[k], now.forces[k]);
    contact_iterated_[b] = 1;
    used = std::move(now);
    set_body_contact_terms(systems_[b], used.tangents);
  }
  // A body's (or rigid group's) Newton step from where its last solve left it.
  void newton_step_from_current_state(std::span<const int> members) {
    if (const int b = members.front(); !systems_[b].rigid) {  // flexible: never grouped
      double num = 0, den = 0;
      residual_body(systems_[b], fext1_, num, den);
      update_body(b, sums_[b], false);
      return;
    }
    if (members.size() > 1) carry_group_pairs_to_current_state(members);
    double num = 0, den = 0;
    for (int b : members) residual_body(systems_[b], fext1_, num, den);
    timed(sums_[members.front()].solve, [&] {
      if (members.size() > 1) RigidBody::group_newton_step(*this, members);
      else RigidBody::newton_step(*this, systems_[members.front()]);
    });
    for (int b : members) kinematics_body(b);
  }
  // A group's pair forces in fc1_ moved from the state of their last shift to the current one (their
  // linearisation); contact_at_end_of_step then adds the rest of the way to the end state.
  void carry_group_pairs_to_current_state(std::span<const int> members) {
    if constexpr (PairTangentPolicy<Contact>) {
      const auto& pairs = contact_.pair_tangents();
      for (int k : group_pairs_[group_of(members.front())]) {
        const Vec3 shift = pair_shift(pairs[k]);
        share_pair_force(pairs[k], shift - pair_predictor_shift_[k], [&](int node, const Vec6& w) { fc1_.segment<6>(6 * node) += w; });
        pair_predictor_shift_[k] = shift;
      }
    }
  }
  // Takes out of fc1_ the plane forces the predictor put on a body's nodes and their shift to the
  // predictor's state (linearised_contact_at_current_state).
  void remove_predictor_plane_forces(int b) {
    if constexpr (BodyPlaneContactPolicy<Contact>) {
      for (const auto& [n, w] : contact_.plane_forces())
        if (model_.node(n).body == b) {
          fc1_.segment<3>(6 * n) -= w.template head<3>();
          if (has_moment(w)) fc1_.segment<3>(6 * n + 3) -= w.template tail<3>();
        }
      const auto& tangents = contact_.nodal_tangents();
      for (size_t k = 0; k < tangents.size(); ++k)
        if (model_.node(tangents[k].node).body == b) subtract_wrench(fc1_, tangents[k], predictor_shift_[k]);
    }
  }
  // A body's effective-matrix contact terms (1 - af) (K + gamma / (beta dt) C), per node, from tangents
  // (a contact off its node: a term of its own, at its point).
  void set_body_contact_terms(detail::BodySystem& bs, const std::vector<NodalContactTangent>& tangents) {
    const double kf = 1 - coef_.alpha_f, cf = coef_.gamma / (coef_.beta * opt_.dt);
    bs.contact.clear();
    for (const auto& t : tangents) {
      const int local = local_index_[t.node];
      const Mat3 k = kf * (t.K + cf * t.C);
      const auto same = std::find_if(bs.contact.begin(), bs.contact.end(),
                                     [&](const auto& c) { return c.local == local && c.at_node() && t.at_node(); });
      if (same != bs.contact.end()) {
        same->K += k;
        same->status += t.status;
      } else {
        bs.contact.push_back({local, t.status, k, t.arm0});
      }
    }
  }

  // A plane contact's force carried by its linearisation from its evaluation to the current state, as
  // force and moment on its node: -(K d + C d') with d the contact point's displacement since.
  Vec6 plane_contact_shift(const NodalContactTangent& t) const {
    const int i = 6 * t.node;
    Vec6 w;
    if (t.at_node()) {
      w << -(t.K * (x_[t.node] - t.x) + t.C * (v_.segment<3>(i) - t.v)), Vec3::Zero();
      return w;
    }
    const Vec3 arm = R_[t.node] * t.arm0;
    const Vec3 f = -(t.K * (x_[t.node] + arm - t.x) + t.C * (v_.segment<3>(i) + v_.segment<3>(i + 3).cross(arm) - t.v));
    w << f, arm.cross(f);
    return w;
  }
  // A contact's force and moment w into f on its node (a contact at its node: the force alone, so that
  // f's moments are untouched to the bit).
  static bool has_moment(const Vec6& w) { return w[3] != 0 || w[4] != 0 || w[5] != 0; }
  static void add_wrench(Eigen::VectorXd& f, const NodalContactTangent& t, const Vec6& w) {
    f.segment<3>(6 * t.node) += w.template head<3>();
    if (!t.at_node()) f.segment<3>(6 * t.node + 3) += w.template tail<3>();
  }
  static void subtract_wrench(Eigen::VectorXd& f, const NodalContactTangent& t, const Vec6& w) {
    f.segment<3>(6 * t.node) -= w.template head<3>();
    if (!t.at_node()) f.segment<3>(6 * t.node + 3) -= w.template tail<3>();
  }

  int check_node(int n) const {
    if (n < 0 || n >= model_.num_nodes()) throw ModelError("node index out of range: " + std::to_string(n));
    return n;
  }

  void setup() {
    const int nn = model_.num_nodes(), ne = model_.num_elements();
    x_.resize(nn);
    u_.assign(nn, Vec3::Zero());
    u0_.assign(nn, Vec3::Zero());
    R_.assign(nn, Mat3::Identity());
    R0_.assign(nn, Mat3::Identity());
    for (int n = 0; n < nn; ++n) x_[n] = model_.node(n).X;
    v_.setZero(6 * nn);
    a_.setZero(6 * nn);
    for (auto* v : {&vn_, &an_, &v_contact_, &Du_, &fint_, &fext0_, &fext1_, &fc0_, &fc1_, &fnet0_, &mass_, &nodal_load_,
                    &fgrav_, &r_, &contact_delta_})
      v->setZero(6 * nn);
    props_.resize(ne);
    E0_.resize(ne);
    frames_.resize(ne);
    d_.assign(ne, Vec12::Zero());
    fl_.assign(ne, Vec12::Zero());
    dn_.assign(ne, Vec12::Zero());
    fd_.assign(ne, Vec12::Zero());
    fdn_.assign(ne, Vec12::Zero());
    committed_.resize(ne);
    for (int e = 0; e < ne; ++e) {
      const auto& el = model_.elements()[e];
      props_[e] = ElementProps::from_model(model_, e);
      E0_[e] = detail::initial_frame(model_.node(el.n1).X, model_.node(el.n2).X, el.y_ref);
      frames_[e] = E0_[e];
      committed_[e] = Element::initial_state(props_[e]);
      // Lumped mass: half the element's mass on each node; rotary inertia isotropic, rho (Iy + Iz) L / 2
      // per node and axis (the section's polar term; isotropic so that no gyroscopic term arises).
      const double m = el.line_mass * props_[e].L0;
      const auto& s = model_.section_of(e);
      const double J = el.line_mass / s.A * (s.Iy + s.Iz) * props_[e].L0;
      for (int node : {el.n1, el.n2}) {
        mass_.segment<3>(6 * node).array() += 0.5 * m;
        mass_.segment<3>(6 * node + 3).array() += 0.5 * J;
      }
    }
    // Point masses. A node with rotary inertia keeps its initial tensor (members' isotropic part and
    // the point's), which a rigid body turns with the node (node_rotary_inertia); the lumped diagonal
    // (mass_) holds the tensor's diagonal, what a flexible body uses: exact for isotropic inertia, an
    // approximation for a node whose anisotropic inertia turns (docs/core/theory.md).
    rotary_index_.assign(nn, -1);
    for (const auto& p : model_.point_masses()) {
      mass_.segment<3>(6 * p.node).array() += p.mass;
      if (p.inertia.isZero(0.0)) continue;
      int& k = rotary_index_[p.node];
      if (k < 0) {
        k = static_cast<int>(rotary0_.size());
        rotary0_.push_back(mass_[6 * p.node + 3] * Mat3::Identity());
      }
      rotary0_[k] += p.inertia_tensor();
      mass_.segment<3>(6 * p.node + 3) += p.inertia_tensor().diagonal();
    }
    trial_ = committed_;
    for (int n = 0; n < nn; ++n)
      if (!(mass_[6 * n] > 0) && model_.node(n).fixed != ALL_DOFS)
        throw ModelError("node " + std::to_string(n) + " of body '" + model_.body(model_.node(n).body).name +
                         "' has no mass (its elements have zero line mass) and is not fixed");
    local_index_.assign(nn, -1);
    systems_.resize(model_.num_bodies());
    sums_.assign(model_.num_bodies(), {});
    fields_.assign(model_.num_bodies(), {});
    rigid_arms_.assign(model_.num_bodies(), {});
    step_nodes_.assign(model_.num_bodies(), {});
    all_local_.assign(model_.num_bodies(), {});
    for (int b = 0; b < model_.num_bodies(); ++b) {
      all_local_[b].resize(model_.body(b).nodes.size());
      std::iota(all_local_[b].begin(), all_local_[b].end(), 0);
    }
    unplaced_.assign(model_.num_bodies(), 0);
    contact_iterated_.assign(model_.num_bodies(), 0);
    solvers_.resize(model_.num_bodies());
    for (int b = 0; b < model_.num_bodies(); ++b) {
      auto& bs = systems_[b];
      bs.nodes = model_.body(b).nodes;
      bs.elements = model_.body(b).elements;
      for (size_t k = 0; k < bs.nodes.size(); ++k) local_index_[bs.nodes[k]] = static_cast<int>(k);
      detail::build_pattern(bs, model_, local_index_);
      bs.fixed.assign(bs.ndof(), 0);
      for (size_t k = 0; k < bs.nodes.size(); ++k)
        for (int i = 0; i < 6; ++i)
          if (model_.node(bs.nodes[k]).fixed & (1u << i)) bs.fixed[6 * k + i] = 1;
      Vec3 c = Vec3::Zero();
      for (int n : bs.nodes) c += model_.node(n).X;
      bs.Xc = bs.nodes.empty() ? c : Vec3(c / bs.nodes.size());
      body_order_.push_back(b);
      solvers_[b] = std::make_unique<LinearSolver>();
      solvers_[b]->analyse(bs.K);
    }
    std::stable_sort(body_order_.begin(), body_order_.end(),
                     [&](int a, int b) { return systems_[a].elements.size() > systems_[b].elements.size(); });
    if (opt_.threads <= 0) opt_.threads = detail::hardware_threads();
  }

  // Initial accelerations from the equations of motion, and the first forces.
  void start() {
    started_ = true;
    evaluate_elements(false);
    if (opt_.stiffness_damping > 0) {  // the damping's rate starts from rest at the present deformations
      dn_ = d_;
      fdn_.assign(fdn_.size(), Vec12::Zero());
      evaluate_elements(false);
    }
    committed_ = trial_;
    if (static_) return;
    external_forces(t_, fext0_);
    contact_forces(t_, v_, fc0_);
    fnet0_ = fext0_ + fc0_ - fint_;
    for (int i = 0; i < a_.size(); ++i) a_[i] = is_fixed(i) ? 0.0 : fnet0_[i] / mass_[i];
    for (auto& bs : systems_)
      if (bs.rigid) RigidBody::initial_acceleration(*this, bs);
    for (int b = 0; b < model_.num_bodies(); ++b) RigidFields::begin(*this, b);
    ledger_.initial_total = energy().total();
  }

  bool is_fixed(int dof) const { return (model_.node(dof / 6).fixed >> (dof % 6)) & 1u; }

  template <class Self, class Archive>
  static void transfer_state_of(Self& s, Archive& ar) {
    std::array<std::size_t, 3> counts{static_cast<std::size_t>(s.model_.num_nodes()),
                                      static_cast<std::size_t>(s.model_.num_elements()),
                                      static_cast<std::size_t>(s.model_.num_bodies())};
    if constexpr (Archive::saving) {
      ar(counts);
    } else {
      std::array<std::size_t, 3> stored{};
      ar(stored);
      ar.expect(stored[0], counts[0], "nodes");
      ar.expect(stored[1], counts[1], "elements");
      ar.expect(stored[2], counts[2], "bodies");
    }
    ar(s.t_, s.load_factor_, s.t_state_, s.steps_, s.started_, s.static_, s.impact_steps_, s.impact_substeps_);
    ar(s.x_, s.u_, s.u0_, s.R_, s.R0_);
    ar(s.v_, s.a_, s.vn_, s.an_, s.v_contact_, s.Du_, s.r_, s.fint_, s.fext0_, s.fext1_, s.fc0_, s.fc1_, s.fnet0_,
       s.nodal_load_, s.fgrav_, s.contact_delta_);
    ar(s.predictor_shift_, s.pair_predictor_shift_, s.pair_active_, s.contact_iterated_, s.groups_, s.group_pairs_,
       s.group_of_);
    ar(s.frames_, s.d_, s.fl_, s.dn_, s.fd_, s.fdn_, s.committed_, s.trial_, s.ledger_, s.timings_, s.fields_);
    for (auto& bs : s.systems_) {
      // The matrix's values in its fixed pattern: as factorised, unless assembled for the next refresh.
      const std::size_t nnz = static_cast<std::size_t>(bs.K.nonZeros());
      if constexpr (Archive::saving) {
        ar(nnz);
        for (std::size_t i = 0; i < nnz; ++i) ar(bs.K.valuePtr()[i]);
      } else {
        std::size_t stored = 0;
        ar(stored);
        ar.expect(stored, nnz, "matrix entries of a body");
        for (std::size_t i = 0; i < nnz; ++i) ar(bs.K.valuePtr()[i]);
      }
      ar(bs.Q_factor, bs.steps_since_refresh, bs.needs_refresh, bs.assembled, bs.rigid, bs.rigid_c0, bs.rigid_dc,
         bs.rigid_Q, bs.contact, bs.contact_factored, bs.status_factored, bs.max_reuse_error, bs.frames_factor, bs.max_frame_drift, bs.drift_refreshes, bs.factored_nodes, bs.contact_columns, bs.contact_column, bs.contact_column_dim,
         bs.contact_columns_used, bs.r, bs.dx, bs.work);
    }
    long factorizations = s.factorizations();
    ar(factorizations);
    if constexpr (!Archive::saving) s.factorizations_offset_ = factorizations;
    ar(s.contact_);
  }
  // A flexible body whose factorisation the next steps reuse gets it again from the loaded matrix (the
  // same values give the same factor); the count of factorisations stays the saved run's.
  void refactorise_loaded_matrices() {
    for (int b = 0; b < model_.num_bodies(); ++b) {
      auto& bs = systems_[b];
      if (bs.rigid || bs.needs_refresh || bs.steps_since_refresh >= opt_.refresh_interval_steps) continue;
      if (bs.assembled)
        throw std::logic_error("furniture_fem: body " + std::to_string(b) + "'s matrix was assembled after its "
                               "factorisation but is not due a refresh: the checkpoint cannot restore its factor");
      solvers_[b]->factorize(bs.K);
    }
    long made = 0;
    for (const auto& solver : solvers_) made += solver->factorizations();
    factorizations_offset_ -= made;
  }

  // What the loads are at time t: the table's acceleration, the scale of the nodal loads and spring
  // targets, and the factor on gravity (statics ramps it with the load factor). Evaluated once per
  // step on the calling thread: the time functions need not be thread-safe.
  struct Loads {
    Vec3 table_acc = Vec3::Zero();
    double scale = 1, gravity_factor = 1;
  };
  Loads loads_at(double t) const {
    Loads l;
    if (static_) {
      l.scale = l.gravity_factor = load_factor_;
      return l;
    }
    if (table_acc_) l.table_acc = table_acc_(t);
    if (load_scale_) l.scale = load_scale_(t);
    return l;
  }
  void external_forces(double t, Eigen::VectorXd& f) {
    const Loads loads = loads_at(t);
    for (int b = 0; b < model_.num_bodies(); ++b) external_forces_body(b, loads, f);
  }
  void external_forces_body(int b, const Loads& loads, Eigen::VectorXd& f) {
    for (int n : systems_[b].nodes) {
      const double m = mass_[6 * n];
      fgrav_.segment<3>(6 * n) = m * opt_.gravity * loads.gravity_factor;
      f.segment<3>(6 * n) = fgrav_.segment<3>(6 * n) - Vec3(m * loads.table_acc);
      f.segment<3>(6 * n + 3).setZero();
      f.segment<6>(6 * n) += loads.scale * nodal_load_.segment<6>(6 * n);
    }
    // A support spring's force k (scale target - u) is split: k scale target is a load (so that a step
    // sees its target at t_{n+1} from its first residual on, in carry-over mode too), k u is internal.
    for (const auto& sp : springs_)
      if (model_.node(sp.node).body == b) f[6 * sp.node + sp.dof] += loads.scale * sp.k * sp.target;
  }

  void contact_forces(double t, const Eigen::VectorXd& v, Eigen::VectorXd& f) {
    f.setZero();
    if constexpr (!std::is_same_v<Contact, NoContact>) {
      const ContactView view{model_, x_, v, t, opt_.dt, &R_};
      contact_.add_forces(view, f);
    }
    gather_contact_tangents();
  }

  // Each body's share of the contact tangents, as the effective-matrix terms
  // (1 - af) (K + gamma / (beta dt) C) of its nodes (statics has none: it evaluates no contact).
  void gather_contact_tangents() {
    if constexpr (ImplicitContactPolicy<Contact>) {
      for (auto& bs : systems_) bs.contact.clear();
      if (static_) return;
      const double dt = opt_.dt, kf = 1 - coef_.alpha_f, cf = coef_.gamma / (coef_.beta * dt);
      for (const auto& t : contact_.nodal_tangents()) {
        auto& bs = systems_[model_.node(t.node).body];
        const Mat3 k = kf * (t.K + cf * t.C);
        const int local = local_index_[t.node];
        if (!bs.contact.empty() && bs.contact.back().local == local && bs.contact.back().at_node() && t.at_node()) {
          bs.contact.back().K += k;
          bs.contact.back().status += t.status;
        } else {
          bs.contact.push_back({local, t.status, k, t.arm0});
        }
      }
    }
    gather_rigid_groups();
  }

  // ---- item-item pairs inside the step: rigid groups ----
  // Rigid bodies that touch each other through pairs with tangents are solved in one system (6 per
  // body, coupled by the pairs' terms), so a stacked item rests on another as on the floor. Groups
  // are rebuilt at every evaluation of the contact; a group's first (lowest) body solves it for all.
  // Pairs with a flexible body stay loads of the predictor (docs/contact/implicit_contact.md).
  int group_of(int b) const { return group_of_.empty() ? -1 : group_of_[b]; }

  void gather_rigid_groups() {
    groups_.clear();
    group_pairs_.clear();
    group_of_.clear();
    pair_active_.clear();
    if constexpr (PairTangentPolicy<Contact>) {
      const auto& pairs = contact_.pair_tangents();
      if (static_ || pairs.empty()) return;
      const int nb = model_.num_bodies();
      std::vector<int> root(nb);
      for (int b = 0; b < nb; ++b) root[b] = b;
      const auto find = [&](int b) {
        while (root[b] != b) b = root[b] = root[root[b]];
        return b;
      };
      pair_active_.assign(pairs.size(), 0);
      for (size_t k = 0; k < pairs.size(); ++k) {
        const auto& p = pairs[k];
        if (p.body_a == p.body_b || !systems_[p.body_a].rigid || !systems_[p.body_b].rigid) continue;
        pair_active_[k] = 1;
        const int ra = find(p.body_a), rb = find(p.body_b);
        if (ra != rb) root[std::max(ra, rb)] = std::min(ra, rb);
      }
      std::vector<int> group_of_root(nb, -1);
      group_of_.assign(nb, -1);
      for (size_t k = 0; k < pairs.size(); ++k) {
        if (!pair_active_[k]) continue;
        const int r = find(pairs[k].body_a);
        if (group_of_root[r] < 0) {
          group_of_root[r] = static_cast<int>(groups_.size());
          groups_.emplace_back();
          group_pairs_.emplace_back();
        }
        group_pairs_[group_of_root[r]].push_back(static_cast<int>(k));
      }
      for (int b = 0; b < nb; ++b)  // ascending: the lowest body of a group leads it
        if (const int g = group_of_root[find(b)]; g >= 0) {
          group_of_[b] = g;
          groups_[g].push_back(b);
        }
    }
  }

  // The relative position and velocity of a pair's contact points (a's minus b's) now.
  Vec3 pair_relative_position(const PairContactTangent& p) const {
    if (p.has_arms()) return x_[p.a0] + R_[p.a0] * p.arm_a0 - (x_[p.b0] + R_[p.b0] * p.arm_b0);
    return (1 - p.s) * x_[p.a0] + p.s * x_[p.a1] - ((1 - p.t) * x_[p.b0] + p.t * x_[p.b1]);
  }
  Vec3 pair_relative_velocity(const PairContactTangent& p) const {
    const auto v = [&](int n) { return Vec3(v_.segment<3>(6 * n)); };
    if (p.has_arms()) {
      const auto w = [&](int n) { return Vec3(v_.segment<3>(6 * n + 3)); };
      return v(p.a0) + w(p.a0).cross(R_[p.a0] * p.arm_a0) - (v(p.b0) + w(p.b0).cross(R_[p.b0] * p.arm_b0));
    }
    return (1 - p.s) * v(p.a0) + p.s * v(p.a1) - ((1 - p.t) * v(p.b0) + p.t * v(p.b1));
  }
  // A pair's linearised force now, less the force at its evaluation.
  Vec3 pair_shift(const PairContactTangent& p) const {
    return -(p.K * (pair_relative_position(p) - p.x) + p.C * (pair_relative_velocity(p) - p.v));
  }
  // Adds a pair force F (on a, -F on b) to the nodes as evaluate_segment_pair shares it: forces by
  // the shares, and the moments that put it at the contact point; calls add(node, 6-vector).
  template <class Add>
  void share_pair_force(const PairContactTangent& p, const Vec3& F, Add&& add) const {
    const Vec3 pa = (1 - p.s) * x_[p.a0] + p.s * x_[p.a1], pb = (1 - p.t) * x_[p.b0] + p.t * x_[p.b1];
    const Vec3 ma = (p.point - pa).cross(F), mb = (p.point - pb).cross(-F);
    Vec6 w;
    const auto put = [&](int n, double share, const Vec3& f, const Vec3& m) {
      w << share * f, share * m;
      add(n, w);
    };
    put(p.a0, 1 - p.s, F, ma);
    put(p.a1, p.s, F, ma);
    put(p.b0, 1 - p.t, -F, mb);
    put(p.b1, p.t, -F, mb);
  }

  // A group's step in carry-over mode: every member's residual, the joint solve, then each member
  // placed, checked and committed (none is committed when one is not finite).
  void solve_and_commit_group(const std::vector<int>& members) {
    for (int m : members) {
      BodyStepSums& s = sums_[m];
      timed(s.solve, [&] { residual_body(systems_[m], fext1_, s.residual_num, s.residual_den); });
    }
    update_group(members);
    resolve_changed_contacts(members);
    if (opt_.check_finite) {
      for (int m : members) {
        BodyStepSums& s = sums_[m];
        s.not_finite = s.not_finite || !increment_finite(m);
        if (s.not_finite) return;
      }
    }
    for (int m : members) commit_body(m, sums_[m]);
  }
  // The joint solve of a group from its members' residuals (r_), and each member moved there.
  void update_group(const std::vector<int>& members) {
    timed(sums_[members.front()].solve, [&] { RigidBody::group_newton_step(*this, members); });
    for (int m : members) {
      auto& bs = systems_[m];
      bs.needs_refresh = false;
      bs.assembled = false;
      timed(sums_[m].elements, [&] {
        kinematics_body(m);
        evaluate_body(m, bs.needs_refresh);
      });
    }
  }

  // The predictor's contact forces are evaluated at the velocity v_contact_ (a better guess of the
  // step's end than the predictor's); their linearisation carries them to the current state.
  void linearised_contact_at_current_state() {
    if constexpr (ImplicitContactPolicy<Contact>) {
      const auto& tangents = contact_.nodal_tangents();
      predictor_shift_.resize(tangents.size());
      for (size_t k = 0; k < tangents.size(); ++k) {
        predictor_shift_[k] = plane_contact_shift(tangents[k]);
        add_wrench(fc1_, tangents[k], predictor_shift_[k]);
      }
    }
    if constexpr (PairTangentPolicy<Contact>) {
      const auto& pairs = contact_.pair_tangents();
      pair_predictor_shift_.assign(pairs.size(), Vec3::Zero());
      for (size_t k = 0; k < pair_active_.size(); ++k) {
        if (!pair_active_[k]) continue;
        pair_predictor_shift_[k] = pair_shift(pairs[k]);
        share_pair_force(pairs[k], pair_predictor_shift_[k], [&](int n, const Vec6& w) { fc1_.segment<6>(6 * n) += w; });
      }
    }
  }

  // A carried-over step solved its equilibrium with the linearised contact forces: those at its end
  // state are the forces its work and the next step's start take (fc0_, fnet0_). The contact policy
  // then evaluates its forces at the end state once more, to commit the history of that state (a stick
  // spring's elongation, a slip direction); what it adds to f is not used.
  void contact_at_end_of_step() {
    if constexpr (ImplicitContactPolicy<Contact>) {
      const StepWork applied = step_work();
      const auto& tangents = contact_.nodal_tangents();
      for (size_t k = 0; k < tangents.size(); ++k) {
        const auto& t = tangents[k];
        if (contact_iterated_[model_.node(t.node).body]) continue;  // its fc1_ holds its end forces already
        const int i = 6 * t.node;
        const Vec6 delta6 = plane_contact_shift(t) - predictor_shift_[k];
        const Vec3 delta = delta6.template head<3>();
        add_wrench(fc0_, t, delta6);
        add_wrench(fnet0_, t, delta6);
        if (t.at_node()) {
          ledger_.contact_work += 0.5 * Du_.segment<3>(i).dot(delta);
          ledger_.contact_work_applied +=
              applied.of_end_change(applied.path(Du_.segment<3>(i), vn_.segment<3>(i), v_.segment<3>(i)), delta);
        } else {
          ledger_.contact_work += 0.5 * Du_.segment<6>(i).dot(delta6);
          ledger_.contact_work_applied +=
              applied.of_end_change(applied.path(Du_.segment<6>(i), vn_.segment<6>(i), v_.segment<6>(i)), delta6);
        }
      }
      if constexpr (PairTangentPolicy<Contact>) {
        const auto& pairs = contact_.pair_tangents();
        for (size_t k = 0; k < pair_active_.size(); ++k) {
          if (!pair_active_[k]) continue;
          share_pair_force(pairs[k], pair_shift(pairs[k]) - pair_predictor_shift_[k], [&](int n, const Vec6& w) {
            fc0_.segment<6>(6 * n) += w;
            fnet0_.segment<6>(6 * n) += w;
            ledger_.contact_work += 0.5 * Du_.segment<6>(6 * n).dot(w);
            ledger_.contact_work_applied += applied.of_end_change(
                applied.path(Du_.segment<6>(6 * n), vn_.segment<6>(6 * n), v_.segment<6>(6 * n)), w);
          });
        }
      }
      contact_delta_.setZero();
      const ContactView view{model_, x_, v_, t_state_, opt_.dt, &R_};
      contact_.end_of_step(view, contact_delta_);
    }
  }

  // Element forces (and, where a body's matrix is due, its tangent) at the current configuration.
  void evaluate_elements(bool assemble_all) {
    pool_.parallel_for(body_order_, opt_.threads,
                         [&](int b) { evaluate_body(b, assemble_all || systems_[b].needs_refresh); });
  }

  void evaluate_body(int b, bool assemble) {
    auto& bs = systems_[b];
    double* Kv = bs.K.valuePtr();
    if (assemble) std::fill(Kv, Kv + bs.K.nonZeros(), 0.0);
    // A rigid body's internal forces are zero from the start and never written: no pass to clear them.
    if (bs.rigid) return RigidBody::evaluate(bs);
    for (int n : bs.nodes) fint_.segment<6>(6 * n).setZero();
    const double kf = static_ ? 1.0 : (1 - coef_.alpha_f);
    // Structural damping: c k_e (d - d_n) / dt on the element's deformations; its tangent c / dt k_e.
    const double cd = static_ ? 0.0 : opt_.stiffness_damping / opt_.dt;
    Vec12 f, fg;
    Mat12 k, kg;
    for (size_t idx = 0; idx < bs.elements.size(); ++idx) {
      const int e = bs.elements[idx];
      const auto& el = model_.elements()[e];
      const auto cr = detail::corotate(model_.node(el.n1).X, model_.node(el.n2).X, u_[el.n1], u_[el.n2], R_[el.n1],
                                       R_[el.n2], E0_[e], props_[e].L0);
      frames_[e] = cr.E;
      d_[e] = cr.d;
      if constexpr (requires { Element::internal_force(props_[e], committed_[e], cr.d, f, trial_[e]); }) {
        if (assemble || cd > 0) Element::response(props_[e], committed_[e], cr.d, f, k, trial_[e]);
        else Element::internal_force(props_[e], committed_[e], cr.d, f, trial_[e]);
      } else {
        Element::response(props_[e], committed_[e], cr.d, f, k, trial_[e]);
      }
      fl_[e] = f;  // the members' own forces (sections, strain energy): without the damping
      if (cd > 0) {
        fd_[e] = cd * (k * (cr.d - dn_[e]));
        f += fd_[e];
        k *= 1 + cd;
      }
      for (int blk = 0; blk < 4; ++blk) fg.segment<3>(3 * blk) = cr.E * f.segment<3>(3 * blk);
      fint_.segment<6>(6 * el.n1) += fg.head<6>();
      fint_.segment<6>(6 * el.n2) += fg.tail<6>();
      if (assemble) {
        for (int i = 0; i < 4; ++i)
          for (int j = 0; j < 4; ++j)
            kg.block<3, 3>(3 * i, 3 * j) = cr.E * k.block<3, 3>(3 * i, 3 * j) * cr.E.transpose();
        if (opt_.geometric_stiffness) {
          // String stiffness of the axial force: N / l (I - e1 e1^T) on the translations.
          const Mat3 G = fl_[e][6] / cr.l * (Mat3::Identity() - cr.E.col(0) * cr.E.col(0).transpose());
          kg.block<3, 3>(0, 0) += G;
          kg.block<3, 3>(6, 6) += G;
          kg.block<3, 3>(0, 6) -= G;
          kg.block<3, 3>(6, 0) -= G;
        }
        const auto& slots = bs.element_slots[idx];
        for (int i = 0; i < 12; ++i)
          for (int j = 0; j < 12; ++j) Kv[slots[i * 12 + j]] += kf * kg(i, j);
      }
    }
    for (const auto& sp : springs_) {
      if (model_.node(sp.node).body != b) continue;
      const int i = 6 * sp.node + sp.dof;
      fint_[i] += sp.k * dof_value(sp.node, sp.dof);  // its target is a load (external_forces)
      if (assemble) Kv[bs.diag_slot[6 * local_index_[sp.node] + sp.dof]] += kf * sp.k;
    }
    if (assemble) {
      const double dt = opt_.dt;
      const double mf = static_ ? 0.0 : coef_.mass_factor(dt, opt_.mass_damping);
      for (size_t k2 = 0; k2 < bs.nodes.size(); ++k2)
        for (int i = 0; i < 6; ++i) {
          const int ld = 6 * static_cast<int>(k2) + i;
          Kv[bs.diag_slot[ld]] += mf * mass_[6 * bs.nodes[k2] + i];
        }
      // Fixed DOFs: identity rows and columns, so the pattern (and the symbolic analysis) stays.
      for (int col = 0; col < bs.ndof(); ++col)
        for (SparseMatrix::InnerIterator it(bs.K, col); it; ++it)
          if (bs.fixed[it.row()] || bs.fixed[col]) it.valueRef() = (it.row() == col) ? 1.0 : 0.0;
      bs.assembled = true;
    }
  }

  // What one body's part of a step produced; summed over the bodies (in body order, so the sums do not
  // depend on the threads' schedule) after each sweep.
  struct BodyStepSums {
    double residual_num = 0, residual_den = 0;  // squared norms of the residual and of the force scale
    double external_work = 0, contact_work = 0, contact_work_applied = 0, damping_work = 0;
    double solve = 0, factorize = 0, elements = 0;  // seconds
    int refreshed = 0, shifted = 0;
    bool solve_failed = false, not_finite = false;
    double residual() const { return std::sqrt(residual_num / std::max(residual_den, 1e-300)); }
    BodyStepSums& operator+=(const BodyStepSums& o) {
      residual_num += o.residual_num;
      residual_den += o.residual_den;
      external_work += o.external_work;
      contact_work += o.contact_work;
      contact_work_applied += o.contact_work_applied;
      damping_work += o.damping_work;
      solve += o.solve;
      factorize += o.factorize;
      elements += o.elements;
      refreshed += o.refreshed;
      shifted += o.shifted;
      solve_failed = solve_failed || o.solve_failed;
      not_finite = not_finite || o.not_finite;
      return *this;
    }
  };

  template <class F>
  void body_sweep(F&& f) {
    timed(timings_.bodies, [&] { pool_.parallel_for(body_order_, sweep_threads(), f); });
  }

  // Waking a helper thread costs about 25 us (detail/parallel.hpp): more than a rigid body's share of
  // a sweep (a few microseconds), so a scene without a flexible body sweeps on one thread.
  int sweep_threads() const {
    const bool any_flexible = std::any_of(systems_.begin(), systems_.end(), [](const auto& bs) { return !bs.rigid; });
    return any_flexible ? opt_.threads : 1;
  }

  // Sums (and clears) what the bodies produced since the last call: the timings and the energy ledger
  // are accumulated; a failed solve or a non-finite increment stops the step with a diagnosis.
  BodyStepSums sum_bodies(double t) {
    BodyStepSums total;
    for (auto& s : sums_) {
      total += s;
      s = {};
    }
    timings_.solve += total.solve;
    timings_.factorize += total.factorize;
    timings_.elements += total.elements;
    ledger_.external_work += total.external_work;
    ledger_.contact_work += total.contact_work;
    ledger_.contact_work_applied += total.contact_work_applied;
    ledger_.damping_work += total.damping_work;
    if (total.solve_failed)
      throw SimulationError(t_, "the linear solver failed: the effective matrix is not positive definite or the "
                                "solution is not finite (an unsupported static model, or a diverging step)");
    if (total.not_finite)
      throw SimulationError(t, "the displacement increment is not finite: " + non_finite_diagnosis());
    return total;
  }

  // Residual of the generalized-alpha equations on one body's DOFs (into r_), and the body's shares
  // of its squared norm and of the squared force scale.
  void residual_body(const detail::BodySystem& bs, const Eigen::VectorXd& fext1, double& num, double& den) {
    const double am = coef_.alpha_m, af = coef_.alpha_f, c = opt_.mass_damping;
    if (const int b = static_cast<int>(&bs - systems_.data()); fields_[b].on) return RigidFields::residual(*this, b, num, den);
    // A node's six DOFs at once (each value by the same operations in the same order as DOF by DOF,
    // so the same bits; the sums below stay in DOF order).
    for (size_t k = 0; k < bs.nodes.size(); ++k) {
      const int i = 6 * bs.nodes[k];
      const Vec6 fx = fext1.segment<6>(i), fc = fc1_.segment<6>(i), fi = fint_.segment<6>(i), m = mass_.segment<6>(i);
      const Vec6 inertia = m.cwiseProduct((1 - am) * a_.segment<6>(i) + am * an_.segment<6>(i));
      const Vec6 damping = (c * m).cwiseProduct((1 - af) * v_.segment<6>(i) + af * vn_.segment<6>(i));
      Vec6 ri = (1 - af) * (fx + fc - fi) + af * fnet0_.segment<6>(i) - inertia - damping;
      const Vec6 scale = fx.cwiseProduct(fx) + fi.cwiseProduct(fi) + inertia.cwiseProduct(inertia) + fc.cwiseProduct(fc);
      for (int j = 0; j < 6; ++j) {
        if (bs.fixed[6 * k + j]) ri[j] = 0.0;
        num += ri[j] * ri[j];
        den += scale[j];
      }
      r_.segment<6>(i) = ri;
    }
  }
  // The whole residual (for diagnoses); returns its norm relative to the force scale.
  double residual() {
    BodyStepSums s;
    for (const auto& bs : systems_) residual_body(bs, fext1_, s.residual_num, s.residual_den);
    return s.residual();
  }

  // The start of a body's step: the state at t_n kept, the predictor "no motion" (Du = 0) with its
  // Newmark velocity and acceleration, the velocity contact sees, and the loads at t_{n+1}.
  // The Newmark rates come in the same pass over the nodes (positions stay: Du = 0): one pass less
  // over their data than a kinematics_body without the placement after it.
  void predict_body(int b, const Loads& loads) {
    auto& bs = systems_[b];
    const double dt = opt_.dt;
    if (fields_[b].refit) RigidFields::refit(*this, b);
    if (fields_[b].on) {
      RigidFields::predict(*this, b, loads);
      contact_iterated_[b] = 0;
      return;
    }
    for (int n : bs.nodes) {
      const int i = 6 * n;
      u0_[n] = u_[n];
      R0_[n] = R_[n];
      vn_.segment<6>(i) = v_.segment<6>(i);
      an_.segment<6>(i) = a_.segment<6>(i);
      Du_.segment<6>(i).setZero();
      v_contact_.segment<6>(i) = vn_.segment<6>(i) + dt * an_.segment<6>(i);
      newmark_rates(i, dt);
    }
    if (bs.rigid) RigidBody::start_step(*this, bs);
    contact_iterated_[b] = 0;
    external_forces_body(b, loads, fext1_);
  }

  // Newmark's velocity and acceleration from the increment Du, and the nodes' placement.
  void kinematics_body(int b) {
    const double dt = opt_.dt;
    auto& bs = systems_[b];
    if (fields_[b].on) return RigidFields::kinematics(*this, b);
    // Every node of a rigid body turns by the same increment: one exponential for all of them.
    const bool same_turn = bs.rigid && !bs.nodes.empty();
    const Mat3 turn = same_turn ? detail::rotation_exp(Du_.segment<3>(6 * bs.nodes.front() + 3)) : Mat3::Identity();
    bs.rigid_at_start = false;
    for (int n : bs.nodes) {
      const int i = 6 * n;
      newmark_rates(i, dt);
      u_[n] = u0_[n] + Du_.segment<3>(i);
      x_[n] = model_.node(n).X + u_[n];
      R_[n] = (same_turn ? turn : detail::rotation_exp(Du_.segment<3>(i + 3))) * R0_[n];
    }
  }

  // Newmark's acceleration and velocity of the node whose first DOF is i, from its increment Du.
  void newmark_rates(int i, double dt) {
    const Vec6 vn = vn_.segment<6>(i), an = an_.segment<6>(i);
    a_.segment<6>(i) = coef_.acceleration<Vec6>(Du_.segment<6>(i), vn, an, dt);
    v_.segment<6>(i) = coef_.velocity<Vec6>(vn, an, a_.segment<6>(i), dt);
  }

  // A force's work over a step, f0 at its start and f1 at its end, as the integrator applies it:
  // M (v1 - v0) = dt ((1 - gamma) f0 + gamma f1), moved through the step's mean velocity, so that the
  // kinetic energy's change is the sum of the forces' works (exactly for Newmark, and for
  // generalized-alpha with rho_inf = 1; with gamma = 1/2 and beta = 1/4 it is the trapezoidal rule on the
  // increment). The ledger's contact_work_applied: whether the contact gave the items energy. Its
  // contact_work (the trapezoidal rule on the increment, an estimate of the law's own work) under the
  // paper's gamma = 5/6 counts half of a contact's start force in a step in which it lets go, where the
  // scheme applies a sixth: a block landing on its side showed 3 to 9 % of its energy as contact_work
  // while its kinetic energy never gained from the contact (docs/core/theory.md, "Energy ledger"). In
  // statics (no velocities) the trapezoidal rule on the increment.
  struct StepWork {
    bool by_increment;
    double dt, gamma;
    // What a force moves through over the step: the mean velocity times dt (the increment in statics).
    template <class D, class V0, class V1>
    typename D::PlainObject path(const D& du, const V0& v0, const V1& v1) const {
      using R = typename D::PlainObject;
      return by_increment ? R(du) : R(0.5 * dt * (v0 + v1));
    }
    template <class P, class F0, class F1>
    double of(const P& path, const F0& f0, const F1& f1) const {
      return by_increment ? 0.5 * path.dot(f0 + f1) : path.dot((1 - gamma) * f0 + gamma * f1);
    }
    // The work of a change of the end force alone (contact_at_end_of_step).
    template <class P, class F1>
    double of_end_change(const P& path, const F1& delta) const {
      return (by_increment ? 0.5 : gamma) * path.dot(delta);
    }
  };
  StepWork step_work() const { return {static_, opt_.dt, coef_.gamma}; }

  // The end of a body's step: the work of the forces over the increment (trapezoidal; the contact's also
  // as applied, StepWork), the element histories committed, the ASI rule applied (integration points
  // move for the next step), and the forces the next step starts from.
  void commit_body(int b, BodyStepSums& s) {
    auto& bs = systems_[b];
    const StepWork applied = step_work();
    if (fields_[b].on) return RigidFields::commit(*this, b, s);
    for (int n : bs.nodes) {
      const int i = 6 * n;
      const auto du = Du_.segment<6>(i);
      s.external_work += 0.5 * du.dot(fext0_.segment<6>(i) + fext1_.segment<6>(i) - fgrav_.segment<6>(i) * 2.0);
      s.contact_work += 0.5 * du.dot(fc0_.segment<6>(i) + fc1_.segment<6>(i));
      s.contact_work_applied +=
          applied.of(applied.path(du, vn_.segment<6>(i), v_.segment<6>(i)), fc0_.segment<6>(i), fc1_.segment<6>(i));
      if (opt_.mass_damping > 0)
        s.damping_work -= 0.5 * opt_.mass_damping *
                          du.dot((mass_.segment<6>(i).array() * (vn_.segment<6>(i) + v_.segment<6>(i)).array()).matrix());
    }
    // A rigid body's elements are never evaluated (no forces, no history): nothing to commit or shift.
    // (Carrying a rigid body's forces in the loop above, one pass less, took more instructions than it
    // saved: 221 -> 294 M instructions over 1000 steps of configuration 3, callgrind.)
    if (!bs.rigid) {
      for (int e : bs.elements) std::swap(committed_[e], trial_[e]);
      s.shifted += shift_integration_points(b);
      if (opt_.stiffness_damping > 0 && !static_)
        for (int e : bs.elements) {  // its force at the step's start and end over the step's deformation
          s.damping_work -= 0.5 * (fdn_[e] + fd_[e]).dot(d_[e] - dn_[e]);
          dn_[e] = d_[e];
          fdn_[e] = fd_[e];
        }
    }
    for (int n : bs.nodes) {
      const int i = 6 * n;
      fext0_.segment<6>(i) = fext1_.segment<6>(i);
      fc0_.segment<6>(i) = fc1_.segment<6>(i);
      fnet0_.segment<6>(i) = fext1_.segment<6>(i) + fc1_.segment<6>(i) - fint_.segment<6>(i);
    }
    ++bs.steps_since_refresh;
  }

  double static_residual() {
    double num = 0, den = 0;
    for (int i = 0; i < r_.size(); ++i) {
      const double ri = is_fixed(i) ? 0.0 : fext1_[i] - fint_[i];
      r_[i] = ri;
      num += ri * ri;
      den += fext1_[i] * fext1_[i] + fint_[i] * fint_[i];
    }
    return std::sqrt(num / std::max(den, 1e-300));
  }

  // Solves every body's system for the residual r_ and adds the result to Du_ (statics). Returns the
  // number of bodies whose matrix was refreshed.
  int solve_bodies() {
    body_sweep([&](int b) { solve_body(b, sums_[b]); });
    return sum_bodies(t_).refreshed;
  }

  // A body's update from its residual: the solve (refreshing the matrix when due), on the first solve
  // of a step the rigid part of the increment put on the finite rotation, then the nodes moved and the
  // element forces evaluated there. False when the solve failed.
  bool update_body(int b, BodyStepSums& s, bool first_solve) {
    if (const int g = group_of(b); g >= 0) {
      if (groups_[g].front() == b) update_group(groups_[g]);
      return true;
    }
    timed(s.solve, [&] {
      solve_body(b, s);
      if (first_solve && opt_.finite_rotation_update && !s.solve_failed && !systems_[b].rigid)
        FlexibleBody::finite_rotation(*this, b);
    });
    if (s.solve_failed) return false;
    timed(s.elements, [&] {
      kinematics_body(b);
      evaluate_body(b, systems_[b].needs_refresh);
    });
    return true;
  }

  // Solves one body's system for its part of the residual r_ and adds the result to Du_, refreshing
  // (assembling and factorising) its matrix first when it is due. The body's kind does the solve.
  void solve_body(int b, BodyStepSums& s) {
    auto& bs = systems_[b];
    if (bs.steps_since_refresh >= opt_.refresh_interval_steps) bs.needs_refresh = true;
    if (bs.needs_refresh && !bs.assembled) evaluate_body(b, true);
    if (bs.rigid) RigidBody::solve(*this, bs, s);
    else FlexibleBody::solve(*this, b, s);
  }

  // A flexible body: its elements' forces and tangents, its sparse effective matrix and its own
  // linear solver, the factorisation reused between refreshes (SimulationOptions::refresh_interval_steps).
  struct FlexibleBody {
    struct ContactChange {
      int local;
      Mat6 d;   // the change of the node's term
      int dim;  // 3: on its translations only; 6: with its rotations
    };

    static void solve(Simulation& sim, int b, BodyStepSums& s) {
      auto& bs = sim.systems_[b];
      const bool reuse = sim.opt_.refresh_interval_steps > 1 && !sim.static_;
      Mat3 Q = Mat3::Identity();
      if (reuse) Q = sim.body_rotation(bs);
      // The contact terms that changed since the factorisation: small ones refined on the solution
      // (refine_solution), the others put on it by the Woodbury identity after the solve or, more than
      // max_contact_updates of them, factorised now.
      std::vector<ContactChange> changes, refine;
      if (reuse && !bs.needs_refresh && sim.opt_.frame_drift_refresh > 0) {
        const double drift = frame_drift(sim, bs, Q * bs.Q_factor.transpose());
        if (drift > sim.opt_.frame_drift_refresh) {
          bs.needs_refresh = true;
          ++bs.drift_refreshes;
        } else {
          bs.max_frame_drift = std::max(bs.max_frame_drift, drift);
        }
      }
      if (!bs.needs_refresh && !sim.static_) {
        changes = contact_changes(sim, b, Q * bs.Q_factor.transpose(), bs.max_reuse_error, refine);
        if (static_cast<int>(changes.size()) > max_contact_updates) bs.needs_refresh = true;
      }
      if (!bs.needs_refresh) {
        if (solve_reused(sim, b, s, Q, changes, refine) || s.solve_failed) return;
        // The refinement did not converge: its nodes go on the Woodbury update, or the body is factorised.
        ++bs.refinement_fallbacks;
        changes.insert(changes.end(), refine.begin(), refine.end());
        refine.clear();
        if (static_cast<int>(changes.size()) > max_contact_updates) bs.needs_refresh = true;
        else {
          solve_reused(sim, b, s, Q, changes, refine);
          return;
        }
      }
      {  // factorised now: asked for, due, or too many changes
        changes.clear();
        refine.clear();
        // A refresh asked for here (too many contact changes) finds K as last factorised: the structure at
        // that configuration and that factorisation's contact terms, which factor_contact_terms would add
        // to a second time. Assembled first, it is the tangent at the current configuration.
        if (!bs.assembled) sim.evaluate_body(b, true);
        factor_contact_terms(sim, bs);
        try {
          sim.timed(s.factorize, [&] { sim.solvers_[b]->factorize(bs.K); });
        } catch (const std::exception&) {
          s.solve_failed = true;
          return;
        }
        bs.Q_factor = Q;
        bs.frames_factor.resize(bs.elements.size());
        for (std::size_t i = 0; i < bs.elements.size(); ++i) bs.frames_factor[i] = sim.frames_[bs.elements[i]];
        bs.needs_refresh = false;
        bs.assembled = false;
        bs.steps_since_refresh = 0;
        bs.contact_column.assign(bs.nodes.size(), -1);  // the columns belong to the old factor
        bs.contact_column_dim.assign(bs.nodes.size(), 0);
        bs.contact_columns_used = 0;
        ++s.refreshed;
      }
      solve_reused(sim, b, s, Q, changes, refine);
    }

    // The reuse takes the body's rigid turn P since the factorisation out of the solve (solve_reused),
    // exact while every member turns with the body. A member that turned on its own since, as the short,
    // stiff members of a chair do while it lands (their frames 2 mrad off the body's when the chair left
    // the floor), has its axial stiffness along a stale direction: the solve's error grows with that
    // stiffness times the angle, a force the next steps carry over, and the chair's energy grew by 17 J
    // within 40 ms of free flight (docs/core/theory.md section 8, "Members that turn on their own").
    // Returns the largest sine of the angle between a member's frame now and its frame at the
    // factorisation turned by P.
    static double frame_drift(const Simulation& sim, const detail::BodySystem& bs, const Mat3& P) {
      if (bs.frames_factor.size() != bs.elements.size()) return 0;
      double worst = 0;
      for (std::size_t i = 0; i < bs.elements.size(); ++i) {
        const Mat3 rel = (P * bs.frames_factor[i]).transpose() * sim.frames_[bs.elements[i]];
        const Vec3 sin_axis(rel(2, 1) - rel(1, 2), rel(0, 2) - rel(2, 0), rel(1, 0) - rel(0, 1));
        worst = std::max(worst, 0.5 * sin_axis.norm());
      }
      return worst;
    }

    // Solves with the factorisation as it is: the changes on the Woodbury update, the refine terms by
    // refine_solution. False when that does not converge or a solve fails (nothing added to Du_ then).
    static bool solve_reused(Simulation& sim, int b, BodyStepSums& s, const Mat3& Q,
                             const std::vector<ContactChange>& changes, const std::vector<ContactChange>& refine) {
      auto& bs = sim.systems_[b];
      // Take the body's rigid rotation since the factorisation out of the right-hand side (P^T r),
      // solve with the old matrix, put it back (P y): exact for a rigidly rotated body. (".template":
      // the types depend on the simulation's; clang requires it, GCC did not.)
      const Mat3 P = Q * bs.Q_factor.transpose();
      for (size_t k = 0; k < bs.nodes.size(); ++k) {
        const int g = bs.nodes[k];
        bs.r.template segment<3>(6 * k) = P.transpose() * sim.r_.template segment<3>(6 * g);
        bs.r.template segment<3>(6 * k + 3) = P.transpose() * sim.r_.template segment<3>(6 * g + 3);
      }
      if (!sim.solvers_[b]->solve(bs.r, bs.dx) || !apply_contact_changes(sim, b, changes, bs.dx)) {
        s.solve_failed = true;
        return false;
      }
      if (!refine.empty()) {
        const int converged = refine_solution(sim, b, changes, refine);
        if (converged < 0) s.solve_failed = true;
        if (converged <= 0) return false;
      }
      for (size_t k = 0; k < bs.nodes.size(); ++k) {
        const int g = bs.nodes[k];
        sim.Du_.template segment<3>(6 * g) += P * bs.dx.template segment<3>(6 * k);
        sim.Du_.template segment<3>(6 * g + 3) += P * bs.dx.template segment<3>(6 * k + 3);
      }
      return true;
    }

    // The refine terms' changes D put on bs.dx = A_w^-1 r (A_w: the factorised matrix with the Woodbury
    // changes) by conjugate gradients on (A_w + D) x = r preconditioned by A_w: D is a few nodes' 3 x 3 or
    // 6 x 6 blocks, each below refine_ratio of its node's diagonal, so the preconditioned matrix is the
    // identity but for a low-rank part near it and CG takes a few solves (the configuration 3 default job
    // inside the step: 4 466 factorisations in 2 s became 128 with 30 solves a step). A_w p is carried
    // along (w = r + beta w) instead of multiplied. 1: converged to refine_tolerance of the solution;
    // 0: not (an indefinite or unsymmetric D, or too many iterations); -1: a solve failed.
    static int refine_solution(Simulation& sim, int b, const std::vector<ContactChange>& changes,
                               const std::vector<ContactChange>& refine) {
      auto& bs = sim.systems_[b];
      const auto times_D = [&](const Eigen::VectorXd& x, Eigen::VectorXd& out) {
        out.setZero();
        for (const auto& ch : refine) {
          if (ch.dim == 3)
            out.template segment<3>(6 * ch.local) = ch.d.template topLeftCorner<3, 3>() * x.template segment<3>(6 * ch.local);
          else
            out.template segment<6>(6 * ch.local) = ch.d * x.template segment<6>(6 * ch.local);
        }
      };
      const auto precondition = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) {
        return sim.solvers_[b]->solve(r, z) && apply_contact_changes(sim, b, changes, z);
      };
      const Eigen::Index n = bs.dx.size();
      Eigen::VectorXd r(n), z(n), p(n), w(n), q(n);
      times_D(bs.dx, r);
      r = -r;  // the residual of x0 = A_w^-1 b: b - (A_w + D) x0 = -D x0
      if (!precondition(r, z)) return -1;
      p = z;
      w = r;  // A_w p
      double rz = r.dot(z);
      if (rz == 0) return 1;
      for (int it = 0; it < max_refine_iterations; ++it) {
        times_D(p, q);
        q += w;  // (A_w + D) p
        const double pq = p.dot(q);
        if (!(pq > 0)) return 0;
        const double alpha = rz / pq;
        bs.dx += alpha * p;
        r -= alpha * q;
        ++bs.refinement_solves;
        if (std::abs(alpha) * p.norm() <= refine_tolerance * bs.dx.norm()) return 1;
        if (!precondition(r, z)) return -1;
        const double rz_next = r.dot(z), beta = rz_next / rz;
        rz = rz_next;
        p = z + beta * p;
        w = r + beta * w;
      }
      return 0;
    }
    static constexpr int max_refine_iterations = 20;
    static constexpr double refine_tolerance = 1e-8;
    static constexpr double refine_ratio = 0.5;
    // The smallest diagonal entry of a node's translations in the effective matrix without its factorised
    // contact term: the mass term m / (beta dt^2) and the members' stiffness, the scale a change is small
    // against.
    static double node_scale(const detail::BodySystem& bs, int local) {
      const double* Kv = bs.K.valuePtr();
      double scale = std::numeric_limits<double>::infinity();
      for (int i = 0; i < 3; ++i)
        scale = std::min(scale, Kv[bs.diag_slot[6 * local + i]] - bs.contact_factored[local](i, i));
      return std::max(scale, 1e-300);
    }

    // The contact terms go into the matrix when it is factorised. Between factorisations a term
    // changes (a contact opens, closes, sticks or slips): the changes that matter, at most
    // max_contact_updates nodes, are put on the solution by the Woodbury identity,
    // (K + U D U^T) x = r => x = dx - Z y, (I + D U^T Z) y = D U^T dx, Z = K^-1 U, U selecting those
    // nodes' translations, or all six DOF for a node with a contact off it (in the factor's frame:
    // terms rotated by P); Z's columns are kept until the next factorisation. A change smaller than
    // contact_change_tolerance of the term is left to the carried-over unbalance (a modified Newton
    // step). More changes than the cap are factorised in the same step: left out, even for a few steps,
    // a stiff contact on light nodes (the `stiff` law on a desk's panel edges: omega dt = 20) diverges
    // within them (docs/contact/implicit_contact.md).
    // Measured on configuration 3 under the `stiff` law, 2 s: caps of 6 to 64 cost the same
    // (17-19 s CPU); 16 factorised 197 times against the 120 of the regular refreshes.
    static constexpr int max_contact_updates = 16;
    static constexpr double contact_change_tolerance = 0.3;
    // A slipping node's tangential slope (friction's secant, mu N / |F*| of the stick spring's) falls as
    // it speeds up, and the step's linearised friction force is that slope times the node's increment
    // from the predictor: a slope left stale by 30 % (1 %) made a sliding frame slide 36 % (0.65 %)
    // short, reused for 100 steps. So any change of it beyond round-off enters the step.
    static constexpr double slip_slope_tolerance = 1e-9;


    // A contact term on its node's six DOF. At the node: K on the translations. At a point off it (a
    // member's surface, arm = R_n arm0): the point moves by du - S dtheta (S = [arm]x) and its force
    // puts the moment S f on the node, so T^T K T with T = [I, -S].
    static Mat6 node_term(const Simulation& sim, const detail::BodySystem& bs, const detail::BodySystem::ContactTerm& c) {
      Mat6 k = Mat6::Zero();
      k.topLeftCorner<3, 3>() = c.K;
      if (c.at_node()) return k;
      const Mat3 S = detail::skew(sim.R_[bs.nodes[c.local]] * c.arm0);
      k.block<3, 3>(0, 3) = -c.K * S;
      k.block<3, 3>(3, 0) = S * c.K;
      k.block<3, 3>(3, 3) = -S * c.K * S;
      return k;
    }
    static bool translational(const Mat6& k) {
      return k.rightCols<3>().isZero(0) && k.bottomLeftCorner<3, 3>().isZero(0);
    }
    // The Frobenius norm (a term on the translations: of its 3 x 3, as the factorisation sees it).
    static double term_norm(const Mat6& k) { return translational(k) ? Mat3(k.topLeftCorner<3, 3>()).norm() : k.norm(); }
    // A term in the factor's frame: each 3 x 3 block P^T B P.
    static Mat6 rotated(const Mat3& P, const Mat6& k) {
      Mat6 r;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) r.block<3, 3>(3 * i, 3 * j) = P.transpose() * Mat3(k.block<3, 3>(3 * i, 3 * j)) * P;
      return r;
    }

    // Each contact node's terms summed (a node with several surface points has several), in the order
    // the nodes first appear in bs.contact; transform(k) is applied to each term first.
    template <class Transform>
    static std::vector<int> sum_node_terms(const Simulation& sim, detail::BodySystem& bs, Transform&& transform) {
      std::vector<int> order;
      bs.contact_seen.assign(bs.nodes.size(), 0);
      bs.contact_now.resize(bs.nodes.size());
      bs.status_now.resize(bs.nodes.size());
      for (const auto& c : bs.contact) {
        const Mat6 k = transform(node_term(sim, bs, c));
        if (bs.contact_seen[c.local]) {
          bs.contact_now[c.local] += k;
          bs.status_now[c.local] += c.status;
        } else {
          bs.contact_seen[c.local] = 1;
          bs.contact_now[c.local] = k;
          bs.status_now[c.local] = c.status;
          order.push_back(c.local);
        }
      }
      return order;
    }

    static void factor_contact_terms(Simulation& sim, detail::BodySystem& bs) {
      bs.contact_factored.assign(bs.nodes.size(), Mat6::Zero());
      bs.status_factored.assign(bs.nodes.size(), 0);
      bs.factored_nodes.clear();
      if (sim.static_) return;
      double* Kv = bs.K.valuePtr();
      bs.factored_nodes = sum_node_terms(sim, bs, [](const Mat6& k) { return k; });
      for (int local : bs.factored_nodes) {
        const Mat6 k = masked(bs, local, bs.contact_now[local]);
        const int n = translational(k) ? 3 : 6;
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j) Kv[bs.node_slots[local][6 * i + j]] += k(i, j);
        bs.contact_factored[local] = k;
        bs.status_factored[local] = bs.status_now[local];
      }
    }
    static Mat6 masked(const detail::BodySystem& bs, int local, Mat6 k) {
      for (int i = 0; i < 6; ++i)
        if (bs.fixed[6 * local + i]) k.row(i).setZero(), k.col(i).setZero();
      return k;
    }

    // The change d of a node's translational term along the contact's normal and in its tangent plane,
    // each relative to that part of the term (now or as factorised, the larger; a part below 1e-3 of the
    // other is noise). The normal: the direction of the column of the term's largest diagonal entry
    // (exact for a term k_n n n^T + k_t (I - n n^T) up to k_t / k_n).
    struct PartChange {
      double normal = 0, tangential = 0;
    };
    static PartChange part_change(const Mat3& d, const Mat3& now, const Mat3& factored) {
      const Mat3 sum = now + factored;
      int j = 0;
      sum.diagonal().cwiseAbs().maxCoeff(&j);
      const Vec3 column = 0.5 * (sum.col(j) + sum.row(j).transpose());
      if (column.norm() == 0) return {};
      const Vec3 n = column.normalized();
      const Mat3 T = Mat3::Identity() - n * n.transpose();
      const double d_n = std::abs(n.dot(d * n)), b_n = std::max(std::abs(n.dot(now * n)), std::abs(n.dot(factored * n)));
      const double d_t = (T * d * T).norm(), b_t = std::max((T * now * T).norm(), (T * factored * T).norm());
      const double floor = std::max(1e-3 * std::max(b_n, b_t), 1e-300);
      return {d_n / std::max(b_n, floor), d_t / std::max(b_t, floor)};
    }
    // Whether a node's status counts a slipping term (contact_status_code).
    static bool slipping(int status) { return (status & 0xff) != 0; }

    // The nodes whose contact changed regime since the factorisation (opened, closed, stuck, slipped,
    // clamped: NodalContactTangent::status), whatever the size of the change; slipping nodes whose
    // tangential slope moved (slip_slope_tolerance); and those whose term moved by more than
    // contact_change_tolerance, as a whole or in its normal or tangential part (part_change); with the
    // change (in the factor's frame: terms rotated by P). A regime change is tested on its own: from
    // stick to slip a node's term keeps its normal part, which outweighs friction's slopes many times,
    // so a norm of the whole term can miss it. The slipping slopes were what it missed: a sliding frame
    // reused for 100 steps slid 0.011 m instead of 0.367 m (docs/contact/implicit_contact.md). The
    // largest relative change left out is the factor-reuse error (factor_reuse_error()).
    static std::vector<ContactChange> contact_changes(Simulation& sim, int b, const Mat3& P, double& left_out,
                                                      std::vector<ContactChange>& refine) {
      auto& bs = sim.systems_[b];
      if (bs.contact_factored.size() != bs.nodes.size()) bs.contact_factored.assign(bs.nodes.size(), Mat6::Zero());
      if (bs.status_factored.size() != bs.nodes.size()) bs.status_factored.assign(bs.nodes.size(), 0);
      std::vector<ContactChange> changes;
      const auto consider = [&](int local, const Mat6& now, int status) {
        const Mat6& factored = bs.contact_factored[local];
        const Mat6 d = now - factored;
        const double change = term_norm(d);
        if (change == 0) return;
        const PartChange part =
            part_change(d.topLeftCorner<3, 3>(), now.topLeftCorner<3, 3>(), factored.topLeftCorner<3, 3>());
        const double relative = std::max({change / std::max(term_norm(now), term_norm(factored)), part.normal,
                                          slipping(status) ? 0.0 : part.tangential});
        const bool slip_slope_moved = slipping(status) && part.tangential > slip_slope_tolerance;
        if (status != bs.status_factored[local] || slip_slope_moved || relative > contact_change_tolerance) {
          const bool small = sim.opt_.contact_refinement && change <= refine_ratio * node_scale(bs, local);
          (small ? refine : changes).push_back({local, d, translational(d) ? 3 : 6});
        } else {
          left_out = std::max(left_out, relative);
        }
      };
      for (int local : sum_node_terms(sim, bs, [&](const Mat6& k) { return rotated(P, k); }))
        consider(local, masked(bs, local, bs.contact_now[local]), bs.status_now[local]);
      for (int local : bs.factored_nodes)
        if (!bs.contact_seen[local]) consider(local, Mat6::Zero(), 0);
      return changes;
    }
    // Puts the changes on a solution x of the factorised matrix (bs.dx, or a refinement's vector) by the
    // Woodbury identity. False when a solve fails.
    static bool apply_contact_changes(Simulation& sim, int b, const std::vector<ContactChange>& changes, Eigen::VectorXd& x) {
      auto& bs = sim.systems_[b];
      if (changes.empty()) return true;
      for (const auto& ch : changes)
        if (bs.contact_column_dim[ch.local] < ch.dim && !add_contact_columns(sim, b, ch.local, ch.dim)) return false;
      std::vector<int> at(changes.size());
      int m = 0;
      for (std::size_t a = 0; a < changes.size(); ++a) at[a] = m, m += changes[a].dim;
      Eigen::MatrixXd S(m, m), D = Eigen::MatrixXd::Zero(m, m);
      Eigen::VectorXd rhs(m);
      for (std::size_t a = 0; a < changes.size(); ++a) {
        const auto& ca = changes[a];
        if (ca.dim == 3) {
          const Mat3 d = ca.d.template topLeftCorner<3, 3>();
          D.template block<3, 3>(at[a], at[a]) = d;
          rhs.template segment<3>(at[a]) = d * x.template segment<3>(6 * ca.local);
        } else {
          D.template block<6, 6>(at[a], at[a]) = ca.d;
          rhs.template segment<6>(at[a]) = ca.d * x.template segment<6>(6 * ca.local);
        }
        for (std::size_t c = 0; c < changes.size(); ++c)
          S.block(at[a], at[c], ca.dim, changes[c].dim) =
              bs.contact_columns.block(6 * ca.local, bs.contact_column[changes[c].local], ca.dim, changes[c].dim);
      }
      const Eigen::VectorXd y = (Eigen::MatrixXd::Identity(m, m) + D * S).partialPivLu().solve(rhs);
      if (!y.allFinite()) return false;
      for (std::size_t c = 0; c < changes.size(); ++c) {
        const int col = bs.contact_column[changes[c].local];
        if (changes[c].dim == 3) x -= bs.contact_columns.middleCols(col, 3) * y.template segment<3>(at[c]);
        else x -= bs.contact_columns.middleCols(col, 6) * y.template segment<6>(at[c]);
      }
      return true;
    }
    // K^-1 e for the first dim DOF of one local node (its translations, then its rotations; zero for a
    // fixed DOF).
    static bool add_contact_columns(Simulation& sim, int b, int local, int dim) {
      auto& bs = sim.systems_[b];
      const int n = bs.ndof(), first = bs.contact_columns_used;
      if (bs.contact_columns.rows() != n || bs.contact_columns.cols() < first + dim)
        bs.contact_columns.conservativeResize(n, std::max<Eigen::Index>(first + dim, 2 * bs.contact_columns.cols()));
      Eigen::VectorXd e = Eigen::VectorXd::Zero(n), z(n);
      for (int i = 0; i < dim; ++i) {
        const int dof = 6 * local + i;
        if (bs.fixed[dof]) {
          bs.contact_columns.col(first + i).setZero();
          continue;
        }
        e[dof] = 1;
        if (!sim.solvers_[b]->solve(e, z)) return false;
        e[dof] = 0;
        bs.contact_columns.col(first + i) = z;
      }
      bs.contact_column[local] = first;
      bs.contact_column_dim[local] = dim;
      bs.contact_columns_used += dim;
      return true;
    }

    // The linear solve moves the nodes of a turning body along tangents: each member stretches by
    // (w dt)^2 / 2 of its length, a spurious axial force that, carried over, excites the stiff axial
    // modes, which the integrator then damps: fast rigid rotation loses its energy (docs/core/theory.md).
    // Here the rigid part of a free body's increment is put on the finite rotation: with theta the
    // body's least-squares turn of the increment and c its mass centre at the step's start, every
    // node's translation gets (exp(theta) - I - [theta]x)(x0 - c), exact for a rigid turn and
    // O(theta^2) for the rest. Bodies with a fixed DOF (they do not turn freely) are left as they are.
    static void finite_rotation(Simulation& sim, int b) {
      const auto& bs = sim.systems_[b];
      const auto& mass = sim.mass_;
      const auto& x = sim.x_;
      auto& Du = sim.Du_;
      if (bs.nodes.size() < 2) return;
      for (char f : bs.fixed)
        if (f) return;
      Vec3 c = Vec3::Zero(), dc = Vec3::Zero();
      double m = 0;
      for (int n : bs.nodes) {
        c += mass[6 * n] * x[n];
        dc += mass[6 * n] * Du.template segment<3>(6 * n);
        m += mass[6 * n];
      }
      c /= m;
      dc /= m;
      // The body's rotation increment: the least-squares rigid turn of the translational increments
      // about the mass centre, J theta = sum m r x (du - dc).
      Mat3 J = Mat3::Zero();
      Vec3 h = Vec3::Zero();
      for (int n : bs.nodes) {
        const Vec3 r = x[n] - c;
        J += mass[6 * n] * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
        h += mass[6 * n] * r.cross(Du.template segment<3>(6 * n) - dc);
      }
      const Eigen::LDLT<Mat3> ldlt(J);
      if (ldlt.info() != Eigen::Success || ldlt.rcond() < 1e-9) return;  // a straight bar: no unique turn
      const Vec3 theta = ldlt.solve(h);
      if (!theta.allFinite() || theta.norm() < 1e-12) return;
      const Mat3 C = detail::rotation_exp(theta) - Mat3::Identity() - detail::skew(theta);
      for (int n : bs.nodes) Du.template segment<3>(6 * n) += C * (x[n] - c);
    }
  };

  // A rigid body (set_rigid): six DOF, the same nodes and masses (the contact may reduce its geometry);
  // its elements carry no forces. Newton on the body's translation and rotation, the residual reduced from the nodal one,
  // the nodes placed exactly on the rigid motion from the start of the step (finite rotation, no drift).
  struct RigidBody {
    // Nothing to assemble: the rigid solve builds its 6 x 6 matrix itself.
    static void evaluate(detail::BodySystem& bs) { bs.assembled = true; }

    static Vec3 mass_centre(const Simulation& sim, const detail::BodySystem& bs) {
      Vec3 c = Vec3::Zero();
      double m = 0;
      for (int n : bs.nodes) {
        c += sim.mass_[6 * n] * sim.x_[n];
        m += sim.mass_[6 * n];
      }
      return c / m;
    }

    // The body's acceleration at the start from the net forces fnet0_ (Newton-Euler about the centre of
    // mass), given to its nodes as the rigid motion's: each node's own f / m is not a rigid motion, and
    // when the contact puts a force on a few support points only it is far off (a block touching the
    // floor at 1 m/s got 100 km/s^2 at its corners, and Newmark carried that into the next steps).
    static void initial_acceleration(Simulation& sim, const detail::BodySystem& bs) {
      if (bs.nodes.empty()) return;
      const Vec3 c = mass_centre(sim, bs);
      Vec3 F = Vec3::Zero(), M = Vec3::Zero();
      Mat3 I = Mat3::Zero();
      double m = 0;
      for (int n : bs.nodes) {
        const Vec3 r = sim.x_[n] - c, f = sim.fnet0_.template segment<3>(6 * n);
        F += f;
        M += r.cross(f) + sim.fnet0_.template segment<3>(6 * n + 3);
        I += sim.mass_[6 * n] * (r.squaredNorm() * Mat3::Identity() - r * r.transpose()) + sim.node_rotary_inertia(n);
        m += sim.mass_[6 * n];
      }
      const Vec3 w = sim.v_.template segment<3>(6 * bs.nodes.front() + 3);  // one angular velocity for all
      const Vec3 ac = F / m, alpha = I.ldlt().solve(M - w.cross(I * w));
      for (int n : bs.nodes) {
        const Vec3 r = sim.x_[n] - c;
        sim.a_.template segment<3>(6 * n) = ac + alpha.cross(r) + w.cross(w.cross(r));
        sim.a_.template segment<3>(6 * n + 3) = alpha;
      }
    }

    // The motion of the step starts at the body's place at t_n.
    static void start_step(const Simulation& sim, detail::BodySystem& bs) {
      bs.rigid_c0 = mass_centre(sim, bs);
      bs.rigid_dc.setZero();
      bs.rigid_Q.setIdentity();
      bs.rigid_at_start = true;
    }

    // Statics has no inertia to hold a rigid body: its solve fails (the caller reports it).
    static void solve(Simulation& sim, detail::BodySystem& bs, BodyStepSums& s) {
      if (sim.static_) {
        s.solve_failed = true;
        return;
      }
      newton_step(sim, bs);
      bs.needs_refresh = false;
      bs.assembled = false;
    }

    // The contact terms reduced like the mass: with T = [I, -S] (dx_n = dc - S dtheta), T^T K T.
    static void add_contact_terms(const Simulation& sim, const detail::BodySystem& bs, const Vec3& c,
                                  Eigen::Matrix<double, 6, 6>& A) {
      for (const auto& ct : bs.contact) {
        const int n = bs.nodes[ct.local];
        const Mat3 S = detail::skew(ct.at_node() ? Vec3(sim.x_[n] - c) : Vec3(sim.x_[n] + sim.R_[n] * ct.arm0 - c));
        A.template block<3, 3>(0, 0) += ct.K;
        A.template block<3, 3>(0, 3) -= ct.K * S;
        A.template block<3, 3>(3, 0) += S * ct.K;
        A.template block<3, 3>(3, 3) -= S * ct.K * S;
      }
    }

    // The nodal residual's rotary inertia is the diagonal D_n in world axes (exact for isotropic D_n).
    // For a node with a point inertia on a rigid body, the moment it should have: the turned tensor
    // I_n = R_n T_n R_n^T (T_n the initial tensor) on the (generalized-alpha) angular acceleration, and
    // the gyroscopic w x I_n w. Returns the correction D alpha - I_n alpha - w x I_n w over the body.
    static Vec3 anisotropic_inertia_moment(const Simulation& sim, const detail::BodySystem& bs) {
      const double am = sim.coef_.alpha_m;
      Vec3 M = Vec3::Zero();
      for (int n : bs.nodes) {
        if (sim.rotary_index_[n] < 0) continue;  // isotropic: the diagonal is exact, w x J w = 0
        const Vec3 D = sim.mass_.template segment<3>(6 * n + 3);
        const Vec3 alpha = (1 - am) * sim.a_.template segment<3>(6 * n + 3) + am * sim.an_.template segment<3>(6 * n + 3);
        const Vec3 w = sim.v_.template segment<3>(6 * n + 3);
        const Mat3 In = sim.node_rotary_inertia(n);
        M += D.cwiseProduct(alpha) - In * alpha - w.cross(In * w);
      }
      return M;
    }

    // Nodal increments dx_n = dc + dtheta x r_n, rotations dtheta; the nodal residual and effective
    // mass reduced to 6 x 6 (T^T r, T^T M* T) and solved.
    static void newton_step(Simulation& sim, detail::BodySystem& bs) {
      const ReducedSystem sys = reduced_system(sim, bs);
      apply_increment(sim, bs, sys.A.ldlt().solve(sys.R));
    }

    // A group of rigid bodies joined by pairs (gather_rigid_groups): the members' 6 x 6 systems on the
    // diagonal, and each pair's terms k = (1 - af) (K + gamma / (beta dt) C) through the motion of its
    // contact point on each body, T = [I, -[point - c]x]: T_a^T k T_a, T_b^T k T_b, -T_a^T k T_b, -T_b^T k T_a.
    static void group_newton_step(Simulation& sim, std::span<const int> members) {
      const int n = static_cast<int>(members.size());
      Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6 * n, 6 * n);
      Eigen::VectorXd R(6 * n);
      std::vector<Vec3> centre(n);
      for (int i = 0; i < n; ++i) {
        const ReducedSystem sys = reduced_system(sim, sim.systems_[members[i]]);
        A.template block<6, 6>(6 * i, 6 * i) = sys.A;
        R.template segment<6>(6 * i) = sys.R;
        centre[i] = sys.c;
      }
      if constexpr (PairTangentPolicy<Contact>) add_pair_terms(sim, members, centre, A);
      const Eigen::VectorXd dq = A.partialPivLu().solve(R);
      for (int i = 0; i < n; ++i) apply_increment(sim, sim.systems_[members[i]], dq.template segment<6>(6 * i));
    }

    // A member template, though called only under `if constexpr`: an explicit instantiation (the compiled
    // core) instantiates every ordinary member of the class, and this one needs a contact with pair tangents
    // (a requires-clause is enough for GCC 12, not for clang 14).
    template <class = void>
    static void add_pair_terms(const Simulation& sim, std::span<const int> members, const std::vector<Vec3>& centre,
                               Eigen::MatrixXd& A) {
      const auto index = [&](int body) {
        return static_cast<int>(std::find(members.begin(), members.end(), body) - members.begin());
      };
      const double kf = 1 - sim.coef_.alpha_f, cf = sim.coef_.gamma / (sim.coef_.beta * sim.opt_.dt);
      const auto& pairs = sim.contact_.pair_tangents();
      // Summed per body pair (detail/rigid_pair_terms.hpp): the group's matrix gets each body pair's
      // blocks once. (Added pair by pair, the 6 x 6 products T^T k T were 9.8 % of configuration 3
      // rigid's instructions, callgrind.)
      detail::RigidPairTerms terms(static_cast<int>(members.size()));
      for (int k : sim.group_pairs_[sim.group_of(members.front())]) {
        const auto& p = pairs[k];
        const int ia = index(p.body_a);
        terms.add(ia, index(p.body_b), kf * (p.K + cf * p.C), p.point - centre[ia]);
      }
      terms.add_to(centre, A);
    }

    struct ReducedSystem {
      Eigen::Matrix<double, 6, 6> A;
      Vec6 R;
      Vec3 c;  // the mass centre the rotations are about
    };
    static ReducedSystem reduced_system(const Simulation& sim, const detail::BodySystem& bs) {
      const double mf = sim.coef_.mass_factor(sim.opt_.dt, sim.opt_.mass_damping);
      if (const auto& F = sim.fields_[&bs - sim.systems_.data()]; F.on) {
        Eigen::Matrix<double, 6, 6> A = detail::rigid_mass_matrix(F.mm, F.Q, mf);
        if (!sim.static_) add_contact_terms(sim, bs, F.c, A);
        return {A, F.R, F.c};
      }
      const auto& mass = sim.mass_;
      const auto& r_nodal = sim.r_;
      // Nodes not moved since start_step: their mass centre is rigid_c0, to the bit.
      const Vec3 c = bs.rigid_at_start ? bs.rigid_c0 : mass_centre(sim, bs);
      Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
      Vec6 R6 = Vec6::Zero();
      // The body's inertia tensor about c (world axes), in the same pass: sum over nodes of
      // m (|r|^2 I - r r^T) + R_n T_n R_n^T, T_n the node's initial rotary inertia (node_rotary_inertia).
      Mat3 I = Mat3::Zero();
      for (int n : bs.nodes) {
        const Vec3 r = sim.x_[n] - c;
        const Mat3 S = detail::skew(r);  // dtheta x r = -S dtheta
        const double m = mf * mass[6 * n];
        // m I on the diagonal only: the off-diagonal terms added +0 to +0 (m >= 0), the same bits.
        for (int j = 0; j < 3; ++j) A(j, j) += m;
        A.template block<3, 3>(0, 3) -= m * S;
        A.template block<3, 3>(3, 0) += m * S;
        const Vec3 rf = r_nodal.template segment<3>(6 * n), rm = r_nodal.template segment<3>(6 * n + 3);
        R6.template head<3>() += rf;
        R6.template tail<3>() += S * rf + rm;
        I += mass[6 * n] * (r.squaredNorm() * Mat3::Identity() - r * r.transpose()) + sim.rigid_node_rotary_inertia(n);
      }
      if (!sim.static_) add_contact_terms(sim, bs, c, A);
      A.template block<3, 3>(3, 3) += mf * I;
      R6.template tail<3>() += anisotropic_inertia_moment(sim, bs);
      return {A, R6, c};
    }
    // The body moved by dq (its centre's translation, then its rotation) on top of the step's motion so far.
    static void apply_increment(Simulation& sim, detail::BodySystem& bs, const Vec6& dq) {
      bs.rigid_dc += dq.template head<3>();
      bs.rigid_Q = detail::rotation_exp(dq.template tail<3>()) * bs.rigid_Q;
      const Vec3 rot = detail::rotation_log(bs.rigid_Q);
      if (auto& F = sim.fields_[&bs - sim.systems_.data()]; F.on) {
        // d_n = dc + (Q_step - I) r_n with r_n = Q_start rho_n the arm at the step's start.
        F.du = {bs.rigid_dc, (bs.rigid_Q - Mat3::Identity()) * F.Q_start};
        F.dtheta = rot;
        F.c = F.c_start + bs.rigid_dc;
        F.Q = bs.rigid_Q * F.Q_start;
        return;
      }
      for (int n : bs.nodes) {
        const Vec3 x0 = sim.model_.node(n).X + sim.u0_[n];
        sim.Du_.template segment<3>(6 * n) = bs.rigid_c0 + bs.rigid_dc + bs.rigid_Q * (x0 - bs.rigid_c0) - x0;
        sim.Du_.template segment<3>(6 * n + 3) = rot;
      }
    }
  };

  // A rigid body stepped on its fields (SimulationOptions::rigid_fields, detail/rigid_affine.hpp): the
  // nodal scheme of RigidBody with every translational field affine in the material arm rho_n and every
  // rotational one the same at every node, so the residual, the 6 x 6 system and the step's works come
  // from the body's mass moments and the nodes with contact forces. Only the nodes the step reads
  // (step_nodes_: those the contact reads and loads) are placed (x_, u_, R_, v_, a_ and the increment
  // Du_, which the contact's end-of-step work reads) once per solve, and their velocities (v_, vn_,
  // v_contact_) at the predictor, where the contact reads them; the others are placed from the fields
  // when read from outside (place_unplaced_nodes; the first second of configuration 3 rigid by hulls,
  // whose contact reads a small part of the 1301 nodes: 1262 M -> 661 M instructions, docs/performance.md 7).
  // Its nodes' u0_, R0_, an_, fext0_ and fext1_ are not kept; fc0_ and fnet0_ hold the contact forces
  // alone (the body's uniform load is g0). Du_ is zero at the predictor only in the fields (not read).
  struct RigidFields {
    using Fields = detail::RigidFieldState;
    struct Arms {  // the material positions and masses, as detail::RigidMassMoments::of reads them
      const Model& model;
      const Vec3& operator[](int n) const { return model.node(n).X; }
    };
    struct Masses {
      const Eigen::VectorXd& mass;
      double operator[](int n) const { return mass[6 * n]; }
    };
    struct Rotary {
      const Eigen::VectorXd& mass;
      Vec3 operator[](int n) const { return mass.template segment<3>(6 * n + 3); }
    };

    // Whether the body can go on its fields: rigid, free of point inertias, nodal loads and springs,
    // and its nodes placed and moving as one rigid body (fitted, then checked node by node).
    static bool eligible(const Simulation& sim, int b) {
      const auto& bs = sim.systems_[b];
      if (!sim.opt_.rigid_fields || !bs.rigid || bs.nodes.empty() || sim.static_) return false;
      for (int n : bs.nodes)
        if (sim.rotary_index_[n] >= 0 || !sim.nodal_load_.template segment<6>(6 * n).isZero(0.0)) return false;
      for (const auto& sp : sim.springs_)
        if (sim.model_.node(sp.node).body == b) return false;
      return true;
    }
    // A node's material arm, kept per body in its nodes' order (rigid_arms_).
    static const Vec3& arm(const Simulation& sim, int n) {
      return sim.rigid_arms_[sim.model_.node(n).body][sim.local_index_[n]];
    }
    static void set_arms(Simulation& sim, int b) {
      const auto& bs = sim.systems_[b];
      auto& arms = sim.rigid_arms_[b];
      arms.resize(bs.nodes.size());
      for (size_t k = 0; k < bs.nodes.size(); ++k) arms[k] = sim.model_.node(bs.nodes[k]).X - sim.fields_[b].mm.centre;
    }
    // a + B r written out: the passes over the nodes are these and stores (Eigen's product was a call).
    static Vec3 affine(const Vec3& a, const Mat3& B, const Vec3& r) {
      return Vec3(a[0] + B(0, 0) * r[0] + B(0, 1) * r[1] + B(0, 2) * r[2],
                  a[1] + B(1, 0) * r[0] + B(1, 1) * r[1] + B(1, 2) * r[2],
                  a[2] + B(2, 0) * r[0] + B(2, 1) * r[1] + B(2, 2) * r[2]);
    }
    static Vec3 at(const detail::AffineField& f, const Vec3& r) { return affine(f.a, f.B, r); }
    // A node's six values: its translational part, then its rotational part.
    static void put(double* node, const Vec3& translation, const Vec3& rotation) {
      for (int j = 0; j < 3; ++j) {
        node[j] = translation[j];
        node[3 + j] = rotation[j];
      }
    }
    static bool nonzero6(const double* p) {
      return (p[0] != 0) | (p[1] != 0) | (p[2] != 0) | (p[3] != 0) | (p[4] != 0) | (p[5] != 0);
    }

    // The fields through the nodes' state (at the start of a run, or after nodes were set from outside);
    // false, and the body stays node by node, when the nodes are not one rigid body's.
    static bool fit(Simulation& sim, int b, Fields& F) {
      const auto& bs = sim.systems_[b];
      const Arms X{sim.model_};
      const Masses m{sim.mass_};
      F.mm = detail::RigidMassMoments::of(bs.nodes, X, m, Rotary{sim.mass_});
      set_arms(sim, b);
      const int n0 = bs.nodes.front();
      F.Q = sim.R_[n0];
      F.c = Vec3::Zero();
      for (int n : bs.nodes) F.c += m[n] * sim.x_[n];
      F.c /= F.mm.mass.w;
      const auto trans = [&](const Eigen::VectorXd& v) {
        return detail::fit_affine_field(bs.nodes, F.mm, [&](int n) -> Vec3 { return v.template segment<3>(6 * n); }, X, m);
      };
      F.f.v = trans(sim.v_);
      F.f.a = trans(sim.a_);
      F.f.w = sim.v_.template segment<3>(6 * n0 + 3);
      F.f.alpha = sim.a_.template segment<3>(6 * n0 + 3);
      // Rounding of the fit is ~1e-15 of the values; anything near 1e-9 is a motion that is not rigid.
      const double size = std::sqrt(F.mm.mass.second.trace() / F.mm.mass.w) + 1.0;
      double vmax = 1, amax = 1;
      for (int n : bs.nodes) {
        vmax = std::max(vmax, sim.v_.template segment<6>(6 * n).cwiseAbs().maxCoeff());
        amax = std::max(amax, sim.a_.template segment<6>(6 * n).cwiseAbs().maxCoeff());
      }
      for (int n : bs.nodes) {
        const Vec3& rho = arm(sim, n);
        const int i = 6 * n;
        if ((sim.x_[n] - (F.c + F.Q * rho)).norm() > 1e-9 * size || (sim.R_[n] - F.Q).norm() > 1e-9 ||
            (sim.v_.template segment<3>(i) - F.f.v.at(rho)).norm() > 1e-9 * vmax ||
            (sim.v_.template segment<3>(i + 3) - F.f.w).norm() > 1e-9 * vmax ||
            (sim.a_.template segment<3>(i) - F.f.a.at(rho)).norm() > 1e-9 * amax ||
            (sim.a_.template segment<3>(i + 3) - F.f.alpha).norm() > 1e-9 * amax)
          return false;
      }
      return true;
    }

    // At the start of a run (start()): the fields from the nodes' state; the nodes' net forces become
    // their contact forces alone (a rigid body has no internal force; its uniform load is g0).
    static void begin(Simulation& sim, int b) {
      Fields& F = sim.fields_[b];
      F = {};
      if (!eligible(sim, b) || !fit(sim, b, F)) return;
      const Loads loads = sim.loads_at(sim.t_);
      F.g0 = sim.opt_.gravity * loads.gravity_factor - loads.table_acc;
      for (int n : sim.systems_[b].nodes)
        sim.fnet0_.template segment<6>(6 * n) = sim.fc0_.template segment<6>(6 * n);
      F.on = true;
    }
    // Nodes set from outside between steps: fitted again, or back to node by node (the nodal arrays
    // the node-by-node step starts from: its external forces at t_n in fext0_ and fnet0_).
    static void refit(Simulation& sim, int b) {
      Fields& F = sim.fields_[b];
      F.refit = false;
      const Vec3 g0 = F.g0;
      if (eligible(sim, b) && fit(sim, b, F)) return;
      F.on = false;
      for (int n : sim.systems_[b].nodes) {
        const int i = 6 * n;
        sim.fext0_.template segment<3>(i) = sim.mass_[i] * g0;
        sim.fext0_.template segment<3>(i + 3).setZero();
        sim.fnet0_.template segment<6>(i) = sim.fext0_.template segment<6>(i) + sim.fc0_.template segment<6>(i);
      }
    }

    // The predictor (Du = 0): Newmark's rates on the fields; the nodes' velocity (the contact's
    // linearisation reads it) and the velocity the contact is evaluated at, vn + dt an.
    static void predict(Simulation& sim, int b, const Loads& loads) {
      auto& bs = sim.systems_[b];
      Fields& F = sim.fields_[b];
      F.c_start = F.c;
      F.Q_start = F.Q;
      F.f.vn = F.f.v;
      F.f.an = F.f.a;
      F.f.wn = F.f.w;
      F.f.alphan = F.f.alpha;
      F.du = {};
      F.dtheta.setZero();
      rates(sim, F);
      F.g1 = sim.opt_.gravity * loads.gravity_factor - loads.table_acc;
      bs.rigid_c0 = F.c;
      bs.rigid_dc.setZero();
      bs.rigid_Q.setIdentity();
      bs.rigid_at_start = true;
      place_start_rates(sim, b, sim.step_nodes(b));
      sim.unplaced_[b] = !sim.step_nodes_[b].empty();
    }
    // Newmark's acceleration and velocity from the increment (IntegratorCoefficients on the fields).
    static void rates(const Simulation& sim, Fields& F) {
      const double dt = sim.opt_.dt;
      F.f.a = sim.coef_.acceleration(F.du, F.f.vn, F.f.an, dt);
      F.f.v = sim.coef_.velocity(F.f.vn, F.f.an, F.f.a, dt);
      F.f.alpha = sim.coef_.acceleration(F.dtheta, F.f.wn, F.f.alphan, dt);
      F.f.w = sim.coef_.velocity(F.f.wn, F.f.alphan, F.f.alpha, dt);
    }
    // The increment's rates and the nodes the step reads placed on the body's motion.
    static void kinematics(Simulation& sim, int b) {
      rates(sim, sim.fields_[b]);
      sim.systems_[b].rigid_at_start = false;
      place_motion(sim, b, sim.step_nodes(b));
      sim.unplaced_[b] = !sim.step_nodes_[b].empty();
    }
    // Nodes ks (local indices) of body b on the body's motion: position, displacement, rotation,
    // velocity, acceleration and increment.
    static void place_motion(const Simulation& sim, int b, std::span<const int> ks) {
      const Fields& F = sim.fields_[b];
      const Vec3 shift = F.c - F.mm.centre;  // u_n = (c - X_c) + (Q - I) rho_n: small u stays precise
      const Mat3 turn = F.Q - Mat3::Identity();
      const auto& arms = sim.rigid_arms_[b];
      const auto& nodes = sim.systems_[b].nodes;
      double* v = sim.v_.data();
      double* a = sim.a_.data();
      double* du = sim.Du_.data();
      for (int k : ks) {
        const int n = nodes[k], i = 6 * n;
        const Vec3& rho = arms[k];
        sim.u_[n] = affine(shift, turn, rho);
        sim.x_[n] = affine(F.c, F.Q, rho);
        sim.R_[n] = F.Q;
        put(v + i, at(F.f.v, rho), F.f.w);
        put(a + i, at(F.f.a, rho), F.f.alpha);
        put(du + i, at(F.du, rho), F.dtheta);
      }
    }
    // Nodes ks's velocities: now, at the step's start, and the one the contact is evaluated at.
    static void place_start_rates(const Simulation& sim, int b, std::span<const int> ks) {
      const Fields& F = sim.fields_[b];
      const detail::AffineField vc = F.f.vn + sim.opt_.dt * F.f.an;
      const Vec3 wc = F.f.wn + sim.opt_.dt * F.f.alphan;
      const auto& arms = sim.rigid_arms_[b];
      const auto& nodes = sim.systems_[b].nodes;
      double* v = sim.v_.data();
      double* vn = sim.vn_.data();
      double* vcon = sim.v_contact_.data();
      for (int k : ks) {
        const int i = 6 * nodes[k];
        put(v + i, at(F.f.v, arms[k]), F.f.w);
        put(vn + i, at(F.f.vn, arms[k]), F.f.wn);
        put(vcon + i, at(vc, arms[k]), wc);
      }
    }
    // Nodes ks placed whole: what a reader from outside sees of them (place_unplaced_nodes).
    static void place(const Simulation& sim, int b, std::span<const int> ks) {
      place_motion(sim, b, ks);
      place_start_rates(sim, b, ks);
    }
    static void place_all(const Simulation& sim, int b) {
      place(sim, b, sim.all_local_[b]);
      sim.unplaced_[b] = 0;
    }
    // A body's state at the start of the step on its fields (step_start_states).
    static void start_states(const Simulation& sim, int b, NodeStates& out) {
      const Fields& F = sim.fields_[b];
      const auto& nodes = sim.systems_[b].nodes;
      const Vec3 shift = F.c_start - F.mm.centre;
      const Mat3 turn = F.Q_start - Mat3::Identity();
      for (size_t k = 0; k < nodes.size(); ++k) {
        const int n = nodes[k], i = 6 * n;
        const Vec3& rho = sim.rigid_arms_[b][k];
        out.u[n] = affine(shift, turn, rho);
        out.x[n] = affine(F.c_start, F.Q_start, rho);
        out.R[n] = F.Q_start;
        put(out.v.data() + i, at(F.f.vn, rho), F.f.wn);
        put(out.a.data() + i, at(F.f.an, rho), F.f.alphan);
      }
    }

    // The nodes carrying forces besides their share of the uniform load: those with contact forces at
    // either end of the step.
    static std::vector<detail::RigidNodeExtra> loaded_nodes(const Simulation& sim, int b) {
      const double af = sim.coef_.alpha_f;
      std::vector<detail::RigidNodeExtra> out;
      for (int k : sim.step_nodes(b)) {
        const int n = sim.systems_[b].nodes[k], i = 6 * n;
        if (!(nonzero6(sim.fc1_.data() + i) | nonzero6(sim.fnet0_.data() + i))) continue;
        const auto fc1 = sim.fc1_.template segment<6>(i), f0 = sim.fnet0_.template segment<6>(i);
        detail::RigidNodeExtra e;
        e.rho = arm(sim, n);
        e.m = sim.mass_[i];
        e.J = sim.mass_.template segment<3>(i + 3);
        e.s = (1 - af) * fc1 + af * f0;
        e.l1.setZero();
        e.fc1 = fc1;
        out.push_back(e);
      }
      return out;
    }
    // The residual reduced to the body (kept for its 6 x 6 solve), its squared norm and force scale.
    static void residual(Simulation& sim, int b, double& num, double& den) {
      Fields& F = sim.fields_[b];
      const auto extra = loaded_nodes(sim, b);
      const auto r = detail::rigid_reduced_residual(F.mm, F.Q, F.f, sim.coef_.alpha_m, sim.coef_.alpha_f,
                                                    sim.opt_.mass_damping, F.g1, F.g0, extra);
      F.R = r.R;
      num += r.num;
      den += r.den;
    }

    // The step's works (the uniform load's and the damping's from the moments, the contact's at its
    // nodes) and the contact forces the next step starts from.
    static void commit(Simulation& sim, int b, BodyStepSums& s) {
      auto& bs = sim.systems_[b];
      Fields& F = sim.fields_[b];
      const StepWork applied = sim.step_work();
      const Vec3 g = sim.opt_.gravity;
      const auto w = detail::rigid_step_work(F.mm, F.du, F.dtheta, F.f, g - F.g0, g - F.g1, sim.opt_.mass_damping);
      s.external_work += w.external;
      s.damping_work += w.damping;
      for (int k : sim.step_nodes(b)) {
        const int i = 6 * bs.nodes[k];
        if (!(nonzero6(sim.fc0_.data() + i) | nonzero6(sim.fc1_.data() + i))) continue;
        const auto fc0 = sim.fc0_.template segment<6>(i), fc1 = sim.fc1_.template segment<6>(i);
        const auto du = sim.Du_.template segment<6>(i);
        s.contact_work += 0.5 * du.dot(fc0 + fc1);
        s.contact_work_applied +=
            applied.of(applied.path(du, sim.vn_.template segment<6>(i), sim.v_.template segment<6>(i)), fc0, fc1);
        sim.fc0_.template segment<6>(i) = fc1;
        sim.fnet0_.template segment<6>(i) = fc1;
      }
      F.g0 = F.g1;
      ++bs.steps_since_refresh;
    }

    static bool finite(const Fields& F) {
      return F.du.a.allFinite() && F.du.B.allFinite() && F.dtheta.allFinite() && F.c.allFinite() && F.Q.allFinite();
    }
    // The increment, the placement and the velocity (what first_non_finite_node checks of the nodes).
    static bool state_finite(const Fields& F) {
      return finite(F) && F.f.v.a.allFinite() && F.f.v.B.allFinite() && F.f.w.allFinite();
    }
  };
  bool increment_finite(int b) const {
    return fields_[b].on ? RigidFields::finite(fields_[b]) : detail::nodes_finite(Du_, systems_[b].nodes);
  }
  // The nodes each body's step reads (step_nodes_), from the contact's nodes_read, taken again when
  // its answer may have changed; a contact without it: every node.
  // One step of the current length to t1 (step() divides an impact's step into several).
  StepInfo step_to(double t1);
  // Into how many sub-steps the next step is divided for the fastest contact closing on a floor or wall
  // (SimulationOptions::max_impact_substeps): 1 unless the contact policy reports one.
  int substeps_for_impacts() const {
    if (opt_.max_impact_substeps <= 1 || static_) return 1;
    if constexpr (requires(const ContactView& view) { contact_.fastest_closing(view); }) {
      const ContactView view{model_, x_, v_, t_, opt_.dt, &R_};
      const double speed = contact_.fastest_closing(view);
      if (!(speed * opt_.dt > opt_.impact_travel)) return 1;  // also NaN: the step's own check reports it
      return static_cast<int>(std::min<double>(std::ceil(speed * opt_.dt / opt_.impact_travel), opt_.max_impact_substeps));
    } else {
      return 1;
    }
  }
  // A new step length: the flexible bodies' effective matrices hold the old one (their mass and
  // damping terms), so they are assembled and factorised again at their next solve.
  void set_step_length(double dt) {
    opt_.dt = dt;
    for (auto& bs : systems_)
      if (!bs.rigid) {
        bs.needs_refresh = true;
        bs.assembled = false;
      }
  }
  void update_step_nodes() {
    if constexpr (requires(std::vector<int>& out) {
                    contact_.nodes_read(model_, 0, out);
                    contact_.nodes_read_revision();
                  }) {
      if (contact_.nodes_read_revision() == step_nodes_revision_) return;
      place_unplaced_nodes();  // left by the old lists
      step_nodes_revision_ = contact_.nodes_read_revision();
      std::vector<int> read;
      for (int b = 0; b < model_.num_bodies(); ++b) {
        auto& local = step_nodes_[b];
        local.clear();
        if (!contact_.nodes_read(model_, b, read)) continue;
        for (int n : read) local.push_back(local_index_[n]);
        std::sort(local.begin(), local.end());
        if (local.size() == systems_[b].nodes.size()) local.clear();
      }
    }
  }
  // The local indices of the nodes body b's step reads.
  const std::vector<int>& step_nodes(int b) const { return step_nodes_[b].empty() ? all_local_[b] : step_nodes_[b]; }
  void place_unplaced_nodes() const {
    for (int b = 0; b < static_cast<int>(unplaced_.size()); ++b)
      if (unplaced_[b]) RigidFields::place_all(*this, b);
  }
  void place_body_nodes(int node) const {
    if (const int b = model_.node(node).body; unplaced_[b]) RigidFields::place_all(*this, b);
  }
  void place_node_if_unplaced(int n) const {
    if (const int b = model_.node(n).body; unplaced_[b])
      RigidFields::place(*this, b, std::span<const int>(&local_index_[n], 1));
  }
  int first_non_finite_node_by_body() const {
    const auto bad = [&](int n) {
      return !(x_[n].allFinite() && R_[n].allFinite() && v_.segment<6>(6 * n).allFinite());
    };
    int first = -1;
    const auto note = [&](int n) {
      if (bad(n) && (first < 0 || n < first)) first = n;
    };
    for (int b = 0; b < model_.num_bodies(); ++b) {
      const auto& nodes = systems_[b].nodes;
      if (unplaced_[b] && !RigidFields::state_finite(fields_[b])) RigidFields::place_all(*this, b);
      if (unplaced_[b])
        for (int k : step_nodes_[b]) note(nodes[k]);
      else
        for (int n : nodes) note(n);
    }
    return first;
  }
  // A node's state or load set from outside after the start: its body's fields are fitted again.
  void nodes_set_from_outside(int node) {
    if (!started_) return;
    auto& F = fields_[model_.node(node).body];
    if (F.on) F.refit = true;
  }

  // Names the first node whose state is not finite, for the diagnosis of a diverged step.
  std::string non_finite_diagnosis() const {
    for (int n = 0; n < model_.num_nodes(); ++n) {
      const bool bad = !x_[n].allFinite() || !v_.segment<6>(6 * n).allFinite() || !Du_.segment<6>(6 * n).allFinite() ||
                       !r_.segment<6>(6 * n).allFinite();
      if (bad)
        return "node " + std::to_string(n) + " of body '" + model_.body(model_.node(n).body).name +
               "' has a non-finite position, velocity or force; the step diverged (try a smaller dt or a softer "
               "penalty)";
    }
    return "a non-finite value appeared; the step diverged (try a smaller dt)";
  }

  Vec3 rotary_momentum(int n) const { return node_rotary_inertia(n) * v_.segment<3>(6 * n + 3); }

  double dof_value(int n, int dof) const {
    return dof < 3 ? u_[n][dof] : detail::rotation_log(R_[n])[dof - 3];
  }
  // Scale of the spring targets at the time of the configuration: load_scale(t_{n+1}) while a step
  // solves for t_{n+1}, like the loads (load_scale(t_n) lagged the targets one step behind them).
  double spring_scale() const { return static_ ? load_factor_ : (load_scale_ ? load_scale_(t_state_) : 1.0); }

  Mat3 body_rotation(const detail::BodySystem& bs) const {
    Vec3 xc = Vec3::Zero();
    for (int n : bs.nodes) xc += x_[n];
    xc /= std::max<size_t>(1, bs.nodes.size());
    return detail::best_rotation(
        static_cast<int>(bs.nodes.size()),
        [&](int i) { return std::pair<Vec3, Vec3>(model_.node(bs.nodes[i]).X, x_[bs.nodes[i]]); }, bs.Xc, xc);
  }

  // The ASI rule on one body's elements, from their committed states: returns how many integration
  // points moved. A body with a moved point has its forces evaluated again at the new points (so the
  // next residual sees them) and its matrix refreshed; the other bodies are not touched.
  int shift_integration_points(int b) {
    int shifted = 0;
    if constexpr (requires(State s) { s.hinge; s.plastic_increment; }) {
      auto& bs = systems_[b];
      int skip = -1;  // a partner whose point was just moved: its d_ and new s are not in equilibrium yet
      for (int e : bs.elements) {
        if (e == skip) continue;  // checked at the next step, from forces at its new point
        const int p = model_.elements()[e].partner;  // pairs are consecutive elements of one member
        State* partner = p >= 0 ? &committed_[p] : nullptr;
        const ElementProps* pp = p >= 0 ? &props_[p] : nullptr;
        if (Element::shift_integration_point(props_[e], committed_[e], d_[e], partner, pp)) {
          ++shifted;
          bs.needs_refresh = true;
          if (p > e) skip = p;
        }
      }
      if (shifted) {
        evaluate_body(b, bs.needs_refresh);
        for (int e : bs.elements) committed_[e] = trial_[e];
      }
    }
    return shifted;
  }
  int shift_integration_points() {
    int shifted = 0;
    for (int b = 0; b < model_.num_bodies(); ++b) shifted += shift_integration_points(b);
    return shifted;
  }

  double strain_energy(int e) const {
    if constexpr (requires(State s) { s.eps_p; }) {
      const auto s = Element::section_forces(props_[e], committed_[e], d_[e]).as_vector();
      double w = 0;
      for (int i = 0; i < 6; ++i) w += 0.5 * s[i] * s[i] / props_[e].D[i];
      return w * props_[e].L0;
    } else {
      return 0.5 * d_[e].dot(fl_[e]);
    }
  }

  const Model& model_;
  Integrator integrator_;
  SimulationOptions opt_;
  IntegratorCoefficients coef_;
  Contact contact_;
  std::function<Vec3(double)> table_acc_;
  std::function<double(double)> load_scale_;
  double t_ = 0, load_factor_ = 1;
  double t_state_ = 0;  // time of the current configuration: t_ between steps, t_{n+1} during a step
  long steps_ = 0;
  long impact_steps_ = 0, impact_substeps_ = 0;
  bool divided_ = false;  // the last step was divided for an impact; its start state:
  double division_start_t_ = 0;
  NodeStates division_start_;
  bool started_ = false, static_ = false;
  long factorizations_offset_ = 0;  // a loaded checkpoint's count, less the factorisations loading made

  // The arrays RigidFields places a body's nodes in are mutable: a body on its fields leaves the nodes
  // its step does not read unplaced, and the const readers place them first (place_unplaced_nodes).
  mutable std::vector<Vec3> x_, u_;  // positions, displacements (kept apart for precision)
  std::vector<Vec3> u0_;
  mutable std::vector<Mat3> R_;
  std::vector<Mat3> R0_;
  std::vector<int> rotary_index_;  // per node: its entry in rotary0_, or -1 (isotropic rotary inertia)
  std::vector<Mat3> rotary0_;      // initial rotary inertia tensors of the nodes with a point inertia
  mutable Eigen::VectorXd v_, a_, vn_, v_contact_, Du_;
  Eigen::VectorXd an_, r_, fint_, fext0_, fext1_, fc0_, fc1_, fnet0_, mass_, nodal_load_, fgrav_;
  Eigen::VectorXd contact_delta_;
  std::vector<Vec6> predictor_shift_;  // the linearised contact forces' shift from v_contact_ to v_ at the predictor
  std::vector<Vec3> pair_predictor_shift_;    // the same for the pairs of rigid groups
  std::vector<char> pair_active_;             // per pair tangent: inside a rigid group's solve
  std::vector<char> contact_iterated_;        // per body: this step's plane forces resolved at its end (fc1_)
  std::vector<std::vector<int>> groups_;      // rigid groups: their bodies, ascending
  std::vector<std::vector<int>> group_pairs_; // each group's pair tangents
  std::vector<int> group_of_;                 // per body: its group, or -1 (empty: no groups)
  std::vector<ElementProps> props_;
  std::vector<Mat3> E0_, frames_;
  std::vector<Vec12> d_, fl_;
  // Structural damping: the deformations at the step's start, and the damping force (local) now and at the
  // step's start.
  std::vector<Vec12> dn_, fd_, fdn_;
  std::vector<State> committed_, trial_;
  std::vector<int> local_index_;
  std::vector<detail::BodySystem> systems_;
  std::vector<detail::RigidFieldState> fields_;  // per body: a rigid body stepped on its fields (RigidFields)
  std::vector<std::vector<Vec3>> rigid_arms_;    // per body on its fields: its nodes' material arms
  // Per body: the local indices of the nodes its step reads (the contact's nodes_read), ascending;
  // empty: every node. A body on its fields places only these (RigidFields); unplaced_ says it left
  // the others unplaced since its fields last moved.
  std::vector<std::vector<int>> step_nodes_;
  std::vector<std::vector<int>> all_local_;  // per body: 0, 1, ..., its node count - 1
  long step_nodes_revision_ = -1;  // the contact's nodes_read_revision() they were taken at
  mutable std::vector<char> unplaced_;
  double step_start_t_ = std::numeric_limits<double>::quiet_NaN();  // step_start_time()
  std::vector<std::unique_ptr<LinearSolver>> solvers_;  // Eigen's solvers are not copyable
  EnergyLedger ledger_;
  StepTimings timings_;
  std::vector<BodyStepSums> sums_;  // each body's part of the current step
  std::vector<int> body_order_;  // bodies by decreasing size: the largest starts first in parallel loops
  detail::PoolHandle pool_;      // the helper threads of those loops (started on the first one)
  template <class F>
  void timed(double& acc, F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    acc += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  struct Spring {
    int node, dof;
    double k, target;
  };
  std::vector<Spring> springs_;
};

// ---- the entry points, defined outside the class ----
// Defined here rather than in the class body, they are not implicitly inline: a translation unit that
// declares an instantiation `extern` (below) compiles none of the solver behind them, and the compiled
// core (furniture_fem::core_compiled) provides them once (docs/performance.md section 6).

template <class Element, class Integrator, class LinearSolver, class Contact>
Simulation<Element, Integrator, LinearSolver, Contact>::Simulation(const Model& model, Integrator integrator,
                                                                  SimulationOptions options, Contact contact)
    : model_(model), integrator_(integrator), opt_(options), coef_(integrator.coefficients()),
      contact_(std::move(contact)) {
  model_.validate();
  if (!(opt_.dt >= SimulationOptions::min_dt) || !std::isfinite(opt_.dt))
    throw ModelError("simulation: dt must be finite and at least " + detail::fmt(SimulationOptions::min_dt) +
                     " s (got " + detail::fmt(opt_.dt) + ")");
  if (opt_.max_impact_substeps < 1)
    throw ModelError("simulation: max_impact_substeps must be at least 1 (got " +
                     std::to_string(opt_.max_impact_substeps) + ")");
  if (!(opt_.impact_travel > 0) || !std::isfinite(opt_.impact_travel))
    throw ModelError("simulation: impact_travel must be positive and finite (got " + detail::fmt(opt_.impact_travel) +
                     " m)");
  if (!(opt_.frame_drift_refresh >= 0) || !std::isfinite(opt_.frame_drift_refresh))
    throw ModelError("simulation: frame_drift_refresh must be finite and at least 0 rad (got " +
                     detail::fmt(opt_.frame_drift_refresh) + ")");
  if (!(opt_.stiffness_damping >= 0) || !std::isfinite(opt_.stiffness_damping))
    throw ModelError("simulation: stiffness_damping must be finite and at least 0 s (got " +
                     detail::fmt(opt_.stiffness_damping) + ")");
  if constexpr (Element::needs_pairs) {
    for (int e = 0; e < model_.num_elements(); ++e)
      if (model_.elements()[e].slot == PairSlot::none)
        throw ModelError(model_.describe_element(e) + ": the " + std::string(Element::name) +
                         " element needs members split into pairs (MemberOptions::pairs)");
  }
  setup();
}

template <class Element, class Integrator, class LinearSolver, class Contact>
StepInfo Simulation<Element, Integrator, LinearSolver, Contact>::step() {
  if (!started_) start();
  update_step_nodes();
  const int n = substeps_for_impacts();
  divided_ = false;
  if (n <= 1) {
    const StepInfo info = step_to(t_ + opt_.dt);
    ++steps_;
    return info;
  }
  // An impact: n equal sub-steps ending where the step would have (the observer sees one step). Its
  // start state is kept whole, for a run that diverges within it (step_start_time()).
  divided_ = true;
  division_start_t_ = t_;
  division_start_.x = positions();
  division_start_.u = displacements();
  division_start_.R = rotations();
  division_start_.v = velocities();
  division_start_.a = accelerations();
  const double dt = opt_.dt, t_end = t_ + dt;
  StepInfo info;
  set_step_length(dt / n);
  try {
    for (int i = 1; i <= n; ++i) {
      const StepInfo sub = step_to(i == n ? t_end : t_ + opt_.dt);
      info.iterations += sub.iterations;
      info.residual = std::max(info.residual, sub.residual);
      info.converged = info.converged && sub.converged;
      info.refreshed_bodies += sub.refreshed_bodies;
      info.shifted_points += sub.shifted_points;
    }
  } catch (...) {
    set_step_length(dt);
    throw;
  }
  set_step_length(dt);
  ++steps_;
  ++impact_steps_;
  impact_substeps_ += n;
  return info;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
StepInfo Simulation<Element, Integrator, LinearSolver, Contact>::step_to(double t1) {
  const auto step_start = std::chrono::steady_clock::now();
  struct AddTotal {
    StepTimings& t;
    std::chrono::steady_clock::time_point s;
    ~AddTotal() { t.total += std::chrono::duration<double>(std::chrono::steady_clock::now() - s).count(); }
  } add_total{timings_, step_start};
  step_start_t_ = std::numeric_limits<double>::quiet_NaN();
  t_state_ = t1;
  // Predictor "no motion" (Du = 0) and the loads at t_{n+1}. Its element forces are the last step's.
  const Loads loads = loads_at(t1);
  body_sweep([&](int b) { predict_body(b, loads); });
  step_start_t_ = t_;
  // The predictor's Newmark velocity, (1 - gamma / beta) v_n, has the wrong sign, and friction or the
  // paper's damping evaluated there would pump energy: contact sees v_n + dt a_n (v_contact_) instead.
  timed(timings_.contact, [&] {
    contact_forces(t1, v_contact_, fc1_);
    linearised_contact_at_current_state();
  });
  if (opt_.check_finite && !(detail::all_finite(fc1_) && detail::all_finite(fext1_))) {
    residual();  // for the diagnosis
    throw SimulationError(t_, "the residual is not finite (NaN or infinity) at the start of the step: " +
                                  non_finite_diagnosis());
  }
  StepKernel kernel{*this, t1};
  const StepInfo info = step_with(integrator_.mode, kernel);
  if (integrator_.mode == EquilibriumMode::carry_over) timed(timings_.contact, [&] { contact_at_end_of_step(); });
  if constexpr (requires { contact_.commit(); }) contact_.commit();
  t_ = t1;
  return info;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
StaticResult Simulation<Element, Integrator, LinearSolver, Contact>::solve_static(int increments, int max_iterations,
                                                                                  double tolerance) {
  const StaticScope statics(*this, StaticScope::restart_dynamics);
  return detail::StaticSolver<Simulation>(*this).load_control(increments, max_iterations, tolerance);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
StaticPath Simulation<Element, Integrator, LinearSolver, Contact>::solve_static_displacement(
    int node, int dof, double target, int increments, int max_iterations, double tolerance, double start_load_factor) {
  const StaticScope statics(*this, StaticScope::restart_dynamics);
  return detail::StaticSolver<Simulation>(*this).displacement_control(node, dof, target, increments, max_iterations,
                                                                      tolerance, start_load_factor);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
StaticPath Simulation<Element, Integrator, LinearSolver, Contact>::solve_static_arc_length(
    const ArcLengthOptions& options) {
  const StaticScope statics(*this, StaticScope::restart_dynamics);
  return detail::StaticSolver<Simulation>(*this).arc_length(options);
}

// What a time-stepping run instantiates of a composition (its constructor and step, both defined out of
// the class), declared `extern` (EXTERN = extern) or instantiated (EXTERN empty), for code that compiles
// a composition's runs once for other units: scene_compiled's scene simulations
// (scene/scene_simulation.hpp), the contact-dynamics tests' rooms. Inside namespace furniture_fem.
#define FFEM_SIMULATION_RUN_MEMBERS(EXTERN, ELEMENT, INTEGRATOR, SOLVER, CONTACT)                                \
  EXTERN template Simulation<ELEMENT, INTEGRATOR, SOLVER, CONTACT>::Simulation(const Model&, INTEGRATOR,          \
                                                                               SimulationOptions, CONTACT); \
  EXTERN template StepInfo Simulation<ELEMENT, INTEGRATOR, SOLVER, CONTACT>::step();                              \
  EXTERN template StepInfo Simulation<ELEMENT, INTEGRATOR, SOLVER, CONTACT>::step_to(double);

// The combinations the compiled core (src/core/simulation_instances.cpp, target
// furniture_fem::core_compiled) instantiates. A program that links it gets FURNITURE_FEM_COMPILED_CORE
// from the target and compiles none of their solver code itself: the README's snippet in 7 s instead of
// 34 s. Header-only use (furniture_fem::core) does not define it and instantiates what it uses.
#ifdef FURNITURE_FEM_COMPILED_CORE
extern template class Simulation<AsiGaussTimoshenko, Newmark, DirectLdltSolver>;
extern template class Simulation<ConventionalTimoshenko, Newmark, DirectLdltSolver>;
extern template class Simulation<CubicEulerBernoulli, Newmark, DirectLdltSolver>;
#endif

}  // namespace furniture_fem
