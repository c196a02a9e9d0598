#include "common/mpi_job_runner.hpp"

#include <mpi.h>

#include <algorithm>
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

// The first error of a stage, on rank 0.
struct StageError {
  Ending ending = Ending::kOk;
  std::string message;
  std::exception_ptr local;  // when one of rank 0's own threads threw it
};

class MpiJobRunner final : public JobRunner {
 public:
  MpiJobRunner(int rank, int size, bool threads_serialized)
      : rank_(rank), size_(size), threads_serialized_(threads_serialized) {}

  std::vector<std::string> Run(const JobStage& stage) override {
    DemandValidStage(stage);
    return rank_ == 0 ? Coordinate(stage) : Work(stage);
  }
  bool writes_outputs() const override { return rank_ == 0; }

 private:
  // Rank 0: hands out the jobs to its own threads and to the other ranks' requests, keeps the
  // results, then sends them (or the first error) to every rank.
  std::vector<std::string> Coordinate(const JobStage& stage) {
    StageResults results(stage, resume_folder());
    const std::vector<int>& todo = results.todo();
    std::mutex mutex;
    size_t next = 0;
    StageError error;
    const auto take = [&]() -> int {
      std::lock_guard<std::mutex> lock(mutex);
      return error.ending != Ending::kOk || next >= todo.size() ? -1 : todo[next++];
    };
    const auto fail = [&](Ending ending, std::string message, std::exception_ptr local) {
      std::lock_guard<std::mutex> lock(mutex);
      if (error.ending == Ending::kOk) error = {ending, std::move(message), std::move(local)};
    };
    const auto guarded = [&](const std::function<void()>& f) {
      try {
        f();
      } catch (const InputError& e) {
        fail(Ending::kInputError, e.what(), std::current_exception());
      } catch (const std::exception& e) {
        fail(Ending::kOtherError, e.what(), std::current_exception());
      }
    };
    std::vector<std::thread> pool;
    const int local_threads = WorkerCount(stage.threads, static_cast<int>(todo.size()));
    for (int t = 0; t < local_threads; ++t) {
      pool.emplace_back([&] {
        for (int i = take(); i >= 0; i = take())
          guarded([&] { results.Add(i, stage.run(i), true); });
      });
    }
    // the other ranks' worker threads: each says hello, then brings a result (or an error)
    // with each request, until it is told that nothing is left.
    std::vector<int> threads_of(static_cast<size_t>(size_), -1),
        retired(static_cast<size_t>(size_));
    int ranks_done = 0;
    auto pause = std::chrono::microseconds(50);
    while (ranks_done < size_ - 1) {
      int flag = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, kTagToRoot, MPI_COMM_WORLD, &flag, &status);
      if (!flag) {
        std::this_thread::sleep_for(pause);
        pause = std::min(pause * 2, std::chrono::microseconds(1000));
        continue;
      }
      pause = std::chrono::microseconds(50);
      int count = 0;
      MPI_Get_count(&status, MPI_BYTE, &count);
      std::string message(static_cast<size_t>(count), '\0');
      const int from = status.MPI_SOURCE;
      MPI_Recv(message.data(), count, MPI_BYTE, from, kTagToRoot, MPI_COMM_WORLD,
               MPI_STATUS_IGNORE);
      guarded([&] {
        ByteReader r(message, "the message of rank " + std::to_string(from));
        const Carries carries = r.EnumValue(Carries::kError);
        const int64_t value = r.IntIn(0, INT_MAX);
        std::string payload = r.String();
        r.Finish();
        if (carries == Carries::kHello) {
          threads_of[static_cast<size_t>(from)] = static_cast<int>(value);
        } else if (carries == Carries::kResult) {
          if (value >= stage.count) throw std::runtime_error("a result for no job");
          results.Add(static_cast<int>(value), std::move(payload), false);
        } else {
          fail(static_cast<Ending>(value), std::move(payload), nullptr);
        }
      });
      const int assigned = take();
      MPI_Request request;
      MPI_Isend(&assigned, 1, MPI_INT, from, kTagAssign, MPI_COMM_WORLD, &request);
      WaitGently(&request);
      if (assigned < 0 &&
          ++retired[static_cast<size_t>(from)] == threads_of[static_cast<size_t>(from)]) {
        ++ranks_done;
      }
    }
    for (std::thread& t : pool) t.join();

    ByteWriter w;
    w.EnumValue(error.ending);
    w.String(error.message);
    std::vector<std::string> all;
    if (error.ending == Ending::kOk) {
      all = results.Take();
      w.UInt(all.size());
      for (const std::string& r : all) w.String(r);
    }
    std::string bytes = w.Take();
    Broadcast(&bytes);
    if (error.local) std::rethrow_exception(error.local);
    Rethrow(error.ending, error.message);
    return all;
  }

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

  static void Rethrow(Ending ending, const std::string& message) {
    if (ending == Ending::kInputError) throw InputError(message);
    if (ending == Ending::kOtherError) throw std::runtime_error(message);
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
