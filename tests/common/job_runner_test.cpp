// Tests of common/job_runner.hpp: the local runner returns every result in index order whatever
// the thread count; the resume folder keeps finished jobs, gives them back to a resumed run of
// the same identity, refuses another identity naming what differs, and runs a damaged job again.

#include "common/job_runner.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <set>

#include "common/errors.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class JobRunnerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("graspsynth_jobs_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A stage of `count` jobs whose result is "job i", counting the jobs that ran.
  JobStage Squares(int count, int threads) {
    JobStage stage;
    stage.name = "squares";
    stage.count = count;
    stage.threads = threads;
    stage.run = [this](int i) {
      ++ran_;
      return std::to_string(i * i);
    };
    return stage;
  }

  static RunIdentity Identity(const std::string& seed) {
    RunIdentity id;
    id.command = "test";
    id.Add("--seed", seed).Add("--name", "a");
    return id;
  }

  fs::path dir_;
  std::atomic<int> ran_{0};
};

TEST_F(JobRunnerTest, LocalRunnerReturnsResultsInIndexOrderForAnyThreadCount) {
  for (int threads : {1, 2, 5}) {
    LocalJobRunner runner;
    std::set<int> finished;
    JobStage stage = Squares(40, threads);
    stage.finished = [&](int i, bool here) {
      EXPECT_TRUE(here);
      EXPECT_TRUE(finished.insert(i).second) << "job " << i << " finished twice";
    };
    const std::vector<std::string> results = runner.Run(stage);
    ASSERT_EQ(results.size(), 40u);
    for (int i = 0; i < 40; ++i) EXPECT_EQ(results[static_cast<size_t>(i)], std::to_string(i * i));
    EXPECT_EQ(finished.size(), 40u);
  }
  LocalJobRunner runner;
  EXPECT_TRUE(runner.Run(Squares(0, 2)).empty());
}

TEST_F(JobRunnerTest, AJobsExceptionReachesTheCaller) {
  LocalJobRunner runner;
  JobStage stage = Squares(10, 2);
  stage.run = [](int i) -> std::string {
    if (i == 7) throw InputError("job 7 is bad");
    return "ok";
  };
  EXPECT_THROW(runner.Run(stage), InputError);
}

TEST_F(JobRunnerTest, AResumedRunTakesTheFinishedJobsAndRunsTheOthers) {
  {
    const ResumeFolder folder(dir_, Identity("1"), false);
    EXPECT_FALSE(folder.resumed());
    folder.Save("squares", 0, "0");
    folder.Save("squares", 3, "9");
  }
  const ResumeFolder folder(dir_, Identity("1"), true);
  EXPECT_TRUE(folder.resumed());
  LocalJobRunner runner;
  runner.set_resume_folder(&folder);
  int resumed = 0;
  JobStage stage = Squares(5, 2);
  stage.finished = [&](int, bool here) { resumed += here ? 0 : 1; };
  const std::vector<std::string> results = runner.Run(stage);
  EXPECT_EQ(results, (std::vector<std::string>{"0", "1", "4", "9", "16"}));
  EXPECT_EQ(ran_, 3);
  EXPECT_EQ(resumed, 2);
  // what ran is kept as well: a second resume runs nothing.
  ran_ = 0;
  EXPECT_EQ(runner.Run(Squares(5, 2)), results);
  EXPECT_EQ(ran_, 0);
  folder.Remove();
  EXPECT_FALSE(fs::exists(dir_));
}

TEST_F(JobRunnerTest, AResumeWithAnotherIdentityIsRefusedNamingWhatDiffers) {
  { const ResumeFolder folder(dir_, Identity("1"), false); }
  try {
    const ResumeFolder folder(dir_, Identity("2"), true);
    FAIL() << "a resume with another seed was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("with --seed '1', now '2'"));
  }
  RunIdentity other = Identity("1");
  other.command = "other";
  EXPECT_THROW(ResumeFolder(dir_, other, true), InputError);
  RunIdentity more = Identity("1");
  more.Add("--extra", "x");
  EXPECT_THROW(ResumeFolder(dir_, more, true), InputError);
  // without --resume, the earlier run is cleared.
  const ResumeFolder fresh(dir_, Identity("2"), false);
  EXPECT_FALSE(fresh.resumed());
}

TEST_F(JobRunnerTest, ANewRunClearsTheFolderAndADamagedJobRunsAgain) {
  {
    const ResumeFolder folder(dir_, Identity("1"), false);
    folder.Save("squares", 1, "1");
    folder.Save("squares", 2, "4");
  }
  // a job file cut short (as no atomic write leaves one, but a disk might).
  const fs::path job = dir_ / "squares" / "2.job";
  const auto size = fs::file_size(job);
  fs::resize_file(job, size - 1);
  const ResumeFolder folder(dir_, Identity("1"), true);
  EXPECT_EQ(folder.Load("squares", 1), std::optional<std::string>("1"));
  EXPECT_FALSE(folder.Load("squares", 2).has_value());
  EXPECT_FALSE(folder.Load("other", 1).has_value());

  const ResumeFolder fresh(dir_, Identity("1"), false);
  EXPECT_FALSE(fresh.Load("squares", 1).has_value());
}

TEST_F(JobRunnerTest, AResumeWithoutAnEarlierRunStartsAfresh) {
  const ResumeFolder folder(dir_, Identity("1"), true);
  EXPECT_FALSE(folder.resumed());
  EXPECT_TRUE(fs::exists(dir_ / "run.json"));
}

TEST_F(JobRunnerTest, IdentityFingerprintsFilesAndFolders) {
  fs::create_directories(dir_ / "in" / "sub");
  std::ofstream(dir_ / "in" / "a.csv") << "1,2\n";
  std::ofstream(dir_ / "in" / "sub" / "b.csv") << "3\n";
  RunIdentity before;
  before.AddFile("demos", dir_ / "in").AddFile("a", dir_ / "in" / "a.csv");
  std::ofstream(dir_ / "in" / "sub" / "b.csv") << "4\n";
  RunIdentity after;
  after.AddFile("demos", dir_ / "in").AddFile("a", dir_ / "in" / "a.csv");
  EXPECT_NE(before.fields[0].second, after.fields[0].second);
  EXPECT_EQ(before.fields[1].second, after.fields[1].second);
  RunIdentity missing;
  EXPECT_THROW(missing.AddFile("x", dir_ / "nothing.json"), InputError);
}

}  // namespace
}  // namespace graspsynth
