#pragma once
// furniture_fem/contact/contact_laws.hpp: contact laws as composed policies, and the pair-level helpers that
// turn two beam segments (or a node and a plane) into nodal forces. Eigen only; no CGAL.
//
//   ContactLaw<Normal, Damping, Friction>   the law; each part is a tiny policy class
//   PaperLaw, PaperAnisotropicFloorLaw, SpringDashpotLaw, HuntCrossleyLaw, StickSlipLaw   presets
//   ContactParams                           runtime values, one set per kind of pair
//   <Part>::parameters                      what a part reads, declared (LawParameter, law_parameter.hpp)
//   ContactState                            per-contact history kept by the caller across steps
//   evaluate_segment_pair / evaluate_node_plane / evaluate_node_rectangle   pair-level helpers
//
// The paper's law (its eqs. 1-4; docs/contact/contact.md), with g = 1 - l/L the penetration ratio:
//   F_p = alpha g^q n,   F_T = -mu alpha g^q v_T/|v_T|,   F_N = -Dc g^q v_N/|v_N|     (l <= L)
// Each part below says which formula it evaluates and how it regularises v/|v| near zero speed.
// See docs/contact/contact.md for the choices, the presets and how to write a new part or law.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "contact_geometry.hpp"
#include "law_parameter.hpp"
#include "../core/model.hpp"

namespace furniture_fem {

// ---------------------------------------------------------------------------------------------
// What a law sees, what it returns, what it remembers.

// Everything a law needs about one contact point, in the world (table) frame.
struct ContactKinematics {
  double l = 0;                      // distance between centre lines, or node-to-plane signed distance
  double L = 0;                      // contact distance: (L1 + L2)/2, or half the width against a plane
  Vec3 n = Vec3::UnitZ();            // unit normal from B towards A (+n on A pushes them apart)
  Vec3 v = Vec3::Zero();             // velocity of A's contact point relative to B's
  Vec3 long_axis = Vec3::Zero();     // A's longer edge in the floor plane (anisotropic friction); may be 0
  double dt = 0;                     // time step (laws with a tangential spring)
};

// Runtime parameters, one set per kind of pair (item-floor, item-wall, item-item). Units SI.
// Each law reads only the fields its parts declare (LawParameter); validate() checks them all.
struct ContactParams {
  static constexpr double newtons_per_kgf = 9.80665;

  double alpha = 0;       // N: penalty coefficient (PowerPenalty)
  double q = 1;           // penalty index (PowerPenalty, PaperSignDamping); 1.5 is Hertz-like
  double Dc = 0;          // N: damping coefficient of the paper (PaperSignDamping)
  double mu = 0;          // dynamic friction coefficient (isotropic friction parts)
  double mu_long = 0;     // friction along the item's longer edge (AnisotropicFloor)
  double mu_short = 0;    // friction along the item's shorter edge (AnisotropicFloor)
  double k_t = 0;         // N/m: tangential stick spring (StickSlip)
  double c_t = 0;         // N s/m: tangential dashpot acting while sticking (StickSlip)
  double v_reg = 1e-3;    // m/s: regularisation speed of v/|v| (0: the exact sign, sign(0) = 0)
  // m: elastic range of the stick spring that lets Coulomb friction hold still (k_t = mu N / stick_length,
  // return mapping; docs/contact/implicit_contact.md). 0: friction regularised by v_reg instead (it creeps).
  // StickSlip has its own spring (k_t, c_t) and ignores it.
  double stick_length = 0;
  double k_lin = 0;       // N/m: linear normal spring (LinearSpring)
  double c_lin = 0;       // N s/m: viscous normal damping (ViscousDamping)
  double k_hc = 0;        // N/m^1.5: Hunt-Crossley stiffness (HuntCrossley)
  double hc_damping = 0;  // s/m: Hunt-Crossley damping factor (HuntCrossley)
  // A law's own parameters (LawParameter::slot): slot i holds the value of the declaration naming it, set
  // once per item at set-up. The built-in laws use none (all 0).
  static constexpr std::size_t max_law_params = 4;
  std::array<double, max_law_params> law_params{};
  // Bit i set: law_params[i] is a force coefficient, scaled with a contact's share of nodes as alpha is
  // (a record's own per_node parameters; the parts' are the law kernel's per_node_mask).
  unsigned law_params_per_node = 0;

  // Every field, named: validate() checks each and pair() combines each, so a new field is seen by both.
  static constexpr auto named_fields() {
    using F = std::pair<const char*, double ContactParams::*>;
    return std::array{F{"alpha", &ContactParams::alpha},   F{"q", &ContactParams::q},
                      F{"Dc", &ContactParams::Dc},         F{"mu", &ContactParams::mu},
                      F{"mu_long", &ContactParams::mu_long}, F{"mu_short", &ContactParams::mu_short},
                      F{"k_t", &ContactParams::k_t},       F{"c_t", &ContactParams::c_t},
                      F{"v_reg", &ContactParams::v_reg},   F{"stick_length", &ContactParams::stick_length},
                      F{"k_lin", &ContactParams::k_lin},   F{"c_lin", &ContactParams::c_lin},
                      F{"k_hc", &ContactParams::k_hc},     F{"hc_damping", &ContactParams::hc_damping}};
  }

  // Negative, NaN or infinite values, and q <= 0 (a force that jumps at first touch), throw
  // ModelError naming the field and the value.
  void validate() const {
    for (const auto& [name, field] : named_fields()) {
      const double value = this->*field;
      if (!std::isfinite(value) || value < 0)
        throw ModelError(std::string("ContactParams: ") + name + " must be finite and non-negative (got " +
                         detail::fmt(value) + ")");
    }
    if (!(q > 0)) throw ModelError("ContactParams: q must be positive (got " + detail::fmt(q) + ")");
  }

  // Two items in contact with each other: every field the mean of theirs, so the pair does not depend
  // on which item comes first (docs/contact/contact.md, "Pair-level helpers"). Equal values are kept to
  // the bit (0.5 (x + x) = x): items that share a value, as every scene's q, mu and v_reg, keep it.
  static ContactParams pair(const ContactParams& a, const ContactParams& b) {
    ContactParams p;
    for (const auto& [name, field] : named_fields()) p.*field = 0.5 * (a.*field + b.*field);
    for (std::size_t i = 0; i < max_law_params; ++i) p.law_params[i] = 0.5 * (a.law_params[i] + b.law_params[i]);
    p.law_params_per_node = a.law_params_per_node | b.law_params_per_node;
    return p;
  }

