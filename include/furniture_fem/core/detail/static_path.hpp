#pragma once
// Internal: the static solves of a Simulation (load control, displacement control, arc-length).
// Users include furniture_fem/core/simulation.hpp, not this file.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/static_path.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif
#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "../errors.hpp"
#include "../model.hpp"
#include "../statics.hpp"
#include "rotation.hpp"

namespace furniture_fem::detail {

// Real roots of a x^2 + b x + c = 0 (a > 0), in the form that does not cancel; false when complex.
inline bool quadratic_roots(double a, double b, double c, double& x1, double& x2) {
  const double disc = b * b - 4 * a * c;
  if (!(a > 0) || !(disc >= 0)) return false;
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  x1 = q / a;
  x2 = q != 0 ? c / q : x1;
  return std::isfinite(x1) && std::isfinite(x2);
}

// Drives a Simulation's static solves (a friend of Simulation; Sim is the Simulation). Every solve
// goes increment by increment from a saved converged state: an increment that fails is undone, so
// the simulation is always left in the last converged state. Bodies are independent in statics (block
// diagonal tangent), and the load factor is one for all of them: the bordered solves (K du_I = r,
// K du_II = f_ref) are done for all bodies at once, with each body's factorisation used twice.
template <class Sim>
class StaticSolver {
 public:
  // Statics cannot hold a rigid body (no stiffness, no inertia): a model error, thrown.
  explicit StaticSolver(Sim& sim) : s_(sim) {
    if (!s_.started_) s_.start();
    for (int b = 0; b < s_.model_.num_bodies(); ++b)
      if (s_.systems_[b].rigid)
        throw SimulationError(s_.t_, "statics cannot hold the rigid body '" + s_.model_.body(b).name +
                                         "' (set_rigid): it has neither stiffness nor, in statics, inertia");
  }

  // Load control: the load factor k / increments, full Newton at each.
  StaticResult load_control(int increments, int max_iterations, double tolerance) {
    StaticResult res;
    double lambda = 0;
    for (int k = 1; k <= increments; ++k) {
      save(lambda);
      const double target = double(k) / increments;
      const Attempt a = settled(newton(target, max_iterations, tolerance),
                                [&] { return newton(target, max_iterations, tolerance); });
      res.iterations += a.iterations;
      res.residual = a.residual;
      if (a.outcome != Outcome::converged) {
        res.converged = false;
        lambda = restore();
        res.reason = why(a, target, max_iterations) + "; left at load factor " + fmt(lambda) +
                     ", the last converged increment (past a limit load, follow the path with "
                     "solve_static_displacement or solve_static_arc_length)";
        break;
      }
      res.increments = k;
      lambda = target;
    }
    res.load_factor = lambda;
    finish(lambda);
    return res;
  }

  // Displacement control: DOF (node, dof) moved to target in equal increments from where it is; the
  // load factor of each increment is what the constraint asks for (bordered Newton).
  StaticPath displacement_control(int node, int dof, double target, int increments, int max_iterations,
                                  double tolerance, double start_load_factor) {
    check_dof("solve_static_displacement", node, dof);
    if (increments < 1) throw ModelError("solve_static_displacement: increments must be at least 1");
    reference_load();
    StaticPath path;
    double lambda = start_load_factor;
    const double v0 = s_.dof_value(node, dof);
    path.points.push_back({lambda, v0, 0});
    // An increment that fails is undone and tried again in halves, down to 1/64 of the nominal
    // step; the step grows back after each success.
    const double nominal = (target - v0) / increments;
    double step = nominal, reached = v0;
    for (;;) {
      save(lambda);
      const bool last = std::abs(target - reached) <= std::abs(step) * (1 + 1e-12);
      const double goal = last ? target : reached + step;
      auto attempt = [&] { return controlled_newton(node, dof, goal, lambda, max_iterations, tolerance); };
      const Attempt a = settled(attempt(), attempt);
      path.iterations += a.iterations;
      if (a.outcome != Outcome::converged) {
        const std::string failure = why(a, lambda, max_iterations);
        lambda = restore();
        step *= 0.5;
        if (std::abs(step) >= std::abs(nominal) / 64) continue;
        path.converged = false;
        path.reason = failure + " (DOF " + std::to_string(dof) + " of node " + std::to_string(node) + " set to " +
                      fmt(goal) + ", after halving the increment 6 times); left at the last converged increment";
        break;
      }
      reached = goal;
      path.points.push_back({lambda, s_.dof_value(node, dof), a.iterations});
      if (last) break;
      step = std::abs(2 * step) > std::abs(nominal) ? nominal : 2 * step;
    }
    if (path.converged) path.reason = "reached the target in " + std::to_string(path.points.size() - 1) + " increments";
    finish(lambda);
    return path;
  }

