#include "common/mpi_job_runner.hpp"

#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include "common/byte_codec.hpp"
#include "common/errors.hpp"
#include "common/parallel.hpp"

namespace graspsynth {
namespace {

constexpr int kTagToRoot = 1;  // a worker thread's hello, result or error, with its request
constexpr int kTagAssign = 2;  // rank 0's answer: the next job, or -1 for none

// What a worker thread's message to rank 0 carries besides its request for a job.
enum class Carries : int64_t { kHello = 0, kResult = 1, kError = 2 };
// How a stage ended, sent with its results.
enum class Ending : int64_t { kOk = 0, kInputError = 1, kOtherError = 2 };

// Waits for `request` to complete without spinning a core (Open MPI's blocking calls poll):
// jobs take seconds, so a millisecond's delay costs nothing.
void WaitGently(MPI_Request* request) {
  auto pause = std::chrono::microseconds(50);
  for (;;) {
    int done = 0;
    MPI_Test(request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(1000));
  }
}

void SendBytes(const std::string& bytes, int to, int tag) {
  MPI_Request request;
  MPI_Isend(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD,
            &request);
  WaitGently(&request);
}

int ReceiveIndex() {
  int index = -1;
  MPI_Request request;
  MPI_Irecv(&index, 1, MPI_INT, 0, kTagAssign, MPI_COMM_WORLD, &request);
  WaitGently(&request);
  return index;
}

// Rank 0's bytes to every rank (any size: in pieces of at most 1 GiB).
void Broadcast(std::string* bytes) {
  uint64_t size = bytes->size();
  MPI_Request request;
  MPI_Ibcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD, &request);
  WaitGently(&request);
  bytes->resize(size);
  constexpr uint64_t kPiece = uint64_t{1} << 30;
  for (uint64_t at = 0; at < size; at += kPiece) {
    const int n = static_cast<int>(std::min(kPiece, size - at));
    MPI_Ibcast(bytes->data() + at, n, MPI_BYTE, 0, MPI_COMM_WORLD, &request);
    WaitGently(&request);
  }
}

// A stage's error as the ranks but 0 rethrow it (StageFailedElsewhere).
class SharedInputError final : public InputError, public StageFailedElsewhere {
 public:
  using InputError::InputError;
};
class SharedRuntimeError final : public std::runtime_error, public StageFailedElsewhere {
 public:
  using std::runtime_error::runtime_error;
};

// A stage's error as rank 0 rethrows it, once every rank has it (StageFailedEverywhere).
class EverywhereInputError final : public InputError, public StageFailedEverywhere {
 public:
  using InputError::InputError;
};
class EverywhereRuntimeError final : public std::runtime_error, public StageFailedEverywhere {
 public:
  using std::runtime_error::runtime_error;
};

// Rethrows a stage's error on rank 0 (kOk: nothing).
void Rethrow(Ending ending, const std::string& message) {
  if (ending == Ending::kInputError) throw EverywhereInputError(message);
  if (ending == Ending::kOtherError) throw EverywhereRuntimeError(message);
}

// The first error of a stage, on rank 0.
struct StageError {
  Ending ending = Ending::kOk;
  std::string message;
};

// Rank 0's part of a stage: hands out the jobs to its own threads and to the other ranks'
// requests, keeps the results, then sends them (or the first error) to every rank.
class StageCoordinator {
 public:
  StageCoordinator(const JobStage& stage, const ResumeFolder* resume, int size)
      : stage_(stage),
        results_(stage, resume),
        threads_of_(static_cast<size_t>(size), -1),
        retired_(static_cast<size_t>(size)) {}

  std::vector<std::string> Run() {
    StartOwnThreads();
    ServeOtherRanks();
    for (std::thread& t : pool_) t.join();
    return Finish();
  }

 private:
  // The next job to hand out, or -1 once none is left or the stage failed.
  int Take() {
    std::lock_guard<std::mutex> lock(mutex_);
    return error_.ending != Ending::kOk || next_ >= results_.todo().size()
               ? -1
               : results_.todo()[next_++];
  }