  // Where a declared parameter is kept, and its scene value stored there (kgf to N ...).
  double& value(const LawParameter& d) { return d.field ? this->*d.field : law_params[d.slot]; }
  double value(const LawParameter& d) const { return d.field ? this->*d.field : law_params[d.slot]; }
  void set(const LawParameter& d, double scene_value) { value(d) = d.stored(scene_value); }

  // A declaration's bit in a share mask: its field's place in named_fields(), or past them its slot.
  static constexpr unsigned storage_bit(const LawParameter& d) {
    constexpr auto fields = named_fields();
    for (std::size_t i = 0; i < fields.size(); ++i)
      if (d.field == fields[i].second) return 1u << i;
    return 1u << (fields.size() + d.slot);
  }
  // The bits of the per_node declarations: what a contact standing for several nodes scales.
  template <class Declarations>
  static constexpr unsigned per_node_mask(const Declarations& declared) {
    unsigned mask = 0;
    for (const LawParameter& d : declared)
      if (d.per_node) mask |= storage_bit(d);
    return mask;
  }
  // A contact standing for `share` nodes: the fields and slots of `mask` (per_node_mask) and the slots of
  // law_params_per_node made `share` times one node's.
  void scale_per_node(double share, unsigned mask) {
    constexpr auto fields = named_fields();
    mask |= law_params_per_node << fields.size();
    for (std::size_t i = 0; mask != 0; ++i, mask >>= 1) {
      if (!(mask & 1u)) continue;
      (i < fields.size() ? this->*(fields[i].second) : law_params[i - fields.size()]) *= share;
    }
  }

  // The paper's rules (Table 4): alpha = the item's weight (given in kgf, stored in N), q = 1,
  // Dc = 1.2 alpha, mu as given (use paper_mu() to derive it from a static coefficient). mu_long
  // and mu_short are set to mu so an anisotropic law is isotropic until told otherwise.
  static ContactParams paper(double weight_kgf, double mu) {
    ContactParams p;
    p.alpha = weight_kgf * newtons_per_kgf;
    p.q = 1;
    p.Dc = 1.2 * p.alpha;
    p.mu = p.mu_long = p.mu_short = mu;
    p.validate();
    return p;
  }
  // The same for the floor, with the two directional coefficients (mu = mu_long, which the paper
  // also uses against walls).
  static ContactParams paper_floor(double weight_kgf, double mu_long, double mu_short) {
    ContactParams p = paper(weight_kgf, mu_long);
    p.mu_short = mu_short;
    p.validate();
    return p;
  }

  // The `stiff` rule: a linear spring per resting node that sinks resting_penetration (2.5 um) under
  // its share of the weight, damped at damping_ratio for that share (k_lin, c_lin; at least critical,
  // contact/stiff_contact.hpp raises it for tall items), with the same force at the same depth for
  // Hunt-Crossley (k_hc, hc_damping 0.5 s/m). Why 2.5 um: with 25 um a block under a held acceleration
  // tips 1.5 % below g b/h, its toe sinking under the whole weight (measured,
  // docs/contact/verification_contact.md); at 2.5 um it holds to 0.99 g b/h, suddenly applied.
  static constexpr double stiff_resting_penetration = 2.5e-6;  // m
  void set_stiff(double mass, int resting_nodes, double damping_ratio = 1.0) {
    const double per_node = mass / std::max(resting_nodes, 1);
    k_lin = per_node * newtons_per_kgf / stiff_resting_penetration;  // newtons_per_kgf: standard gravity
    c_lin = 2 * damping_ratio * std::sqrt(k_lin * per_node);
    k_hc = k_lin / std::sqrt(stiff_resting_penetration);
    hc_damping = 0.5;
  }
};

// The paper's dynamic friction rule: 80% of the measured static coefficient.
constexpr double paper_mu(double static_mu) { return 0.8 * static_mu; }

// Per-contact history, kept by the caller for each contact pair across steps. force() advances it
// by one step in place; a caller that evaluates one step several times (Newton iterations) passes
// a copy of the state committed at the end of the previous step each time, and keeps the copy of
// the last evaluation when the step is accepted.
struct ContactState {
  Vec3 elongation = Vec3::Zero();  // m: tangential spring elongation, world frame (StickSlip)
  bool sticking = false;           // stick flag of the last evaluation
  Vec3 normal = Vec3::Zero();      // last contact normal (orients a degenerate normal); 0: none yet

