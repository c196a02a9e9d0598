// Every kind of input file the commands read, given as a device (an endless stream), a named
// pipe or a folder: each is refused by name with the reason, and the command ends (exit 2, or
// 1 where the other files of a folder go on) instead of reading until memory runs out or
// waiting in open() for a writer. Each command runs under a hang guard (`timeout`), so that a
// regression fails the test instead of hanging the suite; the guard is generous (a busy machine
// stays far under it) because it is no speed claim: the refusals are made before a byte is read.
// An option given an empty value is refused too.

#include <sys/stat.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "tests/utils/paths.hpp"
#include "tests/utils/run_command.hpp"
#include "tests/utils/test_folder.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// The three kinds of path that are not a regular file, each named in the refusal.
struct Hostile {
  std::string label;
  std::string reason;
};
const std::vector<Hostile> kHostile = {
    {"device", "a character device, not a regular file"},
    {"fifo", "a named pipe (FIFO), not a regular file"},
    {"folder", "a folder, not a regular file"},
};

class HostileInputs : public ::testing::Test {
 protected:
  // A path of the kind `label` named `name` (a link to /dev/zero, a FIFO, a folder).
  fs::path Make(const std::string& label, const std::string& name) {
    const fs::path path = dir_ / label / name;
    fs::create_directories(path.parent_path());
    if (label == "device") fs::create_symlink("/dev/zero", path);
    if (label == "fifo") EXPECT_EQ(::mkfifo(path.c_str(), 0600), 0);
    if (label == "folder") fs::create_directories(path);
    return path;
  }
  // Runs `graspsynth <args>` under the hang guard; a command killed by it exits 124.
  static testing::CommandOutput Run(const std::string& args) {
    return testing::RunGraspsynth(args, "", 120);
  }
  static std::string Shipped(const std::string& relative) {
    return (fs::path(::testing::SourceDir()) / relative).string();
  }
  graspsynth::testing::TestFolder folder_;
  const fs::path& dir_ = folder_.path();
};

TEST_F(HostileInputs, EachKindOfInputFileIsRefusedByNameWithoutReadingOrBlocking) {
  const std::string out = (dir_ / "out").string();
  const std::string library = " --library " + Shipped("learning_data/library.json");
  for (const Hostile& h : kHostile) {
    SCOPED_TRACE(h.label);
    // (what the file is, the command that reads it, where the command is given it)
    struct Case {
      std::string kind;
      std::string args;
      fs::path path;
    };
    std::vector<Case> cases;
    const auto add = [&](const std::string& kind, const std::string& name,
                         const std::function<std::string(const std::string&)>& args) {
      std::string file = kind + "_" + name;
      std::replace(file.begin(), file.end(), ' ', '_');
      const fs::path path = Make(h.label, file);
      cases.push_back({kind, args(path.string()), path});
    };
    add("object description", "o.json", [&](const std::string& p) {
      return "synthesize --theta 60 --out " + out + library + " --object " + p;
    });
    add("scene description", "s.json", [&](const std::string& p) {
      return "synthesize --theta 60 --out " + out + library + " --scene " + p;
    });
    add("robot description", "r.urdf", [&](const std::string& p) { return "fk --robot " + p; });
    add("grasp library", "l.json", [&](const std::string& p) {
      return "synthesize --theta 60 --out " + out + " --library " + p;
    });
    add("trajectory file", "t.json",
        [&](const std::string& p) { return "simulate " + p + " --out " + out; });
    add("input file", "q.txt", [&](const std::string& p) { return "fk " + p; });
    add("key file", "k.key",
        [&](const std::string& p) { return "teleop --port 0 --exit-after 0.1 --key-file " + p; });
    add("teleoperation calibration", "c.json", [&](const std::string& p) {
      return "teleop --port 0 --exit-after 0.1 --calibration " + p;
    });
    add("synthetic operator file", "op.json",
        [&](const std::string& p) { return "demos generate --out " + out + " --operator " + p; });
    for (const Case& c : cases) {
      SCOPED_TRACE(c.args);
      const testing::CommandOutput r = Run(c.args);
      // two options check with CLI11's ExistingFile first, which refuses a folder itself.
      if (h.label == "folder" &&
          (c.kind == "trajectory file" || c.kind == "teleoperation calibration")) {
        EXPECT_THAT(r.err, HasSubstr("File is actually a directory: " + c.path.string()));
        EXPECT_NE(r.exit_code, 0);
        EXPECT_NE(r.exit_code, 124) << "the command hung";
        continue;
      }
      EXPECT_EQ(r.exit_code, 2) << r.err;
      EXPECT_THAT(r.err, HasSubstr("cannot read " + c.kind + " '" + c.path.string() + "': it is " +
                                   h.reason));
    }
  }
}

