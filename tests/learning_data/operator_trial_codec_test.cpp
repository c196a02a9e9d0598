// Tests of the bytes of a synthetic operator's trial (learning_data/synthetic_operator.hpp), the
// job result of `graspsynth demos generate`: a trial comes back with every field, to the bit, so
// that the logs are the same bytes whichever process made the trial; the layout is kept; bytes
// cut anywhere, or with more after them, are an InputError.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/byte_codec.hpp"
#include "common/errors.hpp"
#include "learning_data/synthetic_operator.hpp"

namespace graspsynth {
namespace {

// A trial with every optional set and numbers that a rounding would change.
OperatorTrial FullTrial() {
  OperatorTrial t;
  t.position = Eigen::Vector2d(-0.3 + 1e-17, 0.85);
  t.theta_deg = 45.0 + 1e-13;
  t.index = 3;
  t.strategy = 1;
  t.sloppy = true;
  t.success = false;
  t.outcome = TrialOutcome::kTilted;
  t.reason = "the pan tilted 31 deg";
  t.attempts = 2;
  DemoLog& log = t.log;
  log.source = "x-0300_y+0850_theta045_trial03.csv";
  log.metadata.theta_deg = 45.0;
  log.metadata.object_position = Eigen::Vector3d(-0.3, 0.85, 0.761);
  log.metadata.trial = "3";
  log.metadata.operator_name = "synthetic";
  log.metadata.sample_rate_hz = 60.0;
  log.metadata.extra = {{"strategy", "radial"}, {"note", "a, \"quoted\" value"}};
  for (int k = 0; k < 3; ++k) {
    DemoSample s;
    s.t = k / 60.0;
    s.p_WH = Eigen::Vector3d(0.1 * k, 0.7, 1.0 - 1e-3 * k);
    s.q_WH = Eigen::Quaterniond(0.9, 0.1 * k, -0.2, 0.3);
    for (int i = 0; i < s.f.size(); ++i) s.f[i] = 0.01 * i * k;
    s.event = k == 1 ? DemoEvent::kGrasp : k == 2 ? DemoEvent::kEnd : DemoEvent::kNone;
    s.p_WO = Eigen::Vector3d(-0.3, 0.85, 0.761 + 0.01 * k);
    log.samples.push_back(s);
  }
  return t;
}

TEST(OperatorTrialCodec, ATrialComesBackWithEveryField) {
  const OperatorTrial trial = FullTrial();
  const std::string bytes = EncodeOperatorTrial(trial);
  const OperatorTrial back = DecodeOperatorTrial(bytes, "test");
  EXPECT_EQ(EncodeOperatorTrial(back), bytes);
  ASSERT_TRUE(back.position.has_value());
  EXPECT_EQ(back.position->x(), -0.3 + 1e-17);
  EXPECT_EQ(back.theta_deg, 45.0 + 1e-13);
  EXPECT_EQ(back.outcome, TrialOutcome::kTilted);
  EXPECT_EQ(back.attempts, 2);
  EXPECT_EQ(back.log.metadata.extra, trial.log.metadata.extra);
  EXPECT_EQ(back.log.metadata.operator_name, "synthetic");
  ASSERT_EQ(back.log.samples.size(), 3u);
  EXPECT_EQ(back.log.samples[2].q_WH.coeffs(), trial.log.samples[2].q_WH.coeffs());
  EXPECT_EQ(back.log.samples[1].event, DemoEvent::kGrasp);
  EXPECT_EQ(back.log.samples[2].f, trial.log.samples[2].f);

  // a trial the arm could not execute: unset optionals come back unset.
  OperatorTrial bare;
  bare.theta_deg = 60.0;
  const OperatorTrial bare_back = DecodeOperatorTrial(EncodeOperatorTrial(bare), "test");
  EXPECT_FALSE(bare_back.position || bare_back.outcome || bare_back.log.metadata.trial ||
               bare_back.log.metadata.sample_rate_hz);
  EXPECT_TRUE(bare_back.log.samples.empty());
}

// The bytes of FullTrial() as the hand-written codec of operator-trial/1 wrote them
// (fingerprinted): the layout is kept, so resume folders of earlier builds still read.
TEST(OperatorTrialCodec, TheLayoutIsOperatorTrial1) {
  EXPECT_STREQ(kOperatorTrialLayout, "operator-trial/1");
  EXPECT_EQ(Fingerprint(EncodeOperatorTrial(FullTrial())), "3a49a9559845912c");
}

TEST(OperatorTrialCodec, BytesCutAnywhereOrWithMoreAreAnError) {
  const std::string bytes = EncodeOperatorTrial(FullTrial());
  for (size_t n = 0; n < bytes.size(); n += 5) {
    EXPECT_THROW(DecodeOperatorTrial(bytes.substr(0, n), "cut"), InputError) << n << " bytes";
  }
  EXPECT_THROW(DecodeOperatorTrial(bytes + "x", "longer"), InputError);
  // an event outside DemoEvent's values.
  OperatorTrial one_sample = FullTrial();
  one_sample.log.samples.resize(1);
  one_sample.log.samples[0].event = static_cast<DemoEvent>(7);
  EXPECT_THROW(DecodeOperatorTrial(EncodeOperatorTrial(one_sample), "event"), InputError);
}

}  // namespace
}  // namespace graspsynth
