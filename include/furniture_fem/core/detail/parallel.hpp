#pragma once
// Internal: a blocking parallel loop over bodies. Work items are taken in the given order (largest
// body first) from an atomic counter. The helper threads are started once, on the first loop that
// needs them, and wait on a condition variable between loops: an idle thread never spins (on a
// shared, loaded 2-core machine an OpenMP team spinning at its barrier made a step 3 times slower
// than one thread, bench_scenes, configuration 3), and a loop no longer pays a thread's start and
// join (50 us here; a step sweeps its bodies 5 to 10 times). The caller works from the start and
// waits only for a helper that took an item: one that wakes after every item is taken (a wake-up
// costs about 25 us here) finds the loop closed.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/parallel.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif
#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>
#include <type_traits>
#include <vector>

namespace furniture_fem::detail {

// Helper threads that run one loop at a time with the calling thread. Which thread runs which item
// does not change a result: each item writes only its own body's data.
class WorkerPool {
 public:
  WorkerPool() = default;
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;
  ~WorkerPool() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (auto& t : threads_) t.join();
  }

  template <class F>
  void run(const std::vector<int>& order, int threads, F&& body) {
    const int n = static_cast<int>(order.size());
    // A loop started from inside a running one (by the caller or a helper) runs serially.
    if (threads <= 1 || n <= 1 || running_.exchange(true)) {
      for (int i : order) body(i);
      return;
    }
    // A helper that cannot be started (std::system_error) leaves the pool free for the next loop.
    const int helpers = start_helpers(std::min(threads, n) - 1);
    if (helpers == 0) {
      running_ = false;
      for (int i : order) body(i);
      return;
    }
    using Body = std::remove_reference_t<F>;
    Loop loop{order, const_cast<void*>(static_cast<const void*>(&body)),
              [](void* f, int i) { (*static_cast<Body*>(f))(i); }};
    {
      std::lock_guard lock(mutex_);
      loop_ = &loop;
      helpers_ = helpers;
      ++generation_;
    }
    wake_.notify_all();
    loop.work();
    // Every item is taken: close the loop to helpers that have not woken yet, and wait only for those
    // still working on one (a wake-up is not on the critical path).
    std::unique_lock lock(mutex_);
    loop_ = nullptr;
    done_.wait(lock, [&] { return busy_ == 0; });
    running_ = false;
    if (loop.error) std::rethrow_exception(loop.error);
  }

 private:
  struct Loop {
    Loop(const std::vector<int>& o, void* b, void (*c)(void*, int)) : order(o), body(b), call(c) {}
    const std::vector<int>& order;
    void* body;
    void (*call)(void*, int);
    std::atomic<int> next{0};
    std::atomic<bool> failed{false};
    std::exception_ptr error;

    void work() {
      const int n = static_cast<int>(order.size());
      for (int k = next++; k < n; k = next++) {
        try {
          call(body, order[k]);
        } catch (...) {
          if (!failed.exchange(true)) error = std::current_exception();
        }
      }
    }
  };

  // Starts helpers up to `wanted` and returns how many there are; fewer if the system refuses a thread.
  int start_helpers(int wanted) {
    try {
      while (static_cast<int>(threads_.size()) < wanted) {
        const int index = static_cast<int>(threads_.size());
        threads_.emplace_back([this, index] { serve(index); });
      }
    } catch (const std::system_error&) {
    }
    return std::min(wanted, static_cast<int>(threads_.size()));
  }

  // Helper `index` joins each loop that asks for more than `index` helpers, if it is still open.
  void serve(int index) {
    long seen = 0;
    std::unique_lock lock(mutex_);
    for (;;) {
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      if (index >= helpers_ || loop_ == nullptr) continue;
      Loop* loop = loop_;
      ++busy_;
      lock.unlock();
      loop->work();
      lock.lock();
      if (--busy_ == 0) done_.notify_one();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::vector<std::thread> threads_;
  Loop* loop_ = nullptr;
  long generation_ = 0;
  int helpers_ = 0, busy_ = 0;
  bool stop_ = false;
  std::atomic<bool> running_{false};
};

// A WorkerPool started on the first loop that needs helpers (a one-thread run starts none); moved
// with its owner, its threads keep serving it.
class PoolHandle {
 public:
  template <class F>
  void parallel_for(const std::vector<int>& order, int threads, F&& body) {
    if (threads > 1 && order.size() > 1 && !pool_) pool_ = std::make_unique<WorkerPool>();
    if (pool_) return pool_->run(order, threads, std::forward<F>(body));
    for (int i : order) body(i);
  }

 private:
  std::unique_ptr<WorkerPool> pool_;
};

inline int hardware_threads() {
  const unsigned h = std::thread::hardware_concurrency();
  return h == 0 ? 1 : static_cast<int>(h);
}

}  // namespace furniture_fem::detail