  // Member by member in checkpoints (core/checkpoint.hpp): `sticking` is followed by padding bytes.
  template <class Self, class Archive>
    requires std::is_same_v<std::remove_const_t<Self>, ContactState>
  friend void transfer_state(Self& s, Archive& ar) {
    ar(s.elongation, s.sticking, s.normal);
  }
};

// The force of one contact, on A (B receives -on_a), and its linearisation for an implicit step:
// on_a(x_a + dx, v_a + dv) ~ on_a - K dx - C dv (A's contact point moved, B held).
struct ContactForce {
  Vec3 on_a = Vec3::Zero();
  Mat3 K = Mat3::Zero();   // N/m: stiffness (the normal part's slope along n)
  Mat3 C = Mat3::Zero();   // N s/m: damping and friction slopes (a stick spring acts through v dt)
  double normal = 0;       // component of on_a along n: positive pushes apart, negative pulls
  double tangential = 0;   // magnitude of the tangential part
  bool sticking = false;   // friction in its stick regime (see each friction part)
  bool in_contact = false; // l <= L
};

// What the friction part is told about the normal response.
struct NormalForceParts {
  double g = 0;        // penetration ratio 1 - l/L
  double penalty = 0;  // the Normal part's force (alpha g^q for the paper)
  double damping = 0;  // the Damping part's force
  double total = 0;    // penalty + damping, clamped at 0 when the law clamps tensile forces
};

struct TangentialForce {
  Vec3 on_a = Vec3::Zero();
  bool sticking = false;
  Mat3 C = Mat3::Zero();  // -d on_a / d v_t, the slope an implicit step uses
};

// Which normal force scales friction. The paper scales friction by the penalty part alpha g^q
// (eq. 3), not by the total normal force; Coulomb laws use the total. Either is taken compressive
// only (max(., 0)): a contact that pulls carries no friction.
enum class FrictionNormal { penalty, total };

// How v/|v| is regularised near zero speed (the paper gives none):
//   ramp: v / max(|v|, v_reg)           exact above v_reg, linear (viscous-like) below
//   tanh: v/|v| tanh(|v|/v_reg)         smooth everywhere
// v_reg = 0 gives the exact sign function with sign(0) = 0 for both.
enum class SignRegularisation { ramp, tanh };

namespace detail {
inline double friction_normal_force(const NormalForceParts& nf, FrictionNormal which) {
  return std::max(0.0, which == FrictionNormal::penalty ? nf.penalty : nf.total);
}
inline double regularised_scale(double speed, double v_reg, SignRegularisation kind) {
  if (speed <= 0) return 0.0;
  if (v_reg <= 0) return 1.0 / speed;
  if (kind == SignRegularisation::tanh) return std::tanh(speed / v_reg) / speed;
  return 1.0 / std::max(speed, v_reg);
}
inline double regularised_sign(double v, double v_reg, SignRegularisation kind) {
  return v * regularised_scale(std::abs(v), v_reg, kind);
}
inline Vec3 regularised_direction(const Vec3& v, double v_reg, SignRegularisation kind) {
  return v * regularised_scale(v.norm(), v_reg, kind);
}
inline double power(double g, double q) { return q == 1.0 ? g : std::pow(g, q); }

// -d/dv of v * regularised_scale(|v|): phi P + phi'(s) s t t^T on the tangent plane (P = I - n n^T),
// phi the scale, s = |v|, t = v/s. Zero where the scale has no finite slope (v_reg = 0 at rest).
inline Mat3 regularised_slope(const Vec3& v, const Vec3& n, double v_reg, SignRegularisation kind) {
  const Mat3 P = Mat3::Identity() - n * n.transpose();
  const double s = v.norm();
  if (v_reg <= 0 && s <= 0) return Mat3::Zero();
  if (s <= 1e-12 * std::max(v_reg, 1e-300)) return P / v_reg;
  const Vec3 t = v / s;
  const double phi = regularised_scale(s, v_reg, kind);
  double dphi = 0;  // d phi / d s
  if (kind == SignRegularisation::tanh && v_reg > 0) {
    const double th = std::tanh(s / v_reg);
    dphi = (1 - th * th) / (v_reg * s) - th / (s * s);
  } else if (s >= v_reg) {
    dphi = -1 / (s * s);
  }
  return phi * P + dphi * s * t * t.transpose();
}

// The elongation of a stick spring carried into the current tangent plane (its normal component
// removed, its length kept, so a rotating contact keeps its spring force).
inline Vec3 in_tangent_plane(const Vec3& e, const Vec3& n) {
  const double len = e.norm();
  if (!(len > 0)) return Vec3::Zero();
  const Vec3 t = e - e.dot(n) * n;
  const double in_plane = t.norm();
  return in_plane > 1e-12 * len ? Vec3(t * (len / in_plane)) : Vec3::Zero();
}

// The stick spring that lets Coulomb friction hold still: k_t = mu N / stick_length (the cone is
// reached after stick_length of elastic slip), with critical damping for the mass it carries, N / g:
// c_t = 2 sqrt(k_t N / g). Undamped, a suddenly applied load overshoots to twice its value in the spring
// and tips a block at 0.98 g b/h (measured, docs/contact/verification_contact.md).
struct StickSpring {
  double k_t, c_t;
};
inline StickSpring stick_spring(double N, double mu, double stick_length) {
  constexpr double g = 9.80665;
  const double k_t = mu * N / stick_length;
  return {k_t, 2 * std::sqrt(std::max(0.0, k_t * N / g))};
}

// Coulomb friction by return mapping, as in elastoplasticity (Wriggers, Computational Contact
// Mechanics, ch. 5): a stick spring k_t (and dashpot c_t) predicts the force, e* = e + v_t dt,
// F* = -k_t e* - c_t v_t; inside the cone |F*| <= mu N it sticks (F = F*), outside it slips on the cone
// (F = mu N F*/|F*|, the spring reset to -F/k_t so that a reversal sticks at once). mu_of(d) is the
// coefficient for a sliding direction d (a unit vector, or zero when there is none). The slope is
// (k_t dt + c_t) P in stick, and in slip the same scaled by mu N/|F*| (the radial return's secant: the
// consistent slope has no stiffness along the sliding direction, which leaves a stop or a reversal to
// the next step in a carried-over step; measured: a resting block then jitters at 3 mm/s). At rest the
// spring holds: no creep below mu N.
template <class MuOf>
TangentialForce coulomb_return_map(const ContactKinematics& k, double N, double k_t, double c_t, const Vec3& v_t,
                                   ContactState& state, MuOf&& mu_of) {
  const Vec3 e_trial = in_tangent_plane(state.elongation, k.n) + v_t * k.dt;
  const Vec3 f_trial = -k_t * e_trial - c_t * v_t;
  const double f_norm = f_trial.norm();
  const double limit = mu_of(f_norm > 0 ? Vec3(-f_trial / f_norm) : Vec3::Zero()) * N;
  const Mat3 P = Mat3::Identity() - k.n * k.n.transpose();
  const double c_stick = k_t * k.dt + c_t;
  if (f_norm <= limit) {
    state.elongation = e_trial;
    state.sticking = true;
    return {f_trial, true, c_stick * P};
  }
  const Vec3 t = f_trial / f_norm;
  const Vec3 f = limit * t;
  state.elongation = k_t > 0 ? Vec3(-f / k_t) : Vec3::Zero();  // the dashpot's share is not stored
  state.sticking = false;
  return {f, false, (limit / f_norm) * c_stick * P};
}

// Coulomb friction that sticks, on the stick spring of a law without its own (mu_max: the largest
// coefficient the law uses).
template <class MuOf>
TangentialForce sticking_coulomb(const ContactKinematics& k, double N, double mu_max, double stick_length,
                                 const Vec3& v_t, ContactState& state, MuOf&& mu_of) {
  const StickSpring s = stick_spring(N, mu_max, stick_length);
  return coulomb_return_map(k, N, s.k_t, s.c_t, v_t, state, mu_of);
}
}  // namespace detail

// ---------------------------------------------------------------------------------------------
// The parts' parameters: each part lists the keys it reads as `parameters` (LawParameter); the scene keys
// of a law are those of its parts. Shared declarations are named here (q: the penalty and the damping).

namespace part_parameters {
inline double kgf_to_newtons(double v) { return v * ContactParams::newtons_per_kgf; }
// Hunt-Crossley's k_hc from a linear spring's stiffness: the same force at 25 mm of overlap.
inline double onset_to_hertz(double v) { return v / std::sqrt(0.025); }

inline constexpr LawParameter alpha_kgf{.key = "alpha_kgf", .unit = "kgf", .lo = 0, .hi = 1e6, .lo_exclusive = true,
                                        .meaning = "penalty coefficient", .per_node = true,
                                        .field = &ContactParams::alpha, .to_si = &kgf_to_newtons};
inline constexpr LawParameter q{.key = "q", .unit = "-", .lo = 0, .hi = 10, .lo_exclusive = true,
                                .default_value = 1, .meaning = "penalty index", .field = &ContactParams::q};
inline constexpr LawParameter dc_kgf{.key = "dc_kgf", .unit = "kgf", .lo = 0, .hi = 1e6,
                                     .meaning = "damping coefficient", .per_node = true, .field = &ContactParams::Dc,
                                     .to_si = &kgf_to_newtons};
// Friction: mu on every pair kind; mu_long and mu_short on the floor only, each narrowing the one before
// (a part lists them in that order: they are applied so).
inline constexpr LawParameter mu{.key = "mu", .unit = "-", .lo = 0, .hi = 5, .meaning = "dynamic friction",
                                 .field = &ContactParams::mu};
inline constexpr LawParameter floor_mu{.key = "mu_long", .unit = "-", .lo = 0, .hi = 5,
                                       .meaning = "`floor` only: along the longer edge (the isotropic laws' floor mu)",
                                       .floor_only = true, .field = &ContactParams::mu};
inline constexpr LawParameter stiffness(double ContactParams::*field, std::string_view meaning,
                                        double (*to_si)(double) = nullptr) {
  return {.key = "stiffness", .unit = "N/m", .lo = 0, .hi = 1e12, .lo_exclusive = true, .meaning = meaning,
          .per_node = true, .field = field, .to_si = to_si};
}
inline constexpr LawParameter damping(double ContactParams::*field, std::string_view meaning) {
  return {.key = "damping", .unit = "N s/m", .lo = 0, .hi = 1e12, .meaning = meaning, .per_node = true, .field = field};
}
}  // namespace part_parameters

// ---------------------------------------------------------------------------------------------
// Normal parts: force(k, params, g, v_n) -> force along n on A (positive pushes apart).
// v_n = v . n is the normal relative speed: negative while approaching. Optional slopes for the
// implicit step: stiffness() = -d force / d l, damping() = -d force / d v_n (a part without them is
// explicit: its force enters the step as a load).

// Paper eq. 1: alpha g^q. q = 1 is the paper's choice, q = 1.5 Hertz-like; any q > 0 works.
struct PowerPenalty {
  static constexpr bool paper_equation = true;
  static constexpr std::array parameters{part_parameters::alpha_kgf, part_parameters::q};
  double force(const ContactKinematics&, const ContactParams& p, double g, double) const {
    return p.alpha * detail::power(g, p.q);
  }
  // q < 1 has an infinite slope at first touch: taken at g >= 1e-3.
  double stiffness(const ContactKinematics& k, const ContactParams& p, double g, double) const {
    return p.q == 1.0 ? p.alpha / k.L : p.alpha * p.q * std::pow(std::max(g, 1e-3), p.q - 1) / k.L;
  }
};

// k_lin (L - l): a linear spring on the overlap.
struct LinearSpring {
  static constexpr std::array parameters{part_parameters::stiffness(&ContactParams::k_lin, "the linear spring k_lin")};
  double force(const ContactKinematics& k, const ContactParams& p, double, double) const {
    return p.k_lin * (k.L - k.l);
  }
  double stiffness(const ContactKinematics&, const ContactParams& p, double, double) const { return p.k_lin; }
};

// Hunt-Crossley: k_hc d^1.5 (1 + 1.5 hc_damping d'), with d = L - l the overlap and d' = -v_n its
// rate (positive while approaching). The damping is part of this normal force, so it pairs with
// NoDamping; it vanishes with the overlap, so there is no force jump at first touch. During fast
// release the bracket can turn negative: the law's clamp_tensile removes that pull.
struct HuntCrossley {
  static constexpr std::array parameters{part_parameters::stiffness(
      &ContactParams::k_hc, "Hunt-Crossley's k_hc = stiffness / sqrt(0.025 m) (the linear spring's force at 25 mm)",
      &part_parameters::onset_to_hertz)};
  double force(const ContactKinematics& k, const ContactParams& p, double, double v_n) const {
    const double d = k.L - k.l;
    return p.k_hc * d * std::sqrt(d) * (1.0 + 1.5 * p.hc_damping * (-v_n));
  }
  double stiffness(const ContactKinematics& k, const ContactParams& p, double, double v_n) const {
    const double d = k.L - k.l;
    return std::max(0.0, 1.5 * p.k_hc * std::sqrt(d) * (1.0 + 1.5 * p.hc_damping * (-v_n)));
  }
  double damping(const ContactKinematics& k, const ContactParams& p, double, double) const {
    const double d = k.L - k.l;
    return 1.5 * p.hc_damping * p.k_hc * d * std::sqrt(d);
  }
};

// ---------------------------------------------------------------------------------------------
// Damping parts: force(k, params, g, v_n) -> force along n on A.

// Paper eq. 4: -Dc g^q v_N/|v_N|, a force of constant magnitude Dc g^q whose sign opposes the
// normal speed, regularised as chosen (default ramp: -Dc g^q v_n / max(|v_n|, v_reg)).
struct PaperSignDamping {
  static constexpr bool paper_equation = true;
  static constexpr std::array parameters{part_parameters::dc_kgf, part_parameters::q};
  SignRegularisation regularisation = SignRegularisation::ramp;
  double force(const ContactKinematics&, const ContactParams& p, double g, double v_n) const {
    return -p.Dc * detail::power(g, p.q) * detail::regularised_sign(v_n, p.v_reg, regularisation);
  }
  // The set-valued sign at v_n = 0, taken implicitly as the dashpot it is at the evaluated speed
  // (the secant Dc g^q scale(|v_n|), Dc g^q / v_reg inside the ramp): linearised so, the force falls
  // with the speed within the step instead of switching sign a step late, and a resting contact does
  // not chatter (the consistent slope, zero outside the ramp, would leave the switch explicit).
  double damping(const ContactKinematics&, const ContactParams& p, double g, double v_n) const {
    const double speed = std::abs(v_n);
    const double secant = speed > 0 ? detail::regularised_scale(speed, p.v_reg, regularisation)
                                    : (p.v_reg > 0 ? 1.0 / p.v_reg : 0.0);
    return p.Dc * detail::power(g, p.q) * secant;
  }
};

// -c_lin v_n: a linear dashpot.
struct ViscousDamping {
  static constexpr std::array parameters{part_parameters::damping(&ContactParams::c_lin, "the normal dashpot c_lin")};
  double force(const ContactKinematics&, const ContactParams& p, double, double v_n) const { return -p.c_lin * v_n; }
  double damping(const ContactKinematics&, const ContactParams& p, double, double) const { return p.c_lin; }
};

struct NoDamping {
  double force(const ContactKinematics&, const ContactParams&, double, double) const { return 0.0; }
};

// ---------------------------------------------------------------------------------------------
// Friction parts: force(k, params, normal parts, v_t, state) -> tangential force on A.
// v_t is the tangential relative velocity (v minus its normal part).

// Paper eq. 3: -mu N v_T/|v_T| with N = alpha g^q (the penalty part, as the paper writes it). With
// p.stick_length > 0 the sign at v_T = 0 is set-valued, |F_T| <= mu N, solved by return mapping
// (holds still below mu N); with stick_length = 0 it is regularised as chosen (default ramp), and
// "sticking" means |v_T| < v_reg, inside the ramp (it creeps).
struct PaperSignFriction {
  static constexpr bool paper_equation = true;
  static constexpr std::array parameters{part_parameters::mu, part_parameters::floor_mu};
  SignRegularisation regularisation = SignRegularisation::ramp;
  FrictionNormal normal = FrictionNormal::penalty;
  TangentialForce force(const ContactKinematics& k, const ContactParams& p, const NormalForceParts& nf, const Vec3& v_t,
                        ContactState& state) const {
    const double N = detail::friction_normal_force(nf, normal);
    if (p.stick_length > 0)
      return detail::sticking_coulomb(k, N, p.mu, p.stick_length, v_t, state, [&](const Vec3&) { return p.mu; });
    state.elongation.setZero();
    state.sticking = v_t.norm() < p.v_reg;
    return {-p.mu * N * detail::regularised_direction(v_t, p.v_reg, regularisation), state.sticking,
            p.mu * N * detail::regularised_slope(v_t, k.n, p.v_reg, regularisation)};
  }
};

// The paper's friction (eq. 3, same scaling and regularisation as PaperSignFriction) with a
// coefficient that depends on the sliding direction relative to the item's longer edge: the polar
// radius of the ellipse with semi-axes mu_long and mu_short,
//   mu(phi) = 1 / sqrt(cos^2 phi / mu_long^2 + sin^2 phi / mu_short^2)
//           = mu_long mu_short / sqrt(mu_short^2 cos^2 phi + mu_long^2 sin^2 phi),
// phi the angle between v_T and long_axis projected on the contact plane. The force stays opposite
// to v_T (not the maximum-dissipation elliptic force set, whose force direction would differ from
// -v_T). Without a usable long axis (zero, or along n) mu_long applies, as the paper uses the
// longer-edge value against walls.
struct AnisotropicFloor {
  static constexpr bool paper_equation = true;
  // mu sets both coefficients; then mu_long and mu_short each its own.
  static constexpr std::array<LawParameter, 4> parameters{
      part_parameters::mu.with_field(&ContactParams::mu_long), part_parameters::mu.with_field(&ContactParams::mu_short),
      part_parameters::floor_mu.with_field(&ContactParams::mu_long),
      LawParameter{.key = "mu_short", .unit = "-", .lo = 0, .hi = 5, .meaning = "`floor` only: along the shorter edge",
                   .floor_only = true, .field = &ContactParams::mu_short}};
  SignRegularisation regularisation = SignRegularisation::ramp;
  FrictionNormal normal = FrictionNormal::penalty;

