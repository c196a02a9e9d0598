// Tests of the scale-out (docs/scale-out.md): a generalize sweep killed midway (SIGKILL)
// and resumed with --resume ends with the bytes of an uninterrupted run, also when some of its
// kept jobs are damaged or foreign (they run again); a resume with another seed, or of a folder
// another build started, is refused naming it; and, where the build has MPI, generalize, demos
// generate and select under `mpirun -n 3` write the bytes of the single-process run.

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "common/job_runner.hpp"
#include "tests/utils/run_command.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::ReadFileText;
using testing::RunGraspsynth;

// A reduced sweep: a few grasps, each with a nominal trial and one perturbed replay (a nominal
// trial alone under the sanitizers, which run it ten times slower).
#ifdef GRASPSYNTH_SANITIZED
const char* const kSweep = "generalize --orientations 40:70:10 --methods nearest --perturb 0 ";
#else
const char* const kSweep =
    "generalize --orientations 40:70:10 --methods nearest,interp --perturb 1 ";
#endif

class ScaleOut : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("graspsynth_scale_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::vector<std::string> Words(const std::string& text) {
    std::istringstream in(text);
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    return words;
  }

  // Starts `graspsynth <args>` in the background, its output thrown away.
  static pid_t Start(const std::string& args) {
    std::vector<std::string> words = Words(args);
    words.insert(words.begin(), testing::GraspsynthBinary());
    const pid_t pid = ::fork();
    if (pid == 0) {
      const int null = ::open("/dev/null", O_WRONLY);
      ::dup2(null, STDOUT_FILENO);
      ::dup2(null, STDERR_FILENO);
      std::vector<char*> argv;
      for (std::string& w : words) argv.push_back(w.data());
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    return pid;
  }

  static int JobFiles(const fs::path& folder) {
    std::error_code ec;
    int n = 0;
    for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
      if (it->path().extension() == ".job") ++n;
    }
    return n;
  }

  // Runs `graspsynth <args>` and kills it (SIGKILL) once `kept` holds a finished job, long
  // before the last; fails the test when it ends first.
  static void StartAndKill(const std::string& args, const fs::path& kept) {
    const pid_t pid = Start(args);
    ASSERT_GT(pid, 0);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
    int status = 0;
    bool exited = false;
    while (JobFiles(kept) < 1 && std::chrono::steady_clock::now() < deadline) {
      if (::waitpid(pid, &status, WNOHANG) == pid) {
        exited = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ASSERT_FALSE(exited) << "the sweep ended before it could be killed";
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status));
    ASSERT_GE(JobFiles(kept), 1);
  }

  // The sweep run whole into `whole`, then into `killed` and killed there once it kept a job
  // (StartAndKill); *args are the killed run's arguments.
  static void WholeAndKilled(const fs::path& whole, const fs::path& killed, std::string* args) {
    const testing::CommandOutput r = RunGraspsynth(std::string(kSweep) + "--out " + whole.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    *args = std::string(kSweep) + "--threads 1 --out " + killed.string();
    StartAndKill(*args, killed / ".generalization.resume");
  }

  fs::path dir_;
};

TEST_F(ScaleOut, AKilledSweepResumesToTheBytesOfAnUninterruptedOne) {
  const fs::path whole = dir_ / "whole", killed = dir_ / "killed";
  std::string args;
  ASSERT_NO_FATAL_FAILURE(WholeAndKilled(whole, killed, &args));
  const fs::path kept = killed / ".generalization.resume";
  EXPECT_FALSE(fs::exists(killed / "generalization.csv"));

  const testing::CommandOutput r = RunGraspsynth(args + " --resume");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("resuming the run kept in"));
  EXPECT_EQ(ReadFileText(killed / "generalization.csv"),
            ReadFileText(whole / "generalization.csv"));
  EXPECT_FALSE(fs::exists(kept)) << "the finished run leaves its resume folder behind";
}

