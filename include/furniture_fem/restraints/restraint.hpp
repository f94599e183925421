#pragma once
// furniture_fem/restraints/restraint.hpp: one fastening device between a point of an item and the room
// (docs/restraints/restraints.md), and the force it carries.
//
//   RestraintKind          l_bracket, strap, mat, pole, stopper
//   RestraintParams        every kind's numbers (SI); a kind reads the ones it declares
//   RestraintParameter     a parameter as its kind declares it: key, unit, range, default, meaning
//   Restraint              a device placed: its item's node, its anchor, its parameters
//   RestraintState         its history (plastic pull, the pole pad's slip, broken or not, its work)
//   restraint_response()   its force on the item's node at a state, the force's slope and its regime
//
// A restraint acts between one node of an item and a fixed point of the room (all in the table frame).
// Its force and slope enter the implicit step as a floor or wall contact does (contact/room_contact.hpp).
// Failure is final: a broken restraint carries nothing for the rest of the run.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "../core/model.hpp"

namespace furniture_fem {

enum class RestraintKind { l_bracket, strap, mat, pole, stopper };
inline constexpr std::array<RestraintKind, 5> all_restraint_kinds = {
    RestraintKind::l_bracket, RestraintKind::strap, RestraintKind::mat, RestraintKind::pole, RestraintKind::stopper};

inline constexpr std::string_view to_string(RestraintKind k) {
  switch (k) {
    case RestraintKind::l_bracket: return "l_bracket";
    case RestraintKind::strap: return "strap";
    case RestraintKind::mat: return "mat";
    case RestraintKind::pole: return "pole";
    case RestraintKind::stopper: return "stopper";
  }
  return "?";
}
inline std::optional<RestraintKind> restraint_kind_from_string(std::string_view s) {
  for (RestraintKind k : all_restraint_kinds)
    if (to_string(k) == s) return k;
  return std::nullopt;
}

// Every kind's numbers in SI units. Which kind reads which, and what it means there: the declarations
// (restraint_parameters) and docs/restraints/restraints.md.
struct RestraintParams {
  double stiffness = 0;          // N/m: bracket pull, strap and pole axial, mat shear and uplift, stopper bearing
  double shear_stiffness = 0;    // N/m: bracket across its pull direction
  double strength = 0;           // N: bracket pull-out peak, strap tensile, mat peel in shear, stopper crush
  double shear_strength = 0;     // N: bracket across its pull direction (brittle)
  double tension_strength = 0;   // N: mat uplift (brittle)
  double plateau = 0;            // m: bracket plastic pull at its peak before it softens
  double softening = 0;          // m: bracket plastic pull over which the force falls from its peak to zero
  double slack = 0;              // m: strap length beyond taut at the start
  double preload = 0;            // N: pole compression at the start
  double lateral_stiffness = 0;  // N/m: pole pad on the ceiling, stopper's top under the edge, horizontally
  double friction = 0;           // -: pole pad on the ceiling, the item's edge on a stopper
  double slip_strength = 0;      // N: pole telescoping lock (it shortens above it)
  double board_strength = 0;     // N: ceiling board under the pole's pad (it crushes above it)
  double board_travel = 0;       // m: board crush after which the pad has punched through (broken)
  double wedge_height = 0;       // m: stopper under the edge (the scene tilts the item back by it)
  double reach = 0;              // m: stopper's depth ahead of and behind the edge (travelled further: slid off)
  double damping = 0;            // N s/m: stopper's bearing (the elastomer's loss), while it bears
};

// One parameter of a kind: the scene key inside the restraint's object, kept in `field`.
struct RestraintParameter {
  std::string_view key, unit;
  double lo = 0, hi = 0;  // accepted range, both ends included unless lo_exclusive
  bool lo_exclusive = false;
  double default_value = 0;
  std::string_view meaning;  // one line, for the docs table
  double RestraintParams::*field = nullptr;
  bool accepts(double v) const { return (lo_exclusive ? v > lo : v >= lo) && v <= hi; }
  std::string range_text() const {
    std::string text(lo_exclusive ? "(" : "[");
    return text.append(detail::fmt(lo)).append(", ").append(detail::fmt(hi)).append("]");
  }
};

namespace detail {
inline constexpr double restraint_force_max = 1e7;  // N: far beyond any furniture fastening
inline constexpr double restraint_stiffness_max = 1e10;  // N/m
using RP = RestraintParams;
// The defaults: derived in docs/restraints/restraints.md, "Defaults", with their sources and spread.
inline constexpr RestraintParameter l_bracket_parameters[] = {
    {"stiffness", "N/m", 0, restraint_stiffness_max, true, 1.2e5, "pull stiffness (the bracket's leg in bending)", &RP::stiffness},
    {"shear_stiffness", "N/m", 0, restraint_stiffness_max, true, 1.7e6, "stiffness across the pull (the screws' slip)", &RP::shear_stiffness},
    {"strength", "N", 0, restraint_force_max, true, 1000, "pull-out force of its screws (screws: stud)", &RP::strength},
    {"shear_strength", "N", 0, restraint_force_max, true, 2400, "force across the pull that shears it off (screws: stud)", &RP::shear_strength},
    {"plateau", "m", 0, 1, false, 0.002, "plastic pull at the peak force before it softens", &RP::plateau},
    {"softening", "m", 0, 1, true, 0.02, "plastic pull over which the force falls to zero (then broken)", &RP::softening},
};
inline constexpr RestraintParameter strap_parameters[] = {
    {"stiffness", "N/m", 0, restraint_stiffness_max, true, 5e4, "axial stiffness of the strap and its fixings", &RP::stiffness},
    {"strength", "N", 0, restraint_force_max, true, 1000, "tension at which it breaks (its weakest link)", &RP::strength},
    {"slack", "m", 0, 1, false, 0, "length beyond taut at the start", &RP::slack},
};
inline constexpr RestraintParameter mat_parameters[] = {
    {"stiffness", "N/m", 0, restraint_stiffness_max, true, 1.6e4, "shear (and uplift) stiffness of the gel pad", &RP::stiffness},
    {"strength", "N", 0, restraint_force_max, true, 150, "shear force at which the pad peels off", &RP::strength},
    {"tension_strength", "N", 0, restraint_force_max, true, 50, "uplift force at which the pad peels off", &RP::tension_strength},
};
inline constexpr RestraintParameter pole_parameters[] = {
    {"preload", "N", 0, restraint_force_max, false, 200, "compression set when it is fitted", &RP::preload},
    {"stiffness", "N/m", 0, restraint_stiffness_max, true, 1e5, "axial stiffness (the pole and its pads)", &RP::stiffness},
    {"lateral_stiffness", "N/m", 0, restraint_stiffness_max, true, 5e4, "horizontal stiffness of its top pad on the ceiling", &RP::lateral_stiffness},
    {"friction", "-", 0, 5, false, 0.5, "friction coefficient of its top pad on the ceiling", &RP::friction},
    {"slip_strength", "N", 0, restraint_force_max, true, 1000, "compression at which its lock slips (it shortens)", &RP::slip_strength},
    {"board_strength", "N", 0, restraint_force_max, true, 600, "compression at which the ceiling board crushes", &RP::board_strength},
    {"board_travel", "m", 0, 1, true, 0.01, "crush after which the pad has punched through (broken)", &RP::board_travel},
};
inline constexpr RestraintParameter stopper_parameters[] = {
    {"wedge_height", "m", 0.002, 0.05, false, 0.015, "height of the wedge under the edge: the item leans back by it", &RP::wedge_height},
    {"stiffness", "N/m", 0, restraint_stiffness_max, true, 1e6, "bearing stiffness of the wedge under the edge", &RP::stiffness},
    {"lateral_stiffness", "N/m", 0, restraint_stiffness_max, true, 3e5, "horizontal stiffness of the wedge's top under the edge", &RP::lateral_stiffness},
    {"friction", "-", 0, 5, false, 0.5, "friction coefficient of the edge on the wedge", &RP::friction},
    {"strength", "N", 0, restraint_force_max, true, 2000, "bearing force at which the wedge is crushed (then lost)", &RP::strength},
    {"reach", "m", 0, 0.2, true, 0.03, "edge travel over the wedge at which it slides off (then lost)", &RP::reach},
    {"damping", "N s/m", 0, 1e6, false, 5000, "viscous damping of its bearing while it bears", &RP::damping},
};
}  // namespace detail

// The parameters a kind reads, in the order the docs list them.
inline std::span<const RestraintParameter> restraint_parameters(RestraintKind k) {
  switch (k) {
    case RestraintKind::l_bracket: return detail::l_bracket_parameters;
    case RestraintKind::strap: return detail::strap_parameters;
    case RestraintKind::mat: return detail::mat_parameters;
    case RestraintKind::pole: return detail::pole_parameters;
    case RestraintKind::stopper: return detail::stopper_parameters;
  }
  return {};
}
inline const RestraintParameter* find_restraint_parameter(RestraintKind k, std::string_view key) {
  for (const RestraintParameter& p : restraint_parameters(k))
    if (p.key == key) return &p;
  return nullptr;
}
// The kind's defaults (an l_bracket's screws in a stud).
inline RestraintParams default_restraint_params(RestraintKind k) {
  RestraintParams p;
  for (const RestraintParameter& d : restraint_parameters(k)) p.*(d.field) = d.default_value;
  return p;
}

// What an l_bracket's screws go into: a stud (timber) or the wall board alone (gypsum); the board's
// screws pull out and shear off at lower forces and more abruptly (docs/restraints/restraints.md).
enum class ScrewBase { stud, board };
inline void set_screw_base_defaults(RestraintParams& p, ScrewBase base) {
  if (base == ScrewBase::stud) return;
  p.strength = 300;
  p.shear_strength = 600;
  p.plateau = 0.0005;
  p.softening = 0.005;
}

// A device placed. `rest` is the node's position at the start, `anchor` the fixed point it is tied to
// and `normal` the unit normal of the surface it is fixed on, into the room (a wall's; the ceiling's is
// -z, the floor's +z). Tied to another item instead (anchor_node >= 0: a bracket or strap joining two
// items), `anchor` is that item's node at the start and the device acts on the first node's place
// relative to the anchor node's displacement (item_place), with the opposite force on the anchor node;
// `normal` is then the direction from the anchor to the node at the start (+z when they meet), fixed.
struct Restraint {
  std::string name;
  RestraintKind kind = RestraintKind::strap;
  int body = -1, node = -1;
  int anchor_body = -1, anchor_node = -1;  // -1: fixed to the room
  Vec3 rest = Vec3::Zero(), anchor = Vec3::Zero(), normal = Vec3::UnitX();
  RestraintParams p;
  bool between_items() const { return anchor_node >= 0; }
  int node_on(int b) const { return between_items() && b == anchor_body ? anchor_node : node; }  // its node on body b
  // Where the law sees the node: x itself, or, between items, x less the anchor node's displacement
  // (its place y against its place at the start, `anchor`); the same for speeds.
  Vec3 item_place(const Vec3& x, const Vec3& y) const { return between_items() ? Vec3(x - (y - anchor)) : x; }
};

// What a restraint is doing, for outputs and for the implicit step (a change of regime within a step
// solves the body again, as a contact's change of status does).
enum class RestraintRegime : char { idle = 0, elastic = 1, yielding = 2, softening = 3, slipping = 4, broken = 5 };
inline constexpr std::string_view to_string(RestraintRegime r) {
  constexpr std::array<std::string_view, 6> names = {"idle", "elastic", "yielding", "softening", "slipping", "broken"};
  return names[static_cast<int>(r)];
}
// How it broke (RestraintState::failure).
enum class RestraintFailure : char { none = 0, pull_out = 1, shear = 2, tension = 3, peel = 4, uplift = 5, punch_through = 6,
                                     crush = 7, slid_off = 8 };
inline constexpr std::string_view to_string(RestraintFailure f) {
  constexpr std::array<std::string_view, 9> names = {"none", "pull_out", "shear",         "tension", "peel",
                                                     "uplift", "punch_through", "crush", "slid_off"};
  return names[static_cast<int>(f)];
}

// A restraint's history. Evaluations start from the committed state and write a trial; the step's
// commit keeps the trial of the last evaluation (as the contacts' history).
struct RestraintState {
  static constexpr bool checkpoint_as_bytes = true;  // core/checkpoint.hpp: doubles and Vec3s, then chars
  double plastic = 0;          // m: bracket plastic pull; pole shortening (lock slip and board crush)
  double work = 0;             // J: the work it has done on the item, trapezoidal over committed steps
  double peak_force = 0;       // N: the largest force it has carried in the sense that fails it (a bracket's pull)
  double broke_at = -1;        // s: when it broke (committed); -1: intact
  double force = 0;            // N: its force now (tension or compression, signed as its kind says)
  double extension = 0;        // m: its deformation now (pull, stretch, shear, compression)
  double stored = 0;           // J: elastic energy it holds now
  Vec3 slip = Vec3::Zero();    // m: the pole pad's slip on the ceiling
  Vec3 on_item = Vec3::Zero(); // N: its force on the item's node
  Vec3 x = Vec3::Zero();       // m: the node's position at the evaluation
  RestraintRegime regime = RestraintRegime::idle;
  RestraintFailure failure = RestraintFailure::none;
  char pad_[6] = {};           // no padding bytes in a checkpoint
  bool broken() const { return failure != RestraintFailure::none; }
};

// The force on the item's node at position x and velocity v, its slopes (f(x + dx, v + dv) ~ on_item -
// K dx - C dv) and the state it leaves (from the committed state `from`). Only a stopper's bearing
// reads v (its damping); the other kinds are springs.
struct RestraintResponse {
  Vec3 on_item = Vec3::Zero();
  Mat3 K = Mat3::Zero(), C = Mat3::Zero();
  RestraintState state;
};

namespace detail {

// The bracket's pull backbone: elastic at k up to the peak F, a plateau of plastic pull, then softening
// linearly to zero over `softening`; unloading elastic (plastic pull kept). Returns (force, slope) and
// updates the plastic pull p; broken when p passes plateau + softening.
struct Backbone {
  double force = 0, slope = 0;
  RestraintRegime regime = RestraintRegime::elastic;
  bool broken = false;
};
inline Backbone bracket_pull(const RestraintParams& q, double pull, double& p) {
  const double k = q.stiffness, F = q.strength, S = F / q.softening;
  const auto cap = [&](double pp) { return pp <= q.plateau ? F : F - S * (pp - q.plateau); };
  const double trial = k * (pull - p);
  if (trial <= cap(p)) return {trial, k, RestraintRegime::elastic, false};
  const double on_plateau = pull - F / k;
  if (on_plateau <= q.plateau) {
    p = std::max(p, on_plateau);
    return {F, 0, RestraintRegime::yielding, false};
  }
  p = std::max(p, (k * pull - F - S * q.plateau) / (k - S));  // k (pull - p) = cap(p) on the falling branch
  if (p >= q.plateau + q.softening) return {0, 0, RestraintRegime::broken, true};
  return {cap(p), 0, RestraintRegime::softening, false};
}

inline void bracket_response(const Restraint& r, const Vec3& d, RestraintResponse& out) {
  const RestraintParams& q = r.p;
  RestraintState& s = out.state;
  const Vec3& n = r.normal;
  const double pull = d.dot(n);
  const Vec3 across = d - pull * n;
  const Backbone b = bracket_pull(q, pull, s.plastic);
  const Vec3 shear = q.shear_stiffness * across;
  if (b.broken || shear.norm() > q.shear_strength) {
    s.failure = b.broken ? RestraintFailure::pull_out : RestraintFailure::shear;
    return;
  }
  out.on_item = -b.force * n - shear;
  out.K = b.slope * n * n.transpose() + q.shear_stiffness * (Mat3::Identity() - n * n.transpose());
  s.force = b.force;
  s.extension = pull;
  s.regime = b.regime;
  s.stored = 0.5 * b.force * b.force / q.stiffness + 0.5 * shear.squaredNorm() / q.shear_stiffness;
}

inline void strap_response(const Restraint& r, const Vec3& x, RestraintResponse& out) {
  const RestraintParams& q = r.p;
  RestraintState& s = out.state;
  const Vec3 from_anchor = x - r.anchor;
  const double length = from_anchor.norm(), taut = (r.rest - r.anchor).norm() + q.slack;
  s.extension = length - taut;
  if (s.extension <= 0) return;  // slack: idle
  const double tension = q.stiffness * s.extension;
  if (tension > q.strength) {
    s.failure = RestraintFailure::tension;
    return;
  }
  const Vec3 e = from_anchor / length;
  out.on_item = -tension * e;
  out.K = q.stiffness * e * e.transpose() + (tension / length) * (Mat3::Identity() - e * e.transpose());
  s.force = tension;
  s.regime = RestraintRegime::elastic;
  s.stored = 0.5 * tension * tension / q.stiffness;
}

inline void mat_response(const Restraint& r, const Vec3& d, RestraintResponse& out) {
  const RestraintParams& q = r.p;
  RestraintState& s = out.state;
  const Vec3& n = r.normal;
  const double uplift = std::max(0.0, d.dot(n));
  const Vec3 shear = q.stiffness * (d - d.dot(n) * n);
  const double tension = q.stiffness * uplift;
  if (shear.norm() > q.strength || tension > q.tension_strength) {
    s.failure = shear.norm() > q.strength ? RestraintFailure::peel : RestraintFailure::uplift;
    return;
  }
  out.on_item = -shear - tension * n;
  out.K = q.stiffness * (Mat3::Identity() - n * n.transpose());
  if (uplift > 0) out.K += q.stiffness * n * n.transpose();
  s.force = shear.norm();
  s.extension = (d - d.dot(n) * n).norm();
  s.regime = RestraintRegime::elastic;
  s.stored = 0.5 * (shear.squaredNorm() + tension * tension) / q.stiffness;
}

// A pad held sideways on a spring of lateral_stiffness to where it stands (s.slip) up to friction times
// the normal force N, then slipping (a Coulomb return map): a pole's top pad, a stopper's top.
struct PadForce {
  Vec3 force;
  Mat3 slope;
};
inline PadForce pad_friction(const RestraintParams& q, const Vec3& across, const Vec3& normal, double N, RestraintState& s) {
  Vec3 lateral = -q.lateral_stiffness * (across - s.slip);
  Mat3 slope = q.lateral_stiffness * (Mat3::Identity() - normal * normal.transpose());
  const double hold = q.friction * N;
  if (lateral.norm() > hold) {  // the pad slips: the spring's stretch back to what friction holds
    lateral *= hold / lateral.norm();
    s.slip = across + lateral / q.lateral_stiffness;
    slope.setZero();
    s.regime = RestraintRegime::slipping;
  }
  return {lateral, slope};
}

// The pole: compression N = preload + k (rise - shortening), nothing when it would pull; above the lock's
// or the board's strength it shortens at that force (the board's crush beyond board_travel breaks it).
// Its pad holds the item's top horizontally on a spring, up to friction times N (then it slips).
inline void pole_response(const Restraint& r, const Vec3& d, RestraintResponse& out) {
  const RestraintParams& q = r.p;
  RestraintState& s = out.state;
  const Vec3 up = -r.normal;  // the ceiling's normal points down into the room
  const double rise = d.dot(up);
  const double cap = std::min(q.slip_strength, q.board_strength);
  double N = q.preload + q.stiffness * (rise - s.plastic), axial_slope = q.stiffness;
  s.regime = RestraintRegime::elastic;
  if (N > cap) {
    s.plastic = rise - (cap - q.preload) / q.stiffness;
    N = cap;
    axial_slope = 0;
    s.regime = RestraintRegime::yielding;
    if (q.board_strength <= q.slip_strength && s.plastic > q.board_travel) {
      s.failure = RestraintFailure::punch_through;
      return;
    }
  }
  const Vec3 across = d - rise * up;
  if (N <= 0) {  // lifted off the item: the pad lands again where the item's top is then
    s.slip = across;
    s.regime = RestraintRegime::idle;
    s.extension = rise - s.plastic;
    return;
  }
  const PadForce pad = pad_friction(q, across, up, N, s);
  out.on_item = -N * up + pad.force;
  out.K = axial_slope * up * up.transpose() + pad.slope;
  s.force = N;
  s.extension = rise - s.plastic;
  s.stored = 0.5 * N * N / q.stiffness + 0.5 * pad.force.squaredNorm() / q.lateral_stiffness;
}

// The stopper: a wedge fixed to the floor under the item's front edge (the scene has tilted the item back
// onto it). It bears the edge from below, N = stiffness times how far the node has sunk below where it
// stood, nothing when the edge lifts, and holds it sideways as a pole's pad does. Crushed above
// `strength`, or slid off when the edge has travelled `reach` over it: either is final. Its bearing is
// damped (`damping` times the edge's speed into it) while it bears: an undamped spring under a leaning
// item rang on for seconds after the item settled onto it.
inline void stopper_response(const Restraint& r, const Vec3& d, const Vec3& v, RestraintResponse& out) {
  const RestraintParams& q = r.p;
  RestraintState& s = out.state;
  const Vec3& up = r.normal;
  const double sink = -d.dot(up);
  const Vec3 across = d + sink * up;
  s.extension = sink;
  if (across.norm() > q.reach) {
    s.failure = RestraintFailure::slid_off;
    return;
  }
  const double spring = q.stiffness * sink, N = spring - q.damping * v.dot(up);
  if (spring <= 0 || N <= 0) {  // the edge has lifted, or leaves faster than the wedge follows: idle
    s.slip = across;            // its top holds the edge where it lands again
    return;
  }
  if (N > q.strength) {
    s.failure = RestraintFailure::crush;
    return;
  }
  s.regime = RestraintRegime::elastic;
  const PadForce pad = pad_friction(q, across, up, N, s);
  out.on_item = N * up + pad.force;
  out.K = q.stiffness * up * up.transpose() + pad.slope;
  out.C = q.damping * up * up.transpose();
  s.force = N;
  s.stored = 0.5 * spring * spring / q.stiffness + 0.5 * pad.force.squaredNorm() / q.lateral_stiffness;
}

}  // namespace detail

// Restraint r with its node at x moving at v, from the committed state `from` (the trial it leaves in
// .state; its work, peak and break time are left to the commit).
inline RestraintResponse restraint_response(const Restraint& r, const RestraintState& from, const Vec3& x,
                                            const Vec3& v = Vec3::Zero()) {
  RestraintResponse out;
  RestraintState& s = out.state;
  s = from;
  s.force = s.extension = s.stored = 0;
  s.regime = RestraintRegime::idle;
  s.x = x;
  if (!from.broken()) {
    const Vec3 d = x - r.rest;
    switch (r.kind) {
      case RestraintKind::l_bracket: detail::bracket_response(r, d, out); break;
      case RestraintKind::strap: detail::strap_response(r, x, out); break;
      case RestraintKind::mat: detail::mat_response(r, d, out); break;
      case RestraintKind::pole: detail::pole_response(r, d, out); break;
      case RestraintKind::stopper: detail::stopper_response(r, d, v, out); break;
    }
  }
  if (s.broken()) {
    out.on_item.setZero();
    out.K.setZero();
    out.C.setZero();
    s.force = s.stored = 0;
    s.regime = RestraintRegime::broken;
  }
  s.on_item = out.on_item;
  return out;
}

// The state a restraint starts from at its rest position (the pole's preload already on).
inline RestraintState initial_restraint_state(const Restraint& r) {
  RestraintState s = restraint_response(r, RestraintState{}, r.rest).state;
  s.peak_force = std::max(0.0, s.force);
  return s;
}

}  // namespace furniture_fem