  static double mu_for_direction(const ContactParams& p, double cos_phi, double sin_phi) {
    const double den = std::sqrt(p.mu_short * p.mu_short * cos_phi * cos_phi + p.mu_long * p.mu_long * sin_phi * sin_phi);
    return den > 0 ? p.mu_long * p.mu_short / den : 0.0;
  }
  // The coefficient for sliding along d (any length; zero: mu_long).
  static double mu_along(const ContactKinematics& k, const ContactParams& p, const Vec3& d) {
    const Vec3 axis = k.long_axis - k.long_axis.dot(k.n) * k.n;
    const double axis_len = axis.norm(), speed = d.norm();
    if (!(speed > 0) || !(axis_len > 1e-12 * std::max(1.0, k.long_axis.norm()))) return p.mu_long;
    const double c = std::clamp(d.dot(axis) / (speed * axis_len), -1.0, 1.0);
    return mu_for_direction(p, c, std::sqrt(std::max(0.0, 1.0 - c * c)));
  }
  TangentialForce force(const ContactKinematics& k, const ContactParams& p, const NormalForceParts& nf, const Vec3& v_t,
                        ContactState& state) const {
    const double N = detail::friction_normal_force(nf, normal);
    if (p.stick_length > 0)
      return detail::sticking_coulomb(k, N, std::max(p.mu_long, p.mu_short), p.stick_length, v_t, state,
                                      [&](const Vec3& d) { return mu_along(k, p, d); });
    state.elongation.setZero();
    state.sticking = v_t.norm() < p.v_reg;
    const double mu = mu_along(k, p, v_t);
    return {-mu * N * detail::regularised_direction(v_t, p.v_reg, regularisation), state.sticking,
            mu * N * detail::regularised_slope(v_t, k.n, p.v_reg, regularisation)};
  }
};

// Coulomb friction with a smooth regularisation: -mu N v_T / sqrt(|v_T|^2 + v_reg^2), N the total
// normal force (compressive part). Below v_reg it acts like a stiff dashpot, so a block under a
// small force creeps slowly; with p.stick_length > 0 it sticks by return mapping instead.
struct RegularisedCoulomb {
  static constexpr std::array parameters{part_parameters::mu, part_parameters::floor_mu};
  FrictionNormal normal = FrictionNormal::total;
  TangentialForce force(const ContactKinematics& k, const ContactParams& p, const NormalForceParts& nf, const Vec3& v_t,
                        ContactState& state) const {
    const double N = detail::friction_normal_force(nf, normal);
    if (p.stick_length > 0)
      return detail::sticking_coulomb(k, N, p.mu, p.stick_length, v_t, state, [&](const Vec3&) { return p.mu; });
    const double speed2 = v_t.squaredNorm();
    state.elongation.setZero();
    state.sticking = speed2 < p.v_reg * p.v_reg;
    const double den = std::sqrt(speed2 + p.v_reg * p.v_reg);
    if (!(den > 0)) return {Vec3::Zero(), state.sticking};
    const Mat3 P = Mat3::Identity() - k.n * k.n.transpose();
    const Mat3 slope = P / den - v_t * v_t.transpose() / (den * den * den);
    return {Vec3(-p.mu * N * v_t / den), state.sticking, p.mu * N * slope};
  }
};

// Stick-slip Coulomb friction with a tangential spring k_t and an optional dashpot c_t (elastic
// predictor, slip corrector on the Coulomb cone, as in elastoplastic return mapping):
//   1. the elongation e from the previous step is turned into the current tangent plane (its
//      normal component removed, its length kept, so a rotating contact keeps its spring force);
//   2. predictor: e* = e + v_T dt, F* = -k_t e* - c_t v_T;
//   3. |F*| <= mu N: stick, F = F*, e = e*; otherwise slip: F = mu N F*/|F*| and the spring is
//      set to e = -F/k_t, so it sits on the cone and a reversal sticks at once.
// A block under a steady force below mu N therefore stays put (displacement F/k_t plus its elastic
// oscillation, which c_t damps), unlike regularised laws that creep. Without c_t a suddenly applied
// force overshoots to twice its value in the spring and may slip briefly before sticking. N is
// the penalty part by default, matching the paper's scaling and keeping the cone steady while
// PaperSignDamping flips sign.
struct StickSlip {
  static constexpr std::array parameters{
      part_parameters::mu, part_parameters::floor_mu,
      part_parameters::stiffness(&ContactParams::k_t, "the tangential stick spring k_t"),
      part_parameters::damping(&ContactParams::c_t, "the tangential dashpot c_t")};
  FrictionNormal normal = FrictionNormal::penalty;
  static void check(const ContactParams& p) {
    if (!(p.k_t > 0)) throw ModelError("StickSlip: k_t must be positive (got " + detail::fmt(p.k_t) + ")");
  }
  TangentialForce force(const ContactKinematics& k, const ContactParams& p, const NormalForceParts& nf, const Vec3& v_t,
                        ContactState& state) const {
    // dt = 0 (a static solve) leaves the spring where it is; a negative or NaN step is a bug.
    if (!(k.dt >= 0)) throw ModelError("StickSlip: ContactKinematics::dt must be non-negative (got " + detail::fmt(k.dt) + ")");
    const double N = detail::friction_normal_force(nf, normal);
    return detail::coulomb_return_map(k, N, p.k_t, p.c_t, v_t, state, [&](const Vec3&) { return p.mu; });
  }
};

// ---------------------------------------------------------------------------------------------
// Concepts checked where parts and laws are used.

template <class P>
concept NormalForcePolicy = std::default_initializable<P> &&
    requires(const P& part, const ContactKinematics& k, const ContactParams& p, double g, double v_n) {
      { part.force(k, p, g, v_n) } -> std::convertible_to<double>;
    };
template <class P>
concept DampingForcePolicy = NormalForcePolicy<P>;
template <class P>
concept FrictionForcePolicy = std::default_initializable<P> &&
    requires(const P& part, const ContactKinematics& k, const ContactParams& p, const NormalForceParts& nf,
             const Vec3& v_t, ContactState& s) {
      { part.force(k, p, nf, v_t, s) } -> std::same_as<TangentialForce>;
    };

template <class Law>
concept ContactLawPolicy = requires(const Law& law, const ContactKinematics& k, const ContactParams& p, ContactState& s) {
  { law.force(k, p, s) } -> std::same_as<ContactForce>;
};

namespace detail {
template <class P>
constexpr bool is_paper_part = requires { requires P::paper_equation; };
}

// ---------------------------------------------------------------------------------------------
// The law.

// F on A = (N_total) n + F_T, with N_total = Normal + Damping (clamped at 0 when clamp_tensile),
// zero when l > L (the state is then reset: a separated contact forgets its spring).
//
// clamp_tensile: whether the total normal force may pull. The paper's F_N simply opposes v_N, so in
// the release phase with Dc = 1.2 alpha the total is alpha g - 1.2 alpha g < 0: a law with the paper's
// normal and damping parts keeps that (clamp_tensile defaults to false; any friction), every other
// combination defaults to true (contacts push, never glue). Clamped, the paper's sign damping
// (Dc > alpha) lets a resting node go free in every step it rises and pushes it back in the next:
// StickSlipLaw, clamped until 2026-11, kept 3 to 13 mm/s of such chatter at rest.
template <class Normal, class Damping, class Friction>
class ContactLaw {
  static_assert(NormalForcePolicy<Normal>,
                "furniture_fem: the Normal part of a ContactLaw must provide double force(kinematics, params, g, v_n) "
                "const; see docs/contact/contact.md");
  static_assert(DampingForcePolicy<Damping>,
                "furniture_fem: the Damping part of a ContactLaw must provide double force(kinematics, params, g, v_n) "
                "const; see docs/contact/contact.md");
  static_assert(FrictionForcePolicy<Friction>,
                "furniture_fem: the Friction part of a ContactLaw must provide TangentialForce force(kinematics, params, "
                "normal_parts, v_t, state) const; see docs/contact/contact.md");