// The job files of a killed run, damaged as a disk, a copy or another build could leave them:
// each runs again, the summary counts them, and the outputs are the uninterrupted run's bytes.
TEST_F(ScaleOut, DamagedOrForeignJobsRunAgainAndTheResumeEndsWithTheUninterruptedBytes) {
  const fs::path whole = dir_ / "whole", killed = dir_ / "killed";
  std::string args;
  ASSERT_NO_FATAL_FAILURE(WholeAndKilled(whole, killed, &args));
  const fs::path kept = killed / ".generalization.resume";
  fs::path first;
  for (const fs::directory_entry& e : fs::directory_iterator(kept / "synthesis")) {
    if (e.path().extension() == ".job") first = e.path();
  }
  ASSERT_FALSE(first.empty());
  const JobFile job = ParseJobFile(ReadFileText(first), first.string());
  const int rows = static_cast<int>(Words(ReadFileText(whole / "generalization.csv")).size()) - 1;
  ASSERT_GE(rows, 4);
  const auto write = [&](int index, const JobFile& file) {
    std::ofstream(kept / "synthesis" / (std::to_string(index) + ".job"),
                  std::ios::binary | std::ios::trunc)
        << JobFileBytes(file);
  };
  // its row with 8 bytes more behind a right checksum (the wrapper whole: the row's decoding
  // finds them), the same file under another index, and another build's copy.
  JobFile longer = job;
  longer.result += std::string(8, '\0');
  write(static_cast<int>(job.index), longer);
  write(static_cast<int>((job.index + 1) % rows), job);
  JobFile foreign = job;
  foreign.build = "graspsynth 0.0.1, build 0123456789abcdef";
  foreign.index = (job.index + 2) % rows;
  write(static_cast<int>(foreign.index), foreign);

  const testing::CommandOutput r = RunGraspsynth(args + " --resume");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ReadFileText(killed / "generalization.csv"),
            ReadFileText(whole / "generalization.csv"));
  EXPECT_THAT(r.err, HasSubstr(" 3 recomputed"));
  EXPECT_THAT(r.err, HasSubstr("recomputed synthesis/" + std::to_string(job.index) +
                               ".job: synthesis job " + std::to_string(job.index)));
  EXPECT_THAT(r.err, HasSubstr("holds job " + std::to_string(job.index)));
  EXPECT_THAT(r.err, HasSubstr("made by 'graspsynth 0.0.1, build 0123456789abcdef'"));
  EXPECT_FALSE(fs::exists(kept));
}

// A resume folder that another build of graspsynth started is refused, naming the folder and
// that build, and left for it.
TEST_F(ScaleOut, AResumeFolderOfAnotherBuildIsRefusedNamingIt) {
  const std::string args = std::string(kSweep) + "--threads 1 --out " + dir_.string();
  const fs::path kept = dir_ / ".generalization.resume";
  StartAndKill(args, kept);
  std::string manifest = ReadFileText(kept / "run.json");
  const std::string key = "\"build\": \"";
  const size_t at = manifest.find(key);
  ASSERT_NE(at, std::string::npos) << manifest;
  const size_t end = manifest.find('"', at + key.size());
  manifest.replace(at + key.size(), end - at - key.size(), "graspsynth 0.0.1, build 42");
  std::ofstream(kept / "run.json", std::ios::trunc) << manifest;
  const testing::CommandOutput r = RunGraspsynth(args + " --resume");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--resume: the unfinished run in '" + kept.string() +
                               "' was started by 'graspsynth 0.0.1, build 42', not by this build"));
  EXPECT_FALSE(fs::exists(dir_ / "generalization.csv"));
  EXPECT_EQ(ReadFileText(kept / "run.json"), manifest);
}

