// furniture_quake: the main job. Runs a scene file (or, without arguments, the paper's
// configuration 3 under the built-in synthetic 3-D motion for 10 s) and writes a results folder:
// marker, contact-force, sectional-force and energy histories (CSV), the final state of every item
// and a run summary (JSON), a VTU/PVD time series for ParaView, and PNG figures.
//
//   furniture_quake [scene.json] [--out DIR] [--duration S] [--output-interval S] [--no-figures]
//                   [--quiet] [--config K] [--records DIR]
//
// Ctrl-C stops the run cleanly: everything written so far stays readable, the summary says where it
// stopped, and the exit code is 130. Exit codes: 0 completed, 1 bad input, 3 diverged, 130 stopped.
#include <furniture_fem/scene/scene_runner.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <string>

namespace {
std::atomic<bool> g_stop{false};
void on_interrupt(int) { g_stop = true; }

// --help: the usage on stdout, exit 0 (a bad command line is an error on stderr, exit 1).
int print_help() {
  std::cout << "usage: furniture_quake [scene.json] [--out DIR] [--duration S] [--output-interval S] [--no-figures]\n"
               "                       [--quiet] [--config K] [--records DIR]\n"
               "  without a scene: configuration 3 under the built-in synthetic 3-D motion, 10 s\n"
               "  --output-interval S: history rows every S seconds of simulated time (default 0.01)\n"
               "  --config K: the paper's configuration K (1, 2, 3) with the JMA-Kobe records in\n"
               "              --records DIR (default ../shared/ground_motions)\n";
  return 0;
}
}  // namespace

int main(int argc, char** argv) {
  using namespace furniture_fem;
  std::string scene_path, out_dir, records = "../shared/ground_motions";
  std::optional<double> duration;
  std::optional<int> config;
  RunOptions opt;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto next = [&]() -> std::string {
        if (i + 1 >= argc) throw InputError("command line", 0, a, "needs a value");
        return argv[++i];
      };
      // A number with nothing after it ("0.05xyz" and "nan" are refused), named in the error.
      auto number = [&]() {
        const std::string w = next();
        double x = 0;
        if (!text::parse_finite(w, x)) throw InputError("command line", 0, a, "not a finite number: '" + w + "'");
        return x;
      };
      if (a == "--out") out_dir = next();
      else if (a == "--duration") duration = number();
      else if (a == "--output-interval") opt.output_interval = number();
      else if (a == "--no-figures") opt.figures = false;
      else if (a == "--quiet") opt.progress = false;
      else if (a == "--config") {
        const std::string w = next();
        long k = 0;
        if (!text::parse_integer(w, k) || k < 1 || k > 3) throw InputError("command line", 0, a, "not 1, 2 or 3: '" + w + "'");
        config = static_cast<int>(k);
      }
      else if (a == "--records") records = next();
      else if (a == "-h" || a == "--help") return print_help();
      else if (!a.empty() && a[0] == '-') throw InputError("command line", 0, a, "unknown option");
      else scene_path = a;
    }
    SceneSpec spec;
    if (!scene_path.empty()) {
      spec = parse_scene(scene_path);
    } else if (config) {
      spec = configuration(*config, records);
    } else {
      // The built-in default: configuration 3 under the seeded synthetic 3-D motion.
      spec = configuration(3);
      spec.name = "configuration 3, synthetic 3-D motion";
      spec.ground_motion = GroundMotionSpec{};
      spec.ground_motion.source = MotionSource::synthetic;
      spec.ground_motion.pga = 8.0;
      spec.ground_motion.dimensions = MotionDimensions::three_d;
      spec.duration = 10.0;
      spec.outputs.folder = "results/default";
    }
    opt.out_dir = out_dir;
    opt.duration = duration;
    opt.stop = &g_stop;
    std::signal(SIGINT, on_interrupt);
    std::signal(SIGTERM, on_interrupt);
    std::cerr << "furniture_fem " << version_string << ": " << spec.name << "\n";
    const RunSummary s = run_scene(spec, opt);
    std::printf("%s: %s at t = %.3f s after %ld steps, %.1f s wall time (%d elements, %d nodes, %d bodies)\n",
                spec.name.c_str(), s.status.c_str(), s.t_end, s.steps, s.wall_seconds, s.elements, s.nodes, s.bodies);
    if (!s.diagnosis.empty()) std::printf("  %s\n", s.diagnosis.c_str());
    std::printf("  energy ledger imbalance: %.3g of its scale at the end (max %.3g)\n", s.energy_imbalance,
                s.max_energy_imbalance);
    for (const auto& it : s.items)
      std::printf("  %-28s %-16s slide %.3f m  tilt %5.1f deg (max %5.1f)%s%s\n", it.name.c_str(), it.state.c_str(),
                  it.slide, it.tilt_deg, it.max_tilt_deg, it.resting_on.empty() ? "" : "  on ",
                  it.resting_on.c_str());
    std::printf("  results in %s\n", s.out_dir.c_str());
    // A stopped run is not a complete one: scripts see 130 (the shell's code for Ctrl-C).
    if (s.status == "stopped") return 130;
    return s.status == "diverged" ? 3 : 0;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
