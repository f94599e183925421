// Hard inputs: a 200 % JMA-Kobe-like 3-D motion (the built-in synthetic motion scaled to a peak of
// 16 m/s^2 along X, 12 along Y, 6.6 vertical) through run_scene(), and a long shaking (12 s short,
// 120 s full) with a strong phase lasting the whole record. No test reads ../shared.
// Short version (default): configuration 2 for 3 s; configuration 3 rigid / coarse for 12 s.
// FFEM_FULL_STABILITY=1: configuration 3 at full fidelity for 10 s and for 120 s.
#include "stability_support.hpp"

using namespace stability;

namespace strong_motion_tests {  // this file's own names (its group compiles files in batches)

TEST_CASE("stability: 200 % JMA-Kobe-like 3-D input", "[stability][strong_motion]") {
  const bool full = full_mode();
  // Short: configuration 2 (side table, desk, chair: 994 elements) for 3 s, the envelope's rise and
  // the first 1.5 s of the strong phase. Full: configuration 3 (5938 elements) for the whole 10 s.
  SceneSpec s = synthetic_configuration(full ? 3 : 2, 16.0, 1e-3, full ? 10.0 : 3.0, Fidelity::full);
  s.name = "200 % JMA-Kobe-like 3-D";
  const RunSummary sum = run_scene(s, quiet(full ? "kobe200_full" : "kobe200_short"));
  // Measured: configuration 2, 3 s: 0.0075 (end and worst); configuration 3, 10 s: 0.080 at the
  // end, 0.093 at worst (refresh every 0.1 s; every 20 steps: 0.097 / 0.108), lost when the three cabinets land (every cabinet overturns at 200 %).
  // Bounds: x4 margin short, x2.3 full.
  const double bound = full ? 0.25 : 0.03;
  std::string states;
  for (const auto& it : sum.items) states += (states.empty() ? "" : ", ") + it.name + " " + it.state;
  report("200 % JMA-Kobe-like 3-D (pga 16 m/s^2)", sum, "< " + num(bound),
         std::string(full ? "configuration 3, 10 s: " : "configuration 2, 3 s: ") + states);
  require_trusted(sum, bound);
  CHECK(sum.steps == static_cast<long>(std::lround(s.duration / s.dt)));
  for (const auto& it : sum.items) {
    INFO(it.name << ": " << it.state << ", slide " << it.slide << " m, tilt " << it.tilt_deg << " deg");
    CHECK(it.slide < 4.0);  // still on (or next to) the 4 m table
  }
  if (full) {
    // At 200 % the tall cabinet and the separated pair overturn.
    int overturned = 0;
    for (const auto& it : sum.items) overturned += it.tilt_deg > 60;
    CHECK(overturned >= 2);
  }
}

namespace {

// A synthetic 3-D motion of `duration` s whose strong phase lasts until 1 s before the end (the
// built-in one is 10 s long with a 3.5 s strong phase), peaks pga, 0.75 pga, 0.41 pga as the
// built-in default's X, Y, Z.
TableMotion long_motion(double duration, double pga) {
  const auto component = [&](std::uint64_t seed, double peak, double period) {
    SyntheticOptions o;
    o.seed = seed;
    o.duration = duration;
    o.pga = peak;
    o.predominant_period = period;
    o.envelope.strong = duration - o.envelope.rise - 1.0;
    return synthetic_motion(o);
  };
  return TableMotion::three_d(component(101, pga, 0.5), component(102, 0.75 * pga, 0.6), component(103, 0.41 * pga, 0.2));
}

}  // namespace

TEST_CASE("stability: long shaking", "[stability][strong_motion]") {
  const bool full = full_mode();
  const double duration = full ? 120.0 : 12.0;
  // Configuration 3 (walls at x = +-2). Short: the three cabinets rigid, the rest coarse.
  SceneSpec s = synthetic_configuration(3, 4.0, 1e-3, duration, Fidelity::full);
  for (auto& it : s.items)
    it.fidelity = full ? Fidelity::full : (it.kind == ItemKind::tall_cabinet || it.kind == ItemKind::separated_cabinets)
                                              ? Fidelity::rigid
                                              : Fidelity::coarse;
  Scene scene(s, 0, 1);
  scene.motion = long_motion(duration, 4.0);  // the simulation reads scene.motion
  const Outcome o = run(scene, s, duration);
  // Measured: see docs/performance.md (short: rigid / coarse 12 s; full: 120 s at full fidelity).
  const double bound = full ? 0.25 : 0.1;
  double farthest = 0;
  int over = 0;
  for (const auto& it : o.items) {
    farthest = std::max(farthest, it.shift.head<2>().norm());
    over += it.tilt_deg > 60;
  }
  report(std::string("long shaking, ") + (full ? "120 s" : "12 s") + " at 4 m/s^2 3-D", o, "< " + num(bound),
         std::string(full ? "configuration 3 full fidelity" : "configuration 3, cabinets rigid, rest coarse") +
             "; farthest item " + num(farthest) + " m, " + std::to_string(over) + " overturned");
  require_trusted(o, bound);
  CHECK(o.imbalance < 0);
  // Nothing sinks through the floor over the long run (node centres stay above it).
  CHECK(o.min_z > 0.0);
  for (const auto& it : o.items) {
    INFO(it.name << " shift " << it.shift.transpose());
    CHECK(it.shift.norm() < 6.0);
  }
}

namespace {

// One item alone on an open floor under the `stiff` law, every item at full fidelity, 1 ms. The spec
// leaves `contact.implicit` unset: the law's default (every item's floor contact inside the implicit
// step) must apply in C++ as in a scene file. Until 2026-11-26 only the reader applied it; a C++ spec
// kept `rigid`, so a full item's stiff floor spring was explicit: the desk at rest diverges at 0.19 s
// (a scene file with `"implicit": "rigid"`, the same spec, measured 2026-11-26).
SceneSpec stiff_alone(const std::string& kind, double duration) {
  SceneSpec s = open_floor("stiff: " + kind, 1e-3, duration);
  s.contact.law = law_kind<StiffSceneLaw>;
  s.items.push_back({kind, ItemKind(kind), 0.0, 0.0, 0.0, Fidelity::full, {}});
  return s;
}

RunOptions summary_only() {
  RunOptions o;
  o.write_files = false;
  o.progress = false;
  return o;
}

}  // namespace

// The `stiff` law's floor spring holds an item 2.5 um deep under its weight: on a desk's panel edges
// (13 nodes of 11 to 21 g per edge) that is omega dt = 20 at 1 ms, stable only inside the implicit
// step. The flexible bodies' contact changes beyond the Woodbury cap (6 nodes) used to wait up to 20
// steps for a factorisation: the desk diverged at rest within 0.1 s, and the desk, the tall cabinet
// and the separated cabinets alone under the built-in 3-D motion within 0.4 to 0.9 s (2026-11-26).
TEST_CASE("stability: every kind at full fidelity under the stiff law, at rest", "[stability][stiff]") {
  for (const std::string kind : {"tall_cabinet", "separated_cabinets", "side_table", "desk", "office_chair", "bookshelf",
                                 "locker", "table"}) {
    SceneSpec s = stiff_alone(kind, 1.0);
    s.ground_motion.source = MotionSource::points;
    s.ground_motion.points_x = {{0.0, 0.0}};  // the table at rest
    const RunSummary sum = run_scene(s, summary_only());
    std::string finals;
    for (const auto& it : sum.items) finals += it.name + " slide " + num(it.slide) + " m tilt " + num(it.tilt_deg) + " deg; ";
    report("stiff law, full fidelity, " + kind + " at rest, 1 s", sum, "slide < 1e-4 m", finals);
    INFO(kind << ": " << sum.status << " " << sum.diagnosis);
    REQUIRE(sum.status == "completed");
    for (const auto& it : sum.items) {
      INFO(it.name << ": " << it.state << ", slide " << it.slide << " m, tilt " << it.tilt_deg << " deg");
      // The upper separated cabinet stands on the lower through an explicit item-item pair whose friction
      // is regularised: it creeps, 6.3 mm in 1 s here and 13 mm in 3 s (9 mm under the paper's law; 0
      // when both are rigid, a rigid group). Open in issue 10 (docs/contact/implicit_contact.md, "Not yet
      // inside the step"), so only items on the floor are held to the bound here.
      if (!it.resting_on.empty()) continue;
      // Settling onto its springs (2.5 um) and the frame's sag move nothing sideways: drift < 0.1 mm
      // (issue 10's bound; measured at most 4.5 um), no tilt.
      CHECK(it.state == "standing");
      CHECK(it.slide < 1e-4);
      CHECK(it.tilt_deg < 0.05);
    }
  }
}

TEST_CASE("stability: the stiff law at full fidelity under the built-in 3-D motion", "[stability][stiff]") {
  for (const std::string kind : {"desk", "tall_cabinet", "separated_cabinets"}) {
    // The separated cabinets refactorise nearly every step (their item-item contact changes: 2130
    // factorisations in 2 s, 239 of the short suite's 433 s): the short version runs them 1.2 s, past the
    // 0.4 to 0.9 s where they diverged; the full version 2 s like the others.
    const double duration = kind == "separated_cabinets" && !full_mode() ? 1.2 : 2.0;
    SceneSpec s = stiff_alone(kind, duration);
    s.ground_motion.source = MotionSource::synthetic;
    s.ground_motion.dimensions = MotionDimensions::three_d;
    s.ground_motion.pga = 8.0;  // the main job's motion, its first seconds
    const RunSummary sum = run_scene(s, summary_only());
    report("stiff law, full fidelity, " + kind + " alone, built-in 3-D motion (pga 8 m/s^2), " + num(duration) + " s", sum,
           "< 1", "factorisations " + std::to_string(sum.factorizations));
    INFO(kind << ": " << sum.status << " at " << sum.t_end << " s: " << sum.diagnosis);
    REQUIRE(sum.status == "completed");
    CHECK(sum.max_energy_imbalance < 1.0);
  }
}

}  // namespace strong_motion_tests
