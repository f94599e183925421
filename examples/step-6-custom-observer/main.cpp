// step-6: a custom output of a scene run, written as an observer.
//
// What is new relative to step-5: the scene runner (run_scene, the main job's engine) instead of a
// hand-written loop, and an output of our own. The runner steps the scene and calls a list of
// observers, each a small type with begin (the initial state), after_step (every step) and end (once,
// with the run's summary); its own outputs (CSV histories, VTU, JSON, figures) are observers too.
// Here one more observer records, for one item, its tilt and the largest vertical force the floor
// exerts on it since the previous history row (every 10 ms), to a CSV. It sees the run through a
// read-only RunView: the scene, its model and items, and the simulation (positions, section forces,
// contact forces, energy). The run writes no other file (RunOptions::write_files = false): the
// summary still holds every item's final state.
#include <furniture_fem/io/csv.hpp>
#include <furniture_fem/scene/observer.hpp>
#include <furniture_fem/scene/paper_configurations.hpp>
#include <furniture_fem/scene/run_scene.hpp>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

using namespace furniture_fem;

namespace {

class TiltAndFloorForce : public RunObserver {
 public:
  TiltAndFloorForce(std::string item, std::string csv_path) : item_(std::move(item)), path_(std::move(csv_path)) {}

  void begin(const RunView& run) override {
    body_ = run.item(item_).body;
    weight_ = 9.80665 * run.model.body_mass(body_);
    csv_.emplace(path_, std::vector<std::string>{"t", "tilt_deg", "peak_floor_fz"});
    interval_peak_ = floor_force(run);
    write_row(run);
  }
  void after_step(const RunView& run, const StepInfo&) override {
    interval_peak_ = std::max(interval_peak_, floor_force(run));  // every step: an impact lasts a few ms
    if (run.row_due()) write_row(run);
  }
  void end(const RunView&, RunSummary&) override { csv_->flush(); }

  double weight() const { return weight_; }  // N
  double peak_floor_force() const { return run_peak_; }
  double peak_time() const { return run_peak_time_; }
  double max_tilt() const { return max_tilt_; }

 private:
  std::string item_, path_;
  int body_ = -1;
  std::optional<CsvWriter> csv_;
  double weight_ = 0, interval_peak_ = 0, run_peak_ = 0, run_peak_time_ = 0, max_tilt_ = 0;

  // The floor's vertical force on the item (N); body -1 is the floor in the contact's pair forces.
  double floor_force(const RunView& run) {
    for (const auto& pf : run.sim.pair_forces())
      if (pf.body_a == body_ && pf.body_b == -1) {
        if (pf.force_on_a.z() > run_peak_) run_peak_ = pf.force_on_a.z(), run_peak_time_ = run.sim.time();
        return pf.force_on_a.z();
      }
    return 0.0;
  }
  void write_row(const RunView& run) {
    const double tilt = body_tilt_deg(run.sim, run.model, body_);
    max_tilt_ = std::max(max_tilt_, tilt);
    csv_->row({run.sim.time(), tilt, interval_peak_});
    interval_peak_ = 0;
  }
};

}  // namespace

int main() {
  // The paper's configuration 2 (side table, desk, office chair) under the built-in synthetic 3-D
  // motion, 3 s.
  SceneSpec spec = configuration(2, "");
  spec.name = "configuration 2, synthetic 3-D motion, 3 s";
  spec.ground_motion = GroundMotionSpec{};
  spec.ground_motion.source = MotionSource::synthetic;
  spec.ground_motion.pga = 8.0;
  spec.ground_motion.dimensions = MotionDimensions::three_d;
  spec.duration = 3.0;

  RunOptions opt;
  opt.write_files = false;  // no results folder: only our CSV
  opt.progress = false;
  TiltAndFloorForce desk("desk", "step-6-desk.csv");
  const RunSummary s = run_scene(spec, opt, {&desk});

  std::printf("%s: %s at t = %.3f s after %ld steps\n", spec.name.c_str(), s.status.c_str(), s.t_end, s.steps);
  std::printf("desk (weight %.1f N): largest floor force %.1f N at t = %.3f s, largest tilt %.2f deg\n", desk.weight(),
              desk.peak_floor_force(), desk.peak_time(), desk.max_tilt());
  for (const auto& it : s.items)
    std::printf("  %-14s %-9s slide %.3f m  tilt %5.2f deg\n", it.name.c_str(), it.state.c_str(), it.slide, it.tilt_deg);
  std::printf("rows written to step-6-desk.csv\n");
  return s.status == "completed" ? 0 : 1;
}
