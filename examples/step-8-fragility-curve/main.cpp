// step-8: a fragility curve for one cabinet.
//
// What is new relative to step-7: not one run but a study (docs/study/studies.md). The tall cabinet
// stands alone on the table; a study shakes it with three seeded synthetic 3-D motions at six peak
// ground accelerations, six times each with its placement, yaw and friction perturbed, and fits
// P(overturned | PGA) as a lognormal CDF by maximum likelihood, with bootstrap intervals. The study is
// given as JSON text (the same as a study file); every realisation's values follow from the seed and
// its index, so the numbers below are the same on every machine and with any number of workers.
#include <furniture_fem/study/runner.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

using namespace furniture_fem;

namespace {

const char* study_json = R"({
  "name": "step-8",
  "seed": 8,
  "scene": {
    "name": "tall cabinet alone",
    "items": [{"kind": "tall_cabinet", "name": "cabinet", "fidelity": "rigid", "x": 0.0, "y": 0.0}],
    "ground_motion": {"source": "synthetic", "duration": 5.0, "dimensions": "3d"},
    "duration": 5.0,
    "outputs": {"figures": false}
  },
  "intensity": {"measure": "pga", "levels": [2.0, 4.0, 6.0, 8.0, 10.0, 12.0]},
  "ground_motions": [
    {"name": "synthetic_1", "ground_motion": {"source": "synthetic", "seed": 1, "duration": 5.0, "dimensions": "3d"}},
    {"name": "synthetic_2", "ground_motion": {"source": "synthetic", "seed": 2, "duration": 5.0, "dimensions": "3d"}},
    {"name": "synthetic_3", "ground_motion": {"source": "synthetic", "seed": 3, "duration": 5.0, "dimensions": "3d"}}
  ],
  "perturbations": {"x": 0.01, "y": 0.01, "yaw_deg": 1.0, "friction": 0.1},
  "realisations": 6
})";

}  // namespace

int main() {
  const StudySpec study = parse_study_json(nlohmann::json::parse(study_json), "step-8 study");
  StudyOptions opt;
  opt.out_dir = "step-8-results";
  opt.overwrite = true;  // a second run of this program replaces the first one's results
  std::printf("%ld runs: %d levels x %d motions x %d realisations\n", study.num_runs(), study.num_levels(),
              study.num_motions(), study.realisations);

  // What run_study does, in its three parts: the folder, the runs on one worker per core, the outputs.
  const auto start = std::chrono::steady_clock::now();
  StudyFolder folder(study, opt);
  StudyTiming timing;
  timing.workers = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  run_local(folder, folder.pending(), timing.workers, nullptr, opt.progress);
  timing.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  folder.finish("completed", timing);

  // The statistics, from the results in memory (the same numbers as the CSV files).
  const StudyReport report = study_report(study, folder.results());
  std::printf("\nP(overturned | PGA), observed (Wilson 95 %% interval):\n");
  for (const auto& p : report.probabilities)
    if (p.body == "cabinet" && p.state == std::string("overturned"))
      std::printf("  PGA %4.1f m/s^2: %2ld of %2ld  %.2f  [%.2f, %.2f]\n", p.level, p.estimate.successes,
                  p.estimate.trials, p.estimate.p, p.estimate.lo, p.estimate.hi);
  for (const auto& f : report.fragility)
    if (f.body == "cabinet" && f.state == std::string("overturned")) {
      if (!f.fit.identifiable) {
        std::printf("no fragility fit: %s\n", f.fit.message.c_str());
        continue;
      }
      std::printf("lognormal fit: median PGA %.2f m/s^2 [%.2f, %.2f], dispersion beta %.2f [%.2f, %.2f]\n",
                  f.fit.theta, f.interval.theta_lo, f.interval.theta_hi, f.fit.beta, f.interval.beta_lo,
                  f.interval.beta_hi);
      for (double pga : {4.0, 8.0, 12.0})
        std::printf("  fitted P(overturned | PGA = %.0f m/s^2) = %.2f\n", pga, fragility_probability(f.fit, pga));
    }
  std::printf("results in %s (realisations.csv, probabilities.csv, fragility.csv, ...)\n", folder.dir().c_str());
}