 public:
  using normal_part_type = Normal;
  using damping_part_type = Damping;
  using friction_part_type = Friction;
  static constexpr bool paper_equations =
      detail::is_paper_part<Normal> && detail::is_paper_part<Damping> && detail::is_paper_part<Friction>;
  static constexpr bool paper_normal_response = detail::is_paper_part<Normal> && detail::is_paper_part<Damping>;

  bool clamp_tensile = !paper_normal_response;

  ContactLaw() = default;
  explicit ContactLaw(bool clamp_tensile_forces, Normal normal = {}, Damping damping = {}, Friction friction = {})
      : clamp_tensile(clamp_tensile_forces), normal_(normal), damping_(damping), friction_(friction) {}

  Normal& normal_part() { return normal_; }
  Damping& damping_part() { return damping_; }
  Friction& friction_part() { return friction_; }
  const Normal& normal_part() const { return normal_; }
  const Damping& damping_part() const { return damping_; }
  const Friction& friction_part() const { return friction_; }

  // Checks the parameters and what the parts require of them (e.g. StickSlip needs k_t > 0). Call
  // once per parameter set at setup; force() does not re-check in the time loop.
  static void validate(const ContactParams& p) {
    p.validate();
    if constexpr (requires { Normal::check(p); }) Normal::check(p);
    if constexpr (requires { Damping::check(p); }) Damping::check(p);
    if constexpr (requires { Friction::check(p); }) Friction::check(p);
  }

