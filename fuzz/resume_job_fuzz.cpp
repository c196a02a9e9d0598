// Job files of a resume folder (common/job_runner.hpp) and the job results in them, as --resume
// reads them: the file's wrapper and checksum (ParseJobFile), then its result by the file's
// stage, a synthesis table's row (studies/study_codec.hpp) or a synthetic operator's trial
// (learning_data/synthetic_operator.hpp). The input is also decoded as a bare result of each
// kind, since random bytes rarely carry a right checksum.
#include "common/job_runner.hpp"
#include "fuzz/fuzz_support.hpp"
#include "learning_data/synthetic_operator.hpp"
#include "studies/study_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth;
  const std::string_view bytes = fuzz::AsText(data, size);
  fuzz::RefusedOnlyWithInputError([&] {
    const JobFile job = ParseJobFile(bytes, "fuzz.job");
    if (job.stage == "demos") {
      DecodeOperatorTrial(job.result, "fuzz.job");
    } else {
      DecodeStudyRow(job.result, "fuzz.job");
    }
  });
  fuzz::RefusedOnlyWithInputError([&] { DecodeStudyRow(bytes, "fuzz row"); });
  fuzz::RefusedOnlyWithInputError([&] { DecodeOperatorTrial(bytes, "fuzz trial"); });
  return 0;
}
