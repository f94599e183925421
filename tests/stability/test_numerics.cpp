// Numerical parameters pushed past the paper's: a contact penalty 100 times stiffer, and a time step
// five times larger (5 ms). The solver treats contact forces explicitly (they are not in the
// effective matrix), so a stiffer penalty lowers the stable step: a run that cannot be trusted must
// stop as "diverged" with a diagnosis naming the cause, not write garbage. All through run_scene(),
// on configuration 2 (side table, desk, chair) under the built-in synthetic 3-D motion.
// Short version (default): a few seconds of simulated time; FFEM_FULL_STABILITY=1: longer runs.
#include "stability_support.hpp"

#include <furniture_fem/io/csv.hpp>

using namespace stability;

namespace numerics_tests {  // this file's own names (its group compiles files in batches)

namespace {

// Configuration 2 at 100 % (pga 8 m/s^2) with the desk and chair markers, every item's penalty
// alpha scaled by `penalty_factor` (item parameter alpha_kgf: it applies to the item's floor, wall
// and item-item contacts, i.e. the scene's floor and item overrides for each item). These runs are
// past the explicit contact's stable step on purpose: allow_coarse_dt (refused otherwise, below).
SceneSpec configuration2(double dt, double duration, double penalty_factor) {
  SceneSpec s = synthetic_configuration(2, 8.0, dt, duration, Fidelity::full);
  s.allow_coarse_dt = true;
  s.outputs.markers = configuration(2, "").outputs.markers;
  if (penalty_factor != 1.0) {
    Model scratch;
    const auto items = build_scene(s, scratch);
    for (size_t i = 0; i < s.items.size(); ++i)
      s.items[i].params.alpha_kgf = penalty_factor * items[i].contact.alpha / newtons_per_kgf;
  }
  return s;
}

// Every value written to markers.csv and energy.csv finite, and every marker displacement under
// `limit` m: what a stopped run leaves behind is readable and not garbage.
void check_outputs_readable(const std::string& dir, double limit) {
  for (const char* file : {"/markers.csv", "/energy.csv"}) {
    INFO(dir + file);
    const CsvTable t = read_csv(dir + file);
    REQUIRE(t.rows() > 0);
    for (std::size_t c = 0; c < t.columns().size(); ++c)
      for (double v : t.column(c)) REQUIRE(std::isfinite(v));
  }
  // The displacement columns (<marker>_x, _y, _z); _ax, _ay, _az are accelerations (m/s^2).
  const CsvTable m = read_csv(dir + "/markers.csv");
  for (std::size_t c = 1; c < m.columns().size(); ++c) {
    const std::string& name = m.columns()[c];
    if (name.size() > 3 && name[name.size() - 3] == '_' && name[name.size() - 2] == 'a') continue;
    INFO(name);
    for (double v : m.column(c)) CHECK(std::abs(v) < limit);
  }
}

}  // namespace

TEST_CASE("stability: a penalty 100 times stiffer", "[stability][numerics]") {
  const bool full = full_mode();
  SECTION("dt = 5 ms: stops as diverged, naming the penalty and the time step") {
    const SceneSpec s = configuration2(5e-3, full ? 10.0 : 2.0, 100.0);
    const RunOptions opt = quiet("penalty100_dt5ms");
    const RunSummary sum = run_scene(s, opt);
    report("penalty x100, dt = 5 ms", sum, "diverged", "stops at t = " + std::to_string(sum.t_end).substr(0, 5) + " s");
    INFO(sum.diagnosis);
    REQUIRE(sum.status == "diverged");
    CHECK(sum.t_end < s.duration);
    CHECK(sum.diagnosis.find("energy is being created") != std::string::npos);
    CHECK(sum.diagnosis.find("too stiff for the time step") != std::string::npos);
    CHECK(sum.diagnosis.find("alpha_kgf") != std::string::npos);
    // Without the check the run "completes" with items 1e12 m away; with it, what was written
    // stays physical (the table's own displacement is a few cm).
    check_outputs_readable(opt.out_dir, 1.0);
  }
  SECTION("dt = 1 ms: the paper's step is also too large for it") {
    // Without the check: the ledger loses 84 % of its scale by 2 s and the desk hops 0.2 m up and
    // tilts 19 deg, the contact forces having done +0.77 of the scale of net work.
    const SceneSpec s = configuration2(1e-3, full ? 10.0 : 2.0, 100.0);
    const RunOptions opt = quiet("penalty100_dt1ms");
    const RunSummary sum = run_scene(s, opt);
    report("penalty x100, dt = 1 ms", sum, "diverged", "stops at t = " + std::to_string(sum.t_end).substr(0, 5) + " s");
    INFO(sum.diagnosis);
    REQUIRE(sum.status == "diverged");
    CHECK(sum.diagnosis.find("too stiff for the time step") != std::string::npos);
    check_outputs_readable(opt.out_dir, 1.0);
  }
  SECTION("dt = 0.1 ms: stable, the ledger closes") {
    // A tenth of the paper's step is within the stiff penalty's limit (estimate: 0.13 ms for the
    // chair's casters; observed stable). Measured 7.8e-5 over 0.5 s (the envelope's rise), 0.0104
    // over 3 s (into the strong phase; dt = 1 ms with the paper's penalty: 0.002); x10 and x3
    // margins. Short: 0.5 s (5000 steps); full: 3 s.
    const SceneSpec s = configuration2(1e-4, full ? 3.0 : 0.5, 100.0);
    const RunSummary sum = run_scene(s, quiet("penalty100_dt01ms"));
    const double bound = full ? 0.03 : 1e-3;
    report("penalty x100, dt = 0.1 ms", sum, "< " + num(bound), full ? "3 s" : "0.5 s");
    require_trusted(sum, bound);
  }
}

TEST_CASE("stability: a dt past twice the contact's stable step is refused before it runs", "[stability][numerics]") {
  // dt = 5 ms is 3.9 times the estimate (1.28 ms, the chair's floor nodes): the runs below, asked for
  // with allow_coarse_dt, slide the desk 0.06 m instead of 0.11 m in 3 s and lose 59 % of the ledger in 10 s.
  SceneSpec s = configuration2(5e-3, 1.0, 1.0);
  s.allow_coarse_dt = false;
  try {
    run_scene(s, quiet("dt5ms_refused"));
    FAIL("dt = 5 ms ran");
  } catch (const InputError& e) {
    CHECK(e.field() == "dt");
    CHECK_THAT(std::string(e.what()), Catch::Contains("0.005 s is 3.8") &&
                                          Catch::Contains("times the explicit contact's stable step, estimated at 0.00128") &&
                                          Catch::Contains("for item 'office_chair'"));
  }
  s.dt = 2.5e-3;  // within twice the estimate: runs
  s.duration = 0.01;
  CHECK(run_scene(s, quiet("dt2_5ms")).status == "completed");
}

TEST_CASE("stability: a time step five times larger (5 ms)", "[stability][numerics]") {
  const bool full = full_mode();
  // The first 3 s (the envelope's rise and the start of the strong phase), both versions.
  const RunSummary sum = run_scene(configuration2(5e-3, 3.0, 1.0), quiet("dt5ms"));
  // Measured (3 s): 0.157 at the end and at worst (dt = 1 ms: 0.002). Stable but inaccurate: the
  // contact forces, one step behind, already give back +5 % of the scale. Bound: x2 margin.
  report("dt = 5 ms (paper penalty)", sum, "< 0.3", "configuration 2, 3 s");
  require_trusted(sum, 0.3);
  // Against the same run at dt = 1 ms: every item ends within 0.15 m of where it ends there (the
  // desk slides 0.06 m instead of 0.11 m over 3 s: stable, not accurate).
  const RunSummary ref = run_scene(configuration2(1e-3, 3.0, 1.0), quiet("dt1ms"));
  report("dt = 1 ms (reference for 5 ms)", ref, "< 0.01", "configuration 2, 3 s");
  require_trusted(ref, 0.01);
  REQUIRE(ref.items.size() == sum.items.size());
  for (size_t i = 0; i < sum.items.size(); ++i) {
    INFO(sum.items[i].name << ": slide " << sum.items[i].slide << " m at 5 ms, " << ref.items[i].slide << " m at 1 ms");
    CHECK((sum.items[i].cog_displacement - ref.items[i].cog_displacement).norm() < 0.15);
  }
  if (full) {
    // The whole 10 s record. Before the finite-rotation update the lagging contact forces pumped
    // energy in and the run stopped as diverged at t = 8.95 s; now (measured) it completes with 59 %
    // of the ledger's scale lost. Either way it cannot be trusted, and it must say so, naming the
    // time step against the penalty: stopped as diverged, or completed with the loss warning.
    const RunOptions opt = quiet("dt5ms_10s");
    const RunSummary whole = run_scene(configuration2(5e-3, 10.0, 1.0), opt);
    report("dt = 5 ms (paper penalty), whole record", whole, "diverged or warned",
           "configuration 2, 10 s: " + whole.status + " at t = " + num(whole.t_end) + " s");
    INFO(whole.status << ": " << whole.diagnosis);
    CHECK((whole.status == "diverged" || (whole.status == "completed" && whole.energy_imbalance > 0.15)));
    CHECK(whole.diagnosis.find("too stiff for the time step") != std::string::npos);
    check_outputs_readable(opt.out_dir, 1.0);
    // At dt = 1 ms the same 10 s close the ledger to 0.0075 (measured; x2 margin).
    const RunSummary ok = run_scene(configuration2(1e-3, 10.0, 1.0), quiet("dt1ms_10s"));
    report("dt = 1 ms (paper penalty), whole record", ok, "< 0.015", "configuration 2, 10 s");
    require_trusted(ok, 0.015);
  }
}

}  // namespace numerics_tests
