#pragma once

/// @file
/// Runs independent jobs on a few worker threads. Jobs are handed out in index order; which
/// thread runs a job never matters to its result (each job writes only its own output).

#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

namespace graspsynth {

/// The worker count for `jobs` jobs when `threads` were asked for (0: one per hardware
/// thread): at least 1, at most `jobs`.
inline int WorkerCount(int threads, int jobs) {
  const int wanted = threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency());
  return std::clamp(wanted, 1, std::max(1, jobs));
}

/// How `threads` (0: one per hardware thread) are shared between `jobs` independent jobs that
/// can each use worker threads of their own: `outer` jobs run at once, each on `inner` threads.
/// Jobs come first (with as many jobs as threads or more, each job runs on one thread and no
/// thread waits for another's job to end but at the very end); the threads left over when
/// there are fewer jobs go to each job in equal shares.
struct ThreadSplit {
  int outer = 1;
  int inner = 1;
};

/// The ThreadSplit of `threads` over `jobs` jobs (see ThreadSplit).
inline ThreadSplit SplitThreads(int threads, int jobs) {
  const int total = WorkerCount(threads, std::numeric_limits<int>::max());
  const int outer = std::clamp(total, 1, std::max(1, jobs));
  return {outer, std::max(1, total / outer)};
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
  for (int w = 1; w < WorkerCount(threads, count); ++w) {
    try {
      pool.emplace_back(work);
    } catch (const std::system_error&) {
      break;  // the system has no more threads to give: the ones started do the work
    }
  }
  work();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

/// Counts work done by jobs on any worker thread for a progress callback (done, total, what),
/// which it calls under its lock, one call at a time, with the running count.
class ProgressCounter {
 public:
  using Callback = std::function<void(int done, int total, const std::string& what)>;

  ProgressCounter(int total, Callback callback) : total_(total), callback_(std::move(callback)) {}

  /// `count` more units of work are done (0: only says what is being worked on).
  void Add(int count, const std::string& what) {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ += count;
    if (callback_) callback_(done_, total_, what);
  }

 private:
  std::mutex mutex_;
  int done_ = 0;
  const int total_;
  const Callback callback_;
};

}  // namespace graspsynth
