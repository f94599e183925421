#pragma once
// furniture_fem/core/elements.hpp: element policies.
//
// An element policy works in the element's own corotated frame (local x along the chord): it turns
// the 12 local deformation DOFs [u1 v1 w1 tx1 ty1 tz1 u2 v2 w2 tx2 ty2 tz2] into local nodal forces,
// a local tangent and sectional forces, and keeps its own history (plastic strains, the position of
// its integration point). The corotational frame, large rotations and assembly live in the simulation
// (detail/body_system.hpp, simulation.hpp; docs/core/theory.md section 4), so a new element is only the
// small-strain kernel. See docs/core/concept_element.md.
//
// Policies here:
//  - AsiGaussTimoshenko: linear Timoshenko beam, one integration point shifted per the ASI-Gauss rule
//    (docs/core/theory.md sections 1-3): elastic points on the Gauss points of the pair, plastic hinges by
//    shifting the point to the yielding end, return to the elastic position on unloading.
//  - ConventionalTimoshenko: the same element with its point at the centre (s = 0): the conventional
//    one-point element; its plastic hinges follow the original ASI rule.
//  - CubicEulerBernoulli: the exact elastic beam for nodal loads (reference element, no plasticity).
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <concepts>
#include <string_view>
#include <type_traits>

#include "model.hpp"

namespace furniture_fem {

using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// Sectional forces (N, Qy, Qz, Mx, My, Mz) at a point of an element.
struct SectionForces {
  double N = 0, Qy = 0, Qz = 0, Mx = 0, My = 0, Mz = 0;
  double xi = 0;  // where they act, in [-1, 1] along the element
  Vec6 as_vector() const { return (Vec6() << N, Qy, Qz, Mx, My, Mz).finished(); }
};

// Everything an element kernel needs about its member, computed once from the model.
struct ElementProps {
  double L0 = 0;                                   // initial length
  std::array<double, 6> D{};                       // EA, kGA_y, kGA_z, GJ, EI_y, EI_z
  std::array<double, 4> yield{};                   // N0, Mx0, My0, Mz0 (fully plastic values)
  PairSlot slot = PairSlot::none;

