#include "learning_data/representative_selection.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "common/errors.hpp"
#include "simulation/random.hpp"
#include "simulation/robustness.hpp"
#include "tests/learning_data/demo_fixtures.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/run_command.hpp"
#include "tests/utils/scripted_demos.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::ReadFileText;
using testing::ScriptedDemoLog;
using testing::ShippedSimulationModel;
using testing::TestFolder;

// The test set: scripted grasps at 40 deg (two shapes), 60 and 80 deg; one that the robot
// cannot play (its first wrist pose 2 m away); one whose object stays on the table.
const std::vector<DemoLog>& TestDemos() {
  static const std::vector<DemoLog> demos = [] {
    const SimulationModel& model = ShippedSimulationModel();
    std::vector<DemoLog> logs;
    logs.push_back(ScriptedDemoLog(model, 40.0, "demo_040_a.csv"));
    ScriptedGraspOptions other;
    other.theta_deg = 40.0;
    other.grasp_radius = 0.13;
    other.approach_duration = 1.3;
    logs.push_back(ScriptedDemoLog(model, other, "demo_040_b.csv"));
    logs.push_back(ScriptedDemoLog(model, 60.0, "demo_060_a.csv"));
    logs.push_back(ScriptedDemoLog(model, 80.0, "demo_080_a.csv"));
    DemoLog unreachable = ScriptedDemoLog(model, 60.0, "demo_060_far.csv");
    unreachable.samples.front().p_WH += Eigen::Vector3d(2.0, 0.0, 0.0);
    logs.push_back(unreachable);
    DemoLog failed = ScriptedDemoLog(model, 80.0, "demo_080_failed.csv");
    for (DemoSample& s : failed.samples) s.p_WO = failed.samples.front().p_WO;
    logs.push_back(failed);
    return logs;
  }();
  return demos;
}

// Every replay of every demonstration (early_stop off), unless `early_stop`.
SelectionOptions SmallOptions(int threads, bool early_stop = false) {
  SelectionOptions o;
  o.robustness.trials = testing::Scaled(4, 2);
  o.robustness.seed = 11;
  o.robustness.threads = threads;
  o.early_stop = early_stop;
  return o;
}

TEST(SelectionOptions, RejectsBadValues) {
  std::string why;
  EXPECT_TRUE(SelectionOptions{}.IsValid(&why)) << why;
  SelectionOptions o;
  o.robustness.trials = 0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THAT(why, ::testing::HasSubstr("perturbations"));
  o = {};
  o.robustness.threads = -1;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THAT(why, ::testing::HasSubstr("threads"));
  o = {};
  o.min_score = 1.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THAT(why, ::testing::HasSubstr("min_score"));
  o = {};
  o.segmentation.region.radius = -1.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THAT(why, ::testing::HasSubstr("segmentation"));
  o = {};
  o.robustness.perturbation.time_scale_min = 0.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THAT(why, ::testing::HasSubstr("perturbation"));
  GS_EXPECT_THROW_WITH(
      SelectRepresentatives(ShippedSimulationModel(), std::vector<DemoLog>{}, "dir", o), InputError,
      "bad selection option");
}

