// Tests of reading a folder of demonstration logs: bad files are reported, good ones read.

#include "learning_data/demo_directory.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "common/errors.hpp"
#include "tests/learning_data/demo_csv_cases.hpp"
#include "tests/learning_data/demo_fixtures.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

using ::testing::HasSubstr;
using testing::TestFolder;

void WriteFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(DemoDirectory, ReportsEveryBadFileAndReadsTheGoodOnes) {
  const TestFolder folder;
  const auto& dir = folder.path();
  // good files: two written by the writer, one by hand.
  testing::TrialSpec spec;
  spec.trial = "b";
  WriteDemoLog(dir / "b_good.csv", testing::MakeTrial(spec));
  spec.trial = "a";
  WriteDemoLog(dir / "a_good.csv", testing::MakeTrial(spec));
  WriteFile(dir / "z_good.csv", testing::GoodDemoText());
  // ignored: other extensions, hidden files (e.g. an interrupted atomic write). A folder named
  // like a log is rejected by name, as a named pipe or a device would be.
  WriteFile(dir / "notes.txt", "not a log");
  WriteFile(dir / ".a_good.csv.tmp.123.csv", "half a file");
  std::filesystem::create_directories(dir / "folder.csv");

  const std::vector<testing::MalformedCase> cases = testing::MalformedDemoCases();
  for (const testing::MalformedCase& c : cases) WriteFile(dir / ("m_" + c.name + ".csv"), c.text);

  const DemoDirectory demos = ReadDemoDirectory(dir);
  EXPECT_EQ(demos.directory, dir.string());
  ASSERT_EQ(demos.logs.size(), 3u);
  EXPECT_EQ(demos.logs[0].source, (dir / "a_good.csv").string());
  EXPECT_EQ(demos.logs[1].source, (dir / "b_good.csv").string());
  EXPECT_EQ(demos.logs[2].source, (dir / "z_good.csv").string());
  EXPECT_EQ(demos.logs[0].metadata.trial, std::optional<std::string>("a"));
  EXPECT_EQ(demos.logs[2].samples.size(), 4u);

  ASSERT_EQ(demos.rejected.size(), cases.size() + 1);
  for (size_t i = 1; i < demos.rejected.size(); ++i) {
    EXPECT_LT(demos.rejected[i - 1].file, demos.rejected[i].file);  // sorted by name
  }
  EXPECT_EQ(demos.rejected[0].file, (dir / "folder.csv").string());
  EXPECT_THAT(demos.rejected[0].reason, HasSubstr("it is a folder, not a regular file"));
  for (const testing::MalformedCase& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string file = (dir / ("m_" + c.name + ".csv")).string();
    const auto it = std::find_if(demos.rejected.begin(), demos.rejected.end(),
                                 [&](const RejectedDemoFile& r) { return r.file == file; });
    ASSERT_NE(it, demos.rejected.end());
    EXPECT_EQ(it->reason.rfind(file + ":", 0), 0u) << it->reason;
    for (const std::string& part : c.message) EXPECT_THAT(it->reason, HasSubstr(part));
  }
}

TEST(DemoDirectory, AnEmptyFolderGivesNothing) {
  const TestFolder folder;
  const DemoDirectory demos = ReadDemoDirectory(folder.path());
  EXPECT_TRUE(demos.logs.empty());
  EXPECT_TRUE(demos.rejected.empty());
}

TEST(DemoDirectory, AMissingFolderIsAnInputError) {
  const TestFolder folder;
  GS_EXPECT_THROW_WITH(ReadDemoDirectory(folder.path() / "missing"), InputError, "missing",
                       "does not exist");
  WriteFile(folder.path() / "file.csv", testing::GoodDemoText());
  GS_EXPECT_THROW_WITH(ReadDemoDirectory(folder.path() / "file.csv"), InputError, "file.csv",
                       "not a folder");
}

