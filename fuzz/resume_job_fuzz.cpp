// Job files of a resume folder (common/job_runner.hpp) and the job results in them: a synthesis
// table's row (solver/study_codec.hpp) or a synthetic operator's trial (learning_data/
// synthetic_operator.hpp), chosen by the file's stage as --resume reads them.
#include "common/job_runner.hpp"
#include "fuzz/fuzz_support.hpp"
#include "learning_data/synthetic_operator.hpp"
#include "solver/study_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth;
  fuzz::RefusedOnlyWithInputError([&] {
    const JobFile job = ParseJobFile(fuzz::AsText(data, size), "fuzz.job");
    if (job.stage == "demos") {
      DecodeOperatorTrial(job.result, "fuzz.job");
    } else {
      DecodeStudyRow(job.result, "fuzz.job");
    }
  });
  return 0;
}
