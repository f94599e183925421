#pragma once
// furniture_fem/core/detail/flexible_body.hpp: Simulation::FlexibleBody, a flexible body's step: its elements' forces and tangents, its sparse effective matrix and its
// own linear solver, the factorisation reused between refreshes.
// Included by core/simulation.hpp right after the class (a member class of Simulation, defined out of
// the class so that simulation.hpp stays readable); not a header of its own.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/flexible_body.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif
#include "../dense_kernels.hpp"
#include "lu_kernels.hpp"

namespace furniture_fem {

template <class Element, class Integrator, class LinearSolver, class Contact>
struct Simulation<Element, Integrator, LinearSolver, Contact>::FlexibleBody {
  using ContactChange = detail::ContactChange;
  using Woodbury = detail::Woodbury;

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
    if (!sim.solvers_[b]->solve(bs.r, bs.dx) || (!changes.empty() && !woodbury_of(sim, b, changes, bs.solve_woodbury)) ||
        !apply_woodbury(bs, changes, bs.solve_woodbury, bs.dx)) {
      s.solve_failed = true;
      return false;
    }
    if (!refine.empty()) {
      const int converged = refine_solution(sim, b, changes, refine);
      if (converged < 0) s.solve_failed = true;
      if (converged <= 0) return false;
    }
    add_turned(sim, bs, P, bs.dx, 1.0);
    bs.solve_changes = changes;
    bs.solve_turn = P;
    return true;
  }

  // Du_ += scale P x on the body's nodes: x in the factor's frame, turned by P into the current one.
  static void add_turned(Simulation& sim, const detail::BodySystem& bs, const Mat3& P, const Eigen::VectorXd& x,
                         double scale) {
    for (size_t k = 0; k < bs.nodes.size(); ++k) {
      const int g = bs.nodes[k];
      sim.Du_.template segment<3>(6 * g) += scale * (P * x.template segment<3>(6 * k));
      sim.Du_.template segment<3>(6 * g + 3) += scale * (P * x.template segment<3>(6 * k + 3));
    }
  }

