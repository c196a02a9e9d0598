// What the process that gathers a stage's results spends per job, for issue 20's model of the
// speed-up at many ranks (benchmarks/README.md, "Scale-out"; experiments/scaling_report.py):
//
// - BM_KeepResult: StageResults::Add of one job's result (620 bytes, the size of a generalize
//   grasp's result), without a resume folder and with one (an atomic write of a job file in a
//   fresh folder under $TMPDIR, or under the folder given as GRASPSYNTH_BENCH_RESUME_DIR, for a
//   shared file system); the coordinator does this once per job, one job at a time.
// - BM_StageRoundTrip: a stage of jobs that return 620 bytes, instantly (2,000 jobs) or after
//   sleeping 1 ms (400 jobs), one worker thread per process, through the process's runner.
//   Started alone it measures the local runner's cost per job; under `mpirun -n 2` each job
//   that rank 1 runs makes a round trip through rank 0 (request, result, answer), one after
//   another, so 1 / remote_jobs_per_s - 1 / local_jobs_per_s (with 1 ms jobs, which both
//   ranks share) is what a job run elsewhere costs more than one run on rank 0's own thread. Each
//   run of the stage is a collective call: the iteration count is fixed so that the ranks stay in
//   step, under MPI only this benchmark runs (whatever --benchmark_filter says), and only rank 0
//   reports:
//
//     mpirun -n 2 build/benchmarks/job_runner_benchmark

#include <benchmark/benchmark.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "common/job_runner.hpp"
#ifdef GRASPSYNTH_HAS_MPI
#include "common/mpi_job_runner.hpp"
#endif

namespace graspsynth::bench {
namespace {

namespace fs = std::filesystem;

constexpr size_t kResultBytes = 620;
constexpr int kBatch = 1000;  // results kept per timed batch of BM_KeepResult

std::unique_ptr<JobRunner>& ProcessRunner() {
  static std::unique_ptr<JobRunner> runner;
  return runner;
}

fs::path ResumeRoot() {
  const char* dir = std::getenv("GRASPSYNTH_BENCH_RESUME_DIR");
  return dir && *dir ? fs::path(dir) : fs::temp_directory_path();
}

JobStage ResultStage(int count) {
  JobStage stage;
  stage.name = "bench";
  stage.count = count;
  stage.run = [](int) { return std::string(kResultBytes, 'r'); };
  return stage;
}

void BM_KeepResult(benchmark::State& state) {
  const bool saved = state.range(0) != 0;
  const fs::path folder = ResumeRoot() / "graspsynth_job_runner_benchmark.resume";
  const JobStage stage = ResultStage(kBatch);
  const std::string result(kResultBytes, 'r');
  RunIdentity identity;
  identity.command = "bench";
  for (auto _ : state) {
    state.PauseTiming();
    // a fresh folder for each batch, so that every write creates a new job file as in a run
    std::unique_ptr<ResumeFolder> resume;
    if (saved) resume = std::make_unique<ResumeFolder>(folder, identity, false);
    StageResults results(stage, resume.get());
    state.ResumeTiming();
    for (int i = 0; i < kBatch; ++i) results.Add(i, result, false);
    benchmark::DoNotOptimize(results.Take());
  }
  if (saved) ResumeFolder(folder, identity, false).Remove();
  state.SetItemsProcessed(state.iterations() * kBatch);
}
BENCHMARK(BM_KeepResult)->ArgName("saved")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_StageRoundTrip(benchmark::State& state) {
  const auto job_time = std::chrono::microseconds(state.range(0));
  const int jobs = job_time.count() > 0 ? 400 : 2000;
  JobStage stage = ResultStage(jobs);
  stage.threads = 1;
  stage.run = [job_time](int) {
    if (job_time.count() > 0) std::this_thread::sleep_for(job_time);
    return std::string(kResultBytes, 'r');
  };
  std::atomic<int64_t> remote{0};
  stage.finished = [&remote](int, bool here) {
    if (!here) ++remote;
  };
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(ProcessRunner()->Run(stage));
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  const auto total = static_cast<double>(state.iterations()) * jobs;
  const auto far = static_cast<double>(remote.load());
  state.SetItemsProcessed(static_cast<int64_t>(total));
  // jobs per second of this process's worker thread and of the other ranks' (one each)
  state.counters["local_jobs_per_s"] = (total - far) / seconds;
  state.counters["remote_jobs_per_s"] = far / seconds;
}
BENCHMARK(BM_StageRoundTrip)
    ->ArgName("job_us")
    ->Arg(0)
    ->Arg(1000)
    ->Iterations(5)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Prints nothing: the ranks but 0 run the benchmarks in step with rank 0 and keep quiet.
class QuietReporter final : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>&) override {}
};

}  // namespace
}  // namespace graspsynth::bench

int main(int argc, char** argv) {
#ifdef GRASPSYNTH_HAS_MPI
  const graspsynth::MpiSession mpi(&argc, &argv);
  graspsynth::bench::ProcessRunner() = mpi.MakeRunner();
  const bool reports = mpi.rank() == 0;
  const bool collective = mpi.size() > 1;
#else
  graspsynth::bench::ProcessRunner() = std::make_unique<graspsynth::LocalJobRunner>();
  const bool reports = true;
  const bool collective = false;
#endif
  // only rank 0 writes --benchmark_out's file: another rank's would replace it
  std::vector<char*> args(argv, argv + argc);
  if (!reports) {
    std::erase_if(args,
                  [](const char* a) { return std::string_view(a).starts_with("--benchmark_out"); });
  }
  argc = static_cast<int>(args.size());
  args.push_back(nullptr);
  argv = args.data();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  graspsynth::bench::QuietReporter quiet;
  if (!collective) {
    benchmark::RunSpecifiedBenchmarks();
  } else {
    // the collective benchmark alone: BM_KeepResult's iteration count is chosen by timing and
    // would differ between the ranks
    benchmark::RunSpecifiedBenchmarks(reports ? nullptr : &quiet, "BM_StageRoundTrip");
  }
  benchmark::Shutdown();
  return 0;
}