  ContactForce force(const ContactKinematics& k, const ContactParams& p, ContactState& state) const {
    ContactForce out;
    if (!(k.L > 0) || !(k.l <= k.L)) {  // also false for NaN distances
      state = ContactState{};
      return out;
    }
    out.in_contact = true;
    NormalForceParts nf;
    nf.g = 1.0 - k.l / k.L;
    const double v_n = k.v.dot(k.n);
    const Vec3 v_t = k.v - v_n * k.n;
    nf.penalty = normal_.force(k, p, nf.g, v_n);
    nf.damping = damping_.force(k, p, nf.g, v_n);
    nf.total = nf.penalty + nf.damping;
    if (clamp_tensile) nf.total = std::max(0.0, nf.total);
    const TangentialForce ft = friction_.force(k, p, nf, v_t, state);
    state.normal = k.n;
    const bool pushing = !clamp_tensile || nf.penalty + nf.damping > 0;
    const double kn = pushing ? normal_slope(k, p, nf.g, v_n) : 0.0, cn = pushing ? damping_slope(k, p, nf.g, v_n) : 0.0;
    out.K = kn * k.n * k.n.transpose();
    out.C = cn * k.n * k.n.transpose() + ft.C;
    out.on_a = nf.total * k.n + ft.on_a;
    out.normal = nf.total;
    out.tangential = ft.on_a.norm();
    out.sticking = ft.sticking;
    return out;
  }

