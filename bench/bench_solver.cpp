// Per-step cost of the solver core on furniture-sized bodies: element forces (corotational frames and
// element kernels) alone, and whole steps (forces, assembly, factorisation, solve) for each
// linear-solver policy, and whole steps with and without factorisation reuse (Args: bodies, refresh
// interval in steps).
// Run: ./build/bench/bench_solver --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <furniture_fem/core/simulation.hpp>

namespace {
using namespace furniture_fem;

// A room's worth of cabinet-like bodies: each a 0.9 m x 1.8 m grid of 50 x 30 mm tubes at 0.1 m
// spacing (about 700 elements per body), standing on fixed feet.
Model grid_bodies(int bodies) {
  Model m;
  const int s = m.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002));
  const int mat = m.add_material(Material::steel());
  for (int bi = 0; bi < bodies; ++bi) {
    const int b = m.add_body("body" + std::to_string(bi));
    const int nx = 9, nz = 18;
    std::vector<int> g((nx + 1) * (nz + 1));
    for (int i = 0; i <= nx; ++i)
      for (int k = 0; k <= nz; ++k) g[i * (nz + 1) + k] = m.add_node({bi * 1.0 + 0.1 * i, 0, 0.025 + 0.1 * k}, b);
    for (int i = 0; i <= nx; ++i)
      for (int k = 0; k <= nz; ++k) {
        if (i < nx) m.add_member("h", g[i * (nz + 1) + k], g[(i + 1) * (nz + 1) + k], s, mat);
        if (k < nz) m.add_member("v", g[i * (nz + 1) + k], g[i * (nz + 1) + k + 1], s, mat);
      }
    for (int i = 0; i <= nx; ++i) m.fix(g[i * (nz + 1)]);
  }
  return m;
}

template <class Solver>
void BM_Step(benchmark::State& state) {
  const Model m = grid_bodies(static_cast<int>(state.range(0)));
  SimulationOptions o;
  o.refresh_interval_steps = static_cast<int>(state.range(1));
  Simulation<AsiGaussTimoshenko, Newmark, Solver> sim(m, Newmark::paper(), o);
  sim.set_table_acceleration([](double t) { return Vec3(3 * std::sin(10 * t), 0, 0); });
  sim.step();
  for (auto _ : state) sim.step();
  state.counters["elements"] = m.num_elements();
}
BENCHMARK_TEMPLATE(BM_Step, DirectLdltSolver)->Args({6, 1})->Args({6, 50})->Args({12, 50})->Args({24, 50})->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Step, ConjugateGradientSolver)->Args({6, 1})->Args({6, 50})->Unit(benchmark::kMillisecond);

void BM_ElementForces(benchmark::State& state) {
  const Model m = grid_bodies(6);
  Simulation<AsiGaussTimoshenko> sim(m);
  for (auto _ : state) sim.update_internal_forces();
  state.counters["elements"] = m.num_elements();
}
BENCHMARK(BM_ElementForces)->Unit(benchmark::kMillisecond);

}  // namespace
