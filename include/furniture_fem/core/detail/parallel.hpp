#pragma once
// Internal: a blocking parallel loop over bodies. Threads are started per call and joined, so an
// idle thread never spins: on a shared, loaded 2-core machine an OpenMP team spinning at its barrier
// made a step 3 times slower than one thread (bench_scenes, configuration 3). Work items are taken
// in the given order (largest body first) from an atomic counter.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/parallel.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace furniture_fem::detail {

template <class F>
void parallel_for(const std::vector<int>& order, int threads, F&& body) {
  const int n = static_cast<int>(order.size());
  if (threads <= 1 || n <= 1) {
    for (int i : order) body(i);
    return;
  }
  std::atomic<int> next{0};
  std::exception_ptr error;
  std::atomic<bool> failed{false};
  auto worker = [&] {
    for (int k = next++; k < n; k = next++) {
      try {
        body(order[k]);
      } catch (...) {
        if (!failed.exchange(true)) error = std::current_exception();
      }
    }
  };
  const int extra = std::min(threads, n) - 1;
  std::vector<std::thread> pool;
  pool.reserve(extra);
  for (int t = 0; t < extra; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

inline int hardware_threads() {
  const unsigned h = std::thread::hardware_concurrency();
  return h == 0 ? 1 : static_cast<int>(h);
}

}  // namespace furniture_fem::detail
