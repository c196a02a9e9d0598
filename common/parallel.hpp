#pragma once

/// @file
/// Runs independent jobs on a few worker threads. Jobs are handed out in index order; which
/// thread runs a job never matters to its result (each job writes only its own output).

#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace graspsynth {

/// The worker count for `jobs` jobs when `threads` were asked for (0: one per hardware
/// thread): at least 1, at most `jobs`.
inline int WorkerCount(int threads, int jobs) {
  const int wanted = threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency());
  return std::clamp(wanted, 1, std::max(1, jobs));
}

/// Calls job(i) for every i in [0, count) on WorkerCount(threads, count) threads (the calling
/// thread is one of them) and then `done(finished)` under a lock after each job, in the order
/// the jobs finish. The first exception a job throws stops the handing out of jobs and is
/// rethrown once every worker has stopped.
inline void ParallelFor(int count, int threads, const std::function<void(int)>& job,
                        const std::function<void(int finished)>& done = {}) {
  std::atomic<int> next{0};
  std::mutex mutex;
  int finished = 0;
  std::exception_ptr error;
  auto work = [&] {
    for (int i = next++; i < count; i = next++) {
      try {
        job(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        next = count;
        return;
      }
      std::lock_guard<std::mutex> lock(mutex);
      ++finished;
      if (done) done(finished);
    }
  };
  std::vector<std::thread> pool;
  for (int w = 1; w < WorkerCount(threads, count); ++w) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace graspsynth