  static ElementProps from_model(const Model& m, int e) {
    const auto& s = m.section_of(e);
    const auto& mat = m.material_of(e);
    ElementProps p;
    p.L0 = m.element_length(e);
    const double G = mat.G();
    p.D = {mat.E * s.A, G * s.Asy, G * s.Asz, G * s.J, mat.E * s.Iy, mat.E * s.Iz};
    p.yield = {mat.sigma_y * s.A, mat.sigma_y / std::sqrt(3.0) * s.Zpx, mat.sigma_y * s.Zpy, mat.sigma_y * s.Zpz};
    p.slot = m.elements()[e].slot;
    return p;
  }
};

// The element policy concept, checked where a solver is composed.
template <class E>
concept ElementPolicy = requires(const ElementProps& p, typename E::State& st, const typename E::State& cst,
                                 const Vec12& d, Vec12& f, Mat12& k) {
  typename E::State;
  { E::name } -> std::convertible_to<std::string_view>;
  { E::needs_pairs } -> std::convertible_to<bool>;
  { E::initial_state(p) } -> std::same_as<typename E::State>;
  // Trial response from the committed history: local force f, local tangent k, trial history st.
  E::response(p, cst, d, f, k, st);
  { E::section_forces(p, cst, d) } -> std::same_as<SectionForces>;
};

namespace detail {

// Strain-displacement matrix of the one-point linear Timoshenko element at xi = s.
inline Eigen::Matrix<double, 6, 12> timoshenko_B(double L, double s) {
  const double N1 = 0.5 * (1 - s), N2 = 0.5 * (1 + s);
  Eigen::Matrix<double, 6, 12> B = Eigen::Matrix<double, 6, 12>::Zero();
  B(0, 0) = -1 / L; B(0, 6) = 1 / L;                                       // eps      = u'
  B(1, 1) = -1 / L; B(1, 7) = 1 / L; B(1, 5) = -N1; B(1, 11) = -N2;         // gamma_xy = v' - tz
  B(2, 2) = -1 / L; B(2, 8) = 1 / L; B(2, 4) = N1; B(2, 10) = N2;           // gamma_xz = w' + ty
  B(3, 3) = -1 / L; B(3, 9) = 1 / L;                                       // kappa_x
  B(4, 4) = -1 / L; B(4, 10) = 1 / L;                                      // kappa_y
  B(5, 5) = -1 / L; B(5, 11) = 1 / L;                                      // kappa_z
  return B;
}

// Yield function of the fully plastic condition on (N, Mx, My, Mz): f = sum (s_i/s0_i)^2 - 1.
inline double yield_function(const Vec6& sig, const std::array<double, 4>& y) {
  const double a = sig[0] / y[0], b = sig[3] / y[1], c = sig[4] / y[2], d = sig[5] / y[3];
  return a * a + b * b + c * c + d * d - 1.0;
}

// Sectional forces at xi from those at the stress point r: the moments vary linearly (Mz' = -Qy,
// My' = Qz in local x), N, Q and Mx are constant.
inline Vec6 forces_at(const Vec6& sig_r, double r, double xi, double L) {
  Vec6 s = sig_r;
  s[5] = sig_r[5] - sig_r[1] * L * (xi - r) / 2.0;
  s[4] = sig_r[4] + sig_r[2] * L * (xi - r) / 2.0;
  return s;
}

}  // namespace detail

// Placement of the integration point while an element is elastic.
struct GaussPairPlacement {
  // First element of a pair (near its end i): stress point r = 1 - 2/sqrt(3), so s = -r; the second
  // mirrors it. Both stress points then sit on the Gauss points of the pair taken as one element.
  static double elastic_point(PairSlot slot) {
    const double r = 1.0 - 2.0 / std::sqrt(3.0);
    switch (slot) {
      case PairSlot::first: return -r;
      case PairSlot::second: return r;
      default: return 0.0;
    }
  }
  static constexpr bool needs_pairs = true;
};
struct CentrePlacement {
  static double elastic_point(PairSlot) { return 0.0; }
  static constexpr bool needs_pairs = false;
};

// Linear Timoshenko element with one adaptively shifted integration point (ASI / ASI-Gauss).
template <class Placement>
struct ShiftedIntegrationTimoshenko {
  static constexpr bool needs_pairs = Placement::needs_pairs;
  static constexpr std::string_view name =
      Placement::needs_pairs ? std::string_view("ASI-Gauss Timoshenko") : std::string_view("one-point Timoshenko (s = 0)");

  struct State {
    double s = 0;              // integration point
    int hinge = 0;             // 0 elastic, -1 / +1 plastic hinge at that end
    Vec6 eps_p = Vec6::Zero(); // plastic generalised strains (N, Mx, My, Mz), plus the initial
                               // strains that keep the forces continuous across point shifts
    double plastic_increment = 0;  // plastic multiplier of the last trial (0 when elastic)
    double plastic_work = 0;
    bool moved = false;        // the point moved (ASI rule) from s_from; rebased at the next response
    double s_from = 0;

    // Member by member in checkpoints (core/checkpoint.hpp): `hinge` and `moved` are followed by padding.
    template <class Self, class Archive>
      requires std::is_same_v<std::remove_const_t<Self>, State>
    friend void transfer_state(Self& st, Archive& ar) {
      ar(st.s, st.hinge, st.eps_p, st.plastic_increment, st.plastic_work, st.moved, st.s_from);
    }
  };

  static State initial_state(const ElementProps& p) {
    State st;
    st.s = Placement::elastic_point(p.slot);
    return st;
  }

  static Vec6 generalized_strain(const ElementProps& p, double s, const Vec12& d) {
    return detail::timoshenko_B(p.L0, s) * d;
  }

