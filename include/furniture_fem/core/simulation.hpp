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
#include <unordered_map>
#include <utility>
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
  // s; a valid step length (step_length.hpp: finite, at least min_dt), checked by the integrator's stepper.
  double dt = 1e-3;
  static constexpr double min_dt = min_step_length;
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
// relative displacement of a's point from b's. When both bodies are rigid, or both flexible, the
// simulation solves them together with these terms (groups); otherwise the force stays a load of the
// predictor.
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
    for (const auto& solver : solvers_)
      if (solver) made += solver->factorizations();
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
  void set_rigid(int body, bool rigid = true) { set_rigid(std::vector<int>{body}, rigid); }
  // Several bodies at once (the contact's geometry is made again once: a room of many items).
  void set_rigid(const std::vector<int>& bodies, bool rigid = true);
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
    prepare_matrix(body);
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
    while (t_ < t_end - 0.5 * stepper_.dt()) {
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
  // Kinetic energy (J) of node n's lumped mass and rotary inertia: a body's is the sum over its nodes.
  double kinetic_energy(int n) const {
    return place_node_if_unplaced(n), 0.5 * (mass_[6 * n] * v_.segment<3>(6 * n).squaredNorm() + v_.segment<3>(6 * n + 3).dot(rotary_momentum(n)));
  }
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
    for (int n = 0; n < model_.num_nodes(); ++n) e.kinetic += kinetic_energy(n);
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
    for (const auto& s : solvers_)
      if (s) f += s->factorizations();
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
  class StaticScope;  // core/detail/step_kernel.hpp

  // What a step scheme (CarryOverScheme, IteratedScheme in integrators.hpp) drives: the sweeps over
  // the bodies of the step to t1, and the options it reads.
  class StepKernel;  // core/detail/step_kernel.hpp

  // A body's whole step in carry-over mode: residual, solve, update and commit while its data is in
  // the core's cache; a failed solve or a non-finite increment leaves it uncommitted (sum_bodies
  // reports it).
  void solve_and_commit_body(int b);

  // A body's (or rigid group's) step again while its floor and wall contacts at the step's end
  // differ in status from those it was solved with: a Newton step from the end state with the
  // contacts evaluated there (forces into fc1_ in place of the ones it held, their slopes into the
  // 6 x 6 system; a group's pairs carried by their linearisation to that state). The forces a body
  // ends with are the last evaluation's carried by its linearisation to the end state, as
  // contact_at_end_of_step does for the others (which then skips the body). Statuses that stop
  // changing mean the last solve had the right contacts; a status that keeps flipping (a clamp with no
  // consistent side) is left after contact_iterations. A flexible body's Newton step goes through its
  // factorisation with the new contact terms (low-rank update, or refactorised beyond the cap).
  void resolve_changed_contacts(std::span<const int> members);
  // Puts a body's plane contacts `now` in place of `used` (of the predictor's, the first time): their
  // forces in fc1_, their slopes in its system.
  template <class Contacts>
  void replace_plane_contacts(int b, Contacts& used, Contacts&& now, bool first);
  // A body's (or rigid group's) Newton step from where its last solve left it.
  void newton_step_from_current_state(std::span<const int> members);
  // A group's pair forces in fc1_ moved from the state of their last shift to the current one (their
  // linearisation); contact_at_end_of_step then adds the rest of the way to the end state.
  void carry_group_pairs_to_current_state(std::span<const int> members);
  // Takes out of fc1_ the plane forces the predictor put on a body's nodes and their shift to the
  // predictor's state (linearised_contact_at_current_state).
  void remove_predictor_plane_forces(int b);
  // A body's effective-matrix contact terms (1 - af) (K + gamma / (beta dt) C), per node, from tangents
  // (a contact off its node: a term of its own, at its point).
  void set_body_contact_terms(detail::BodySystem& bs, const std::vector<NodalContactTangent>& tangents);

  // A plane contact's force carried by its linearisation from its evaluation to the current state, as
  // force and moment on its node: -(K d + C d') with d the contact point's displacement since.
  Vec6 plane_contact_shift(const NodalContactTangent& t) const;
  // A contact's force and moment w into f on its node (a contact at its node: the force alone, so that
  // f's moments are untouched to the bit).
  static bool has_moment(const Vec6& w);
  static void add_wrench(Eigen::VectorXd& f, const NodalContactTangent& t, const Vec6& w);
  static void subtract_wrench(Eigen::VectorXd& f, const NodalContactTangent& t, const Vec6& w);

  int check_node(int n) const;

  void setup();
  // A body's sparse matrix pattern and its solver's symbolic analysis, made when the body first needs
  // them: a rigid body never does (a room of 10 000 rigid items would otherwise hold 10 000 unused
  // patterns and analyses, about two thirds of its memory).
  void prepare_matrix(int body);
  void prepare_flexible_matrices();

  // Initial accelerations from the equations of motion, and the first forces.
  void start();

  bool is_fixed(int dof) const;

  template <class Self, class Archive>
  static void transfer_state_of(Self& s, Archive& ar);
  // A flexible body whose factorisation the next steps reuse gets it again from the loaded matrix (the
  // same values give the same factor); the count of factorisations stays the saved run's.
  void refactorise_loaded_matrices();

  // What the loads are at time t: the table's acceleration, the scale of the nodal loads and spring
  // targets, and the factor on gravity (statics ramps it with the load factor). Evaluated once per
  // step on the calling thread: the time functions need not be thread-safe.
  struct Loads {
    Vec3 table_acc = Vec3::Zero();
    double scale = 1, gravity_factor = 1;
  };
  Loads loads_at(double t) const;
  void external_forces(double t, Eigen::VectorXd& f);
  void external_forces_body(int b, const Loads& loads, Eigen::VectorXd& f);

  void contact_forces(double t, const Eigen::VectorXd& v, Eigen::VectorXd& f);

  // Each body's share of the contact tangents, as the effective-matrix terms
  // (1 - af) (K + gamma / (beta dt) C) of its nodes (statics has none: it evaluates no contact).
  void gather_contact_tangents();

  // ---- item-item pairs inside the step: groups ----
  // Bodies joined by pairs with tangents are solved together, all rigid (one system, 6 per body) or all
  // flexible (solve_flexible_group), rebuilt at every evaluation of the contact; a group's lowest body
  // solves it for all. A rigid and a flexible body's pair stays a load of the predictor.
  int group_of(int b) const;
  void gather_pair_groups();

  // The relative position and velocity of a pair's contact points (a's minus b's) now.
  Vec3 pair_relative_position(const PairContactTangent& p) const;
  Vec3 pair_relative_velocity(const PairContactTangent& p) const;
  // A pair's linearised force now, less the force at its evaluation.
  Vec3 pair_shift(const PairContactTangent& p) const;
  // Adds a pair force F (on a, -F on b) to the nodes as evaluate_segment_pair shares it: forces by
  // the shares, and the moments that put it at the contact point; calls add(node, 6-vector).
  template <class Add>
  void share_pair_force(const PairContactTangent& p, const Vec3& F, Add&& add) const;

  // A group's step in carry-over mode: every member's residual, the joint solve, then each member
  // placed, checked and committed (none is committed when one is not finite).
  void solve_and_commit_group(const std::vector<int>& members);
  // The joint solve of a group from its members' residuals (r_), and each member moved there. False
  // when a flexible member's solve failed.
  bool update_group(std::span<const int> members, bool first_solve);
  // A flexible group's solve: each member by its own system S, then the pairs' terms D on the pair
  // nodes' translations U by the Woodbury identity: x = x0 - S^-1 U y, (I + D G) y = D U^T x0,
  // G = U^T S^-1 U (FlexibleBody::pair_flexibility), by GMRES near the last factorised (I + D G)
  // (detail/group_layout.hpp; docs/contact/implicit_contact.md). False when a solve failed.
  bool solve_flexible_group(std::span<const int> members, bool first_solve);
  // A flexible group's pair nodes (member i's from first[i], as its locals) and its terms D by 3 x 3 block.
  struct GroupPairNodes : detail::GroupLayout {
    struct Block { int row, col; Mat3 k; };
    std::vector<Block> terms;
  };
  GroupPairNodes group_pair_nodes(std::span<const int> members, const std::vector<int>& pairs) const;
  // G of each member at layout's nodes; false when a solve failed.
  bool group_flexibility(const detail::GroupLayout& layout, std::vector<Eigen::MatrixXd>& G);
  static Eigen::MatrixXd group_matrix(const GroupPairNodes& g, const std::vector<Eigen::MatrixXd>& G);  // I + D G
  const std::vector<PairContactTangent>& pair_tangents() const;  // the contact's (none without them)
  // f(node, w) for a pair's four nodes, w the node's share of the relative displacement (a's positive).
  template <class F>
  static void for_pair_sides(const PairContactTangent& p, F&& f);

  // The predictor's contact forces are evaluated at the velocity v_contact_ (a better guess of the
  // step's end than the predictor's); their linearisation carries them to the current state.
  void linearised_contact_at_current_state();

  // A carried-over step solved its equilibrium with the linearised contact forces: those at its end
  // state are the forces its work and the next step's start take (fc0_, fnet0_). The contact policy
  // then evaluates its forces at the end state once more, to commit the history of that state (a stick
  // spring's elongation, a slip direction); what it adds to f is not used.
  void contact_at_end_of_step();

  // Element forces (and, where a body's matrix is due, its tangent) at the current configuration.
  void evaluate_elements(bool assemble_all);

  void evaluate_body(int b, bool assemble);

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
  void body_sweep(F&& f);

  // Waking a helper thread costs about 25 us (detail/parallel.hpp): more than a rigid body's share of
  // a sweep (a few microseconds), so a scene without a flexible body sweeps on one thread.
  int sweep_threads() const;

  // Sums (and clears) what the bodies produced since the last call: the timings and the energy ledger
  // are accumulated; a failed solve or a non-finite increment stops the step with a diagnosis.
  BodyStepSums sum_bodies(double t);

  // Residual of the generalized-alpha equations on one body's DOFs (into r_), and the body's shares
  // of its squared norm and of the squared force scale.
  void residual_body(const detail::BodySystem& bs, const Eigen::VectorXd& fext1, double& num, double& den);
  // The whole residual (for diagnoses); returns its norm relative to the force scale.
  double residual();

  // The start of a body's step: the state at t_n kept, the predictor "no motion" (Du = 0) with its
  // Newmark velocity and acceleration, the velocity contact sees, and the loads at t_{n+1}.
  // The Newmark rates come in the same pass over the nodes (positions stay: Du = 0): one pass less
  // over their data than a kinematics_body without the placement after it.
  void predict_body(int b, const Loads& loads);

  // Newmark's velocity and acceleration from the increment Du, and the nodes' placement.
  void kinematics_body(int b);

  // The stepper's acceleration and velocity of the node whose first DOF is i, from its increment Du.
  void newmark_rates(int i);

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
  StepWork step_work() const;

  // The end of a body's step: the work of the forces over the increment (trapezoidal; the contact's also
  // as applied, StepWork), the element histories committed, the ASI rule applied (integration points
  // move for the next step), and the forces the next step starts from.
  void commit_body(int b, BodyStepSums& s);

  double static_residual();

  // Solves every body's system for the residual r_ and adds the result to Du_ (statics). Returns the
  // number of bodies whose matrix was refreshed.
  int solve_bodies();

  // A body's update from its residual: the solve (refreshing the matrix when due), on the first solve
  // of a step the rigid part of the increment put on the finite rotation, then the nodes moved and the
  // element forces evaluated there. False when the solve failed.
  bool update_body(int b, BodyStepSums& s, bool first_solve);

  // Solves one body's system for its part of the residual r_ and adds the result to Du_, refreshing
  // (assembling and factorising) its matrix first when it is due. The body's kind does the solve.
  void solve_body(int b, BodyStepSums& s);

  // A flexible body: its elements' forces and tangents, its sparse effective matrix and its own
  // linear solver, the factorisation reused between refreshes (SimulationOptions::refresh_interval_steps).
  struct FlexibleBody;  // core/detail/flexible_body.hpp

  // A rigid body (set_rigid): six DOF, the same nodes and masses (the contact may reduce its geometry);
  // its elements carry no forces. Newton on the body's translation and rotation, the residual reduced from the nodal one,
  // the nodes placed exactly on the rigid motion from the start of the step (finite rotation, no drift).
  struct RigidBody;  // core/detail/rigid_body.hpp

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
  struct RigidFields;  // core/detail/rigid_fields.hpp
  bool increment_finite(int b) const;
  // The nodes each body's step reads (step_nodes_), from the contact's nodes_read, taken again when
  // its answer may have changed; a contact without it: every node.
  // One step of the current length to t1 (step() divides an impact's step into several).
  StepInfo step_to(double t1);
  // Into how many sub-steps the next step is divided for the fastest contact closing on a floor or wall
  // (SimulationOptions::max_impact_substeps): 1 unless the contact policy reports one.
  int substeps_for_impacts() const;
  // A new step length: the flexible bodies' effective matrices hold the old one (their mass and
  // damping terms), so they are assembled and factorised again at their next solve.
  void set_step_length(double dt);
  void update_step_nodes();
  // The local indices of the nodes body b's step reads.
  const std::vector<int>& step_nodes(int b) const;
  void place_unplaced_nodes() const;
  void place_body_nodes(int node) const;
  void place_node_if_unplaced(int n) const;
  int first_non_finite_node_by_body() const;
  // A node's state or load set from outside after the start: its body's fields are fitted again.
  void nodes_set_from_outside(int node);

  // Names the first node whose state is not finite, for the diagnosis of a diverged step.
  std::string non_finite_diagnosis() const;

  Vec3 rotary_momentum(int n) const;

  double dof_value(int n, int dof) const;
  // Scale of the spring targets at the time of the configuration: load_scale(t_{n+1}) while a step
  // solves for t_{n+1}, like the loads (load_scale(t_n) lagged the targets one step behind them).
  double spring_scale() const;

  Mat3 body_rotation(const detail::BodySystem& bs) const;

  // The ASI rule on one body's elements, from their committed states: returns how many integration
  // points moved. A body with a moved point has its forces evaluated again at the new points (so the
  // next residual sees them) and its matrix refreshed; the other bodies are not touched.
  int shift_integration_points(int b);
  int shift_integration_points();

  double strain_energy(int e) const;

  const Model& model_;
  Integrator integrator_;
  SimulationOptions opt_;
  // The integrator's stepper, the owner of the current step length: opt_.dt, or an impact's sub-step
  // (set_step_length remakes it).
  using StepperType = decltype(std::declval<const Integrator&>().stepper(1.0));
  StepperType stepper_;
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
  std::vector<char> pair_active_;             // per pair tangent: inside a group's solve
  std::vector<char> contact_iterated_;        // per body: this step's plane forces resolved at its end (fc1_)
  std::vector<std::vector<int>> groups_;      // groups (all rigid or all flexible): their bodies, ascending
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

}  // namespace furniture_fem

// The members defined out of the class (core/detail/), before the instantiations below.
#define FURNITURE_FEM_CORE_INTERNAL
#include "detail/step_kernel.hpp"
#include "detail/simulation_contact_step.hpp"
#include "detail/simulation_setup.hpp"
#include "detail/simulation_pairs.hpp"
#include "detail/simulation_sweep.hpp"
#include "detail/simulation_step_nodes.hpp"
#include "detail/flexible_body.hpp"
#include "detail/rigid_body.hpp"
#include "detail/rigid_fields.hpp"
#include "detail/simulation_entry_points.hpp"
#undef FURNITURE_FEM_CORE_INTERNAL

namespace furniture_fem {

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
