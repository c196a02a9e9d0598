// Tests of studies/study_codec.hpp: a synthesis table's row comes back from its bytes with every
// field, so that the study's files are the same bytes whichever process made the row; and bytes
// cut anywhere are an InputError.

#include "studies/study_codec.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "common/byte_codec.hpp"
#include "common/errors.hpp"
#include "studies/study_report.hpp"
#include "tests/utils/study_rows.hpp"

namespace graspsynth {
namespace {

using testing::FullRow;

TEST(StudyCodec, ARowComesBackWithEveryField) {
  const StudyRow row = FullRow();
  const std::string bytes = EncodeStudyRow(row);
  const StudyRow back = DecodeStudyRow(bytes, "test");
  EXPECT_EQ(EncodeStudyRow(back), bytes);
  EXPECT_EQ(back.at->y(), 0.87 + 1e-17);
  EXPECT_EQ(back.used, SynthesisMethod::kNearest);
  EXPECT_EQ(back.fallback_reason.used_placement, "(-0.25, 0.85, 60 deg)");
  EXPECT_EQ(back.nominal_outcome, TrialOutcome::kTilted);
  EXPECT_EQ(back.nominal_hold.load_share, row.nominal_hold.load_share);
  ASSERT_TRUE(back.sensitivity.has_value());
  EXPECT_EQ(back.sensitivity->rows[0].low.physics.variation.object_com_offset.y(), -0.02);
  EXPECT_EQ(back.sensitivity->rows[1].high.physics.time_step, 0.001);
  EXPECT_EQ(back.seed, row.seed);
  ASSERT_TRUE(back.mujoco.has_value());
  EXPECT_EQ(back.mujoco->slip_worst, 0.031);
  EXPECT_EQ(back.mujoco->failing, "pyramidal/soft");
  EXPECT_EQ(back.source_thetas_deg, row.source_thetas_deg);
  // the files made from the row are the same bytes.
  EXPECT_EQ(StudySynthesisCsv({back}), StudySynthesisCsv({row}));

  // a row that did not run: unset optionals come back unset.
  StudyRow bare;
  bare.method = "line";
  const StudyRow bare_back = DecodeStudyRow(EncodeStudyRow(bare), "test");
  EXPECT_FALSE(bare_back.at || bare_back.used || bare_back.status || bare_back.nominal_outcome ||
               bare_back.sensitivity || bare_back.mujoco);
  EXPECT_EQ(StudySynthesisCsv({bare_back}), StudySynthesisCsv({bare}));
}

// The bytes of FullRow() in study-row/2 (fingerprinted): study-row/1 (the hand-written codec's
// layout) with the nominal hold's margin (hold_margin, hold_margin_shortfall) after nominal_hold
// and the MuJoCo sweep's summary after the sensitivity table. A change of the bytes is a change
// of the layout, and resume folders of another layout are refused.
TEST(StudyCodec, TheLayoutIsStudyRow2) {
  EXPECT_STREQ(kStudyRowLayout, "study-row/2");
  EXPECT_EQ(Fingerprint(EncodeStudyRow(FullRow())), "d008fe3af92e2c20");
}

TEST(StudyCodec, BytesCutAnywhereOrWithMoreAreAnError) {
  const std::string bytes = EncodeStudyRow(FullRow());
  for (size_t n = 0; n < bytes.size(); n += 3) {
    EXPECT_THROW(DecodeStudyRow(bytes.substr(0, n), "cut"), InputError) << n << " bytes";
  }
  EXPECT_THROW(DecodeStudyRow(bytes + "x", "longer"), InputError);
}

}  // namespace
}  // namespace graspsynth
