#include "simulation/trial_record.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "common/errors.hpp"
#include "kinematics/pose_math.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/simulation_fixtures.hpp"
#include "tests/utils/test_folder.hpp"

namespace graspsynth {
namespace {

using testing::ExampleTrajectory;
using testing::HandKeptOpen;
using ::testing::HasSubstr;
using testing::ShippedSimulationModel;

// A small record with every kind of field: two frames, contacts in the second.
TrialRecord SmallRecord() {
  TrialRecord r;
  r.trajectory = "grasp.json";
  r.theta_deg = 65.0;
  r.object_xy = Eigen::Vector2d(-0.3, 0.9);
  r.record_interval = 0.01;
  r.outcome = TrialOutcome::kDropped;
  r.reason = "object slipped or dropped: lifted up to 25.9 mm, 25.9 mm at the end";
  r.lift = 0.0259;
  r.max_lift = 0.02591;
  r.simulated_time = 9.232;
  for (int k = 0; k < 2; ++k) {
    TrialRecordFrame f;
    f.t = 0.01 * k;
    for (int i = 0; i < kArmDof; ++i) f.arm[i] = 0.1 * i + k;
    for (int i = 0; i < kHandDof; ++i) f.hand[i] = 0.05 * i - 0.2 * k;
    f.p_WO = Eigen::Vector3d(-0.3, 0.9, 0.025 + 0.001 * k);
    f.q_WO = Eigen::Quaterniond(Eigen::AngleAxisd(0.3 + k, Eigen::Vector3d(1, 2, 3).normalized()));
    if (k == 1) {
      f.contacts.push_back({Eigen::Vector3d(-0.31, 0.88, 0.04), 2.5, 3});
      f.contacts.push_back({Eigen::Vector3d(-0.29, 0.87, 0.05), 0.0, 20});
    }
    r.frames.push_back(f);
  }
  return r;
}

TrialRecord Parse(const std::string& text) {
  return ReadTrialRecord(JsonReader::Parse(text, "trial.json"));
}

// The record's text with the first occurrence of `from` replaced by `to`.
std::string Edited(const std::string& from, const std::string& to) {
  std::string text = TrialRecordToJson(SmallRecord());
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(TrialRecord, RoundTripsThroughItsJson) {
  const TrialRecord a = SmallRecord();
  const std::string text = TrialRecordToJson(a);
  EXPECT_THAT(text, HasSubstr("\"format\": \"graspsynth-trial-record/1\""));
  EXPECT_THAT(text, HasSubstr("\"outcome\": \"dropped\""));
  const TrialRecord b = Parse(text);
  EXPECT_EQ(b.trajectory, a.trajectory);
  EXPECT_EQ(b.theta_deg, a.theta_deg);
  ASSERT_TRUE(b.object_xy.has_value());
  EXPECT_EQ(*b.object_xy, *a.object_xy);
  EXPECT_EQ(b.record_interval, a.record_interval);
  EXPECT_EQ(b.outcome, a.outcome);
  EXPECT_EQ(b.reason, a.reason);
  EXPECT_EQ(b.lift, a.lift);
  EXPECT_EQ(b.simulated_time, a.simulated_time);
  ASSERT_EQ(b.frames.size(), a.frames.size());
  for (size_t k = 0; k < a.frames.size(); ++k) {
    const TrialRecordFrame& fa = a.frames[k];
    const TrialRecordFrame& fb = b.frames[k];
    EXPECT_EQ(fb.t, fa.t);
    EXPECT_LE((fb.arm - fa.arm).cwiseAbs().maxCoeff(), 5e-7);
    EXPECT_LE((fb.hand - fa.hand).cwiseAbs().maxCoeff(), 5e-7);
    EXPECT_LE((fb.p_WO - fa.p_WO).norm(), 1e-6);
    EXPECT_LE(fb.q_WO.angularDistance(fa.q_WO), 1e-5);
    ASSERT_EQ(fb.contacts.size(), fa.contacts.size());
    for (size_t c = 0; c < fa.contacts.size(); ++c) {
      EXPECT_LE((fb.contacts[c].p_WC - fa.contacts[c].p_WC).norm(), 1e-6);
      EXPECT_EQ(fb.contacts[c].force, fa.contacts[c].force);
      EXPECT_EQ(fb.contacts[c].hand_link, fa.contacts[c].hand_link);
    }
  }
  // written again, the same bytes.
  EXPECT_EQ(TrialRecordToJson(b), text);
  // one frame per line.
  EXPECT_THAT(text, HasSubstr("\n  {\"t\":0.01,"));
}

TEST(TrialRecord, LeavesOutAnObjectXyItDoesNotHave) {
  TrialRecord a = SmallRecord();
  a.object_xy.reset();
  const std::string text = TrialRecordToJson(a);
  EXPECT_THAT(text, ::testing::Not(HasSubstr("object_xy")));
  EXPECT_FALSE(Parse(text).object_xy.has_value());
}

TEST(TrialRecord, WritesAtomicallyAndLoads) {
  const testing::TestFolder dir;
  const auto path = dir.path() / "trial.json";
  WriteTrialRecord(path, SmallRecord());
  EXPECT_EQ(LoadTrialRecord(path).frames.size(), 2u);
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().filename(), "trial.json");  // no temporary left
  }
  GS_EXPECT_THROW_WITH(LoadTrialRecord(dir.path() / "none.json"), InputError, "none.json");
}

TEST(TrialRecord, RefusesBadInputNamingTheField) {
  GS_EXPECT_THROW_WITH(Parse(Edited("graspsynth-trial-record/1", "graspsynth-trajectory/1")),
                       InputError, "trial.json", "format", "graspsynth-trial-record/1",
                       "graspsynth-trajectory/1");
  GS_EXPECT_THROW_WITH(Parse(Edited("\"outcome\": \"dropped\"", "\"outcome\": \"fell\"")),
                       InputError, "field 'outcome'", "one of success, not_lifted", "\"fell\"");
  GS_EXPECT_THROW_WITH(Parse(Edited(" \"reason\"", " \"colour\": 1,\n \"reason\"")), InputError,
                       "field 'colour'", "only the fields");
  GS_EXPECT_THROW_WITH(Parse(Edited(" \"lift_m\": 0.0259,\n", "")), InputError, "field 'lift_m'",
                       "found nothing");
  GS_EXPECT_THROW_WITH(Parse(Edited("\"record_interval_s\": 0.01", "\"record_interval_s\": 0")),
                       InputError, "field 'record_interval_s'", "> 0");
  GS_EXPECT_THROW_WITH(Parse(Edited("{\"t\":0.01,", "{\"t\":0,")), InputError,
                       "field 'frames[1].t'", "a time after");
  GS_EXPECT_THROW_WITH(Parse(Edited("\"arm\":[0.0,", "\"arm\":[")), InputError,
                       "field 'frames[0].arm'", "7");
  GS_EXPECT_THROW_WITH(Parse(Edited("\"object_quaternion\":[", "\"object_quaternion\":[0.5,")),
                       InputError, "frames[0].object_quaternion");
  GS_EXPECT_THROW_WITH(Parse(Edited("\"f\":2.5", "\"f\":\"strong\"")), InputError,
                       "field 'frames[1].contacts[0].f'", "\"strong\"");
  GS_EXPECT_THROW_WITH(Parse(Edited("\"link\":3", "\"link\":3.5")), InputError,
                       "frames[1].contacts[0].link");
  TrialRecord empty = SmallRecord();
  empty.frames.clear();
  GS_EXPECT_THROW_WITH(Parse(TrialRecordToJson(empty)), InputError, "field 'frames'",
                       "at least one frame");
  GS_EXPECT_THROW_WITH(Parse("[1, 2]"), InputError, "trial.json");
}

// The shipped example grasp, recorded: the frames follow the physics (the object lifted at
// the end, contacts with force while it is held), and observing the trial changes nothing.
TEST(TrialRecord, RecordsTheTrialAsSimulated) {
  const SimulationModel& model = ShippedSimulationModel();
  TrialOptions options;
  options.record_interval = 1.0 / 30.0;
  const RecordedTrial recorded = RunRecordedTrial(model, ExampleTrajectory(), options, "ex.json");
  const TrialResult plain = RunTrial(model, ExampleTrajectory(), options);
  EXPECT_EQ(recorded.result.outcome, plain.outcome);
  EXPECT_EQ(recorded.result.lift, plain.lift);
  EXPECT_EQ(recorded.result.simulated_time, plain.simulated_time);

  const TrialRecord& r = recorded.record;
  ASSERT_TRUE(r.success()) << r.reason;
  EXPECT_EQ(r.reason, plain.reason);
  EXPECT_EQ(r.trajectory, "ex.json");
  EXPECT_EQ(r.frames.size(), plain.states.size());
  const double rest_z = r.frames.front().p_WO.z();
  EXPECT_GT(r.frames.back().p_WO.z(), rest_z + 0.05);
  EXPECT_NEAR(r.frames.back().p_WO.z() - rest_z, r.lift, 1e-3);
  EXPECT_TRUE(r.frames.front().contacts.empty());
  int loaded = 0;
  for (const TrialRecordFrame& f : r.frames) {
    double force = 0.0;
    for (const RecordedContact& c : f.contacts) force += c.force;
    if (f.p_WO.z() > rest_z + 0.05 && force > 0.0) ++loaded;
  }
  EXPECT_GT(loaded, 5);  // held by contacts that carry it
  for (const TrialRecordFrame& f : r.frames) {
    for (const RecordedContact& c : f.contacts) {
      EXPECT_LT((c.p_WC - f.p_WO).norm(), 0.5);  // on the object, not elsewhere
    }
  }
  // and a grasp that cannot hold: the object never leaves the table.
  const RecordedTrial open = RunRecordedTrial(model, HandKeptOpen(), options, "open.json");
  EXPECT_FALSE(open.record.success());
  EXPECT_LT(open.record.frames.back().p_WO.z(), rest_z + 0.05);
}

}  // namespace
}  // namespace graspsynth
