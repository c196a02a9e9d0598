// Tests of common/job_runner.hpp: the local runner returns every result in index order whatever
// the thread count; the resume folder keeps finished jobs, gives them back to a resumed run of
// the same build and identity, refuses another identity or build naming what differs, and runs
// again (counting it as recomputed) a job whose file is damaged, whose checksum fails, whose
// payload does not decode or is of another layout, or that another build made.

#include "common/job_runner.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
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
    stage.payload = "square/1";
    // a kept result must be the square of its index.
    stage.check = [](int i, std::string_view bytes) {
      if (bytes != std::to_string(i * i)) {
        throw InputError("job " + std::to_string(i) + ": '" + std::string(bytes) +
                         "' is not its square");
      }
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
    folder.Save(Squares(5, 1), 0, "0");
    folder.Save(Squares(5, 1), 3, "9");
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
  EXPECT_EQ(folder.summary().taken, 2);
  EXPECT_EQ(folder.summary().recomputed, 0);
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
  const JobStage squares = Squares(4, 1);
  {
    const ResumeFolder folder(dir_, Identity("1"), false);
    folder.Save(squares, 1, "1");
    folder.Save(squares, 2, "4");
  }
  // a job file cut short (as no atomic write leaves one, but a disk might).
  const fs::path job = dir_ / "squares" / "2.job";
  const auto size = fs::file_size(job);
  fs::resize_file(job, size - 1);
  const ResumeFolder folder(dir_, Identity("1"), true);
  EXPECT_EQ(folder.Load(squares, 1), std::optional<std::string>("1"));
  EXPECT_FALSE(folder.Load(squares, 2).has_value());
  JobStage other = squares;
  other.name = "other";
  EXPECT_FALSE(folder.Load(other, 1).has_value());  // no file: nothing recomputed
  EXPECT_EQ(folder.summary().taken, 1);
  EXPECT_EQ(folder.summary().recomputed, 1);
  EXPECT_THAT(folder.summary().reasons.at(0), HasSubstr("squares/2.job"));

  const ResumeFolder fresh(dir_, Identity("1"), false);
  EXPECT_FALSE(fresh.Load(squares, 1).has_value());
}

// The bytes of the job file at `path`, rewritten by `change` (which gets the parsed file).
void Rewrite(const fs::path& path, const std::function<void(JobFile*)>& change) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), {}};
  JobFile job = ParseJobFile(bytes, path.string());
  change(&job);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << JobFileBytes(job);
}

TEST_F(JobRunnerTest, AKeptJobThatDoesNotCheckOutRunsAgainAndTheRunEndsWithTheRightResults) {
  {
    const ResumeFolder folder(dir_, Identity("1"), false);
    LocalJobRunner runner;
    runner.set_resume_folder(&folder);
    runner.Run(Squares(6, 2));
  }
  // job 1: a payload that does not decode as the stage's result (the wrapper is whole and its
  // checksum is right); job 2: a payload changed behind its checksum; job 3: another build's
  // result; job 4: a result of another layout; job 5: a job file of another index.
  Rewrite(dir_ / "squares" / "1.job", [](JobFile* j) { j->result = "1.0000"; });
  {
    std::ifstream in(dir_ / "squares" / "2.job", std::ios::binary);
    std::string bytes{std::istreambuf_iterator<char>(in), {}};
    const size_t at = bytes.rfind('4');
    ASSERT_NE(at, std::string::npos);
    bytes[at] = '5';
    std::ofstream(dir_ / "squares" / "2.job", std::ios::binary | std::ios::trunc) << bytes;
  }
  Rewrite(dir_ / "squares" / "3.job", [](JobFile* j) { j->build = "graspsynth 0.0.9, build 0"; });
  Rewrite(dir_ / "squares" / "4.job", [](JobFile* j) { j->payload = "square/0"; });
  fs::copy_file(dir_ / "squares" / "0.job", dir_ / "squares" / "5.job",
                fs::copy_options::overwrite_existing);
  const ResumeFolder folder(dir_, Identity("1"), true);
  LocalJobRunner runner;
  runner.set_resume_folder(&folder);
  ran_ = 0;
  EXPECT_EQ(runner.Run(Squares(6, 2)), (std::vector<std::string>{"0", "1", "4", "9", "16", "25"}));
  EXPECT_EQ(ran_, 5);
  const ResumeSummary summary = folder.summary();
  EXPECT_EQ(summary.taken, 1);
  EXPECT_EQ(summary.recomputed, 5);
  const auto reason = [&](const std::string& job) {
    for (const std::string& r : summary.reasons) {
      if (r.find(job) != std::string::npos) return r;
    }
    std::string all;
    for (const std::string& r : summary.reasons) all += r + " | ";
    return "no reason for " + job + " among " + all;
  };
  EXPECT_THAT(reason("squares/1.job"), HasSubstr("'1.0000' is not its square"));
  EXPECT_THAT(reason("squares/2.job"), HasSubstr("checksum"));
  EXPECT_THAT(reason("squares/3.job"), HasSubstr("made by 'graspsynth 0.0.9, build 0'"));
  EXPECT_THAT(reason("squares/4.job"), HasSubstr("layout 'square/0', not 'square/1'"));
  EXPECT_THAT(reason("squares/5.job"), HasSubstr("holds job 0"));
  // what ran again was kept: a second resume takes all six.
  const ResumeFolder again(dir_, Identity("1"), true);
  runner.set_resume_folder(&again);
  ran_ = 0;
  runner.Run(Squares(6, 2));
  EXPECT_EQ(ran_, 0);
  EXPECT_EQ(again.summary().taken, 6);
}

TEST_F(JobRunnerTest, AResumeFolderOfAnotherBuildOrVersionIsRefusedNamingIt) {
  { const ResumeFolder folder(dir_, Identity("1"), false); }
  const fs::path manifest = dir_ / "run.json";
  std::ifstream in(manifest);
  const std::string text{std::istreambuf_iterator<char>(in), {}};
  EXPECT_THAT(text, HasSubstr("\"build\": \"" + std::string(BuildId()) + "\""));
  EXPECT_THAT(std::string(BuildId()), HasSubstr("graspsynth "));
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string changed = text;
    const size_t at = changed.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    changed.replace(at, from.size(), to);
    std::ofstream(manifest, std::ios::trunc) << changed;
  };
  with(std::string(BuildId()), "graspsynth 0.0.9, build 0123456789abcdef");
  try {
    const ResumeFolder folder(dir_, Identity("1"), true);
    FAIL() << "a resume folder of another build was taken";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(dir_.string()));
    EXPECT_THAT(e.what(), HasSubstr("by 'graspsynth 0.0.9, build 0123456789abcdef', not by this "
                                    "build"));
    EXPECT_THAT(e.what(), HasSubstr("start afresh without --resume"));
  }
  // the earlier version's format, which had no build at all.
  with("graspsynth-resume/2", "graspsynth-resume/1");
  try {
    const ResumeFolder folder(dir_, Identity("1"), true);
    FAIL() << "a resume folder of another version was taken";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("another version of graspsynth"));
  }
  EXPECT_TRUE(fs::exists(manifest)) << "a refused resume leaves the folder as it was";
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