TEST(DemoDirectory, ANamedFolderNamesEachFileJoinedToTheName) {
  const TestFolder folder;
  const auto& dir = folder.path();
  WriteFile(dir / "a_good.csv", testing::GoodDemoText());
  const testing::MalformedCase bad = testing::MalformedDemoCases().front();
  WriteFile(dir / "m_bad.csv", bad.text);

  const DemoDirectory demos = ReadDemoDirectory(dir, "shipped/demos");
  EXPECT_EQ(demos.directory, "shipped/demos");
  ASSERT_EQ(demos.logs.size(), 1u);
  EXPECT_EQ(demos.logs[0].source, "shipped/demos/a_good.csv");
  EXPECT_EQ(demos.logs[0].samples.size(), 4u);  // read from `dir`, whatever the name
  ASSERT_EQ(demos.rejected.size(), 1u);
  EXPECT_EQ(demos.rejected[0].file, "shipped/demos/m_bad.csv");
  EXPECT_EQ(demos.rejected[0].reason.rfind("shipped/demos/m_bad.csv:", 0), 0u)
      << demos.rejected[0].reason;
  for (const std::string& part : bad.message)
    EXPECT_THAT(demos.rejected[0].reason, HasSubstr(part));
}

TEST(DemoDirectory, ARelativeFolderIsNamedAsGiven) {
  const TestFolder folder;
  std::filesystem::create_directories(folder.path() / "demos");
  WriteFile(folder.path() / "demos" / "a_good.csv", testing::GoodDemoText());
  const std::filesystem::path previous = std::filesystem::current_path();
  std::filesystem::current_path(folder.path());
  const DemoDirectory demos = ReadDemoDirectory("./demos");
  std::filesystem::current_path(previous);
  EXPECT_EQ(demos.directory, "./demos");
  ASSERT_EQ(demos.logs.size(), 1u);
  EXPECT_EQ(demos.logs[0].source, "./demos/a_good.csv");
}

TEST(DemoDirectory, TheShippedFolderIsNamedRelativeToTheProjectRoot) {
  const DemoDirectory shipped = ReadDefaultDemoDirectory();
  EXPECT_EQ(shipped.directory, "learning_data/demos");
  ASSERT_EQ(shipped.logs.size(), 90u);
  EXPECT_TRUE(shipped.rejected.empty());
  EXPECT_EQ(shipped.logs[0].source, "learning_data/demos/theta020_trial01.csv");
  // the same logs as the folder read by its path, which names it as given (absolute).
  const DemoDirectory by_path = ReadDemoDirectory(DefaultDemoDirectory());
  EXPECT_EQ(by_path.directory, DefaultDemoDirectory().string());
  ASSERT_EQ(by_path.logs.size(), shipped.logs.size());
  for (size_t i = 0; i < shipped.logs.size(); ++i) {
    EXPECT_EQ(by_path.logs[i].source,
              (DefaultDemoDirectory() / std::filesystem::path(shipped.logs[i].source).filename())
                  .string());
    EXPECT_EQ(FormatDemoLog(by_path.logs[i]), FormatDemoLog(shipped.logs[i]));
  }
  EXPECT_EQ(ReadDefaultDemoDirectory("saucepan").directory, "learning_data/objects/saucepan/demos");
}

TEST(DemoDirectory, EachObjectHasItsLearningDataFolderAndThePanKeepsItsOwn) {
  EXPECT_EQ(ObjectLearningDataDirectory("pan").filename(), "learning_data");
  EXPECT_EQ(DefaultDemoDirectory(), ObjectLearningDataDirectory("pan") / "demos");
  const std::filesystem::path mug = ObjectLearningDataDirectory("mug");
  EXPECT_EQ(mug, ObjectLearningDataDirectory("pan") / "objects" / "mug");
  EXPECT_EQ(DefaultDemoDirectory("mug"), mug / "demos");
}

}  // namespace
}  // namespace graspsynth
