#pragma once

/// @file
/// A synthesis table's row (StudyRow) as bytes, for the job runner (common/job_runner.hpp): a
/// row synthesized by another process of an MPI job, or kept in a resume folder, comes back as
/// the same values, every number to the bit.

#include <string>
#include <string_view>

#include "studies/study.hpp"

namespace graspsynth {

/// The bytes of `row`: its field list (studies/study_fields.hpp) through common/field_codec.hpp.
std::string EncodeStudyRow(const StudyRow& row);

/// The layout of EncodeStudyRow's bytes, kept with them in resume folders; change it with the
/// layout.
/// study-row/2: study-row/1 with the nominal hold's margin (hold_margin, hold_margin_shortfall)
/// after nominal_hold and the MuJoCo sweep's summary (an optional) after the sensitivity table.
inline constexpr const char* kStudyRowLayout = "study-row/2";

/// The row EncodeStudyRow wrote. Throws InputError naming `source` for bytes that are not one.
StudyRow DecodeStudyRow(std::string_view bytes, const std::string& source);

}  // namespace graspsynth