  // A moved point keeps the element's sectional forces: those at the new stress point are the old
  // state's carried along the element (N, Q, Mx constant, moments linear; detail::forces_at), and the
  // difference to the elastic strains at the new point becomes initial strain in eps_p. The nodal
  // forces are then continuous across a shift, as in the incremental formulation of the ASI papers;
  // re-evaluating the total strains at the new point instead turns the hinge's rotation into a
  // spurious shear (a jump of the reaction on unloading, and chattering hinges in dynamics).
  static State rebased(const ElementProps& p, const State& c, const Vec12& d) {
    State r = c;
    r.moved = false;
    const Vec6 eps_old = generalized_strain(p, c.s_from, d), eps_new = generalized_strain(p, c.s, d);
    Vec6 sig_old;
    for (int i = 0; i < 6; ++i) sig_old[i] = p.D[i] * (eps_old[i] - c.eps_p[i]);
    const Vec6 sig_new = detail::forces_at(sig_old, -c.s_from, -c.s, p.L0);
    for (int i = 0; i < 6; ++i) r.eps_p[i] = eps_new[i] - sig_new[i] / p.D[i];
    return r;
  }
  static void move_point(State& st, double s_new) {
    if (!st.moved) st.s_from = st.s;
    st.moved = true;
    st.s = s_new;
  }

  static void response(const ElementProps& p, const State& c0, const Vec12& d, Vec12& f, Mat12& k, State& t) {
    evaluate<true>(p, c0, d, f, &k, t);
  }
  // Forces and trial history without the tangent (most evaluations of a step reuse a matrix): the
  // 12 x 12 product is most of the kernel's cost.
  static void internal_force(const ElementProps& p, const State& c0, const Vec12& d, Vec12& f, State& t) {
    evaluate<false>(p, c0, d, f, nullptr, t);
  }
  template <bool WithTangent>
  static void evaluate(const ElementProps& p, const State& c0, const Vec12& d, Vec12& f, Mat12* k, State& t) {
    const State c = c0.moved ? rebased(p, c0, d) : c0;
    t = c;
    const auto B = detail::timoshenko_B(p.L0, c.s);
    const Vec6 eps = B * d;
    Vec6 sig;
    for (int i = 0; i < 6; ++i) sig[i] = p.D[i] * (eps[i] - c.eps_p[i]);
    Eigen::Matrix<double, 6, 6> Dt = Eigen::Matrix<double, 6, 6>::Zero();
    for (int i = 0; i < 6; ++i) Dt(i, i) = p.D[i];
    t.plastic_increment = 0;
    if (c.hinge != 0 && detail::yield_function(sig, p.yield) > 0) return_map(p, c, sig, Dt, t);
    f.noalias() = p.L0 * B.transpose() * sig;
    if constexpr (WithTangent) k->noalias() = p.L0 * B.transpose() * Dt * B;
  }


  static SectionForces section_forces(const ElementProps& p, const State& c0, const Vec12& d) {
    const State c = c0.moved ? rebased(p, c0, d) : c0;
    const Vec6 eps = generalized_strain(p, c.s, d);
    Vec6 sig;
    for (int i = 0; i < 6; ++i) sig[i] = p.D[i] * (eps[i] - c.eps_p[i]);
    return {sig[0], sig[1], sig[2], sig[3], sig[4], sig[5], -c.s};
  }

