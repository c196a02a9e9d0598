#pragma once

/// @file
/// Where a stage's independent jobs run, and how a long run survives being killed.
///
/// A stage is a list of independent jobs (a grasp to synthesize and validate, an orientation's
/// demonstrations to score, a demonstration to record), each of which returns its result as
/// bytes (common/byte_codec.hpp). A JobRunner runs them: on this process's threads
/// (LocalJobRunner), or spread over the processes of an MPI job (common/mpi_job_runner.hpp).
/// Either way every process gets every result back, in index order, and goes on with the same
/// values; only one process (writes_outputs()) writes files. A job's result never depends on
/// where it ran (its random streams come from its own seed), so the results are the same bytes
/// for any number of processes and threads.
///
/// With a ResumeFolder, each finished job is written to the folder as it comes in (atomically),
/// and a run started again with resume on takes the finished jobs from there and runs only the
/// others. The folder's identity (the build of the program, the command, its arguments and the
/// fingerprints of its input files) must match the new run's, or the resume is refused naming
/// what differs. A kept job is taken only when everything about it checks out (its file's
/// wrapper, its payload's checksum, layout and build, and the stage's own decoding of it);
/// otherwise it runs again and is counted as recomputed.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace graspsynth {

/// Marks the exception that JobRunner::Run throws on every process of an MPI job when a stage
/// failed: an InputError or a std::runtime_error with the message of the error the stage met,
/// so that every process goes the same way. Each process then ends by itself (none needs to end
/// the others, as MPI_Abort would: it raced with their MPI_Finalize and could leave mpirun
/// waiting for ever).
class StageFailedEverywhere {
 public:
  virtual ~StageFailedEverywhere() = default;
};

/// A StageFailedEverywhere on the processes that do not write the outputs: the process that
/// does reports the error, the others need not.
class StageFailedElsewhere : public StageFailedEverywhere {};

/// A stage of independent jobs.
struct JobStage {
  /// Names the stage in the resume folder and in messages, e.g. "synthesis"; letters, digits,
  /// '-' and '_' only. Each stage of one run has its own name.
  std::string name;
  int count = 0;    ///< jobs, numbered 0..count-1
  int threads = 1;  ///< worker threads of each process (0: one per core)
  /// Runs job i and returns its result as bytes. Called on any process and any worker thread;
  /// an exception stops the stage and is rethrown by JobRunner::Run on every process.
  std::function<std::string(int)> run;
  /// Called on the process that writes the outputs, one call at a time, when job i's result
  /// is in: `here` is true when one of its own threads ran it (and counted the job's own
  /// progress), false for a job run elsewhere or taken from the resume folder. May be empty.
  std::function<void(int i, bool here)> finished;
  /// The layout of a result's bytes, e.g. "study-row/1", kept with each result in the resume
  /// folder: a kept result of another layout runs again. Change it with the layout.
  std::string payload;
  /// Decodes job i's result kept in the resume folder and throws InputError when its bytes are
  /// not a result of that job (it then runs again). May be empty (every kept result is taken).
  std::function<void(int i, std::string_view bytes)> check;
};

/// What identifies a run for --resume: the command, and every argument and input (as a
/// fingerprint, common/byte_codec.hpp's Fingerprint) that can change a result, in a fixed order.
struct RunIdentity {
  std::string command;
  std::vector<std::pair<std::string, std::string>> fields;  ///< (name, value)

  /// Adds (name, value).
  RunIdentity& Add(std::string name, std::string value) {
    fields.emplace_back(std::move(name), std::move(value));
    return *this;
  }
  /// Adds (name, the fingerprint of the file at `path`, or of every file below it when it is a
  /// folder, in name order). Throws InputError naming the path when it cannot be read.
  RunIdentity& AddFile(std::string name, const std::filesystem::path& path);
};

/// What a resumed run did with the jobs its folder kept.
struct ResumeSummary {
  int taken = 0;       ///< kept jobs taken as they were
  int recomputed = 0;  ///< kept jobs that did not check out and ran again
  /// Why, for the first few recomputed jobs ("synthesis/3.job: the result's checksum ...").
  std::vector<std::string> reasons;
};

/// The finished jobs of a run, kept in a folder so that the run can be resumed (see the file
/// comment). Files: `run.json` (the build and the identity) and `<stage>/<index>.job` (a
/// result, with its build, its layout and its checksum).
class ResumeFolder {
 public:
  /// Opens `folder` for the run `identity`. Without `resume`, starts afresh: whatever an
  /// earlier run left there is removed. With `resume`, keeps the finished jobs of the earlier
  /// run after checking that it was made by this build of the program (BuildId()) with this
  /// identity; throws InputError naming the folder and the first field that differs (with both
  /// values), and leaves the folder as it was. A folder that does not exist holds no finished
  /// job (the run starts afresh and `resumed()` says so).
  ResumeFolder(std::filesystem::path folder, const RunIdentity& identity, bool resume);