  // Keeps the stage's first error.
  void Fail(Ending ending, std::string message) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (error_.ending == Ending::kOk) error_ = {ending, std::move(message)};
  }

  void Guarded(const std::function<void()>& f) {
    try {
      f();
    } catch (const InputError& e) {
      Fail(Ending::kInputError, e.what());
    } catch (const std::exception& e) {
      Fail(Ending::kOtherError, e.what());
    }
  }

  void StartOwnThreads() {
    const int threads = WorkerCount(stage_.threads, static_cast<int>(results_.todo().size()));
    for (int t = 0; t < threads; ++t) {
      pool_.emplace_back([this] {
        for (int i = Take(); i >= 0; i = Take()) {
          Guarded([&] { results_.Add(i, stage_.run(i), true); });
        }
      });
    }
  }

  // The other ranks' worker threads: each says hello, then brings a result (or an error) with
  // each request, until it is told that nothing is left.
  void ServeOtherRanks() {
    const int others = static_cast<int>(threads_of_.size()) - 1;
    int ranks_done = 0;
    std::string message;
    while (ranks_done < others) {
      const int from = ReceiveGently(&message);
      Guarded([&] { Handle(message, from); });
      const int assigned = Take();
      MPI_Request request;
      MPI_Isend(&assigned, 1, MPI_INT, from, kTagAssign, MPI_COMM_WORLD, &request);
      WaitGently(&request);
      const auto rank = static_cast<size_t>(from);
      if (assigned < 0 && ++retired_[rank] == threads_of_[rank]) ++ranks_done;
    }
  }

  // The next message to rank 0 from any rank (into `message`); returns its sender. Probes
  // without spinning a core, as WaitGently does.
  static int ReceiveGently(std::string* message) {
    auto pause = std::chrono::microseconds(50);
    int flag = 0;
    MPI_Status status;
    for (;;) {
      MPI_Iprobe(MPI_ANY_SOURCE, kTagToRoot, MPI_COMM_WORLD, &flag, &status);
      if (flag) break;
      std::this_thread::sleep_for(pause);
      pause = std::min(pause * 2, std::chrono::microseconds(1000));
    }
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    message->assign(static_cast<size_t>(count), '\0');
    MPI_Recv(message->data(), count, MPI_BYTE, status.MPI_SOURCE, kTagToRoot, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    return status.MPI_SOURCE;
  }

  void Handle(const std::string& message, int from) {
    ByteReader r(message, "the message of rank " + std::to_string(from));
    const Carries carries = r.EnumValue(Carries::kError);
    const int64_t value = r.IntIn(0, INT_MAX);
    std::string payload = r.String();
    r.Finish();
    if (carries == Carries::kHello) {
      threads_of_[static_cast<size_t>(from)] = static_cast<int>(value);
    } else if (carries == Carries::kResult) {
      if (value >= stage_.count) throw std::runtime_error("a result for no job");
      results_.Add(static_cast<int>(value), std::move(payload), false);
    } else {
      Fail(static_cast<Ending>(value), std::move(payload));
    }
  }

  // Sends every result, or the stage's error, to every rank, and returns the results or
  // rethrows the error here.
  std::vector<std::string> Finish() {
    ByteWriter w;
    w.EnumValue(error_.ending);
    w.String(error_.message);
    std::vector<std::string> all;
    if (error_.ending == Ending::kOk) {
      all = results_.Take();
      w.UInt(all.size());
      for (const std::string& r : all) w.String(r);
    }
    std::string bytes = w.Take();
    Broadcast(&bytes);
    Rethrow(error_.ending, error_.message);
    return all;
  }

  const JobStage& stage_;
  StageResults results_;
  std::mutex mutex_;  // next_ and error_
  size_t next_ = 0;
  StageError error_;
  std::vector<std::thread> pool_;
  std::vector<int> threads_of_;  // per rank: its worker threads (from its hello)
  std::vector<int> retired_;     // per rank: its threads told that nothing is left
};

class MpiJobRunner final : public JobRunner {
 public:
  MpiJobRunner(int rank, int size, bool threads_serialized)
      : rank_(rank), size_(size), threads_serialized_(threads_serialized) {}

