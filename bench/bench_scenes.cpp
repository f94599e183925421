// Per-step cost of the paper's configurations 1, 2 and 3 (built-in synthetic 3-D motion, dt = 1 ms),
// and of 2, 4, 8 and 16 copies of configuration 3 side by side (scaling; separate scenes are its
// control), with the time split into contact (nodes against floor and walls, broad phase, narrow
// phase with the law), the sweep over the bodies (wall), and inside it the thread time of element
// forces and of the solves (incl. assembly and factorisations). Counters: ms per step.
//   ./build/bench/bench_scenes --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// Every measurement is 200 steps (two refreshes of the factorisations at the default interval).
// The end-to-end figure (configuration 3, 10 s of 3-D input, every item at full ASI-Gauss fidelity)
// is the main job itself: /usr/bin/time -v ./build/examples/furniture_quake --no-figures (see docs/performance.md).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <sys/resource.h>

#include <furniture_fem/scene/scene_runner.hpp>

namespace {
using namespace furniture_fem;

SceneSpec synthetic(SceneSpec s) {
  s.ground_motion = GroundMotionSpec{};
  s.ground_motion.source = MotionSource::synthetic;
  s.ground_motion.pga = 8.0;
  s.ground_motion.dimensions = MotionDimensions::three_d;
  s.outputs = OutputSpec{};
  return s;
}

// Configuration 3 copied `copies` times along Y on a table made long enough for them.
SceneSpec copies_of_configuration3(int copies) {
  SceneSpec base = synthetic(configuration(3));
  SceneSpec s = base;
  s.items.clear();
  s.table.size_y = 4.0 * copies;
  s.walls = default_walls(s.table);
  for (int c = 0; c < copies; ++c)
    for (auto it : base.items) {
      it.name += "_" + std::to_string(c);
      it.y += 4.0 * (c - 0.5 * (copies - 1));
      s.items.push_back(it);
    }
  return s;
}

// refresh 0: the scene's default (every 0.1 s); threads 0: all hardware threads.
void run_steps(benchmark::State& state, const SceneSpec& spec, int refresh, int threads = 0) {
  SceneSimulation<DirectLdltSolver> scene(spec, refresh, threads);
  auto& sim = *scene.sim;
  for (int i = 0; i < 20; ++i) sim.step();  // settle, first factorisations
  const StepTimings t0 = sim.timings();
  const auto c0 = sim.contact_model().timings();
  const long s0 = sim.steps();
  const long b0 = sim.contact_model().broad_phase_runs();
  long steps_with_shift = 0;
  for (auto _ : state) steps_with_shift += sim.step().shifted_points > 0;
  const StepTimings t = sim.timings();
  const auto c = sim.contact_model().timings();
  const double n = double(sim.steps() - s0);
  state.counters["elements"] = scene.model->num_elements();
  state.counters["ms_elements"] = 1e3 * (t.elements - t0.elements) / n;
  state.counters["ms_contact"] = 1e3 * (t.contact - t0.contact) / n;
  // The contact's parts: nodes against floor and walls, broad phase, narrow phase with the law.
  state.counters["ms_planes"] = 1e3 * (c.planes - c0.planes) / n;
  state.counters["ms_broad"] = 1e3 * (c.broad - c0.broad) / n;
  state.counters["ms_narrow_law"] = 1e3 * (c.pairs - c0.pairs) / n;
  state.counters["ms_solve"] = 1e3 * (t.solve - t0.solve) / n;
  state.counters["ms_factorize"] = 1e3 * (t.factorize - t0.factorize) / n;
  state.counters["ms_bodies"] = 1e3 * (t.bodies - t0.bodies) / n;
  state.counters["ms_other"] = 1e3 * (t.other() - t0.other()) / n;
  // How often a step moved an integration point, and how often the broad phase re-ran: both are
  // events anywhere in the scene, so their frequency grows with the scene's size.
  state.counters["shift_step_fraction"] = steps_with_shift / n;
  state.counters["broad_runs_per_step"] = (sim.contact_model().broad_phase_runs() - b0) / n;
}

void BM_Configuration(benchmark::State& state) {
  run_steps(state, synthetic(configuration(static_cast<int>(state.range(0)))), static_cast<int>(state.range(1)));
}
BENCHMARK(BM_Configuration)
    ->ArgNames({"config", "refresh"})
    ->Args({1, 100})->Args({2, 100})->Args({3, 100})->Args({3, 1})->Args({3, 20})
    ->Iterations(200)  // two refreshes at the default interval in every measurement
    ->Unit(benchmark::kMillisecond);

// Scaling, on all hardware threads and on one (threads 1 separates the algorithm's growth from
// the threads' sharing of caches and memory bandwidth).
// The whole run loop (runner.hpp: the same loop as furniture_quake and the ensembles) on configuration
// 3 for 0.2 s with no files written: what the observers of the summary (final states, peaks, energy
// checks at every row) cost on top of the stepping of BM_Configuration. Counter: ms per step.
void BM_RunLoop(benchmark::State& state) {
  SceneSpec spec = synthetic(configuration(3));
  RunOptions opt;
  opt.write_files = false;
  opt.progress = false;
  opt.duration = 0.2;
  long steps = 0;
  double seconds = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    steps += run_scene(spec, opt).steps;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  state.counters["ms_per_step"] = 1e3 * seconds / double(steps);
}
BENCHMARK(BM_RunLoop)->Iterations(3)->Unit(benchmark::kMillisecond);

void BM_ConfigurationCopies(benchmark::State& state) {
  run_steps(state, copies_of_configuration3(static_cast<int>(state.range(0))), 0, static_cast<int>(state.range(1)));
}
BENCHMARK(BM_ConfigurationCopies)
    ->ArgNames({"copies", "threads"})
    ->Args({1, 0})->Args({2, 0})->Args({4, 0})->Args({8, 0})->Args({16, 0})->Args({1, 1})->Args({8, 1})
    ->Iterations(200)
    ->Unit(benchmark::kMillisecond);

// The control for the scaling: `scenes` separate one-copy scenes, stepped in turn. Together they do
// the work of that many copies in one scene and hold as much memory, but nothing in any of them sees
// the others. If they cost what the copies cost, whatever the copies cost beyond `copies` times one
// copy comes from the memory the scene occupies (one copy's data stays in the caches from step to
// step, eight copies' data does not), not from the algorithm.
void BM_SeparateScenes(benchmark::State& state) {
  using Scene = SceneSimulation<DirectLdltSolver>;
  const int threads = static_cast<int>(state.range(1));
  std::vector<std::unique_ptr<Scene>> scenes;
  for (int k = 0; k < state.range(0); ++k) scenes.push_back(std::make_unique<Scene>(copies_of_configuration3(1), 0, threads));
  for (auto& scene : scenes)
    for (int i = 0; i < 20; ++i) scene->sim->step();
  for (auto _ : state)
    for (auto& scene : scenes) scene->sim->step();
  state.counters["elements"] = static_cast<double>(scenes.size() * scenes.front()->model->num_elements());
}
BENCHMARK(BM_SeparateScenes)
    ->ArgNames({"scenes", "threads"})
    ->Args({1, 0})->Args({8, 0})->Args({8, 1})
    ->Iterations(200)
    ->Unit(benchmark::kMillisecond);

// Restraints (issue 49): configuration 3 with every item rigid under the synthetic motion, free (0),
// with ten straps slack enough never to pull (1: what evaluating ten restraints costs, the motion the
// free room's to the bit), and with ten working devices (2: examples/scenes/configuration3_fastened.json's
// brackets, straps and mats; the motion is another). Target (issue 49): 1 within 5 % of 0.
SceneSpec restrained_configuration3(int variant) {
  SceneSpec s = synthetic(configuration(3));
  for (auto& it : s.items) it.fidelity = Fidelity::rigid;
  s.outputs = OutputSpec{};
  const auto add = [&](RestraintKind kind, const std::string& item, const std::string& point, double slack = 0) {
    RestraintSpec r;
    r.name = item + "_" + point + "_" + std::to_string(s.restraints.size());
    for (char& ch : r.name)
      if (ch == '/') ch = '_';
    r.kind = kind;
    r.item = item;
    r.point = point;
    if (kind != RestraintKind::mat) r.wall = "wall_plus_x";
    if (slack > 0) r.values["slack"] = slack;
    s.restraints.push_back(r);
  };
  if (variant == 1) {
    for (const char* item : {"tall_cabinet", "separated_cabinets/upper"})
      for (const char* p : {"top_back_left", "top_back_right", "top_back_centre"}) add(RestraintKind::strap, item, p, 0.5);
    for (const char* p : {"top_front_left", "top_front_right", "top_left_centre", "top_right_centre"})
      add(RestraintKind::strap, "tall_cabinet", p, 0.5);
  }
  if (variant == 2) {
    for (const char* p : {"top_back_left", "top_back_right"}) add(RestraintKind::l_bracket, "tall_cabinet", p);
    for (const char* p : {"top_back_left", "top_back_right"}) add(RestraintKind::strap, "separated_cabinets/upper", p, 0.01);
    for (const char* item : {"tall_cabinet", "separated_cabinets/lower"})
      for (const char* p : {"bottom_front_left", "bottom_front_right"}) add(RestraintKind::mat, item, p);
    for (const char* p : {"bottom_back_left", "bottom_back_right"}) add(RestraintKind::mat, "desk", p);
  }
  return s;
}
void BM_Restraints(benchmark::State& state) { run_steps(state, restrained_configuration3(static_cast<int>(state.range(0))), 0); }
BENCHMARK(BM_Restraints)->ArgName("variant")->Arg(0)->Arg(1)->Arg(2)->Iterations(2000)->Unit(benchmark::kMillisecond);

// Setting up a room of n rigid items (blocks of 50 kg on a 1 m grid, rigid pairs by their hulls): the
// scene's checks (validate) and the simulation's construction (model, contact, hulls, hull pairs), what
// a run does before its first step. Counters: ms per item, flat when the set-up is linear in the items
// (issue 51, item 4), and the process's peak resident memory so far (getrusage; the sizes run in
// increasing order, so each row's figure is its own set-up's peak or close to it):
//   ./build/bench/bench_scenes --benchmark_filter=RoomSetup
SceneSpec room_of_blocks(int n) {
  SceneSpec s = synthetic(configuration(3));
  const int side = static_cast<int>(std::ceil(std::sqrt(double(n))));
  s.items.clear();
  s.obstacles.clear();
  s.table.size_x = s.table.size_y = side + 2.0;
  s.walls = default_walls(s.table);
  s.contact.rigid_pairs = RigidPairContact::hulls;
  for (int k = 0; k < n; ++k) {
    ItemSpec it;
    it.kind = ItemKind::block;
    it.name = "block_" + std::to_string(k);
    it.fidelity = Fidelity::rigid;
    it.x = (k / side) - 0.5 * (side - 1);
    it.y = (k % side) - 0.5 * (side - 1);
    it.params.mass_kg = 50.0;
    s.items.push_back(it);
  }
  return s;
}

void BM_RoomSetup(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const SceneSpec spec = room_of_blocks(n);
  double seconds = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    validate(spec);
    SceneSimulation<DirectLdltSolver> scene(spec);
    benchmark::DoNotOptimize(scene.sim.get());
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  state.counters["ms_per_item"] = 1e3 * seconds / (double(n) * double(state.iterations()));
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_MB"] = double(usage.ru_maxrss) / 1024.0;  // Linux: ru_maxrss in kB
}
BENCHMARK(BM_RoomSetup)->ArgName("items")->Arg(100)->Arg(316)->Arg(1000)->Arg(3162)->Arg(10000)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
