#pragma once
// An observer that sets a run's stop flag after a given step, as Ctrl-C would between two steps: for
// tests of stopping and resuming.
#include <furniture_fem/scene/observer.hpp>

#include <atomic>

namespace ffem_test {

class StopAfter : public furniture_fem::RunObserver {
 public:
  // at: the step after which to stop; -1: never (the same observers as a stopped run, for its resume).
  StopAfter(std::atomic<bool>& flag, long at) : flag_(flag), at_(at) {}
  void after_step(const furniture_fem::RunView& run, const furniture_fem::StepInfo&) override {
    if (run.sim.steps() == at_) flag_ = true;
  }

 private:
  std::atomic<bool>& flag_;
  long at_;
};

}  // namespace ffem_test
