#include "studies/study_codec.hpp"

#include "common/field_codec.hpp"
#include "studies/study_fields.hpp"

namespace graspsynth {

std::string EncodeStudyRow(const StudyRow& row) { return EncodeFields(row); }

StudyRow DecodeStudyRow(std::string_view bytes, const std::string& source) {
  return DecodeFields<StudyRow>(bytes, source);
}

}  // namespace graspsynth