  /// The result of job `index` of `stage` that an earlier run finished, if any, when its file
  /// is whole, made by this build, for this stage and job, of the stage's payload layout, with
  /// its checksum, and `stage.check` decodes it; otherwise std::nullopt (the job runs again,
  /// and a file that was there is counted in summary() as recomputed, with the reason).
  std::optional<std::string> Load(const JobStage& stage, int index) const;
  /// Keeps the result of job `index` of `stage` (atomically).
  void Save(const JobStage& stage, int index, std::string_view bytes) const;
  /// The kept jobs taken and recomputed so far.
  ResumeSummary summary() const;
  /// The run is over and its outputs are written: removes the folder.
  void Remove() const;

  const std::filesystem::path& folder() const { return folder_; }
  /// Whether an earlier run's folder was found and kept.
  bool resumed() const { return resumed_; }

 private:
  std::filesystem::path JobPath(const std::string& stage, int index) const;

  std::filesystem::path folder_;
  bool resumed_ = false;
  mutable std::mutex mutex_;
  mutable ResumeSummary summary_;
};

/// A job file of a resume folder (`<stage>/<index>.job`): the format tag, the build that made
/// it, the stage's name, the job's index, its result's layout, a checksum of the result and the
/// result's bytes.
struct JobFile {
  std::string build;  ///< BuildId() of the program that wrote it
  std::string stage;
  int64_t index = 0;
  std::string payload;  ///< JobStage::payload
  std::string result;
};

/// The bytes of `job` as a job file (with the checksum of its result), and back. ParseJobFile
/// throws InputError naming `source` for bytes that are not a job file or whose result does not
/// match its checksum.
std::string JobFileBytes(const JobFile& job);
JobFile ParseJobFile(std::string_view bytes, const std::string& source);

/// Runs stages of independent jobs (see the file comment).
class JobRunner {
 public:
  virtual ~JobRunner() = default;

  /// Runs every job of `stage` not already in the resume folder and returns every result, in
  /// index order, on every process. Every process calls Run for the same stages in the same
  /// order.
  virtual std::vector<std::string> Run(const JobStage& stage) = 0;
  /// Whether this process writes the outputs and reports progress (the only process, or the
  /// first of an MPI job).
  virtual bool writes_outputs() const { return true; }

  /// Keeps finished jobs in `folder` from now on (nullptr: nowhere). Not owned.
  void set_resume_folder(const ResumeFolder* folder) { resume_ = folder; }
  const ResumeFolder* resume_folder() const { return resume_; }

 private:
  const ResumeFolder* resume_ = nullptr;
};

/// Runs a stage's jobs on this process's threads (ParallelFor).
class LocalJobRunner final : public JobRunner {
 public:
  std::vector<std::string> Run(const JobStage& stage) override;
};

/// The results of one stage on the process that gathers them: takes the finished jobs from the
/// resume folder, keeps each new result (in the folder too) and calls the stage's `finished`,
/// one result at a time whatever thread brings it. Shared by the runners.
class StageResults {
 public:
  StageResults(const JobStage& stage, const ResumeFolder* resume);

  /// The jobs still to run, in index order.
  const std::vector<int>& todo() const { return todo_; }
  /// Job i's result is in (thread-safe).
  void Add(int i, std::string bytes, bool here);
  /// Every result, in index order (once every job of todo() was added).
  std::vector<std::string> Take() { return std::move(results_); }

 private:
  void Keep(int i, std::string bytes, bool here, bool save);

  const JobStage& stage_;
  const ResumeFolder* resume_;
  std::vector<std::string> results_;
  std::vector<int> todo_;
  std::mutex mutex_;
};

/// The build of this program, for resume folders: "graspsynth <version>, build <16 hex
/// digits>", the version and the 64-bit FNV-1a fingerprint of the file that holds this code
/// (the executable, or the Python module), read once; any rebuild that changes the code is
/// another build. The version alone when that file cannot be read.
std::string_view BuildId();

/// Demands (GS_DEMAND) a valid stage: a name of letters, digits, '-' and '_', count >= 0 and a
/// job function. Stages are made by the code, never from input.
void DemandValidStage(const JobStage& stage);

}  // namespace graspsynth
