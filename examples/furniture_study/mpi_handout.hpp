#pragma once
// furniture_study under MPI: rank 0 hands out runs one at a time, every rank (rank 0 included) runs
// them. Built only when CMake finds MPI (FFEM_WITH_MPI).
//
// Rank 0's main thread serves requests (MPI calls from that thread only: MPI_THREAD_FUNNELED), while
// its own worker thread takes runs from the same counter. A worker's request carries its previous
// result (JSON), which rank 0 records: one writer of the results folder, and no shared file system
// needed by the workers. A worker that is stopped (Ctrl-C reaches every rank through mpirun) tells
// rank 0, which then hands out nothing more.
#include <furniture_fem/study/runner.hpp>

#include <mpi.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace furniture_fem::mpi_study {

enum Tag : int { tag_request = 1, tag_reply = 2, tag_stats = 3 };
inline constexpr long no_more_runs = -1;

struct Request {
  std::string result_json;  // empty: none (the first request)
  bool stopped = false;
};

// Rank 0: serves the other ranks until each has been told there is no more, while `local_workers`
// threads run the same pending list. Returns whether every run was done.
inline bool serve(StudyFolder& folder, const std::vector<long>& pending, int local_workers, std::atomic<bool>& stop,
                  bool progress, StudyTiming& timing) {
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  std::atomic<std::size_t> next{0};
  StudyProgress bar(folder.study().num_runs(), folder.done(), progress, local_workers + ranks - 1);
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto take = [&]() -> long {
    const std::size_t k = next.fetch_add(1);
    return (k < pending.size() && !stop) ? pending[k] : no_more_runs;
  };
  std::vector<std::thread> threads;
  for (int i = 0; i < local_workers; ++i)
    threads.emplace_back([&] {
      try {
        for (long run; (run = take()) != no_more_runs;) {
          const RunResult r = run_realisation(folder.study(), run, &stop);
          if (r.status == "stopped") break;
          folder.record(r);
          bar.update(folder.done(), folder.failed());
        }
      } catch (...) {  // a write error: reported after the ranks are released
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        stop = true;
      }
    });
  int remote_open = ranks - 1;
  double wait_sum = 0;
  long wait_count = 0;
  while (remote_open > 0) {
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
    if (!flag) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      continue;
    }
    int bytes = 0;
    MPI_Get_count(&st, MPI_CHAR, &bytes);
    std::string msg(static_cast<std::size_t>(bytes), '\0');
    MPI_Recv(msg.data(), bytes, MPI_CHAR, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (st.MPI_TAG == tag_stats) {  // "<sum of waits> <count>" from a worker that is done
      double s = 0;
      long c = 0;
      if (std::sscanf(msg.c_str(), "%lf %ld", &s, &c) == 2) wait_sum += s, wait_count += c;
      --remote_open;
      continue;
    }
    // A request: "S" (stopped), or "R" followed by the previous result's JSON, or "R" alone.
    if (!msg.empty() && msg[0] == 'S') stop = true;
    if (msg.size() > 1 && msg[0] == 'R') {
      folder.record(run_result_from_json(nlohmann::json::parse(msg.substr(1))));
      bar.update(folder.done(), folder.failed());
    }
    const long run = (!msg.empty() && msg[0] == 'S') ? no_more_runs : take();
    MPI_Send(&run, 1, MPI_LONG, st.MPI_SOURCE, tag_reply, MPI_COMM_WORLD);
  }
  for (auto& t : threads) t.join();
  bar.update(folder.done(), folder.failed(), true);
  if (error) std::rethrow_exception(error);
  if (wait_count > 0) timing.handout_seconds_mean = wait_sum / static_cast<double>(wait_count);
  return !stop && folder.done() == folder.study().num_runs();
}

// Ranks 1..K-1: ask, run, send the result with the next request; at the end, the hand-out waits.
inline void work(const StudySpec& study, std::atomic<bool>& stop) {
  std::string message = "R";
  double wait_sum = 0;
  long wait_count = 0;
  for (;;) {
    const auto t0 = std::chrono::steady_clock::now();
    MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, tag_request, MPI_COMM_WORLD);
    long run = no_more_runs;
    MPI_Recv(&run, 1, MPI_LONG, 0, tag_reply, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    wait_sum += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++wait_count;
    if (run == no_more_runs) break;
    const RunResult r = run_realisation(study, run, &stop);
    message = r.status == "stopped" ? "S" : "R" + to_json(r).dump();
  }
  char stats[64];
  std::snprintf(stats, sizeof stats, "%.9g %ld", wait_sum, wait_count);
  MPI_Send(stats, static_cast<int>(std::strlen(stats)), MPI_CHAR, 0, tag_stats, MPI_COMM_WORLD);
}

}  // namespace furniture_fem::mpi_study
