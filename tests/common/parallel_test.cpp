#include "common/parallel.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace graspsynth {
namespace {

TEST(WorkerCount, IsAtLeastOneAndAtMostTheJobs) {
  EXPECT_EQ(WorkerCount(4, 2), 2);
  EXPECT_EQ(WorkerCount(2, 10), 2);
  EXPECT_EQ(WorkerCount(3, 0), 1);
  EXPECT_GE(WorkerCount(0, 1000), 1);  // one per hardware thread
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

}  // namespace
}  // namespace graspsynth
