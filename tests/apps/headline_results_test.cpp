// The README's headline results, guarded (Release suite, label "headline"; skipped under the
// sanitizers, which make the physics ten times slower).
//
// The default study (`graspsynth run`, about half an hour on 2 cores with the physics
// perturbation, most of it the representative selection) is split in two checks that fit the
// suite's budget:
// - the committed study files (experiments/results/study_summary.txt, written by
//   `graspsynth run` with the defaults) state the README's figures: Table I 9 of 9 within 5 mm /
//   2 deg; interp+refine 17/17 nominal successes, 17/17 gate passes, mean robustness 0.93;
//   line+refine 15/17, 14/17, 0.81 (the physics perturbation, the 30 deg tilt limit, the
//   physics-checked fallback of a failed blend and 20 gate replays per grasp on);
// - a fresh run of the study's stages 1 and 3 on the shipped data (`graspsynth analyze` for
//   Table I, `graspsynth generalize` with the study's orientations, methods, 20 gate replays
//   and seed on the shipped library, which is what the default selection makes: same seed, 20
//   replays per demonstration) reaches those figures within the tolerance below. About 8 min
//   on 2 cores.
//
// Tolerance. Table I and the nominal trials are deterministic (no perturbation), so they must
// match exactly. The gate's 20 perturbed replays per grasp are seeded, so the same code gives
// the same figures; the tolerance admits a change that draws other perturbations (a seed
// derivation, the order of random draws) but not a real loss. Over 17 x 20 = 340 replays the
// standard deviation of the mean robustness is sqrt(p (1 - p) / 340): 0.021 at line+refine's
// p = 0.81, 0.014 at interp+refine's 0.93. We allow 0.03 below the README's two-digit figure
// (0.005 of rounding, then 1.2 and 1.8 standard deviations).
// A grasp at robustness 0.9 or 1.0 loses the gate (>= 0.8) only by three unlucky replays more,
// so at most one gate pass fewer per method.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tests/utils/paths.hpp"
#include "tests/utils/run_command.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::ReadFileText;
using testing::RunGraspsynth;

// The README's figures of the default study (seed 1), per method.
struct Headline {
  int rows = 0;
  int nominal_successes = 0;
  int passed = 0;
  double mean_robustness = 0.0;
};
const std::map<std::string, Headline> kReadme = {{"interp+refine", {17, 17, 17, 0.93}},
                                                 {"line+refine", {17, 15, 14, 0.81}}};
constexpr int kTableIWithin = 9;
constexpr int kTableIRows = 9;
constexpr double kRobustnessTolerance = 0.03;  // see the file comment
constexpr int kGatePassTolerance = 1;          // see the file comment

class HeadlineResults : public ::testing::Test {
 protected:
  void SetUp() override {
#ifdef GRASPSYNTH_SANITIZED
    GTEST_SKIP() << "the headline study runs in the Release suite only";
#endif
    dir_ = fs::temp_directory_path() /
           ("graspsynth_headline_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
};

std::vector<std::string> Split(const std::string& line, char sep) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  for (std::string f; std::getline(in, f, sep);) fields.push_back(f);
  return fields;
}

TEST_F(HeadlineResults, CommittedStudyStatesTheReadmeFigures) {
  const std::string summary =
      ReadFileText(fs::path(testing::SourceDir()) / "experiments/results/study_summary.txt");
  EXPECT_THAT(summary, HasSubstr("Table I 9 of 9 orientations within 5 mm / 2 deg"));
  for (const auto& [method, h] : kReadme) {
    char line[200];
    std::snprintf(line, sizeof(line),
                  "%s: %d/%d nominal successes, %d/%d passed the gate, mean robustness %.2f",
                  method.c_str(), h.nominal_successes, h.rows, h.passed, h.rows, h.mean_robustness);
    EXPECT_THAT(summary, HasSubstr(line));
  }
}

TEST_F(HeadlineResults, TableIOfTheShippedDemonstrationsMatchesThePaper) {
  const fs::path demos = fs::path(testing::SourceDir()) / "learning_data" / "demos";
  const testing::CommandOutput r =
      RunGraspsynth("analyze " + demos.string() + " --out " + (dir_ / "analysis.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const size_t at = r.out.find("paper Table I: ");
  ASSERT_NE(at, std::string::npos) << r.out;
  int within = -1, rows = -1;
  ASSERT_EQ(std::sscanf(r.out.c_str() + at, "paper Table I: %d of %d", &within, &rows), 2);
  EXPECT_EQ(rows, kTableIRows);
  EXPECT_GE(within, kTableIWithin) << r.out;
  EXPECT_THAT(r.out, HasSubstr("within 5 mm / 2 deg"));
}

TEST_F(HeadlineResults, StudySynthesisReachesTheReadmeFigures) {
  const testing::CommandOutput r = RunGraspsynth(
      "generalize --orientations 20:100:5 --methods interp+refine,line+refine --perturb 20 "
      "--seed 1 --threads 2 --name headline --out " +
      dir_.string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  std::istringstream csv(ReadFileText(dir_ / "headline.csv"));
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  const std::vector<std::string> header = Split(line, ',');
  std::map<std::string, int> column;
  for (size_t i = 0; i < header.size(); ++i) column[header[i]] = static_cast<int>(i);
  std::map<std::string, Headline> fresh;
  std::map<std::string, double> robustness_sum;
  while (std::getline(csv, line)) {
    const std::vector<std::string> f = Split(line, ',');
    ASSERT_GT(f.size(), static_cast<size_t>(column["passed"])) << line;
    Headline& h = fresh[f[column["method"]]];
    ++h.rows;
    EXPECT_EQ(f[column["status"]], "ok") << line;
    h.nominal_successes += f[column["nominal_success"]] == "1";
    h.passed += f[column["passed"]] == "1";
    robustness_sum[f[column["method"]]] += std::stod(f[column["robustness"]]);
  }
  ASSERT_EQ(fresh.size(), kReadme.size());
  for (const auto& [method, readme] : kReadme) {
    Headline& h = fresh[method];
    h.mean_robustness = robustness_sum[method] / h.rows;
    SCOPED_TRACE(method);
    EXPECT_EQ(h.rows, readme.rows);
    EXPECT_GE(h.nominal_successes, readme.nominal_successes);
    EXPECT_GE(h.passed, readme.passed - kGatePassTolerance);
    EXPECT_GE(h.mean_robustness, readme.mean_robustness - kRobustnessTolerance);
  }
}

}  // namespace
}  // namespace graspsynth
