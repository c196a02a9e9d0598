#include "common/parallel.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace graspsynth {
namespace {

TEST(WorkerCount, IsAtLeastOneAndAtMostTheJobs) {
  EXPECT_EQ(WorkerCount(4, 2), 2);
  EXPECT_EQ(WorkerCount(2, 10), 2);
  EXPECT_EQ(WorkerCount(3, 0), 1);
  EXPECT_GE(WorkerCount(0, 1000), 1);  // one per hardware thread
}

TEST(SplitThreads, GivesEachJobOneThreadUntilThereAreMoreThreadsThanJobs) {
  const auto split = [](int threads, int jobs) {
    const ThreadSplit s = SplitThreads(threads, jobs);
    return std::vector<int>{s.outer, s.inner};
  };
  EXPECT_EQ(split(2, 9), (std::vector<int>{2, 1}));
  EXPECT_EQ(split(2, 1), (std::vector<int>{1, 2}));
  EXPECT_EQ(split(8, 3), (std::vector<int>{3, 2}));  // 2 threads are left over
  EXPECT_EQ(split(1, 5), (std::vector<int>{1, 1}));
  EXPECT_EQ(split(4, 0), (std::vector<int>{1, 4}));
  const ThreadSplit all = SplitThreads(0, 1);  // one per hardware thread, all to the one job
  EXPECT_EQ(all.outer, 1);
  EXPECT_EQ(all.inner, WorkerCount(0, 1000000));
}

TEST(ParallelFor, RunsEveryJobOnceAndCountsThemAsTheyFinish) {
  for (int threads : {1, 3}) {
    std::vector<int> runs(50, 0);
    std::vector<int> finished;
    ParallelFor(
        static_cast<int>(runs.size()), threads, [&](int i) { ++runs[static_cast<size_t>(i)]; },
        [&](int n) { finished.push_back(n); });
    for (int r : runs) EXPECT_EQ(r, 1);
    ASSERT_EQ(finished.size(), runs.size());
    for (size_t k = 0; k < finished.size(); ++k) EXPECT_EQ(finished[k], static_cast<int>(k) + 1);
  }
}

TEST(ParallelFor, RethrowsTheFirstErrorAndHandsOutNoMoreJobs) {
  for (int threads : {1, 2}) {
    std::vector<int> runs(40, 0);
    EXPECT_THROW(ParallelFor(static_cast<int>(runs.size()), threads,
                             [&](int i) {
                               ++runs[static_cast<size_t>(i)];
                               if (i == 5) throw std::runtime_error("job 5");
                             }),
                 std::runtime_error);
    int ran = 0;
    for (int r : runs) ran += r;
    // on one thread the jobs after the failed one are never handed out (on two, the other
    // worker may finish them first: the jobs are instantaneous).
    if (threads == 1) {
      EXPECT_EQ(ran, 6);
    }
    EXPECT_LE(ran, static_cast<int>(runs.size()));
  }
  EXPECT_NO_THROW(ParallelFor(0, 2, [](int) { throw std::runtime_error("no job"); }));
}

TEST(ProgressCounter, ReportsTheRunningCountFromEveryWorker) {
  std::vector<int> seen;
  ProgressCounter counter(100, [&](int done, int total, const std::string& what) {
    EXPECT_EQ(total, 100);
    EXPECT_EQ(what, "job");
    seen.push_back(done);
  });
  ParallelFor(50, 3, [&](int) { counter.Add(2, "job"); });
  ASSERT_EQ(seen.size(), 50u);
  for (size_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], 2 * static_cast<int>(k + 1));
  ProgressCounter silent(1, {});
  silent.Add(1, "nobody listens");  // no callback: nothing to call
}

}  // namespace
}  // namespace graspsynth
