// Rigid fidelity against MuJoCo (issue 10, item 5): configuration 3 with every item rigid under the
// JMA-Kobe NS record, 5 to 15 s, 10 s at dt = 1 ms (examples/scenes/configuration3_rigid.json), and,
// when MuJoCo was found at configure time, the same six boxes in MuJoCo (the program of
// shared/anchors/mujoco_room, its model compiled in), side by side in one run. Each iteration steps
// both once through the 10 s; counters: seconds of each (stepping only, one thread) and their ratio.
// Two variants: the items meeting by their members' element pairs (the scene's contact.rigid_pairs,
// "members") and by their hulls ("hulls", docs/contact/contact.md, "Rigid pairs by their hulls").
//   ./build/bench/bench_rigid --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// The record is read through the scene file (../shared/ground_motions beside the repository); the
// benchmark is skipped with a message when it is absent. Final slides and tilts go to stderr.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <furniture_fem/scene/scene_runner.hpp>

#ifdef FFEM_HAVE_MUJOCO
#include <mujoco/mujoco.h>
#include <unistd.h>
#endif

namespace {
using namespace furniture_fem;
using clock_type = std::chrono::steady_clock;

const std::string scene_file = std::string(FFEM_SOURCE_DIR) + "/examples/scenes/configuration3_rigid.json";

double seconds_since(clock_type::time_point t0) {
  return std::chrono::duration<double>(clock_type::now() - t0).count();
}

struct RunResult {
  double seconds = 0;
  std::vector<std::string> final_states;  // "name slide m tilt deg"
};

std::string final_state_line(const std::string& name, double slide, double tilt) {
  char line[160];
  std::snprintf(line, sizeof line, "%-26s slide %.3f m  tilt %5.1f deg", name.c_str(), slide, tilt);
  return line;
}

// Ours: the scene's simulation stepped through its duration on one thread (outputs aside).
RunResult run_furniture_fem(const SceneSpec& spec) {
  SceneSimulation<DirectLdltSolver> scene(spec, 0, 1);
  auto& sim = *scene.sim;
  const auto t0 = clock_type::now();
  sim.run_until(spec.duration);
  RunResult r;
  r.seconds = seconds_since(t0);
  for (const auto& it : scene.items) {
    Vec3 shift;
    const Mat3 Q = detail::body_rotation_of(sim, *scene.model, it.body, &shift);
    r.final_states.push_back(final_state_line(it.name, std::hypot(shift.x(), shift.y()), detail::tilt_of(Q)));
  }
  return r;
}

#ifdef FFEM_HAVE_MUJOCO
// shared/anchors/mujoco_room/room.c: the six boxes (the paper's sizes, masses and floor friction, the
// upper cabinet on the lower one) on the 4 m table between two walls, in the table frame.
const char* const mujoco_room_xml =
    "<mujoco><option timestep='0.001' gravity='0 0 -9.80665' cone='elliptic'/><worldbody>"
    "<geom type='plane' size='2 2 0.1' friction='0 0.005 0.0001'/>"
    "<geom type='box' pos='-2.05 0 1.2' size='0.05 2 1.2' friction='0 0.005 0.0001'/>"
    "<geom type='box' pos='2.05 0 1.2' size='0.05 2 1.2' friction='0 0.005 0.0001'/>"
    "<body name='tall_cabinet' pos='-1.75 -1.2 0.925'><freejoint/><geom type='box' size='0.2 0.45 0.925' mass='43.6' friction='0.278'/></body>"
    "<body name='lower_cabinet' pos='-1.75 0.2 0.56'><freejoint/><geom type='box' size='0.2 0.45 0.56' mass='28.8' friction='0.23'/></body>"
    "<body name='upper_cabinet' pos='-1.75 0.2 1.486'><freejoint/><geom type='box' size='0.2 0.45 0.365' mass='21.3' friction='0.169'/></body>"
    "<body name='desk' pos='0.3 0 0.35'><freejoint/><geom type='box' size='0.35 0.6 0.35' mass='30.5' friction='0.377'/></body>"
    "<body name='side_table' pos='0.3 1.2 0.31'><freejoint/><geom type='box' size='0.17 0.275 0.308' mass='8.0' friction='0.094'/></body>"
    "<body name='office_chair' pos='1.2 0 0.405'><freejoint/><geom type='box' size='0.26 0.26 0.405' mass='6.2' friction='0.065'/></body>"
    "</worldbody></mujoco>";

// MuJoCo 2.2.2 reads models from files: the string goes through a temporary one.
mjModel* load_mujoco_room() {
  char path[] = "/tmp/ffem_mujoco_room_XXXXXX";
  const int fd = mkstemp(path);
  if (fd < 0) return nullptr;
  const std::string xml = mujoco_room_xml;
  const bool written = write(fd, xml.data(), xml.size()) == static_cast<ssize_t>(xml.size());
  close(fd);
  char error[1000] = "";
  mjModel* m = written ? mj_loadXML(path, nullptr, error, sizeof error) : nullptr;
  unlink(path);
  if (!m) std::fprintf(stderr, "MuJoCo room: %s\n", error);
  return m;
}

// The AT2 file as room.c reads it (samples in g after four header lines, DT on the fourth), so that the
// boxes get room.c's table acceleration to the last bit.
struct RawAt2 {
  double dt = 0;
  std::vector<double> g;
};
RawAt2 read_at2_as_room_c(const std::string& path) {
  RawAt2 r;
  std::ifstream in(path);
  std::string line;
  for (int i = 0; i < 4 && std::getline(in, line); ++i) {
    const auto at = line.find("DT");
    const auto eq = at == std::string::npos ? at : line.find('=', at);
    if (i == 3 && eq != std::string::npos) r.dt = std::atof(line.c_str() + eq + 1);
  }
  for (double a; in >> a;) r.g.push_back(a);
  return r;
}

// room.c's stepping: the record from window_start for duration, linear between samples.
RunResult run_mujoco(const RawAt2& record, double window_start, double duration) {
  RunResult r;
  mjModel* m = load_mujoco_room();
  if (!m) return r;
  mjData* d = mj_makeData(m);
  const auto t0 = clock_type::now();
  const int n = static_cast<int>(record.g.size());
  while (d->time < duration) {
    const double s = (window_start + d->time) / record.dt;
    const int i = static_cast<int>(s);
    const double w = s - i;
    const double table_acc = i + 1 < n ? (record.g[i] * (1 - w) + record.g[i + 1] * w) * 9.80665 : 0.0;
    m->opt.gravity[0] = -table_acc;
    mj_step(m, d);
  }
  r.seconds = seconds_since(t0);
  for (int k = 1; k < m->nbody; ++k) {  // slide in the plane, tilt from upright (room.c's measures)
    const double* q = d->qpos + 7 * (k - 1);
    const double* q0 = m->qpos0 + 7 * (k - 1);
    const double tilt = 2 * std::acos(std::fmin(1.0, std::sqrt(q[3] * q[3] + q[6] * q[6]))) * 180 / M_PI;
    r.final_states.push_back(final_state_line(mj_id2name(m, mjOBJ_BODY, k), std::hypot(q[0] - q0[0], q[1] - q0[1]), tilt));
  }
  mj_deleteData(d);
  mj_deleteModel(m);
  return r;
}
#endif

void print_final_states(const char* who, const RunResult& r) {
  std::fprintf(stderr, "%s: %.3f s\n", who, r.seconds);
  for (const auto& line : r.final_states) std::fprintf(stderr, "  %s\n", line.c_str());
}

void BM_RigidConfiguration3AgainstMuJoCo(benchmark::State& state) {
  SceneSpec spec = parse_scene(scene_file);
  spec.contact.rigid_pairs = state.range(0) ? RigidPairContact::hulls : RigidPairContact::members;
  const std::string record_path = spec.resolve(spec.ground_motion.file_x);
  if (!std::filesystem::exists(record_path)) {
    state.SkipWithError(("the JMA-Kobe NS record is not there: " + record_path).c_str());
    return;
  }
#ifdef FFEM_HAVE_MUJOCO
  const RawAt2 record = read_at2_as_room_c(record_path);
  if (!(record.dt > 0)) {
    state.SkipWithError(("no DT on the fourth line of " + record_path).c_str());
    return;
  }
#endif
  double ours_total = 0, mujoco_total = 0;
  static bool printed[2] = {false, false};  // the final states once per variant, not at every repetition
  for (auto _ : state) {
    const RunResult ours = run_furniture_fem(spec);
    ours_total += ours.seconds;
    state.SetIterationTime(ours.seconds);
#ifdef FFEM_HAVE_MUJOCO
    const RunResult mujoco = run_mujoco(record, spec.ground_motion.window_start, spec.duration);
    mujoco_total += mujoco.seconds;
#endif
    if (!printed[state.range(0)]) {
      print_final_states(state.range(0) ? "furniture_fem, every item rigid, pairs by hulls"
                                        : "furniture_fem, every item rigid, pairs by members",
                         ours);
#ifdef FFEM_HAVE_MUJOCO
      print_final_states("MuJoCo 2.2.2, six boxes", mujoco);
#endif
      printed[state.range(0)] = true;
    }
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["ffem_s"] = ours_total / n;
#ifdef FFEM_HAVE_MUJOCO
  state.counters["mujoco_s"] = mujoco_total / n;
  state.counters["ratio"] = mujoco_total > 0 ? ours_total / mujoco_total : 0.0;
#else
  state.SetLabel("MuJoCo not found at configure time: furniture_fem alone");
#endif
}
BENCHMARK(BM_RigidConfiguration3AgainstMuJoCo)
    ->ArgName("hulls")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kSecond)
    ->UseManualTime()
    ->Iterations(1);

}  // namespace