  std::vector<std::string> Run(const JobStage& stage) override {
    DemandValidStage(stage);
    return rank_ == 0 ? StageCoordinator(stage, resume_folder(), size_).Run() : Work(stage);
  }
  bool writes_outputs() const override { return rank_ == 0; }

 private:
  // Any other rank: its worker threads ask rank 0 for jobs until none is left, then the stage's
  // results come from rank 0.
  std::vector<std::string> Work(const JobStage& stage) {
    const int threads = threads_serialized_ ? WorkerCount(stage.threads, stage.count) : 1;
    std::mutex mpi;  // one MPI call at a time (MPI_THREAD_SERIALIZED)
    const auto message = [](Carries carries, int64_t value, std::string_view payload) {
      ByteWriter w;
      w.EnumValue(carries);
      w.Int(value);
      w.String(payload);
      return w.Take();
    };
    // a fault for the tests (docs/scale-out.md): the first job of the stage named by
    // GRASPSYNTH_TEST_FAIL_STAGE that this rank runs fails, as a job that meets bad input does.
    const char* fail = std::getenv("GRASPSYNTH_TEST_FAIL_STAGE");
    std::atomic<bool> failed{fail == nullptr || stage.name != fail};
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) {
      pool.emplace_back([&] {
        std::string out = message(Carries::kHello, threads, "");
        for (;;) {
          int i = -1;
          {
            std::lock_guard<std::mutex> lock(mpi);
            SendBytes(out, 0, kTagToRoot);
            i = ReceiveIndex();
          }
          if (i < 0) return;
          try {
            if (!failed.exchange(true)) {
              throw InputError("rank " + std::to_string(rank_) + ": job " + std::to_string(i) +
                               " of stage '" + stage.name +
                               "' failed (GRASPSYNTH_TEST_FAIL_STAGE, a test's fault)");
            }
            out = message(Carries::kResult, i, stage.run(i));
          } catch (const InputError& e) {
            out = message(Carries::kError, static_cast<int64_t>(Ending::kInputError), e.what());
          } catch (const std::exception& e) {
            out = message(Carries::kError, static_cast<int64_t>(Ending::kOtherError), e.what());
          }
        }
      });
    }
    for (std::thread& t : pool) t.join();

    std::string bytes;
    Broadcast(&bytes);
    ByteReader r(bytes, "the results of stage '" + stage.name + "' from rank 0");
    const Ending ending = r.EnumValue(Ending::kOtherError);
    const std::string text = r.String();
    if (ending == Ending::kInputError) throw SharedInputError(text);
    if (ending == Ending::kOtherError) throw SharedRuntimeError(text);
    if (r.UInt() != static_cast<uint64_t>(stage.count)) {
      throw std::runtime_error("rank 0 sent the results of another stage than '" + stage.name +
                               "'");
    }
    std::vector<std::string> all(static_cast<size_t>(stage.count));
    for (std::string& s : all) s = r.String();
    r.Finish();
    return all;
  }

  int rank_;
  int size_;
  bool threads_serialized_;
};

}  // namespace

MpiSession::MpiSession(int* argc, char*** argv) {
  if (!std::getenv("OMPI_COMM_WORLD_SIZE") && !std::getenv("PMIX_RANK") &&
      !std::getenv("PMI_SIZE")) {
    return;
  }
  int provided = MPI_THREAD_SINGLE;
  MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided);
  active_ = true;
  threads_serialized_ = provided >= MPI_THREAD_SERIALIZED;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  if (active_) MPI_Finalize();
}

void MpiSession::AbortAll(int code) const {
  if (active_) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

std::unique_ptr<JobRunner> MpiSession::MakeRunner() const {
  if (size_ < 2) return std::make_unique<LocalJobRunner>();
  return std::make_unique<MpiJobRunner>(rank_, size_, threads_serialized_);
}

}  // namespace graspsynth