  // Crisfield's cylindrical arc-length method over the translational DOFs (ArcLengthOptions).
  StaticPath arc_length(const ArcLengthOptions& o) {
    check_dof("solve_static_arc_length", o.node, o.dof);
    reference_load();
    translation_mask();
    StaticPath path;
    double lambda = o.start_load_factor;
    const double v0 = s_.dof_value(o.node, o.dof);
    path.points.push_back({lambda, v0, 0});
    double length = o.arc_length;
    if (!(length > 0)) {
      evaluate(lambda);
      if (!solve(fref_, du2_)) return stop(path, false, "the linear solver failed at the start", lambda);
      length = 0.05 * std::sqrt(dot(du2_, du2_));
    }
    const double max_length = o.max_arc_length > 0 ? o.max_arc_length : 4 * length;
    const double min_length = o.min_arc_length > 0 ? o.min_arc_length : length / 1024;
    prev_.setZero(fref_.size());
    for (int k = 0; k < o.max_increments;) {
      save(lambda);
      double next = lambda;
      const Attempt a = settled(arc_increment(length, next, o.max_iterations, o.tolerance, false),
                                [&] { return arc_increment(length, next, o.max_iterations, o.tolerance, true); });
      path.iterations += a.iterations;
      if (a.outcome != Outcome::converged) {
        restore();
        length *= 0.5;  // a shorter increment: fewer hinges at once, a smaller turn past a limit point
        if (length < min_length)
          return stop(path, false,
                      why(a, next, o.max_iterations) + "; the arc length was cut below " + fmt(min_length) +
                          "; left at the last converged increment",
                      lambda);
        continue;
      }
      ++k;
      lambda = next;
      prev_ = inc_;
      const double v = s_.dof_value(o.node, o.dof);
      path.points.push_back({lambda, v, a.iterations});
      if (lambda >= o.max_load_factor) return stop(path, true, "reached the maximum load factor", lambda);
      if (std::abs(v - v0) >= o.max_displacement) return stop(path, true, "reached the maximum displacement", lambda);
      length = std::min(max_length, 1.5 * length);  // back towards the longest after a cut
    }
    return stop(path, true, "reached the maximum number of increments (" + std::to_string(o.max_increments) + ")",
                lambda);
  }

 private:
  enum class Outcome { converged, no_convergence, solver_failed, not_finite, uncontrollable, no_root };
  struct Attempt {
    Outcome outcome = Outcome::no_convergence;
    int iterations = 0;
    double residual = 0;
  };

  static std::string why(const Attempt& a, double lambda, int max_iterations) {
    const std::string at = " at load factor " + fmt(lambda);
    switch (a.outcome) {
      case Outcome::solver_failed:
        return "the linear solver failed" + at + ": the tangent is singular (a mechanism formed, or a part of the "
                                                 "model is not held)";
      case Outcome::not_finite: return "the residual is not finite" + at + " (the iterations diverged)";
      case Outcome::uncontrollable:
        return "the reference load does not move the controlled DOF (its response there is zero)" + at;
      case Outcome::no_root: return "the arc-length constraint has no real root" + at;
      default:
        return "no convergence in " + std::to_string(max_iterations) + " iterations" + at + ", relative residual " +
               fmt(a.residual);
    }
  }