  // Closest-point return onto f = sum P_i sig_i^2 - 1 (P_i = 1/sig0_i^2) over the components
  // (N, Mx, My, Mz) with the diagonal elastic matrix: sig_i = sig_tr_i / (1 + 2 dl D_i P_i), a scalar
  // equation in dl solved by Newton (monotone, convex: converges from dl = 0). Consistent tangent.
  static void return_map(const ElementProps& p, const State& c, Vec6& sig, Eigen::Matrix<double, 6, 6>& Dt, State& t) {
    constexpr std::array<int, 4> comp{0, 3, 4, 5};
    std::array<double, 4> P{}, Dk{}, tr{};
    for (int j = 0; j < 4; ++j) {
      P[j] = 1.0 / (p.yield[j] * p.yield[j]);
      Dk[j] = p.D[comp[j]];
      tr[j] = sig[comp[j]];
    }
    double dl = 0;
    for (int it = 0; it < 60; ++it) {
      double g = -1, dg = 0;
      for (int j = 0; j < 4; ++j) {
        const double den = 1 + 2 * dl * Dk[j] * P[j];
        const double sj = tr[j] / den;
        g += P[j] * sj * sj;
        dg += -4 * P[j] * P[j] * Dk[j] * tr[j] * tr[j] / (den * den * den);
      }
      if (std::abs(g) < 1e-13) break;
      dl -= g / dg;
    }
    Eigen::Vector4d n, xi;
    for (int j = 0; j < 4; ++j) {
      const double den = 1 + 2 * dl * Dk[j] * P[j];
      sig[comp[j]] = tr[j] / den;
      t.eps_p[comp[j]] = c.eps_p[comp[j]] + 2 * dl * P[j] * sig[comp[j]];
      n[j] = 2 * P[j] * sig[comp[j]];
      xi[j] = Dk[j] / den;
    }
    const double nXn = (n.array() * xi.array() * n.array()).sum();
    // The tangent keeps 1e-6 of the stiffness along the flow direction: a node whose elements are all
    // hinged at it (both sides of a mid-span hinge) would otherwise have a zero pivot in statics. The
    // forces are the perfectly plastic ones, so converged results do not depend on it.
    constexpr double keep = 1e-6;
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        Dt(comp[a], comp[b]) = (a == b ? xi[a] : 0.0) - (1.0 - keep) * xi[a] * n[a] * n[b] * xi[b] / nXn;
    t.plastic_increment = dl;
    double work = 0;
    for (int j = 0; j < 4; ++j) work += sig[comp[j]] * (t.eps_p[comp[j]] - c.eps_p[comp[j]]);
    t.plastic_work = c.plastic_work + work;
  }

  // The ASI rule, applied once a step has converged (so the shift acts from the next step on):
  // an elastic element whose end reaches the fully plastic condition moves its point to put the
  // stress point on that end (s = -xi_end) and its pair partner returns to s = 0; a hinged element
  // that unloads (no plastic increment, trial inside the surface) returns to its elastic position.
  // Returns true when a point moved (the tangent has changed).
  static bool shift_integration_point(const ElementProps& p, State& st, const Vec12& d, State* partner,
                                      const ElementProps* partner_props) {
    if (st.hinge == 0) {
      const Vec6 eps = generalized_strain(p, st.s, d);
      Vec6 sig;
      for (int i = 0; i < 6; ++i) sig[i] = p.D[i] * (eps[i] - st.eps_p[i]);
      const double r = -st.s;
      const double f_minus = detail::yield_function(detail::forces_at(sig, r, -1.0, p.L0), p.yield);
      const double f_plus = detail::yield_function(detail::forces_at(sig, r, 1.0, p.L0), p.yield);
      if (std::max(f_minus, f_plus) < 0) return false;
      st.hinge = f_plus >= f_minus ? 1 : -1;
      move_point(st, -double(st.hinge));
      if (partner && partner->hinge == 0) move_point(*partner, 0.0);
      return true;
    }
    const Vec6 eps = generalized_strain(p, st.s, d);
    Vec6 sig;
    for (int i = 0; i < 6; ++i) sig[i] = p.D[i] * (eps[i] - st.eps_p[i]);
    if (st.plastic_increment > 0 || detail::yield_function(sig, p.yield) > -1e-6) return false;
    st.hinge = 0;
    move_point(st, Placement::elastic_point(p.slot));
    if (partner && partner->hinge == 0 && partner_props)
      move_point(*partner, Placement::elastic_point(partner_props->slot));
    return true;
  }
};

using AsiGaussTimoshenko = ShiftedIntegrationTimoshenko<GaussPairPlacement>;
using ConventionalTimoshenko = ShiftedIntegrationTimoshenko<CentrePlacement>;

// Reference element: the cubic (Hermite) Euler-Bernoulli beam, exact for nodal loads. Elastic only.
struct CubicEulerBernoulli {
  static constexpr bool needs_pairs = false;
  static constexpr std::string_view name = "cubic Euler-Bernoulli";
  struct State {
    double s = 0;
    int hinge = 0;

