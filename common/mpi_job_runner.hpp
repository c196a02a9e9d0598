#pragma once

/// @file
/// The JobRunner of an MPI job (Open MPI; built when GRASPSYNTH_MPI is on, see the README's
/// "Running at scale"). Every process (rank) runs the same command with the same arguments,
/// reads the same inputs and computes the same stages; within a stage the jobs are handed out
/// one at a time, to whichever worker thread of whichever rank asks next (dynamic load
/// balancing: jobs differ in length). Rank 0 hands them out, runs jobs on its own threads as
/// well, keeps every result (and the resume folder), and sends the whole stage's results to
/// every rank at the end of the stage, so that all ranks go on with the same values. Only rank 0
/// writes outputs. MPI stays out of every other header.

#include <memory>

#include "common/job_runner.hpp"

namespace graspsynth {

/// MPI for this process, when it was started as one of an MPI job's processes (mpirun, srun:
/// the environment has OMPI_COMM_WORLD_SIZE, PMIX_RANK or PMI_SIZE); otherwise nothing is
/// initialized and the process is a job of one.
class MpiSession {
 public:
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  /// Ends every process of the job with `code` (after an error on one of them, which the
  /// others would otherwise wait for).
  [[noreturn]] void AbortAll(int code) const;
  /// The runner of this process: an MpiJobRunner for a job of two or more processes, else a
  /// LocalJobRunner.
  std::unique_ptr<JobRunner> MakeRunner() const;

 private:
  bool active_ = false;
  bool threads_serialized_ = false;  // MPI calls may come from any thread, one at a time
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace graspsynth