  // The flexibility of the body's pair nodes (locals) through the operator of its last solve (the
  // factorisation with that solve's Woodbury changes; the changes refined by conjugate gradients are
  // left out): G = U^T S^-1 U in the current frame, 3 x 3 blocks node by node, from the factor's
  // columns K^-1 U (kept until the next factorisation) at those nodes' rows only. A group's pair terms
  // act through it (Simulation::solve_flexible_group). False when a solve fails.
  static bool pair_flexibility(Simulation& sim, int b, const std::vector<int>& locals, Eigen::MatrixXd& G) {
    auto& bs = sim.systems_[b];
    for (int local : locals)
      if (bs.contact_column_dim[local] < 3 && !add_contact_columns(sim, b, local, 3)) return false;
    const auto n = static_cast<Eigen::Index>(locals.size());
    const auto column = [&](Eigen::Index j) { return bs.contact_column[locals[j]]; };
    G.resize(3 * n, 3 * n);
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = 0; j < n; ++j) G.block<3, 3>(3 * i, 3 * j) = bs.contact_columns.template block<3, 3>(6 * locals[i], column(j));
    if (!bs.solve_changes.empty()) {  // G -= Z_PF (I + D S_FF)^-1 D Z_FP, as apply_woodbury on each column
      const Woodbury& w = bs.solve_woodbury;
      Eigen::MatrixXd X(w.m, 3 * n), Z(3 * n, w.m);
      for (std::size_t a = 0; a < bs.solve_changes.size(); ++a) {
        const auto& ca = bs.solve_changes[a];
        for (Eigen::Index j = 0; j < n; ++j) {
          X.block(w.at[a], 3 * j, ca.dim, 3) =
              ca.d.topLeftCorner(ca.dim, ca.dim) * bs.contact_columns.block(6 * ca.local, column(j), ca.dim, 3);
          Z.block(3 * j, w.at[a], 3, ca.dim) = bs.contact_columns.block(6 * locals[j], bs.contact_column[ca.local], 3, ca.dim);
        }
      }
      const Eigen::MatrixXd Y = detail::solve_lu(w.lu, X);
      if (!Y.allFinite()) return false;
      G.noalias() -= Z * Y;
    }
    const Mat3& P = bs.solve_turn;
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = 0; j < n; ++j) G.block<3, 3>(3 * i, 3 * j) = P * G.block<3, 3>(3 * i, 3 * j) * P.transpose();
    return true;
  }
  // The body's increment less S^-1 U y: y the forces on its pair nodes (locals; current frame).
  static bool subtract_pair_response(Simulation& sim, int b, const std::vector<int>& locals, const Eigen::VectorXd& y) {
    auto& bs = sim.systems_[b];
    const Mat3& P = bs.solve_turn;
    Eigen::VectorXd v = Eigen::VectorXd::Zero(bs.ndof());
    for (std::size_t i = 0; i < locals.size(); ++i)
      v += bs.contact_columns.middleCols(bs.contact_column[locals[i]], 3) * (P.transpose() * y.segment<3>(3 * i));
    if (!apply_woodbury(bs, bs.solve_changes, bs.solve_woodbury, v)) return false;
    add_turned(sim, bs, P, v, -1.0);
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
    // z starts at zero: an iterative linear solver (CG) takes a vector of the right size as its first
    // guess, and an uninitialised one made runs with CG differ from run to run (within CG's tolerance,
    // grown by contact to 2.7e-9 m over 0.3 s; valgrind: "depends on uninitialised value(s)").
    Eigen::VectorXd r(n), z = Eigen::VectorXd::Zero(n), p(n), w(n), q(n);
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
  // The Woodbury system of a set of changes (detail::Woodbury). False when a solve fails (adding a
  // node's columns).
  static bool woodbury_of(Simulation& sim, int b, const std::vector<ContactChange>& changes, Woodbury& w) {
    auto& bs = sim.systems_[b];
    for (const auto& ch : changes)
      if (bs.contact_column_dim[ch.local] < ch.dim && !add_contact_columns(sim, b, ch.local, ch.dim)) return false;
    w.at.resize(changes.size());
    w.m = 0;
    for (std::size_t a = 0; a < changes.size(); ++a) w.at[a] = w.m, w.m += changes[a].dim;
    Eigen::MatrixXd S(w.m, w.m), D = Eigen::MatrixXd::Zero(w.m, w.m);
    for (std::size_t a = 0; a < changes.size(); ++a) {
      const auto& ca = changes[a];
      D.block(w.at[a], w.at[a], ca.dim, ca.dim) = ca.d.topLeftCorner(ca.dim, ca.dim);
      for (std::size_t c = 0; c < changes.size(); ++c)
        S.block(w.at[a], w.at[c], ca.dim, changes[c].dim) =
            bs.contact_columns.block(6 * ca.local, bs.contact_column[changes[c].local], ca.dim, changes[c].dim);
    }
    detail::factorize_lu(w.lu, Eigen::MatrixXd(Eigen::MatrixXd::Identity(w.m, w.m) + D * S));
    return true;
  }
  // Puts the changes on a solution x of the factorised matrix (bs.dx, or a refinement's vector) by the
  // Woodbury identity. False when a solve fails.
  static bool apply_contact_changes(Simulation& sim, int b, const std::vector<ContactChange>& changes, Eigen::VectorXd& x) {
    if (changes.empty()) return true;
    Woodbury w;
    return woodbury_of(sim, b, changes, w) && apply_woodbury(sim.systems_[b], changes, w, x);
  }
  // The same with the changes' Woodbury system already formed.
  static bool apply_woodbury(const detail::BodySystem& bs, const std::vector<ContactChange>& changes, const Woodbury& w,
                             Eigen::VectorXd& x) {
    if (changes.empty()) return true;
    Eigen::VectorXd rhs(w.m);
    for (std::size_t a = 0; a < changes.size(); ++a) {
      const auto& ca = changes[a];
      if (ca.dim == 3) rhs.template segment<3>(w.at[a]) = Mat3(ca.d.template topLeftCorner<3, 3>()) * x.template segment<3>(6 * ca.local);
      else rhs.template segment<6>(w.at[a]) = ca.d * x.template segment<6>(6 * ca.local);
    }
    const Eigen::VectorXd y = detail::solve_lu(w.lu, rhs);
    if (!y.allFinite()) return false;
    for (std::size_t c = 0; c < changes.size(); ++c) {
      const int col = bs.contact_column[changes[c].local];
      if (changes[c].dim == 3) x -= bs.contact_columns.middleCols(col, 3) * y.template segment<3>(w.at[c]);
      else x -= bs.contact_columns.middleCols(col, 6) * y.template segment<6>(w.at[c]);
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
    Eigen::VectorXd e = Eigen::VectorXd::Zero(n), z = Eigen::VectorXd::Zero(n);  // z: CG's first guess (refine_solution)
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
    Vec3 theta;
    if (!detail::ldlt_solve_if_regular(J, h, 1e-9, theta)) return;  // a straight bar: no unique turn
    if (!theta.allFinite() || theta.norm() < 1e-12) return;
    const Mat3 C = detail::rotation_exp(theta) - Mat3::Identity() - detail::skew(theta);
    for (int n : bs.nodes) Du.template segment<3>(6 * n) += C * (x[n] - c);
  }
};

}  // namespace furniture_fem