TEST_F(ScaleOut, AResumeWithAnotherSeedIsRefusedNamingIt) {
  // an earlier run's folder, as a killed run leaves it (its identity written first).
  const std::string args = std::string(kSweep) + "--out " + dir_.string();
  const pid_t pid = Start(args);
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
  while (!fs::exists(dir_ / ".generalization.resume" / "run.json") &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(fs::exists(dir_ / ".generalization.resume" / "run.json"));

  const testing::CommandOutput r = RunGraspsynth(args + " --seed 7 --resume");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--resume: the unfinished run in"));
  EXPECT_THAT(r.err, HasSubstr("with --seed '1', now '7'"));
  EXPECT_FALSE(fs::exists(dir_ / "generalization.csv"));
  // the earlier run's kept work is still there for a resume with its own arguments.
  EXPECT_TRUE(fs::exists(dir_ / ".generalization.resume" / "run.json"));
}

#ifdef GRASPSYNTH_MPIEXEC
// Runs `graspsynth <args>` as an MPI job of `ranks` processes; its stdout in *out. `env`
// (NAME=VALUE) is set on every rank. Under a hang guard of 5 minutes (exit 124).
int RunMpi(int ranks, const std::string& args, const fs::path& dir, std::string* out,
           const std::string& env = "") {
  const std::string mpirun = (env.empty() ? std::string() : env + " ") + "timeout -k 10 300 " +
                             std::string(GRASPSYNTH_MPIEXEC) +
                             (env.empty() ? std::string() : " -x " + env.substr(0, env.find('='))) +
                             " --oversubscribe -n " + std::to_string(ranks) + " " +
                             (::geteuid() == 0 ? "--allow-run-as-root " : "") +
                             testing::GraspsynthBinary() + " " + args + " > " +
                             (dir / "out").string() + " 2> " + (dir / "err").string();
  const int status = std::system(mpirun.c_str());
  *out = ReadFileText(dir / "out") + ReadFileText(dir / "err");
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The sweep run by one process (one thread) into `one`: the bytes an MPI job must write.
void SweepOnOneProcess(const fs::path& one) {
  const testing::CommandOutput r =
      RunGraspsynth(std::string(kSweep) + "--threads 1 --out " + one.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(ScaleOut, ThreeMpiRanksWriteTheBytesOfOneProcess) {
  const fs::path one = dir_ / "one", three = dir_ / "three";
  ASSERT_NO_FATAL_FAILURE(SweepOnOneProcess(one));
  fs::create_directories(dir_);
  std::string out;
  ASSERT_EQ(RunMpi(3, std::string(kSweep) + "--threads 2 --out " + three.string(), dir_, &out), 0)
      << out;
  EXPECT_EQ(ReadFileText(three / "generalization.csv"), ReadFileText(one / "generalization.csv"));
  // rank 0 alone reports: one summary line per method, not three.
  EXPECT_EQ(out.find("nearest: "), out.rfind("nearest: ")) << out;
  EXPECT_FALSE(fs::exists(three / ".generalization.resume"));
}

// A job that fails on another rank than the first fails the stage on every rank: the command
// ends with that job's error (exit 2), the resume folder keeps only whole results, and a resume
// writes the bytes of one process.
TEST_F(ScaleOut, AJobFailingOnAnotherRankEndsTheRunAndItsResumeIsTheBytesOfOneProcess) {
  const fs::path one = dir_ / "one", three = dir_ / "three";
  ASSERT_NO_FATAL_FAILURE(SweepOnOneProcess(one));
  const std::string args = std::string(kSweep) + "--threads 1 --out " + three.string();
  std::string out;
  EXPECT_EQ(RunMpi(3, args, dir_, &out, "GRASPSYNTH_TEST_FAIL_STAGE=synthesis"), 2) << out;
  EXPECT_THAT(out, HasSubstr("of stage 'synthesis' failed (GRASPSYNTH_TEST_FAIL_STAGE"));
  EXPECT_FALSE(fs::exists(three / "generalization.csv"));
  const fs::path kept = three / ".generalization.resume";
  ASSERT_TRUE(fs::exists(kept / "run.json"));
  ASSERT_EQ(RunMpi(3, args + " --resume", dir_, &out), 0) << out;
  EXPECT_THAT(out, HasSubstr("resuming the run kept in"));
  EXPECT_THAT(out, HasSubstr(" 0 recomputed"));
  EXPECT_EQ(ReadFileText(three / "generalization.csv"), ReadFileText(one / "generalization.csv"));
}

// The pid of the process of MPI rank `rank` whose command line holds `marker`, or -1.
pid_t RankProcess(int rank, const std::string& marker) {
  const std::string want = "OMPI_COMM_WORLD_RANK=" + std::to_string(rank);
  for (const fs::directory_entry& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = ReadFileText(e.path() / "cmdline");
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (cmdline.find(marker) == std::string::npos) continue;
    if (cmdline.find("graspsynth") == std::string::npos) continue;
    const std::string environ = ReadFileText(e.path() / "environ");
    for (size_t at = 0; at < environ.size();) {
      const size_t end = std::min(environ.find('\0', at), environ.size());
      if (environ.compare(at, end - at, want) == 0) return std::stoi(name);
      at = end + 1;
    }
  }
  return -1;
}

// A rank killed in the middle of a job ends the MPI job; its resume, under three ranks again,
// writes the bytes of one process.
TEST_F(ScaleOut, AnMpiJobWhoseRankIsKilledMidJobResumesToTheBytesOfOneProcess) {
  const fs::path one = dir_ / "one", three = dir_ / "three";
  ASSERT_NO_FATAL_FAILURE(SweepOnOneProcess(one));
  const std::string args = std::string(kSweep) + "--threads 1 --out " + three.string();
  const std::string mpirun = std::string(GRASPSYNTH_MPIEXEC) + " --oversubscribe -n 3 " +
                             (::geteuid() == 0 ? "--allow-run-as-root " : "") +
                             testing::GraspsynthBinary() + " " + args + " > /dev/null 2>&1";
  const pid_t job = ::fork();
  if (job == 0) {
    ::setpgid(0, 0);  // a group of its own, which the hang guard below can end whole
    ::execl("/bin/sh", "sh", "-c", mpirun.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ASSERT_GT(job, 0);
  const fs::path kept = three / ".generalization.resume";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  pid_t victim = -1;
  int status = 0;
  bool ended = false;
  while (std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(job, &status, WNOHANG) == job) {
      ended = true;
      break;
    }
    if (JobFiles(kept) >= 1 && (victim = RankProcess(1, three.string())) > 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_FALSE(ended) << "the MPI job ended before a rank could be killed";
  ASSERT_GT(victim, 0) << "rank 1 was not found";
  ::kill(victim, SIGKILL);
  // mpirun ends the others; should it hang instead, the guard ends it and the test fails.
  const auto guard = std::chrono::steady_clock::now() + std::chrono::minutes(2);
  while (::waitpid(job, &status, WNOHANG) != job) {
    if (std::chrono::steady_clock::now() > guard) {
      ADD_FAILURE() << "mpirun did not end after rank 1 was killed";
      ::kill(-job, SIGKILL);
      ::waitpid(job, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_NE(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 0) << "mpirun ended well without rank 1";
  EXPECT_FALSE(fs::exists(three / "generalization.csv"));
  ASSERT_TRUE(fs::exists(kept / "run.json"));

  std::string out;
  ASSERT_EQ(RunMpi(3, args + " --resume", dir_, &out), 0) << out;
  EXPECT_THAT(out, HasSubstr("resuming the run kept in"));
  EXPECT_EQ(ReadFileText(three / "generalization.csv"), ReadFileText(one / "generalization.csv"));
  EXPECT_FALSE(fs::exists(kept));
}

TEST_F(ScaleOut, DemonstrationsAndTheSelectionUnderThreeRanksAreTheBytesOfOneProcess) {
  fs::create_directories(dir_);
  const std::string demos = "demos generate --trials-per-orientation 1 --quiet --threads 1 ";
  testing::CommandOutput r = RunGraspsynth(demos + "--out " + (dir_ / "d1").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string out;
  ASSERT_EQ(RunMpi(3, demos + "--out " + (dir_ / "d3").string(), dir_, &out), 0) << out;
  int logs = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(dir_ / "d1")) {
    const fs::path name = e.path().filename();
    EXPECT_EQ(ReadFileText(dir_ / "d3" / name), ReadFileText(e.path())) << name;
    logs += e.path().extension() == ".csv" ? 1 : 0;
  }
  EXPECT_EQ(logs, 9);

  const std::string select = "select " + (dir_ / "d1").string() + " --perturb 1 --threads 1 ";
  r = RunGraspsynth(select + "--out " + (dir_ / "one.json").string());
  ASSERT_LE(r.exit_code, 1) << r.err;
  ASSERT_EQ(RunMpi(3, select + "--out " + (dir_ / "three.json").string(), dir_, &out), r.exit_code)
      << out;
  EXPECT_EQ(ReadFileText(dir_ / "three.json"), ReadFileText(dir_ / "one.json"));
}
#endif

}  // namespace
}  // namespace graspsynth