  void check_dof(const char* who, int node, int dof) const {
    s_.check_node(node);
    if (dof < 0 || dof > 5) throw ModelError(std::string(who) + ": dof must be 0..5 (got " + std::to_string(dof) + ")");
    if (s_.dof_fixed(node, dof))
      throw ModelError(std::string(who) + ": DOF " + std::to_string(dof) + " of node " + std::to_string(node) +
                       " is fixed");
  }

  // The load at load factor 1 (nodal loads, gravity, spring targets), zero on the fixed DOFs: the
  // loads are linear in the load factor, so this is their derivative.
  void reference_load() {
    s_.load_factor_ = 1;
    fref_.setZero(s_.fext1_.size());
    s_.external_forces(s_.t_, fref_);
    for (int i = 0; i < fref_.size(); ++i)
      if (s_.is_fixed(i)) fref_[i] = 0;
  }
  void translation_mask() {
    mask_.setZero(fref_.size());
    for (int i = 0; i < mask_.size(); ++i) mask_[i] = (i % 6 < 3 && !s_.is_fixed(i)) ? 1.0 : 0.0;
  }
  double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
    return (a.array() * mask_.array() * b.array()).sum();
  }

  // Forces, every body's tangent and the residual r_ at the current configuration and load factor;
  // returns the relative residual.
  double evaluate(double lambda) {
    cached_ = false;
    s_.load_factor_ = lambda;
    s_.external_forces(s_.t_, s_.fext1_);
    s_.evaluate_elements(true);
    for (auto& bs : s_.systems_) bs.needs_refresh = true;
    return s_.static_residual();
  }
  // K out = rhs, every body with its tangent (factorised by the first solve after evaluate, then
  // reused). False when a factorisation or a substitution failed.
  bool solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& out) {
    if (&rhs != &s_.r_) s_.r_ = rhs;
    s_.Du_.setZero();
    try {
      s_.solve_bodies();
    } catch (const SimulationError&) {
      return false;
    }
    out = s_.Du_;
    return out.allFinite();
  }
  // evaluate(lambda), unless advance has just evaluated the configuration at lambda.
  double evaluated(double lambda) {
    if (cached_ && lambda == cached_lambda_) {
      cached_ = false;
      return cached_residual_;
    }
    return evaluate(lambda);
  }
  // Moves the configuration by alpha du and the load factor from lambda by alpha dlambda, and evaluates
  // it there. alpha = 1 unless (search) that leaves the relative residual above twice `before`: a
  // Newton step thrown far along a nearly singular direction of the tangent. A joint hinged on both
  // sides (two members' ends yield together where their moments are equal) keeps only 1e-6 of its
  // elastic stiffness along the hinges' flow, while the hinges unload elastically when pushed back:
  // the full step overshoots by orders of magnitude. Then alpha is halved, up to 10 times, until the
  // residual is below twice `before`, or the smallest residual is kept. Returns alpha.
  double advance(const Eigen::VectorXd& du, double lambda, double dlambda, double before, bool search) {
    step_u_ = s_.u_;
    step_R_ = s_.R_;
    apply(du);
    double best_alpha = 1, alpha = 1, best = evaluate(lambda + dlambda);
    for (int k = 1; search && !(best <= 2 * before) && k <= 10; ++k) {
      alpha = 0.5 * alpha;
      move_from_step(alpha, du);
      const double r = evaluate(lambda + alpha * dlambda);
      if (r < best || !std::isfinite(best)) {
        best = r;
        best_alpha = alpha;
      }
    }
    if (alpha != best_alpha) {
      move_from_step(best_alpha, du);
      best = evaluate(lambda + best_alpha * dlambda);
    }
    cached_ = true;
    cached_lambda_ = lambda + best_alpha * dlambda;
    cached_residual_ = best;
    return best_alpha;
  }
  void move_from_step(double alpha, const Eigen::VectorXd& du) {
    s_.u_ = step_u_;
    s_.R_ = step_R_;
    du_step_ = alpha * du;
    apply(du_step_);
  }
  void apply(const Eigen::VectorXd& du) {
    for (int n = 0; n < s_.model_.num_nodes(); ++n) {
      s_.u_[n] += du.template segment<3>(6 * n);
      s_.x_[n] = s_.model_.node(n).X + s_.u_[n];
      s_.R_[n] = rotation_exp(du.template segment<3>(6 * n + 3)) * s_.R_[n];
    }
  }
  // An increment that converged (a) is committed and the ASI rule applied. When it moved integration
  // points, the forces at a new hinge can be off the yield surface (its section yielded beyond Mp
  // within the increment that makes it a hinge): equilibrium is sought again under the increment's
  // constraint (`again`) and committed. Without this, an increment could carry a load past the
  // collapse load (by what the last hinge's section took elastically beyond Mp) and report it as
  // converged. The ASI rule is not applied to that second solve: its small change would close hinges
  // that merely did not flow in it (the rule closes a hinge without a plastic increment), and they
  // would open again at the next increment, a plateau that wobbles; hinges that form or close in it
  // are found at the end of the next increment.
  template <class Again>
  Attempt settled(Attempt a, Again&& again) {
    if (a.outcome != Outcome::converged) return a;
    s_.committed_ = s_.trial_;
    if (s_.shift_integration_points() == 0) return a;
    const Attempt b = again();
    if (b.outcome == Outcome::converged) s_.committed_ = s_.trial_;
    return {b.outcome, a.iterations + b.iterations, b.residual};
  }
  void save(double lambda) {
    saved_u_ = s_.u_;
    saved_R_ = s_.R_;
    saved_committed_ = s_.committed_;
    saved_lambda_ = lambda;
  }
  // Back to the saved state (forces evaluated there); returns its load factor.
  double restore() {
    s_.u_ = saved_u_;
    s_.R_ = saved_R_;
    for (int n = 0; n < s_.model_.num_nodes(); ++n) s_.x_[n] = s_.model_.node(n).X + s_.u_[n];
    s_.committed_ = saved_committed_;
    evaluate(saved_lambda_);
    return saved_lambda_;
  }
  // The state left: forces and trial histories of the configuration, every matrix due for refresh.
  void finish(double lambda) { evaluate(lambda); }
  StaticPath& stop(StaticPath& path, bool converged, std::string reason, double lambda) {
    path.converged = converged;
    path.reason = std::move(reason);
    finish(lambda);
    return path;
  }

  Attempt newton(double lambda, int max_iterations, double tolerance) {
    Attempt a;
    for (int it = 0;; ++it) {
      a.residual = evaluated(lambda);
      if (!std::isfinite(a.residual)) return ended(a, Outcome::not_finite);
      if (a.residual < tolerance) return ended(a, Outcome::converged);
      if (it == max_iterations) return a;
      if (!solve(s_.r_, du_)) return ended(a, Outcome::solver_failed);
      advance(du_, lambda, 0, a.residual, true);
      ++a.iterations;
    }
  }
  static Attempt ended(Attempt a, Outcome o) {
    a.outcome = o;
    return a;
  }

  // Newton with the load factor as an unknown and DOF c = (node, dof) held at goal: each iteration
  // du = du_I + dl du_II with dl such that the DOF's update closes the gap to the goal.
  Attempt controlled_newton(int node, int dof, double goal, double& lambda, int max_iterations, double tolerance) {
    const int c = 6 * node + dof;
    const double step = std::abs(goal - s_.dof_value(node, dof));
    Attempt a;
    for (int it = 0;; ++it) {
      a.residual = evaluated(lambda);
      if (!std::isfinite(a.residual)) return ended(a, Outcome::not_finite);
      const double miss = goal - s_.dof_value(node, dof);
      // Translations meet the goal exactly after one iteration; rotations (rotation vector) converge to it.
      const bool on_goal = std::abs(miss) <= 1e-9 * step + 1e-15;
      if (a.residual < tolerance && on_goal) return ended(a, Outcome::converged);
      if (it == max_iterations) return a;
      if (!solve(s_.r_, du1_) || !solve(fref_, du2_)) return ended(a, Outcome::solver_failed);
      if (!(std::abs(du2_[c]) > 1e-12 * du2_.lpNorm<Eigen::Infinity>())) return ended(a, Outcome::uncontrollable);
      const double dl = (miss - du1_[c]) / du2_[c];
      du_ = du1_ + dl * du2_;
      lambda += advance(du_, lambda, dl, a.residual, on_goal) * dl;  // on the goal: a pure correction
      ++a.iterations;
    }
  }

  // One arc-length increment from the saved state: inc_ (the increment's displacement) of translational
  // length `length`, lambda updated. The first iteration takes the tangent predictor's root in the
  // direction of the last increment (sign of prev . du_II: past a limit point the tangent's response
  // to the load turns against the path, and the load factor decreases); the others take the root whose
  // increment is closest in direction to the current one (Crisfield 1981).
  // With resume, the iterations go on from the increment reached (inc_, dlam_: after a hinge formed).
  Attempt arc_increment(double length, double& lambda, int max_iterations, double tolerance, bool resume) {
    if (!resume) {
      lambda0_ = lambda;
      dlam_ = 0;
      inc_.setZero(fref_.size());
    }
    Attempt a;
    for (int it = 0;; ++it) {
      a.residual = evaluated(lambda0_ + dlam_);
      if (!std::isfinite(a.residual)) return ended(a, Outcome::not_finite);
      lambda = lambda0_ + dlam_;
      if ((it > 0 || resume) && a.residual < tolerance) return ended(a, Outcome::converged);
      if (it == max_iterations) return a;
      if (!solve(s_.r_, du1_) || !solve(fref_, du2_)) return ended(a, Outcome::solver_failed);
      base_ = inc_ + du1_;
      double x1 = 0, x2 = 0;
      if (!quadratic_roots(dot(du2_, du2_), 2 * dot(du2_, base_), dot(base_, base_) - length * length, x1, x2))
        return ended(a, Outcome::no_root);
      double pick;
      if (it == 0 && !resume) {
        const double sign = dot(prev_, du2_) < 0 ? -1.0 : 1.0;
        pick = sign * x1 >= sign * x2 ? x1 : x2;
      } else {
        pick = dot(base_ + x1 * du2_, inc_) >= dot(base_ + x2 * du2_, inc_) ? x1 : x2;
      }
      du_ = du1_ + pick * du2_;
      const double alpha = advance(du_, lambda0_ + dlam_, pick, a.residual, it > 0 || resume);
      inc_ += alpha * du_;
      dlam_ += alpha * pick;
      ++a.iterations;
    }
  }

  Sim& s_;
  std::vector<Vec3> saved_u_;
  std::vector<Mat3> saved_R_;
  std::vector<typename Sim::State> saved_committed_;
  double saved_lambda_ = 0, lambda0_ = 0, dlam_ = 0;  // arc-length: the increment's start and its load factor step
  std::vector<Vec3> step_u_;  // the configuration before a Newton step (advance)
  std::vector<Mat3> step_R_;
  bool cached_ = false;
  double cached_lambda_ = 0, cached_residual_ = 0;
  Eigen::VectorXd fref_, mask_, du_, du1_, du2_, du_step_, inc_, prev_, base_;
};

}  // namespace furniture_fem::detail