    // Member by member in checkpoints (core/checkpoint.hpp): `hinge` is followed by padding bytes.
    template <class Self, class Archive>
      requires std::is_same_v<std::remove_const_t<Self>, State>
    friend void transfer_state(Self& st, Archive& ar) {
      ar(st.s, st.hinge);
    }
  };
  static State initial_state(const ElementProps&) { return {}; }

  static Mat12 stiffness(const ElementProps& p) {
    const double L = p.L0, L2 = L * L, L3 = L2 * L;
    const double EA = p.D[0], GJ = p.D[3], EIy = p.D[4], EIz = p.D[5];
    Mat12 k = Mat12::Zero();
    auto put = [&](int i, int j, double v) { k(i, j) += v; if (i != j) k(j, i) += v; };
    put(0, 0, EA / L); put(6, 6, EA / L); put(0, 6, -EA / L);
    put(3, 3, GJ / L); put(9, 9, GJ / L); put(3, 9, -GJ / L);
    // bending in x-y (v, tz)
    put(1, 1, 12 * EIz / L3); put(7, 7, 12 * EIz / L3); put(1, 7, -12 * EIz / L3);
    put(1, 5, 6 * EIz / L2); put(1, 11, 6 * EIz / L2); put(7, 5, -6 * EIz / L2); put(7, 11, -6 * EIz / L2);
    put(5, 5, 4 * EIz / L); put(11, 11, 4 * EIz / L); put(5, 11, 2 * EIz / L);
    // bending in x-z (w, ty): ty = -w'
    put(2, 2, 12 * EIy / L3); put(8, 8, 12 * EIy / L3); put(2, 8, -12 * EIy / L3);
    put(2, 4, -6 * EIy / L2); put(2, 10, -6 * EIy / L2); put(8, 4, 6 * EIy / L2); put(8, 10, 6 * EIy / L2);
    put(4, 4, 4 * EIy / L); put(10, 10, 4 * EIy / L); put(4, 10, 2 * EIy / L);
    return k;
  }
  static void response(const ElementProps& p, const State& c, const Vec12& d, Vec12& f, Mat12& k, State& t) {
    t = c;
    k = stiffness(p);
    f = k * d;
  }
  // Sectional forces at the centre, from the end forces (equilibrium of the half element).
  static SectionForces section_forces(const ElementProps& p, const State&, const Vec12& d) {
    const Vec12 f = stiffness(p) * d;
    const double h = p.L0 / 2;
    SectionForces s;
    s.N = f[6];
    s.Qy = f[7];
    s.Qz = f[8];
    s.Mx = f[9];
    s.Mz = f[11] + f[7] * h;  // Mz' = -Qy: end 2 has Mz(0) - Qy h
    s.My = f[10] - f[8] * h;  // My' = Qz
    s.xi = 0;
    return s;
  }
};

// Readable checks at the API boundary.
template <class E>
constexpr bool check_element_policy() {
  static_assert(ElementPolicy<E>,
                "furniture_fem: the Element policy must provide State, name, needs_pairs, initial_state(props), "
                "response(props, committed, d, f, k, trial) and section_forces(props, state, d); see "
                "docs/core/concept_element.md");
  return true;
}

}  // namespace furniture_fem