TEST_F(HostileInputs, FilesNamedInsideOtherFilesAreRefusedByNameToo) {
  for (const Hostile& h : kHostile) {
    SCOPED_TRACE(h.label);
    // a mesh part of an object, and the object of a scene.
    const fs::path mesh = Make(h.label, "handle.stl");
    const fs::path object = dir_ / h.label / "object.json";
    std::ofstream(object) << R"({"format": "graspsynth-object/1", "name": "hostile",
      "parts": [{"name": "body", "type": "mesh", "file": ")"
                          << mesh.string() << R"(", "mass": 0.2}],
      "handle": {"start_radius": 0.08, "end_radius": 0.38, "axis_height": 0.045}})";
    testing::CommandOutput r =
        Run("synthesize --theta 60 --out " + (dir_ / "g.json").string() + " --library " +
            Shipped("learning_data/library.json") + " --object " + object.string());
    EXPECT_THAT(r.err, HasSubstr("cannot read mesh '" + mesh.string() + "': it is " + h.reason));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    const fs::path inner = Make(h.label, "inner.json");
    std::ifstream shipped(Shipped("models/scene.json"));
    std::string scene{std::istreambuf_iterator<char>(shipped), {}};
    const std::string from = "\"objects/pan.json\"";
    scene.replace(scene.find(from), from.size(), "\"" + inner.string() + "\"");
    std::ofstream(dir_ / h.label / "scene.json") << scene;
    r = Run("synthesize --theta 60 --out " + (dir_ / "g.json").string() + " --scene " +
            (dir_ / h.label / "scene.json").string());
    EXPECT_THAT(r.err, HasSubstr("cannot read object description '" + inner.string() + "': it is " +
                                 h.reason));
    EXPECT_EQ(r.exit_code, 2) << r.err;
  }
}

TEST_F(HostileInputs, ADemonstrationLogThatIsNotARegularFileIsNamedAndTheOthersAreRead) {
  const fs::path demos = dir_ / "demos";
  fs::create_directories(demos);
  fs::copy_file(Shipped("learning_data/demos/theta060_trial01.csv"),
                demos / "theta060_trial01.csv");
  fs::create_symlink("/dev/zero", demos / "theta060_trial02.csv");
  ASSERT_EQ(::mkfifo((demos / "theta060_trial03.csv").c_str(), 0600), 0);
  const testing::CommandOutput r =
      Run("analyze " + demos.string() + " --out " + (dir_ / "report.json").string());
  EXPECT_THAT(r.err,
              HasSubstr("cannot read demonstration log '" +
                        (demos / "theta060_trial02.csv").string() + "': it is a character device"));
  EXPECT_THAT(
      r.err, HasSubstr("cannot read demonstration log '" +
                       (demos / "theta060_trial03.csv").string() + "': it is a named pipe (FIFO)"));
  EXPECT_NE(r.exit_code, 124) << "the command hung";
  EXPECT_NE(r.exit_code, 0) << r.err;
}

// An empty value used to mean "not given" without a word (--object '', --at ''), and
// "--object= --out X" lost --out: each is refused, naming the option.
TEST_F(HostileInputs, AnEmptyValueIsRefusedNamingTheOption) {
  const std::string out = " --out " + (dir_ / "g.json").string();
  for (const std::string& args :
       {"synthesize --theta 60" + out + " --object ''", "synthesize --theta 60" + out + " --at ''",
        "synthesize --theta 60 --object=" + out, std::string("fk --robot ''")}) {
    SCOPED_TRACE(args);
    const testing::CommandOutput r = Run(args);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_THAT(r.err, HasSubstr(args.find("--at") != std::string::npos      ? "--at: "
                                 : args.find("--robot") != std::string::npos ? "--robot: "
                                                                             : "--object: "));
    EXPECT_THAT(r.err, HasSubstr("an empty value (leave the option out to take its default)"));
    EXPECT_FALSE(fs::exists(dir_ / "g.json"));
  }
}

}  // namespace
}  // namespace graspsynth
