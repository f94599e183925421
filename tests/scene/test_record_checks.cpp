// A scene is honest about its input (issue 12, item 4): a record whose peak lies outside the plausible
// band for its declared unit is an error naming the likely unit mistake and the key to set (check_pga:
// false runs it as given); ground_motion.scale_to scales a record to a target PGA (exactly) or PGV (the
// trapezoid velocity, checked here against an independent integration of the table motion); a run past
// the motion's end is an error unless pad_after_end asks for it; window.end past the record, a low-pass
// corner above Nyquist and the synthetic motion's ignored keys are errors; "cg" with any law is kept as
// asked. Every record is written here (no ../shared).
#include <catch2/catch.hpp>

#include <furniture_fem/scene/scene_runner.hpp>

#include "../support/scene_input.hpp"

#include "../support/block_scene.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

using namespace furniture_fem;
using nlohmann::json;
using Catch::Matchers::Contains;

namespace record_checks_tests {  // this file's own names (its group compiles files in batches)

namespace {

constexpr double g0 = 9.80665;

std::string scratch(const std::string& name) {
  const auto dir = std::filesystem::path(FFEM_TEST_TMP) / "record_checks" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

// A decaying two-tone "record" of n samples dt apart, peak near `amplitude` (any unit).
std::vector<double> samples(double amplitude, int n, double dt, double phase = 0.0) {
  std::vector<double> a(n);
  for (int i = 0; i < n; ++i) {
    const double t = i * dt;
    a[i] = amplitude * std::exp(-0.3 * t) *
           (std::sin(2 * std::numbers::pi * 1.3 * t + phase) + 0.4 * std::sin(2 * std::numbers::pi * 3.1 * t));
  }
  return a;
}

// "time value" lines in whatever unit the numbers are meant.
std::string write_record(const std::string& path, const std::vector<double>& a, double dt) {
  std::ofstream out(path);
  char buf[64];
  for (std::size_t i = 0; i < a.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.17g %.17g\n", dt * double(i), a[i]);
    out << buf;
  }
  return path;
}

std::string write_at2(const std::string& path, const std::vector<double>& a, double dt) {
  std::ofstream out(path);
  out << "PEER NGA STRONG MOTION DATABASE RECORD\ntest record, written by the test\n"
         "ACCELERATION TIME SERIES IN UNITS OF G\n";
  char buf[64];
  std::snprintf(buf, sizeof buf, "NPTS=%6zu, DT= %.4f SEC\n", a.size(), dt);
  out << buf;
  for (std::size_t i = 0; i < a.size(); ++i) {
    std::snprintf(buf, sizeof buf, " %15.7E", a[i]);
    out << buf << ((i % 5 == 4 || i + 1 == a.size()) ? "\n" : "");
  }
  return path;
}

using ffem_test::block_scene;

SceneSpec scene_in(const std::string& dir, const json& motion, double duration = 1.0) {
  SceneSpec s = parse_scene_json(block_scene(motion, duration), dir + "/scene.json");
  s.base_dir = dir;
  return s;
}

std::string motion_error(const SceneSpec& s) {
  try {
    validate(s);
    (void)scene_table_motion(s);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::string read_error(const json& j) { return ffem_test::scene_error(j, "scene.json"); }

RunOptions quiet() {
  RunOptions o;
  o.write_files = false;
  o.progress = false;
  return o;
}

}  // namespace

TEST_CASE("a record in gal read as g is an error naming the likely unit and the key to set", "[scene][records]") {
  const std::string dir = scratch("units");
  const double dt = 0.01;
  const auto gal = samples(300.0, 1001, dt);  // about 300 gal: a strong record
  double peak = 0;
  for (double a : gal) peak = std::max(peak, std::abs(a));
  write_record(dir + "/gal.txt", gal, dt);
  const json motion = {{"source", "file"}, {"format", "columns"}, {"units", "g"}, {"lowpass_hz", 0},
                       {"files", {{"x", "gal.txt"}}}};

  SECTION("declared g: the message names the peak, the unit and \"units\": \"gal\"") {
    const std::string e = motion_error(scene_in(dir, motion));
    INFO(e);
    char text[32];
    std::snprintf(text, sizeof text, "peaks at %g g", peak);
    CHECK_THAT(e, Contains("scene.json: ground_motion.units:") && Contains(text) && Contains("\"units\": \"g\"") &&
                      Contains("outside the plausible band [0.0005, 5] g") &&
                      Contains("probably in gal (cm/s^2), read as g") && Contains("set \"units\": \"gal\"") &&
                      Contains("\"check_pga\": false"));
  }
  SECTION("the same numbers as gal run, with the peak in m/s^2") {
    json m = motion;
    m["units"] = "gal";
    const TableMotion t = scene_table_motion(scene_in(dir, m));
    CHECK(t.x.peak() == Approx(0.01 * peak).epsilon(1e-12));
  }
  SECTION("check_pga: false runs the record as given (the key changes the result)") {
    json m = motion;
    m["check_pga"] = false;
    const SceneSpec s = scene_in(dir, m);
    CHECK_FALSE(s.ground_motion.check_pga);
    const TableMotion t = scene_table_motion(s);
    CHECK(t.x.peak() == Approx(g0 * peak).epsilon(1e-12));
    CHECK(to_json(s)["ground_motion"]["check_pga"] == false);
  }
  SECTION("a record in g read as gal (the columns default): probably g") {
    write_record(dir + "/g.txt", samples(0.3, 1001, dt), dt);
    const std::string e =
        motion_error(scene_in(dir, {{"source", "file"}, {"format", "columns"}, {"files", {{"x", "g.txt"}}}}));
    INFO(e);
    CHECK_THAT(e, Contains("ground_motion.units") && Contains("gal, the default of format \"columns\"") &&
                      Contains("probably in g, read as gal (cm/s^2)") && Contains("set \"units\": \"g\""));
  }
  SECTION("m/s^2 read as g: probably m/s^2") {
    write_record(dir + "/ms2.txt", samples(8.0, 1001, dt), dt);  // about 8 m/s^2
    json m = motion;
    m["files"]["x"] = "ms2.txt";
    const std::string e = motion_error(scene_in(dir, m));
    INFO(e);
    CHECK_THAT(e, Contains("probably in m/s^2, read as g") && Contains("set \"units\": \"m/s2\""));
  }
  SECTION("an AT2 file in gal: the file is named, its format states the unit") {
    write_at2(dir + "/gal.AT2", gal, dt);
    const std::string e =
        motion_error(scene_in(dir, {{"source", "file"}, {"format", "at2"}, {"files", {{"x", "gal.AT2"}}}}));
    INFO(e);
    CHECK_THAT(e, Contains("ground_motion.files.x:") && Contains("gal.AT2") && Contains("format \"at2\"") &&
                      Contains("probably in gal (cm/s^2), read as g"));
  }
  SECTION("a record of zeros") {
    write_record(dir + "/zero.txt", std::vector<double>(100, 0.0), dt);
    json m = motion;
    m["files"]["x"] = "zero.txt";
    CHECK_THAT(motion_error(scene_in(dir, m)), Contains("zero everywhere"));
  }
}

TEST_CASE("scale_to pga gives the target peak exactly, on the larger horizontal component", "[scene][records]") {
  const std::string dir = scratch("scale_pga");
  const double dt = 0.005;
  write_record(dir + "/x.txt", samples(2.0, 2001, dt), dt);        // m/s^2
  write_record(dir + "/y.txt", samples(4.0, 2001, dt, 0.7), dt);   // the larger horizontal peak
  write_record(dir + "/z.txt", samples(9.0, 2001, dt, 1.3), dt);   // vertical: larger still, not counted
  json motion = {{"source", "file"},   {"format", "columns"}, {"units", "m/s2"}, {"dimensions", "3d"},
                 {"lowpass_hz", 0},    {"files", {{"x", "x.txt"}, {"y", "y.txt"}, {"z", "z.txt"}}},
                 {"scale_to", {{"pga", 3.0}}}};
  const SceneSpec s = scene_in(dir, motion);
  REQUIRE(s.ground_motion.scale_to);
  double k = 0;
  const TableMotion t = scene_table_motion(s, &k);
  const double horizontal = std::max(t.x.peak(), t.y.peak());
  CHECK(std::abs(horizontal - 3.0) <= 1e-12 * 3.0);
  CHECK(std::abs(t.y.peak() - 3.0) <= 1e-12 * 3.0);  // y holds the larger peak
  const TableMotion raw = scene_table_motion(scene_in(dir, [&] { json m = motion; m.erase("scale_to"); return m; }()));
  CHECK(k == Approx(3.0 / raw.y.peak()).epsilon(1e-14));
  // every component by the same factor: the ratios stay
  CHECK(t.z.peak() / t.x.peak() == Approx(raw.z.peak() / raw.x.peak()).epsilon(1e-12));

  SECTION("level multiplies after the scaling") {
    motion["level"] = 0.5;
    const TableMotion half = scene_table_motion(scene_in(dir, motion));
    CHECK(std::abs(std::max(half.x.peak(), half.y.peak()) - 1.5) <= 1e-12 * 1.5);
  }
  SECTION("1-D: the x component's peak") {
    json m = motion;
    m["dimensions"] = "1d";
    m["files"] = {{"x", "x.txt"}};
    const TableMotion one = scene_table_motion(scene_in(dir, m));
    CHECK(std::abs(one.x.peak() - 3.0) <= 1e-12 * 3.0);
  }
  SECTION("the run reports the factor") {
    json m = motion;
    m["dimensions"] = "1d";
    m["files"] = {{"x", "x.txt"}};
    SceneSpec one = scene_in(dir, m);
    one.duration = 0.05;
    RunOptions o = quiet();
    o.write_files = true;
    o.out_dir = dir + "/out";
    const RunSummary sum = run_scene(one, o);
    CHECK(sum.status == "completed");
    std::ifstream in(dir + "/out/summary.json");
    const json written = json::parse(in);
    CHECK(written.at("ground_motion_scale_factor").get<double>() == sum.ground_motion_scale);
    CHECK(written.at("scene").at("ground_motion").at("scale_to") == json{{"pga", 3.0}});
    CHECK(sum.ground_motion_scale == Approx(3.0 / scene_table_motion(scene_in(dir, [&] {
                                                    json u = m;
                                                    u.erase("scale_to");
                                                    return u;
                                                  }())).x.peak()).epsilon(1e-14));
  }
}

TEST_CASE("scale_to pgv matches an independent integration of the table motion", "[scene][records]") {
  const std::string dir = scratch("scale_pgv");
  const double dt = 0.01;
  const auto a = samples(150.0, 1501, dt);  // gal
  write_record(dir + "/x.txt", a, dt);
  const json motion = {{"source", "file"}, {"format", "columns"}, {"units", "gal"}, {"lowpass_hz", 0},
                       {"files", {{"x", "x.txt"}}}, {"scale_to", {{"pgv", 0.5}}}};
  const TableMotion t = scene_table_motion(scene_in(dir, motion));
  // The table's velocity from rest by the trapezoid rule on a grid ten times finer than the record's,
  // reading the motion as the simulation does (TableMotion::at). The acceleration is linear between
  // samples, so the fine trapezoid is exact at its points; between two samples the exact velocity lies
  // above the chord of the samples' velocities by at most |a[i+1] - a[i]| dt / 8. The scaled record's
  // peak over the samples is the target, so the fine peak lies in [target, target + max|da| dt / 8].
  const int sub = 10;
  double v = 0, peak = 0, prev = t.at(0.0).x();
  for (int j = 1; j <= sub * (int(a.size()) - 1); ++j) {
    const double now = t.at(j * dt / sub).x();
    v += 0.5 * (dt / sub) * (prev + now);
    prev = now;
    peak = std::max(peak, std::abs(v));
  }
  double max_da = 0;
  for (std::size_t i = 1; i < t.x.acc.size(); ++i) max_da = std::max(max_da, std::abs(t.x.acc[i] - t.x.acc[i - 1]));
  const double bound = max_da * dt / 8;
  INFO("fine-grid peak velocity " << peak << " m/s, target 0.5, bound " << bound);
  CHECK(peak >= 0.5 * (1 - 1e-12));
  CHECK(peak <= 0.5 + bound + 1e-12);
  CHECK(bound < 0.01 * 0.5);  // the record is smooth enough that the check means something
}

TEST_CASE("scale_to jma: the motion the run gets has the target JMA intensity, all its components counted", "[scene][records]") {
  const std::string dir = scratch("scale_jma");
  const double dt = 0.01;
  write_record(dir + "/x.txt", samples(2.0, 2001, dt), dt);
  write_record(dir + "/y.txt", samples(3.0, 2001, dt, 0.7), dt);
  write_record(dir + "/z.txt", samples(1.5, 2001, dt, 1.3), dt);
  json motion = {{"source", "file"}, {"format", "columns"}, {"units", "m/s2"}, {"dimensions", "3d"}, {"lowpass_hz", 0},
                 {"files", {{"x", "x.txt"}, {"y", "y.txt"}, {"z", "z.txt"}}}, {"scale_to", {{"jma", 6.2}}}};
  double k = 0;
  const TableMotion t = scene_table_motion(scene_in(dir, motion), &k);
  // Measured again on the table's components by the excitation module: the target, to rounding.
  CHECK(jma_intensity({t.x, t.y, t.z}).intensity == Approx(6.2).margin(1e-10));
  // The vertical counts: measured on the horizontals alone the factor would be larger.
  const TableMotion raw = scene_table_motion(scene_in(dir, [&] { json m = motion; m.erase("scale_to"); return m; }()));
  CHECK(k == Approx(std::pow(10.0, 0.5 * (6.2 - jma_intensity({raw.x, raw.y, raw.z}).intensity))).epsilon(1e-12));
  CHECK(k < std::pow(10.0, 0.5 * (6.2 - jma_intensity({raw.x, raw.y}).intensity)) * (1 - 1e-3));
  SECTION("level multiplies after: half the motion is 2 log10 2 lower") {
    motion["level"] = 0.5;
    const TableMotion half = scene_table_motion(scene_in(dir, motion));
    CHECK(jma_intensity({half.x, half.y, half.z}).intensity == Approx(6.2 - 2 * std::log10(2.0)).margin(1e-10));
  }
  SECTION("1-D: the x component alone") {
    motion["dimensions"] = "1d";
    motion["files"] = {{"x", "x.txt"}};
    const TableMotion one = scene_table_motion(scene_in(dir, motion));
    CHECK(jma_intensity({one.x}).intensity == Approx(6.2).margin(1e-10));
  }
}

TEST_CASE("scale_to is read strictly, named by its key path, and round-trips", "[scene][records]") {
  json j = block_scene({{"source", "file"}, {"format", "at2"}, {"files", {{"x", "r.AT2"}}}, {"scale_to", {{"pgv", 0.5}}}});
  const SceneSpec s = parse_scene_json(j, "scene.json");
  REQUIRE(s.ground_motion.scale_to);
  CHECK(s.ground_motion.scale_to->measure == ScaleMeasure::pgv);
  CHECK(s.ground_motion.scale_to->value == 0.5);
  CHECK(to_json(s)["ground_motion"]["scale_to"] == json{{"pgv", 0.5}});
  CHECK(to_json(parse_scene_json(to_json(s), "again.json")) == to_json(s));

  const auto error_with = [&](const json& target) {
    json k = j;
    k["ground_motion"]["scale_to"] = target;
    try {
      (void)parse_scene_json(k, "scene.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(error_with({{"pga", -1.0}}), Contains("scene.json: ground_motion.scale_to.pga: must be positive (got -1.0)"));
  CHECK_THAT(error_with({{"pgv", 0.0}}), Contains("ground_motion.scale_to.pgv: must be positive"));
  CHECK_THAT(error_with({{"pga", 3.0}, {"pgv", 0.5}}), Contains("ground_motion.scale_to: give exactly one of"));
  CHECK_THAT(error_with(json::object()), Contains("ground_motion.scale_to: give exactly one of"));
  CHECK_THAT(error_with({{"pgd", 0.1}}), Contains("ground_motion.scale_to.pgd: unknown scale target"));
  CHECK_THAT(error_with({{"jma", -6.0}}), Contains("ground_motion.scale_to.jma: must be positive (got -6"));
  CHECK_THAT(error_with({{"jma", 6.0}, {"pga", 3.0}}), Contains("ground_motion.scale_to: give exactly one of"));
  {
    json k = j;
    k["ground_motion"]["scale_to"] = {{"jma", 6.2}};
    const SceneSpec jm = parse_scene_json(k, "scene.json");
    CHECK(jm.ground_motion.scale_to->measure == ScaleMeasure::jma);
    CHECK(to_json(jm)["ground_motion"]["scale_to"] == json{{"jma", 6.2}});
  }
  CHECK_THAT(error_with({{"pga", "3 m/s2"}}), Contains("ground_motion.scale_to.pga: expected a number"));
  CHECK_THAT(error_with(3.0), Contains("ground_motion.scale_to"));
  CHECK_THAT(read_error(block_scene({{"source", "synthetic"}, {"scale_to", {{"pga", 3.0}}}})),
             Contains("ground_motion.scale_to: only used with source \"file\""));

  SECTION("a SceneSpec made in code: NaN and negative targets, other sources") {
    SceneSpec c = s;
    c.ground_motion.file_x = "";
    c.ground_motion.source = MotionSource::synthetic;
    c.ground_motion.scale_to = ScaleTarget{ScaleMeasure::pga, 3.0};
    CHECK_THROWS_WITH(validate(c), Contains("ground_motion.scale_to: only used with source \"file\""));
    c.ground_motion.source = MotionSource::points;
    c.ground_motion.points_x = {{0.0, 1.0}};
    CHECK_THROWS_WITH(validate(c), Contains("ground_motion.scale_to: only used with source \"file\""));
    c.ground_motion.source = MotionSource::file;
    c.ground_motion.file_x = "/no/such/record.txt";
    for (double bad : {std::numeric_limits<double>::quiet_NaN(), -2.0, 0.0}) {
      c.ground_motion.scale_to = ScaleTarget{ScaleMeasure::pgv, bad};
      CHECK_THROWS_WITH(validate(c), Contains("ground_motion.scale_to.pgv: must be a positive finite velocity in m/s"));
    }
  }
}

TEST_CASE("a run past the motion's end is an error unless pad_after_end asks for it", "[scene][records]") {
  const std::string dir = scratch("window");
  const double dt = 0.01;
  write_record(dir + "/short.txt", samples(1.0, 201, dt), dt);  // m/s^2, 2 s
  const json motion = {{"source", "file"}, {"format", "columns"}, {"units", "m/s2"}, {"files", {{"x", "short.txt"}}}};

  SECTION("the scene's duration") {
    const SceneSpec s = scene_in(dir, motion, 3.0);
    try {
      (void)run_scene(s, quiet());
      FAIL("no error for a run past the record");
    } catch (const InputError& e) {
      INFO(e.what());
      CHECK_THAT(std::string(e.what()), Contains("scene.json: duration: the run lasts 3 s but the record ends 2 s") &&
                                            Contains("ground_motion.window") && Contains("pad_after_end"));
    }
  }
  SECTION("the run option, named as the program names it") {
    const SceneSpec s = scene_in(dir, motion, 1.0);
    RunOptions o = quiet();
    o.duration = 2.5;
    o.duration_source = "command line";
    o.duration_key = "--duration";
    CHECK_THROWS_WITH(run_scene(s, o), Contains("command line: --duration: the run lasts 2.5 s but the record ends 2 s"));
    o.duration = 2.0;  // exactly the record: runs
    CHECK(run_scene(s, o).status == "completed");
  }
  SECTION("the window: the run starts at window.start") {
    json m = motion;
    m["window"] = {{"start", 0.5}};
    CHECK_THROWS_WITH(run_scene(scene_in(dir, m, 1.6), quiet()),
                      Contains("the record ends 1.5 s after the run's start (ground_motion.window from 0.5 s"));
  }
  SECTION("pad_after_end: true runs on with the table at rest (the key changes the result)") {
    json m = motion;
    m["pad_after_end"] = true;
    const SceneSpec s = scene_in(dir, m, 3.0);
    CHECK(s.ground_motion.pad_after_end);
    const RunSummary sum = run_scene(s, quiet());
    CHECK(sum.status == "completed");
    CHECK(sum.t_end == Approx(3.0));
    const TableMotion t = scene_table_motion(s);
    CHECK(t.at(2.5).norm() == 0.0);
    CHECK(to_json(s)["ground_motion"]["pad_after_end"] == true);
  }
  SECTION("window.end past the record's end") {
    json m = motion;
    m["window"] = {{"start", 0.0}, {"end", 5.0}};
    CHECK_THAT(motion_error(scene_in(dir, m)),
               Contains("ground_motion.window.end: 5 s is past the end of record 'short'") &&
                   Contains("spans [0, 2] s") && Contains("pad_after_end"));
    m["pad_after_end"] = true;
    CHECK(scene_table_motion(scene_in(dir, m)).x.t_end() == Approx(2.0));
  }
  SECTION("the synthetic motion lasts its duration, and a run past it is an error") {
    const json synthetic = {{"source", "synthetic"}, {"duration", 4.0}};
    const SceneSpec s = scene_in(dir, synthetic, 5.0);
    CHECK(scene_table_motion(s).x.t_end() == Approx(4.0));  // was 10 s whatever the key said
    CHECK_THROWS_WITH(run_scene(s, quiet()), Contains("duration: the run lasts 5 s but the synthetic motion lasts 4 s "
                                                      "(ground_motion.duration)"));
  }
}

TEST_CASE("substitutions that were silent are errors", "[scene][records]") {
  SECTION("solver cg with a law other than the paper's") {
    // Was replaced by "direct" silently (issue 12), then refused (CG was built for two laws); now every law
    // runs with either solver (issue 48): the scene keeps what it asked for.
    json j = block_scene({{"source", "synthetic"}});
    j["solver"] = "cg";
    j["contact"] = {{"law", "spring_dashpot"}};
    CHECK(read_error(j) == "no error");
    CHECK(parse_scene_json(j, "scene.json").solver == SolverKind::cg);
  }
  SECTION("a low-pass corner at or above the record's Nyquist frequency") {
    const std::string dir = scratch("nyquist");
    write_record(dir + "/r.txt", samples(1.0, 201, 0.02), 0.02);  // Nyquist 25 Hz
    const json m = {{"source", "file"}, {"format", "columns"}, {"units", "m/s2"}, {"lowpass_hz", 30.0},
                    {"files", {{"x", "r.txt"}}}};
    CHECK_THAT(motion_error(scene_in(dir, m)),
               Contains("ground_motion.lowpass_hz: 30 Hz is not below the Nyquist frequency 25 Hz"));
  }
  SECTION("low-pass and window keys with a synthetic motion") {
    CHECK_THAT(read_error(block_scene({{"source", "synthetic"}, {"lowpass_hz", 5.0}})),
               Contains("ground_motion.lowpass_hz: not applied to a synthetic motion"));
    CHECK_THAT(read_error(block_scene({{"source", "synthetic"}, {"window", {{"start", 1.0}}}})),
               Contains("ground_motion.window: not applied to a synthetic motion"));
    SceneSpec s = parse_scene_json(block_scene({{"source", "synthetic"}}), "scene.json");
    s.ground_motion.lowpass_hz = 5;
    CHECK_THROWS_WITH(validate(s), Contains("ground_motion.lowpass_hz: not applied to a synthetic motion"));
  }
}

}  // namespace record_checks_tests