TEST(DemoSeed, DependsOnTheSeedAndTheFileNameOnly) {
  EXPECT_EQ(DemoSeed(1, "demo_040_a.csv"), DemoSeed(1, "demo_040_a.csv"));
  EXPECT_NE(DemoSeed(1, "demo_040_a.csv"), DemoSeed(1, "demo_040_b.csv"));
  EXPECT_NE(DemoSeed(1, "demo_040_a.csv"), DemoSeed(2, "demo_040_a.csv"));
  EXPECT_NE(DemoSeed(1, ""), DemoSeed(2, ""));
  // a fixed function of its inputs: shipped libraries name these seeds, so the value must never
  // change between builds, platforms or releases.
  EXPECT_EQ(DemoSeed(1, "demo_040_a.csv"), 10064076256808515830ull);
  // as documented: stream FNV-1a-64(name) of the seed.
  uint64_t fnv = 0xcbf29ce484222325ull;
  for (const char c : std::string("x.csv"))
    fnv = (fnv ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
  EXPECT_EQ(DemoSeed(9, "x.csv"), SplitMix64::ForStream(9, fnv).Next());
  std::set<uint64_t> seeds;
  for (int i = 0; i < 1000; ++i) seeds.insert(DemoSeed(5, "demo_" + std::to_string(i) + ".csv"));
  EXPECT_EQ(seeds.size(), 1000u);
}

SelectionCandidate Candidate(const std::string& file, int successes, int trials, bool nominal,
                             double duration) {
  SelectionCandidate c;
  c.score.file = file;
  c.score.trials = trials;
  c.score.successes = successes;
  c.score.score = trials > 0 ? double(successes) / trials : 0.0;
  const Interval ci = WilsonInterval(successes, trials);
  c.score.ci_low = ci.lo;
  c.score.ci_high = ci.hi;
  c.score.nominal_success = nominal;
  c.motion_duration = duration;
  return c;
}

TEST(PreferredRepresentative, FollowsTheTieRule) {
  // a higher score wins whatever else.
  EXPECT_TRUE(PreferredRepresentative(Candidate("z.csv", 9, 10, false, 9.0),
                                      Candidate("a.csv", 8, 10, true, 1.0)));
  EXPECT_FALSE(PreferredRepresentative(Candidate("a.csv", 8, 10, true, 1.0),
                                       Candidate("z.csv", 9, 10, false, 9.0)));
  // equal score: the higher Wilson lower bound (more replays).
  EXPECT_TRUE(PreferredRepresentative(Candidate("z.csv", 20, 20, false, 9.0),
                                      Candidate("a.csv", 10, 10, true, 1.0)));
  // then a successful nominal replay.
  EXPECT_TRUE(PreferredRepresentative(Candidate("z.csv", 7, 10, true, 9.0),
                                      Candidate("a.csv", 7, 10, false, 1.0)));
  // then the shorter grasping motion.
  EXPECT_TRUE(PreferredRepresentative(Candidate("z.csv", 7, 10, true, 1.0),
                                      Candidate("a.csv", 7, 10, true, 1.5)));
  // then the file name.
  EXPECT_TRUE(PreferredRepresentative(Candidate("a.csv", 7, 10, true, 1.0),
                                      Candidate("b.csv", 7, 10, true, 1.0)));
  EXPECT_FALSE(PreferredRepresentative(Candidate("b.csv", 7, 10, true, 1.0),
                                       Candidate("a.csv", 7, 10, true, 1.0)));
  // a strict order: nothing is preferred to itself.
  const SelectionCandidate c = Candidate("a.csv", 7, 10, true, 1.0);
  EXPECT_FALSE(PreferredRepresentative(c, c));
  EXPECT_THAT(std::string(kTieRule), ::testing::HasSubstr("highest score"));
}

TEST(SelectRepresentatives, PicksTheMostRobustPerOrientationWhateverTheThreads) {
  const std::vector<DemoLog>& demos = TestDemos();
  const SimulationModel& model = ShippedSimulationModel();
  for (const DemoLog& log : demos) ASSERT_FALSE(log.samples.empty()) << log.source;

  std::vector<std::pair<int, int>> reported;
  const SelectionResult one = SelectRepresentatives(
      model, demos, "demos", SmallOptions(1),
      [&](int done, int total, const std::string&) { reported.emplace_back(done, total); });
  const int n = SmallOptions(1).robustness.trials;
  // 5 successful demonstrations (the failed one is skipped), 1 + n replays each.
  ASSERT_FALSE(reported.empty());
  EXPECT_EQ(reported.back().first, 5 * (n + 1));
  EXPECT_EQ(reported.back().second, 5 * (n + 1));
  for (size_t i = 1; i < reported.size(); ++i) EXPECT_GE(reported[i].first, reported[i - 1].first);

  EXPECT_EQ(one.logs, 6);
  EXPECT_EQ(one.unsuccessful, 1);
  const GraspLibrary& library = one.library;
  EXPECT_EQ(library.seed, 11u);
  EXPECT_EQ(library.perturbations, n);
  EXPECT_EQ(library.demo_directory, "demos");
  EXPECT_EQ(library.tie_rule, std::string(kTieRule));

  // every successful demonstration is scored, by theta then file.
  ASSERT_EQ(library.scores.size(), 5u);
  const std::vector<std::string> files = {"demo_040_a.csv", "demo_040_b.csv", "demo_060_a.csv",
                                          "demo_060_far.csv", "demo_080_a.csv"};
  for (size_t i = 0; i < files.size(); ++i) {
    const DemoScore& s = library.scores[i];
    EXPECT_EQ(s.file, files[i]);
    EXPECT_EQ(s.seed, DemoSeed(11, s.file));
    EXPECT_EQ(s.trial, std::filesystem::path(s.file).stem().string());
    if (s.file == "demo_060_far.csv") {
      EXPECT_EQ(s.score, 0.0);
      EXPECT_EQ(s.trials, 0);
      EXPECT_FALSE(s.selected);
      EXPECT_THAT(s.failures, ::testing::HasSubstr("not replayable"));
      EXPECT_THAT(s.failures, ::testing::HasSubstr("not reachable"));
      continue;
    }
    EXPECT_EQ(s.trials, n);
    EXPECT_EQ(s.score, double(s.successes) / n);
    const Interval ci = WilsonInterval(s.successes, n);
    EXPECT_EQ(s.ci_low, ci.lo);
    EXPECT_EQ(s.ci_high, ci.hi);
    // the scripted grasp works: the demonstration replays and lifts the pan.
    EXPECT_TRUE(s.nominal_success) << s.file;
    EXPECT_GT(s.successes, 0) << s.file << ": " << s.failures;
  }
  ASSERT_EQ(one.issues.size(), 1u);
  EXPECT_EQ(one.issues[0].file, "demo_060_far.csv");
  EXPECT_EQ(one.issues[0].kind, SelectionIssueKind::kNotReplayable);

  // one entry per orientation: the candidate preferred by the tie rule.
  ASSERT_EQ(library.entries.size(), 3u);
  EXPECT_TRUE(one.unselected_thetas.empty());
  std::map<double, std::vector<SelectionCandidate>> by_theta;
  for (const DemoScore& s : library.scores) {
    const auto log = std::find_if(demos.begin(), demos.end(),
                                  [&](const DemoLog& l) { return l.source == s.file; });
    ASSERT_NE(log, demos.end());
    by_theta[s.theta_deg].push_back({s, Segment(*log, {}).motion.duration()});
  }
  size_t e = 0;
  for (const auto& [theta, candidates] : by_theta) {
    ASSERT_LT(e, library.entries.size());
    const LibraryEntry& entry = library.entries[e++];
    EXPECT_EQ(entry.theta_deg, theta);
    int selected = 0;
    for (const SelectionCandidate& c : candidates) {
      if (c.score.file == entry.file) {
        EXPECT_TRUE(c.score.selected);
        EXPECT_EQ(entry.score, c.score.score);
        ++selected;
      } else {
        EXPECT_FALSE(c.score.selected);
        const auto chosen = std::find_if(candidates.begin(), candidates.end(),
                                         [&](const auto& x) { return x.score.file == entry.file; });
        EXPECT_TRUE(PreferredRepresentative(*chosen, c)) << entry.file << " vs " << c.score.file;
        EXPECT_GE(entry.score, c.score.score);
      }
    }
    EXPECT_EQ(selected, 1) << theta;
    // the entry's motion is the segmentation's, the lift the operator's (scripted: 10 cm over
    // the settle, lift and end phases: 0.3 + 1.0 + 0.2 s).
    const auto log = std::find_if(demos.begin(), demos.end(),
                                  [&](const DemoLog& l) { return l.source == entry.file; });
    const SegmentedTrial seg = Segment(*log, {});
    ASSERT_EQ(entry.motion.waypoints.size(), seg.motion.waypoints.size());
    EXPECT_EQ(entry.motion.grasp().t, seg.motion.grasp().t);
    EXPECT_TRUE(entry.motion.grasp().p_WH == seg.motion.grasp().p_WH);
    EXPECT_EQ(entry.trial, std::filesystem::path(entry.file).stem().string());
    EXPECT_NEAR(entry.lift_height, 0.10, 2e-3);
    EXPECT_NEAR(entry.lift_duration, 1.5, 0.05);
  }

  // two threads and the logs in the reverse order: the same library, byte for byte.
  const std::vector<DemoLog> reversed(demos.rbegin(), demos.rend());
  const SelectionResult two = SelectRepresentatives(model, reversed, "demos", SmallOptions(2));
  const TestFolder folder;
  WriteGraspLibrary(one.library, folder.path() / "one.json");
  WriteGraspLibrary(two.library, folder.path() / "two.json");
  EXPECT_EQ(ReadFileText(folder.path() / "one.json"), ReadFileText(folder.path() / "two.json"));
}

TEST(SelectRepresentatives, EarlyStopKeepsTheRepresentativesAndTheirScores) {
  // a third 40 deg demonstration, gripping 5 cm further out (its replays fail more often).
  const SimulationModel& model = ShippedSimulationModel();
  std::vector<DemoLog> demos = TestDemos();
  ScriptedGraspOptions off;
  off.theta_deg = 40.0;
  off.grasp_radius = 0.18;
  demos.push_back(ScriptedDemoLog(model, off, "demo_040_off.csv"));
  const int n = SmallOptions(1).robustness.trials;
  const SelectionResult all = SelectRepresentatives(model, demos, "demos", SmallOptions(2));
  std::vector<std::pair<int, int>> reported;
  const SelectionResult early = SelectRepresentatives(
      model, demos, "demos", SmallOptions(1, true),
      [&](int done, int total, const std::string&) { reported.emplace_back(done, total); });

  // the same entries, the representatives' scores and every nominal replay the same.
  const TestFolder folder;
  GraspLibrary entries_only = all.library;
  entries_only.scores.clear();
  WriteGraspLibrary(entries_only, folder.path() / "all.json");
  entries_only.entries = early.library.entries;
  WriteGraspLibrary(entries_only, folder.path() / "early.json");
  EXPECT_EQ(ReadFileText(folder.path() / "all.json"), ReadFileText(folder.path() / "early.json"));
  ASSERT_EQ(all.library.scores.size(), early.library.scores.size());
  std::map<double, const DemoScore*> selected;
  for (const DemoScore& s : early.library.scores) {
    if (s.selected) selected[s.theta_deg] = &s;
  }
  int stopped = 0;
  for (size_t i = 0; i < all.library.scores.size(); ++i) {
    const DemoScore& a = all.library.scores[i];
    const DemoScore& e = early.library.scores[i];
    SCOPED_TRACE(a.file);
    ASSERT_EQ(a.file, e.file);
    EXPECT_EQ(a.selected, e.selected);
    EXPECT_EQ(a.nominal_success, e.nominal_success);
    EXPECT_TRUE(a.stopped.empty());
    if (e.stopped.empty()) {
      // scored in full: the same replays, the same figures.
      EXPECT_EQ(a.trials, e.trials);
      EXPECT_EQ(a.successes, e.successes);
      EXPECT_EQ(a.failures, e.failures);
      continue;
    }
    // stopped: fewer replays, the first ones of the full evaluation (the same stream), and
    // too many failures among them to win over its orientation's representative.
    ++stopped;
    EXPECT_LT(e.trials, n);
    EXPECT_FALSE(e.selected);
    EXPECT_LE(e.successes, a.successes);
    const DemoScore& winner = *selected.at(e.theta_deg);
    EXPECT_LE(n - (e.trials - e.successes), winner.successes);
    EXPECT_THAT(e.stopped, ::testing::HasSubstr(winner.file));
  }
  EXPECT_GE(stopped, 1) << "the off-handle demonstration should stop early";
  EXPECT_EQ(reported.back(), std::make_pair(6 * (n + 1), 6 * (n + 1)));

  // the early-stopped library is the same bytes whatever the thread count.
  const SelectionResult two = SelectRepresentatives(model, demos, "demos", SmallOptions(2, true));
  WriteGraspLibrary(early.library, folder.path() / "one.json");
  WriteGraspLibrary(two.library, folder.path() / "two.json");
  EXPECT_EQ(ReadFileText(folder.path() / "one.json"), ReadFileText(folder.path() / "two.json"));
  // and reads back with its `stopped` reasons.
  const GraspLibrary back = ReadGraspLibrary(folder.path() / "one.json");
  ASSERT_EQ(back.scores.size(), early.library.scores.size());
  for (size_t i = 0; i < back.scores.size(); ++i) {
    EXPECT_EQ(back.scores[i].stopped, early.library.scores[i].stopped);
  }
}

TEST(SelectRepresentatives, AnOrientationWithoutASuccessfulReplayHasNoEntry) {
  // only the unreachable demonstration: scored 0, nothing selected.
  const std::vector<DemoLog> demos = {TestDemos()[4]};
  const SelectionResult r =
      SelectRepresentatives(ShippedSimulationModel(), demos, "demos", SmallOptions(1));
  ASSERT_EQ(r.library.scores.size(), 1u);
  EXPECT_EQ(r.library.scores[0].score, 0.0);
  EXPECT_TRUE(r.library.entries.empty());
  EXPECT_EQ(r.unselected_thetas, std::vector<double>{60.0});
}

TEST(SelectRepresentatives, RefusesTwoLogsWithTheSameFileName) {
  std::vector<DemoLog> demos = {TestDemos()[0], TestDemos()[0]};
  demos[1].source = "other/" + demos[1].source;
  GS_EXPECT_THROW_WITH(
      SelectRepresentatives(ShippedSimulationModel(), demos, "demos", SmallOptions(1)), InputError,
      "same file name 'demo_040_a.csv'");
}

TEST(SelectRepresentatives, ReadsAFolderAndReportsItsBadFiles) {
  const TestFolder folder;
  WriteDemoLog(folder.path() / "demo_060_a.csv", TestDemos()[2]);
  WriteDemoLog(folder.path() / "demo_080_failed.csv", TestDemos()[5]);
  std::ofstream(folder.path() / "broken.csv") << "# format: graspsynth-demo/1\n";
  const SelectionResult r =
      SelectRepresentatives(ShippedSimulationModel(), folder.path(), SmallOptions(2));
  EXPECT_EQ(r.logs, 2);
  EXPECT_EQ(r.unsuccessful, 1);
  ASSERT_EQ(r.issues.size(), 1u);
  EXPECT_EQ(r.issues[0].file, "broken.csv");
  EXPECT_EQ(r.issues[0].kind, SelectionIssueKind::kUnreadable);
  EXPECT_THAT(r.issues[0].reason, ::testing::HasSubstr("broken.csv"));
  ASSERT_EQ(r.library.entries.size(), 1u);
  EXPECT_EQ(r.library.entries[0].file, "demo_060_a.csv");
  EXPECT_EQ(r.library.demo_directory, folder.path().string());
  GS_EXPECT_THROW_WITH(
      SelectRepresentatives(ShippedSimulationModel(), folder.path() / "none", SmallOptions(1)),
      InputError, "none");
}

}  // namespace
}  // namespace graspsynth