 private:
  // The parts' slopes where they give them (a part without one enters the step explicitly).
  double normal_slope(const ContactKinematics& k, const ContactParams& p, double g, double v_n) const {
    double s = 0;
    if constexpr (requires { normal_.stiffness(k, p, g, v_n); }) s += normal_.stiffness(k, p, g, v_n);
    if constexpr (requires { damping_.stiffness(k, p, g, v_n); }) s += damping_.stiffness(k, p, g, v_n);
    return s;
  }
  double damping_slope(const ContactKinematics& k, const ContactParams& p, double g, double v_n) const {
    double s = 0;
    if constexpr (requires { normal_.damping(k, p, g, v_n); }) s += normal_.damping(k, p, g, v_n);
    if constexpr (requires { damping_.damping(k, p, g, v_n); }) s += damping_.damping(k, p, g, v_n);
    return s;
  }

  [[no_unique_address]] Normal normal_{};
  [[no_unique_address]] Damping damping_{};
  [[no_unique_address]] Friction friction_{};
};

// Presets. The paper's exact law; the paper's law with direction-dependent floor friction; and
// the classical alternatives the toolkit compares it with.
using PaperLaw = ContactLaw<PowerPenalty, PaperSignDamping, PaperSignFriction>;
using PaperAnisotropicFloorLaw = ContactLaw<PowerPenalty, PaperSignDamping, AnisotropicFloor>;
using SpringDashpotLaw = ContactLaw<LinearSpring, ViscousDamping, RegularisedCoulomb>;
using HuntCrossleyLaw = ContactLaw<HuntCrossley, NoDamping, RegularisedCoulomb>;
using StickSlipLaw = ContactLaw<PowerPenalty, PaperSignDamping, StickSlip>;

#define FURNITURE_FEM_CONTACT_LAW_MESSAGE                                                             \
  "furniture_fem: a contact law must provide force(kinematics, params, state) returning ContactForce " \
  "(a const member function taking ContactKinematics, ContactParams and ContactState&); see docs/contact/contact.md"

// ---------------------------------------------------------------------------------------------
// Pair-level helpers: geometry + kinematics + law + distribution to the nodes.

// Two beam elements as segments A (a0 -> a1) and B (b0 -> b1), world frame, with the nodes'
// translational velocities. L is the contact distance (the mean member width).
struct SegmentPair {
  Vec3 a0 = Vec3::Zero(), a1 = Vec3::Zero(), b0 = Vec3::Zero(), b1 = Vec3::Zero();
  Vec3 va0 = Vec3::Zero(), va1 = Vec3::Zero(), vb0 = Vec3::Zero(), vb1 = Vec3::Zero();
  double L = 0;
  double dt = 0;
  Vec3 long_axis = Vec3::Zero();  // A's longer edge, for anisotropic laws (usually 0 between items)
};

struct SegmentPairForces {
  bool in_contact = false;
  SegmentSegmentClosest closest;
  ContactKinematics kinematics;
  ContactForce force;
  Vec3 on_a0 = Vec3::Zero(), on_a1 = Vec3::Zero(), on_b0 = Vec3::Zero(), on_b1 = Vec3::Zero();
  // Moments that carry the force from the contact point (midway between the closest points) to the
  // centre lines; only the tangential part contributes. Adding them to the nodes' rotational DOFs
  // makes the pair exactly torque-free; a translational-only scheme may drop them (torque error
  // l n x F_T per pair).
  Vec3 moment_a0 = Vec3::Zero(), moment_a1 = Vec3::Zero(), moment_b0 = Vec3::Zero(), moment_b1 = Vec3::Zero();
};

// Evaluates one segment pair:
//  - closest points (s on A, t on B) and the normal from B to A (contact_normal; state.normal
//    orients it when the centre lines touch);
//  - velocity of each closest point by linear interpolation of its nodes' translational
//    velocities (nodal rotations are not used: the contact point sits on the centre line);
//  - the law's force F on A, shared by the same parameters: a0 gets (1-s) F, a1 s F,
//    b0 -(1-t) F, b1 -t F. The shares sum to F and -F (no net force), and the lever arms reproduce
//    F acting at p_A and -F at p_B, so the only net moment is (p_A - p_B) x F = l n x F, zero for the
//    normal part; the moments above cancel the tangential remainder.
// Out of contact (l > L) the state is reset and all forces are zero.
template <class Law>
SegmentPairForces evaluate_segment_pair(const Law& law, const SegmentPair& pair, const ContactParams& params,
                                        ContactState& state) {
  static_assert(ContactLawPolicy<Law>, FURNITURE_FEM_CONTACT_LAW_MESSAGE);
  SegmentPairForces out;
  out.closest = closest_points_segment_segment(pair.a0, pair.a1, pair.b0, pair.b1);
  const auto& c = out.closest;
  if (!(c.distance <= pair.L)) {
    state = ContactState{};
    return out;
  }
  ContactKinematics& k = out.kinematics;
  k.l = c.distance;
  k.L = pair.L;
  k.n = contact_normal(c, pair.a1 - pair.a0, pair.b1 - pair.b0, state.normal);
  k.v = ((1 - c.s) * pair.va0 + c.s * pair.va1) - ((1 - c.t) * pair.vb0 + c.t * pair.vb1);
  k.long_axis = pair.long_axis;
  k.dt = pair.dt;
  out.force = law.force(k, params, state);
  out.in_contact = out.force.in_contact;
  const Vec3& F = out.force.on_a;
  out.on_a0 = (1 - c.s) * F;
  out.on_a1 = c.s * F;
  out.on_b0 = -(1 - c.t) * F;
  out.on_b1 = -c.t * F;
  const Vec3 m = -0.5 * (c.p_WA - c.p_WB).cross(F);  // (contact point - p_A) x F, and the same for B
  out.moment_a0 = (1 - c.s) * m;
  out.moment_a1 = c.s * m;
  out.moment_b0 = (1 - c.t) * m;
  out.moment_b1 = c.t * m;
  return out;
}

// A node against a rigid plane or rectangle: its position and translational velocity (world
// frame), L = half the node's member width, and the velocity of the obstacle (zero in the table
// frame for the floor and walls).
struct NodeOnPlane {
  Vec3 p_WN = Vec3::Zero();
  Vec3 v_WN = Vec3::Zero();
  double L = 0;
  double dt = 0;
  Vec3 long_axis = Vec3::Zero();
  Vec3 v_W_obstacle = Vec3::Zero();
};

struct NodePlaneForces {
  bool in_contact = false;
  PointPlaneDistance geometry;
  ContactKinematics kinematics;
  ContactForce force;
  Vec3 on_node = Vec3::Zero();
  // Moment of the tangential force about the node, the force acting at the middle of the overlap
  // (0.5 (l + L) below the node); optional for the solver, as for segment pairs.
  Vec3 moment_on_node = Vec3::Zero();
};

namespace detail {
// The kinematics of a node at signed distance l from a plane of unit normal n.
inline ContactKinematics node_kinematics(const NodeOnPlane& node, double l, const Vec3& n) {
  ContactKinematics k;
  k.l = l;  // negative behind the plane: g > 1, the penalty keeps growing
  k.L = node.L;
  k.n = n;
  k.v = node.v_WN - node.v_W_obstacle;
  k.long_axis = node.long_axis;
  k.dt = node.dt;
  return k;
}

// The law's force on a node within reach of the plane (l <= node.L, checked by the caller): what
// RoomContact evaluates per node and plane, without the foot point and the moment (its hot path).
template <class Law>
ContactForce node_force(const Law& law, const NodeOnPlane& node, double l, const Vec3& n, const ContactParams& params,
                        ContactState& state) {
  return law.force(node_kinematics(node, l, n), params, state);
}

template <class Law>
NodePlaneForces node_against(const Law& law, const NodeOnPlane& node, const PointPlaneDistance& d,
                             const ContactParams& params, ContactState& state) {
  NodePlaneForces out;
  out.geometry = d;
  if (!(d.signed_distance <= node.L)) {
    state = ContactState{};
    return out;
  }
  const ContactKinematics& k = out.kinematics = node_kinematics(node, d.signed_distance, d.n_W);
  out.force = law.force(k, params, state);
  out.in_contact = out.force.in_contact;
  out.on_node = out.force.on_a;
  out.moment_on_node = (-0.5 * (k.l + k.L) * k.n).cross(out.force.on_a);
  return out;
}
}  // namespace detail

// Node against an unbounded plane (the floor): l is the signed distance, n the plane's normal.
template <class Law>
NodePlaneForces evaluate_node_plane(const Law& law, const NodeOnPlane& node, const Plane& plane,
                                    const ContactParams& params, ContactState& state) {
  static_assert(ContactLawPolicy<Law>, FURNITURE_FEM_CONTACT_LAW_MESSAGE);
  return detail::node_against(law, node, point_plane(node.p_WN, plane), params, state);
}

// Node against a bounded rectangle (a wall panel): no contact when the node's projection falls
// outside the rectangle.
template <class Law>
NodePlaneForces evaluate_node_rectangle(const Law& law, const NodeOnPlane& node, const Rectangle& rect,
                                        const ContactParams& params, ContactState& state) {
  static_assert(ContactLawPolicy<Law>, FURNITURE_FEM_CONTACT_LAW_MESSAGE);
  const auto d = point_rectangle(node.p_WN, rect);
  if (!d) {
    state = ContactState{};
    NodePlaneForces out;
    return out;
  }
  return detail::node_against(law, node, *d, params, state);
}

#undef FURNITURE_FEM_CONTACT_LAW_MESSAGE

}  // namespace furniture_fem
