#pragma once
// furniture_fem/core/detail/simulation_setup.hpp: setting up: the bodies' systems, the first accelerations and forces, the state a checkpoint
// saves and loads.
// Included by core/simulation.hpp right after the class: member functions of Simulation defined out of
// the class (declared, with what they do, in it); not a header of its own.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/simulation_setup.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif

namespace furniture_fem {

template <class Element, class Integrator, class LinearSolver, class Contact>
inline int Simulation<Element, Integrator, LinearSolver, Contact>::check_node(int n) const {
  if (n < 0 || n >= model_.num_nodes()) throw ModelError("node index out of range: " + std::to_string(n));
  return n;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::set_rigid(const std::vector<int>& bodies, bool rigid) {
  if (started_) throw ModelError("set_rigid: call before the first step");
  for (int body : bodies) {
    if (body < 0 || body >= model_.num_bodies()) throw ModelError("set_rigid: unknown body " + std::to_string(body));
    if (rigid)
      for (int n : model_.body(body).nodes)
        if (model_.node(n).fixed)
          throw ModelError("set_rigid: body '" + model_.body(body).name + "' has supported node " +
                           std::to_string(n) + "; a rigid body must be free");
  }
  for (int body : bodies) {
    systems_[body].rigid = rigid;
    // Forces a static solve may have left: a rigid body's stay zero (evaluate_body no longer clears them).
    if (rigid)
      for (int n : model_.body(body).nodes) fint_.segment<6>(6 * n).setZero();
  }
  // The contact may then test a reduced geometry of the bodies (RoomContact: their hulls' nodes).
  if constexpr (requires { contact_.set_rigid(model_, bodies, rigid); }) {
    contact_.set_rigid(model_, bodies, rigid);
  } else if constexpr (requires { contact_.set_rigid(model_, bodies[0], rigid); }) {
    for (int body : bodies) contact_.set_rigid(model_, body, rigid);
  }
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::setup() {
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
    bs.fixed.assign(bs.ndof(), 0);
    for (size_t k = 0; k < bs.nodes.size(); ++k)
      for (int i = 0; i < 6; ++i)
        if (model_.node(bs.nodes[k]).fixed & (1u << i)) bs.fixed[6 * k + i] = 1;
    Vec3 c = Vec3::Zero();
    for (int n : bs.nodes) c += model_.node(n).X;
    bs.Xc = bs.nodes.empty() ? c : Vec3(c / bs.nodes.size());
    body_order_.push_back(b);
  }
  std::stable_sort(body_order_.begin(), body_order_.end(),
                   [&](int a, int b) { return systems_[a].elements.size() > systems_[b].elements.size(); });
  if (opt_.threads <= 0) opt_.threads = detail::hardware_threads();
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::prepare_matrix(int b) {
  if (solvers_[b]) return;
  detail::build_pattern(systems_[b], model_, local_index_);
  solvers_[b] = std::make_unique<LinearSolver>();
  solvers_[b]->analyse(systems_[b].K);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::prepare_flexible_matrices() {
  for (int b = 0; b < model_.num_bodies(); ++b)
    if (!systems_[b].rigid) prepare_matrix(b);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::start() {
  started_ = true;
  prepare_flexible_matrices();
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

template <class Element, class Integrator, class LinearSolver, class Contact>
inline bool Simulation<Element, Integrator, LinearSolver, Contact>::is_fixed(int dof) const {
  return (model_.node(dof / 6).fixed >> (dof % 6)) & 1u;
}

template <class Element, class Integrator, class LinearSolver, class Contact>
template <class Self, class Archive>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::transfer_state_of(Self& s, Archive& ar) {
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
  for (int b = 0; b < s.model_.num_bodies(); ++b) {
    auto& bs = s.systems_[b];
    // The matrix's values in its fixed pattern: as factorised, unless assembled for the next refresh.
    // A body whose matrix was never made (rigid, or not started) has none.
    std::size_t nnz = static_cast<std::size_t>(bs.K.nonZeros());
    if constexpr (Archive::saving) {
      ar(nnz);
      for (std::size_t i = 0; i < nnz; ++i) ar(bs.K.valuePtr()[i]);
    } else {
      std::size_t stored = 0;
      ar(stored);
      if (stored > 0) s.prepare_matrix(b);
      nnz = static_cast<std::size_t>(bs.K.nonZeros());
      ar.expect(stored, nnz, "matrix entries of a body");
      for (std::size_t i = 0; i < nnz; ++i) ar(bs.K.valuePtr()[i]);
    }
    ar(bs.Q_factor, bs.steps_since_refresh, bs.needs_refresh, bs.assembled, bs.rigid, bs.rigid_c0, bs.rigid_dc,
       bs.rigid_Q, bs.contact, bs.contact_factored, bs.status_factored, bs.max_reuse_error, bs.frames_factor, bs.max_frame_drift, bs.drift_refreshes, bs.factored_nodes, bs.contact_columns, bs.contact_column, bs.contact_column_dim,
       bs.contact_columns_used, bs.r, bs.dx, bs.work, bs.group_factor);
  }
  long factorizations = s.factorizations();
  ar(factorizations);
  if constexpr (!Archive::saving) s.factorizations_offset_ = factorizations;
  ar(s.contact_);
}

template <class Element, class Integrator, class LinearSolver, class Contact>
inline void Simulation<Element, Integrator, LinearSolver, Contact>::refactorise_loaded_matrices() {
  for (int b = 0; b < model_.num_bodies(); ++b) {
    auto& bs = systems_[b];
    if (bs.rigid || bs.needs_refresh || bs.steps_since_refresh >= opt_.refresh_interval_steps) continue;
    if (bs.assembled)
      throw std::logic_error("furniture_fem: body " + std::to_string(b) + "'s matrix was assembled after its "
                             "factorisation but is not due a refresh: the checkpoint cannot restore its factor");
    solvers_[b]->factorize(bs.K);
  }
  long made = 0;
  for (const auto& solver : solvers_)
    if (solver) made += solver->factorizations();
  factorizations_offset_ -= made;
}

}  // namespace furniture_fem
