// Tests of `graspsynth analyze` through the built binary, on a temporary folder of generated logs.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/analysis/table_i_demos.hpp"
#include "tests/utils/run_command.hpp"

namespace graspsynth {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::ReadFileText;
using testing::RunGraspsynth;

// The Table I set written to `dir`, plus (if `with_bad_file`) one malformed file.
void WriteDemoSet(const std::filesystem::path& dir, bool with_bad_file) {
  for (const DemoLog& log : testing::TableIDemos()) WriteDemoLog(dir / log.source, log);
  if (with_bad_file) {
    DemoLog log = testing::MakeTrial(testing::TrialSpec{});
    std::string text = FormatDemoLog(log);
    // a NaN in the wrist y of the first sample (line 8: 7 metadata lines, then the header).
    std::string::size_type line_start = 0;
    for (int i = 0; i < 7; ++i) line_start = text.find('\n', line_start) + 1;
    const std::string::size_type y = text.find(',', text.find(',', line_start) + 1) + 1;
    text.replace(y, text.find(',', y) - y, "nan");
    std::ofstream(dir / "broken.csv") << text;
  }
}

TEST(AnalyzeCommand, AnalyzesAFolderAndNamesTheBadFile) {
  const testing::TestFolder folder;
  const auto demos = folder.path() / "demos";
  std::filesystem::create_directories(demos);
  WriteDemoSet(demos, true);
  const auto report = folder.path() / "out" / "report.json";
  const auto table = folder.path() / "out" / "table.md";
  const auto r = RunGraspsynth("analyze " + demos.string() + " --out " + report.string() +
                               " --table " + table.string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("rejected " + (demos / "broken.csv").string()));
  EXPECT_THAT(r.err, HasSubstr("broken.csv:8: column 3 'wrist_y': not a finite number: 'nan'"));
  EXPECT_THAT(r.out, HasSubstr("read 67 demonstration log(s)"));
  EXPECT_THAT(r.out, HasSubstr("1 rejected"));
  EXPECT_THAT(r.out, HasSubstr("wrist line: converged"));
  EXPECT_THAT(r.out, HasSubstr("9 of 9 orientations within"));
  EXPECT_THAT(r.out, HasSubstr("wrote " + report.string()));

  const json j = json::parse(ReadFileText(report));
  EXPECT_EQ(j.at("format"), "graspsynth-analysis/1");
  EXPECT_EQ(j.at("orientations").size(), 9u);
  EXPECT_EQ(j.at("counts").at("used"), 67);
  ASSERT_EQ(j.at("rejected").size(), 1u);
  EXPECT_EQ(j["rejected"][0].at("file"), (demos / "broken.csv").string());
  EXPECT_NEAR(j["orientations"][8].at("grasp").at("eta_deg").get<double>(), -40.6, 1e-9);
  EXPECT_THAT(ReadFileText(table), HasSubstr("9 of 9 orientations within tolerance"));
  // nothing half-written is left behind.
  for (const auto& entry : std::filesystem::directory_iterator(report.parent_path())) {
    EXPECT_NE(entry.path().filename().string().front(), '.') << entry.path();
  }
}

// Only the paper's pan has a published Table I: for another object the report's
// paper_comparison is null and the table is ours alone.
// A folder given as a relative path is recorded as given, and each file joined to it: no path
// of the machine in the report (the absolute one is recorded as given above).
TEST(AnalyzeCommand, ARelativeFolderIsRecordedAsGiven) {
  const testing::TestFolder folder;
  std::filesystem::create_directories(folder.path() / "demos");
  WriteDemoSet(folder.path() / "demos", true);
  const auto r = RunGraspsynth("analyze ./demos --out out/report.json", "", 0, folder.path());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_THAT(r.out, HasSubstr("from ./demos ("));
  const std::string text = ReadFileText(folder.path() / "out" / "report.json");
  EXPECT_THAT(text, Not(HasSubstr(folder.path().string())));
  const json j = json::parse(text);
  EXPECT_EQ(j.at("directory"), "./demos");
  EXPECT_EQ(j.at("rejected").at(0).at("file"), "./demos/broken.csv");
  EXPECT_THAT(j["rejected"][0].at("reason").get<std::string>(), HasSubstr("./demos/broken.csv:8:"));
  for (const json& row : j.at("orientations")) {
    for (const json& file : row.at("files")) {
      EXPECT_EQ(file.get<std::string>().rfind("./demos/theta", 0), 0u) << file;
    }
  }
}

TEST(AnalyzeCommand, AnotherObjectHasNoPaperComparison) {
  const testing::TestFolder folder;
  const auto demos = folder.path() / "demos";
  std::filesystem::create_directories(demos);
  WriteDemoSet(demos, false);
  const auto report = folder.path() / "report.json";
  const auto table = folder.path() / "table.md";
  const auto r = RunGraspsynth("analyze " + demos.string() + " --object saucepan --out " +
                               report.string() + " --table " + table.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("paper Table I: none for this object"));
  const json j = json::parse(ReadFileText(report));
  EXPECT_TRUE(j.at("paper_comparison").is_null());
  EXPECT_EQ(j.at("orientations").size(), 9u);
  const std::string md = ReadFileText(table);
  EXPECT_THAT(md, HasSubstr("the paper has no table for this object"));
  EXPECT_THAT(md, HasSubstr("| 100 | 5 | 0.410 | -39.8 | 0.321 | -40.6 |"));
  EXPECT_THAT(md, ::testing::Not(HasSubstr("paper |")));
}

TEST(AnalyzeCommand, OptionsReachTheAnalysis) {
  const testing::TestFolder folder;
  WriteDemoSet(folder.path(), false);
  const auto report = folder.path() / "report.json";
  const auto r = RunGraspsynth("analyze " + folder.path().string() + " --out " + report.string() +
                               " --region sphere --region-radius 0.5 --robust-loss cauchy "
                               "--loss-scale 0.004 --line-points trials");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const json j = json::parse(ReadFileText(report));
  EXPECT_EQ(j.at("options").at("region").at("shape"), "sphere");
  EXPECT_EQ(j.at("options").at("region").at("radius_m"), 0.5);
  EXPECT_EQ(j.at("options").at("robust_loss"), "cauchy");
  EXPECT_EQ(j.at("options").at("loss_scale_m"), 0.004);
  EXPECT_EQ(j.at("options").at("line_points"), "trials");
  EXPECT_EQ(j.at("wrist_line").at("n_points"), 67);
  // with a 0.5 m sphere the pre-grasp moves out to the 0.46 m approach sample.
  EXPECT_NEAR(j["orientations"][0].at("pregrasp").at("d").get<double>(), 0.46, 1e-6);
}

TEST(AnalyzeCommand, AConfigFileSetsTheOptionsAndTheFlagsOverrideIt) {
  const testing::TestFolder folder;
  WriteDemoSet(folder.path(), false);
  const auto config = folder.path() / "options.json";
  std::ofstream(config) << R"({"robust_loss": "cauchy", "loss_scale": 0.004, "region": "sphere"})";
  const auto report = folder.path() / "report.json";
  auto r = RunGraspsynth("analyze " + folder.path().string() + " --out " + report.string() +
                         " --config " + config.string() + " --loss-scale 0.003");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(ReadFileText(report));
  EXPECT_EQ(j.at("options").at("region").at("shape"), "sphere");
  EXPECT_EQ(j.at("options").at("robust_loss"), "cauchy");
  EXPECT_EQ(j.at("options").at("loss_scale_m"), 0.003);
  std::ofstream(config) << R"({"loss_scale": 0})";
  r = RunGraspsynth("analyze " + folder.path().string() + " --out " + report.string() +
                    " --config " + config.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("field 'loss_scale': must be > 0 (got 0)"));
}

TEST(AnalyzeCommand, PlotsFigure8WithGnuplot) {
  const testing::TestFolder folder;
  WriteDemoSet(folder.path(), false);
  const auto svg = folder.path() / "fig8.svg";
  const auto r = RunGraspsynth("analyze " + folder.path().string() + " --out " +
                               (folder.path() / "r.json").string() + " --plot " + svg.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("wrote " + svg.string()));
  const std::string text = ReadFileText(svg);
  ASSERT_FALSE(text.empty());
  EXPECT_TRUE(text.rfind("<?xml", 0) == 0 || text.rfind("<svg", 0) == 0) << text.substr(0, 80);
  EXPECT_THAT(text, HasSubstr("<svg"));
  EXPECT_THAT(text, HasSubstr("<path"));
  EXPECT_THAT(text, HasSubstr("wrist line"));
  EXPECT_THAT(text, HasSubstr("</svg>"));
}

TEST(AnalyzeCommand, MissingGnuplotIsAClearError) {
  const testing::TestFolder folder;
  WriteDemoSet(folder.path(), false);
  const auto r = RunGraspsynth(
      "analyze " + folder.path().string() + " --out " + (folder.path() / "r.json").string() +
      " --plot " + (folder.path() / "f.svg").string() + " --gnuplot /nonexistent/gnuplot");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--plot needs gnuplot"));
  EXPECT_THAT(r.err, HasSubstr("/nonexistent/gnuplot"));
  EXPECT_FALSE(std::filesystem::exists(folder.path() / "f.svg"));
}

TEST(AnalyzeCommand, BadInvocationsFail) {
  const testing::TestFolder folder;
  auto r = RunGraspsynth("analyze " + (folder.path() / "missing").string() + " --out " +
                         (folder.path() / "r.json").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("does not exist"));
  r = RunGraspsynth("analyze " + folder.path().string() + " --out " +
                    (folder.path() / "r.json").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("no demonstration logs"));
  r = RunGraspsynth("analyze " + folder.path().string() + " --out r.json --robust-loss l1");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.err, HasSubstr("--robust-loss"));
  r = RunGraspsynth("analyze " + folder.path().string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.err, HasSubstr("--out"));
}

TEST(AnalyzeCommand, HelpDescribesTheOptions) {
  const auto r = RunGraspsynth("analyze --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* option :
       {"--out", "--plot", "--table", "--region", "--region-radius", "--robust-loss",
        "--loss-scale", "--line-points", "graspsynth-demo/1", "Exit status"}) {
    EXPECT_THAT(r.out, HasSubstr(option));
  }
}

}  // namespace
}  // namespace graspsynth
