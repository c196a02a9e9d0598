#include "learning_data/grasp_library.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>

#include "common/errors.hpp"
#include "simulation/random.hpp"
#include "tests/learning_data/demo_fixtures.hpp"
#include "tests/utils/data_dir_override.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/paths.hpp"
#include "tests/utils/run_command.hpp"

namespace graspsynth {
namespace {

using json = nlohmann::ordered_json;
using testing::ReadFileText;
using testing::TestFolder;

// Random but exact values: the round trip must keep every bit.
GraspingMotion RandomMotion(SplitMix64& rng, double theta_deg, int n) {
  GraspingMotion m;
  m.theta = theta_deg * M_PI / 180.0;
  m.p_WO = Eigen::Vector3d(rng.Normal(), rng.Normal(), rng.Normal());
  m.source = "demo_" + std::to_string(static_cast<int>(theta_deg)) + ".csv (trial 3)";
  double t = 0.0;
  for (int i = 0; i < n; ++i) {
    MotionWaypoint w;
    w.t = t;
    t += rng.Uniform(0.001, 0.1);
    w.p_WH = Eigen::Vector3d(rng.Normal(), rng.Normal(), rng.Normal());
    w.q_WH =
        Eigen::Quaterniond(rng.Normal(), rng.Normal(), rng.Normal(), rng.Normal()).normalized();
    if (w.q_WH.w() < 0.0) w.q_WH.coeffs() = -w.q_WH.coeffs();
    for (int k = 0; k < kHandDof; ++k) w.f[k] = rng.Uniform(-1.0, 2.0);
    m.waypoints.push_back(w);
  }
  return m;
}

GraspLibrary SampleLibrary() {
  SplitMix64 rng(7);
  GraspLibrary library;
  library.demo_directory = "learning_data/demos";
  library.seed = 0xFFFFFFFFFFFFFFF1ull;  // above 2^63: must stay unsigned
  library.perturbations = 20;
  library.tie_rule = "highest score, then the file name";
  for (int i = 0; i < 4; ++i) {
    DemoScore s;
    s.file = "demo_" + std::to_string(i) + ".csv";
    s.trial = i == 2 ? "" : std::to_string(i);
    s.theta_deg = i < 2 ? 40.0 : 60.0 + 0.1 * i;
    s.trials = 20;
    s.successes = 17 - i;
    s.score = s.successes / 20.0;
    s.ci_low = rng.Uniform(0.0, 0.5);
    s.ci_high = rng.Uniform(0.5, 1.0);
    s.nominal_success = i != 3;
    s.seed = rng.Next();
    s.failures = i == 0 ? "" : "dropped 3, not_lifted " + std::to_string(i);
    s.selected = i == 0 || i == 2;
    library.scores.push_back(s);
  }
  for (double theta : {40.0, 60.2}) {
    LibraryEntry e;
    e.theta_deg = theta;
    e.file = theta == 40.0 ? "demo_0.csv" : "demo_2.csv";
    e.trial = theta == 40.0 ? "0" : "";
    e.score = theta == 40.0 ? 0.85 : 0.75;
    e.motion = RandomMotion(rng, theta, 7);
    e.lift_height = rng.Uniform(0.05, 0.15);
    e.lift_duration = rng.Uniform(0.5, 2.0);
    library.entries.push_back(e);
  }
  // a library of one object position (format version 1).
  library.entries[1].motion.p_WO = library.entries[0].motion.p_WO;
  return library;
}

// A library over placements: the sample's entries at two more positions (format version 2).
GraspLibrary PlacementsLibrary() {
  GraspLibrary library = SampleLibrary();
  const std::vector<LibraryEntry> base = library.entries;
  library.entries.clear();
  for (const Eigen::Vector2d& xy :
       {Eigen::Vector2d(-0.30, 0.80), Eigen::Vector2d(-0.30, 0.90), Eigen::Vector2d(-0.2, 0.85)}) {
    for (LibraryEntry e : base) {
      const Eigen::Vector3d shift(xy.x() - e.motion.p_WO.x(), xy.y() - e.motion.p_WO.y(), 0.0);
      e.motion.p_WO.head<2>() = xy;
      for (MotionWaypoint& w : e.motion.waypoints) w.p_WH += shift;
      library.entries.push_back(e);
    }
  }
  for (size_t i = 0; i < library.scores.size(); ++i) {
    library.scores[i].xy = Eigen::Vector2d(-0.3 + 0.05 * static_cast<double>(i), 0.8);
  }
  return library;
}

// Bit-exact equality of two libraries, field by field.
void ExpectIdentical(const GraspLibrary& a, const GraspLibrary& b) {
  EXPECT_EQ(a.demo_directory, b.demo_directory);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.perturbations, b.perturbations);
  EXPECT_EQ(a.tie_rule, b.tie_rule);
  ASSERT_EQ(a.scores.size(), b.scores.size());
  for (size_t i = 0; i < a.scores.size(); ++i) {
    const DemoScore& x = a.scores[i];
    const DemoScore& y = b.scores[i];
    EXPECT_EQ(x.file, y.file);
    EXPECT_EQ(x.trial, y.trial);
    EXPECT_EQ(x.theta_deg, y.theta_deg);
    EXPECT_EQ(x.trials, y.trials);
    EXPECT_EQ(x.successes, y.successes);
    EXPECT_EQ(x.score, y.score);
    EXPECT_EQ(x.ci_low, y.ci_low);
    EXPECT_EQ(x.ci_high, y.ci_high);
    EXPECT_EQ(x.nominal_success, y.nominal_success);
    EXPECT_EQ(x.seed, y.seed);
    EXPECT_EQ(x.failures, y.failures);
    EXPECT_EQ(x.selected, y.selected);
    if (a.HasPositions()) {
      EXPECT_EQ(x.xy, y.xy);
    }
  }
  ASSERT_EQ(a.entries.size(), b.entries.size());
  for (size_t i = 0; i < a.entries.size(); ++i) {
    const LibraryEntry& x = a.entries[i];
    const LibraryEntry& y = b.entries[i];
    EXPECT_EQ(x.theta_deg, y.theta_deg);
    EXPECT_EQ(x.file, y.file);
    EXPECT_EQ(x.trial, y.trial);
    EXPECT_EQ(x.score, y.score);
    EXPECT_EQ(x.lift_height, y.lift_height);
    EXPECT_EQ(x.lift_duration, y.lift_duration);
    EXPECT_EQ(x.motion.theta, y.motion.theta);
    EXPECT_TRUE(x.motion.p_WO == y.motion.p_WO);
    EXPECT_EQ(x.motion.source, y.motion.source);
    ASSERT_EQ(x.motion.waypoints.size(), y.motion.waypoints.size());
    for (size_t k = 0; k < x.motion.waypoints.size(); ++k) {
      const MotionWaypoint& u = x.motion.waypoints[k];
      const MotionWaypoint& v = y.motion.waypoints[k];
      EXPECT_EQ(u.t, v.t);
      EXPECT_TRUE(u.p_WH == v.p_WH) << k;
      EXPECT_TRUE(u.q_WH.coeffs() == v.q_WH.coeffs()) << k;
      EXPECT_TRUE(u.f == v.f) << k;
    }
  }
}

TEST(GraspLibrary, RoundTripKeepsEveryBit) {
  const TestFolder folder;
  const GraspLibrary library = SampleLibrary();
  const auto path = folder.path() / "sub" / "library.json";
  WriteGraspLibrary(library, path);
  const GraspLibrary read = ReadGraspLibrary(path);
  ExpectIdentical(library, read);
  // writing what was read gives the same bytes.
  const auto again = folder.path() / "again.json";
  WriteGraspLibrary(read, again);
  EXPECT_EQ(ReadFileText(path), ReadFileText(again));
  const json j = json::parse(ReadFileText(path));
  EXPECT_EQ(j.at("format"), "graspsynth-library/1");
  EXPECT_TRUE(j.at("seed").is_number_unsigned());
  // no temporary file is left beside it.
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(folder.path() / "sub")) {
    (void)e;
    ++files;
  }
  EXPECT_EQ(files, 1);
}

TEST(GraspLibrary, OnePositionIsVersion1AndSeveralAreVersion2) {
  const GraspLibrary one = SampleLibrary();
  EXPECT_FALSE(one.HasPositions());
  const json j1 = json::parse(GraspLibraryToJson(one));
  EXPECT_EQ(j1["format"], "graspsynth-library/1");
  EXPECT_FALSE(j1["entries"][0].contains("placement"));
  EXPECT_FALSE(j1["scores"][0].contains("placement"));

  const TestFolder folder;
  const GraspLibrary several = PlacementsLibrary();
  EXPECT_TRUE(several.HasPositions());
  const auto path = folder.path() / "placements.json";
  WriteGraspLibrary(several, path);
  const json j2 = json::parse(ReadFileText(path));
  EXPECT_EQ(j2["format"], "graspsynth-library/2");
  EXPECT_EQ(j2["entries"][0]["placement"], json({{"x", -0.3}, {"y", 0.8}, {"theta_deg", 40.0}}));
  EXPECT_EQ(j2["scores"][1]["placement"]["x"], -0.25);
  const GraspLibrary read = ReadGraspLibrary(path);
  ExpectIdentical(several, read);
  EXPECT_EQ(*read.entries[3].placement().xy, Eigen::Vector2d(-0.3, 0.9));
  EXPECT_EQ(read.entries[3].placement().theta, 60.2 * kDeg);
  EXPECT_EQ(GraspLibraryToJson(read), ReadFileText(path));
}

TEST(GraspLibrary, Version2PlacementsMustIncreaseAndAgreeWithTheirMotions) {
  json j = json::parse(GraspLibraryToJson(PlacementsLibrary()));
  json swapped = j;
  std::swap(swapped["entries"][1],
            swapped["entries"][2]);  // (-0.3, 0.8, 60.2) after (-0.3, 0.9, 40)
  try {
    ParseGraspLibrary(swapped.dump(), "swapped.json");
    FAIL() << "entries out of order were accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("swapped.json"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("entries[2].placement"));
  }
  json moved = j;
  moved["entries"][0]["placement"]["x"] = -0.31;
  try {
    ParseGraspLibrary(moved.dump(), "moved.json");
    FAIL() << "a placement away from its motion was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("entries[0].placement"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("object_position"));
  }
}

TEST(GraspLibrary, QuaternionsAreWrittenSignNormalized) {
  const TestFolder folder;
  GraspLibrary library = SampleLibrary();
  MotionWaypoint& w = library.entries[0].motion.waypoints[2];
  const Eigen::Vector4d original = w.q_WH.coeffs();
  w.q_WH.coeffs() = -original;  // the same orientation with w < 0
  ASSERT_LT(w.q_WH.w(), 0.0);
  const auto path = folder.path() / "library.json";
  WriteGraspLibrary(library, path);
  const json j = json::parse(ReadFileText(path));
  for (const json& e : j["entries"]) {
    for (const json& wp : e["motion"]["waypoints"]) {
      EXPECT_GE(wp["quaternion"][0].get<double>(), 0.0);
    }
  }
  const GraspLibrary read = ReadGraspLibrary(path);
  EXPECT_TRUE(read.entries[0].motion.waypoints[2].q_WH.coeffs() == original);
}

TEST(GraspLibrary, WriterRefusesWhatTheReaderWouldReject) {
  const TestFolder folder;
  GraspLibrary library = SampleLibrary();
  library.entries[1].lift_height = std::numeric_limits<double>::quiet_NaN();
  const auto path = folder.path() / "library.json";
  GS_EXPECT_THROW_WITH(WriteGraspLibrary(library, path), InputError,
                       "field 'entries[1].lift_height': expected a finite number, found null");
  EXPECT_FALSE(std::filesystem::exists(path));
}

class MalformedLibrary : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = folder_.path() / "library.json";
    WriteGraspLibrary(SampleLibrary(), path_);
    good_ = json::parse(ReadFileText(path_));
  }
  // Writes `edit` applied to the good document and expects ReadGraspLibrary to reject it with
  // a message holding the file name and every part.
  void ExpectRejected(const std::function<void(json&)>& edit,
                      std::initializer_list<std::string> parts) {
    json j = good_;
    edit(j);
    std::ofstream(path_) << j.dump(1);
    try {
      ReadGraspLibrary(path_);
      ADD_FAILURE() << "accepted: " << j.dump().substr(0, 200);
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr(path_.string()));
      for (const std::string& part : parts) EXPECT_THAT(e.what(), ::testing::HasSubstr(part));
    }
  }

  TestFolder folder_;
  std::filesystem::path path_;
  json good_;
};

TEST_F(MalformedLibrary, MissingFileAndBadJson) {
  GS_EXPECT_THROW_WITH(ReadGraspLibrary(folder_.path() / "none.json"), InputError, "none.json",
                       "cannot read");
  std::ofstream(path_) << "{\"format\": \"graspsynth-library/1\", ";
  GS_EXPECT_THROW_WITH(ReadGraspLibrary(path_), InputError, path_.string(), "not valid JSON");
  std::ofstream(path_) << "[1, 2]";
  GS_EXPECT_THROW_WITH(ReadGraspLibrary(path_), InputError,
                       path_.string() + ": the document: expected an object, found [1,2]");
}

TEST_F(MalformedLibrary, WrongFormatOrVersion) {
  ExpectRejected(
      [](json& j) { j["format"] = "graspsynth-library/3"; },
      {"field 'format': expected \"graspsynth-library/1\", found \"graspsynth-library/3\""});
  // version 2 without its placements.
  ExpectRejected([](json& j) { j["format"] = "graspsynth-library/2"; },
                 {"field 'scores[0].placement': expected an object"});
  ExpectRejected([](json& j) { j["format"] = "graspsynth-analysis/1"; },
                 {"found \"graspsynth-analysis/1\""});
  ExpectRejected([](json& j) { j.erase("format"); },
                 {"field 'format': expected \"graspsynth-library/1\", found nothing"});
}

TEST_F(MalformedLibrary, MissingField) {
  ExpectRejected([](json& j) { j.erase("scores"); },
                 {"field 'scores': expected an array, found nothing"});
  ExpectRejected([](json& j) { j["scores"][1].erase("ci_low"); },
                 {"field 'scores[1].ci_low': expected a number in [0, 1], found nothing"});
  ExpectRejected([](json& j) { j["entries"][1]["motion"]["waypoints"][3].erase("fingers"); },
                 {"field 'entries[1].motion.waypoints[3].fingers': expected an array of 16 finite "
                  "numbers, found nothing"});
  ExpectRejected([](json& j) { j["entries"][0].erase("motion"); },
                 {"field 'entries[0].motion': expected an object, found nothing"});
}

TEST_F(MalformedLibrary, IllTypedField) {
  ExpectRejected([](json& j) { j["scores"][0]["score"] = "high"; },
                 {"field 'scores[0].score': expected a number in [0, 1], found \"high\""});
  ExpectRejected([](json& j) { j["scores"][2]["selected"] = 1; },
                 {"field 'scores[2].selected': expected true or false, found 1"});
  ExpectRejected([](json& j) { j["seed"] = -3; },
                 {"field 'seed': expected a non-negative integer, found -3"});
  ExpectRejected([](json& j) { j["perturbations"] = 2.5; },
                 {"field 'perturbations': expected an integer in [0, 2147483647], found 2.5"});
  ExpectRejected(
      [](json& j) {
        j["entries"][0]["motion"]["waypoints"][0]["position"] = {1, 2};
      },
      {"field 'entries[0].motion.waypoints[0].position': expected an array of 3 finite numbers, "
       "found [1,2]"});
  ExpectRejected(
      [](json& j) { j["entries"][1]["motion"]["waypoints"][4]["fingers"][15] = nullptr; },
      {"field 'entries[1].motion.waypoints[4].fingers[15]': expected a finite number, found null"});
  ExpectRejected([](json& j) { j["entries"] = json::object(); },
                 {"field 'entries': expected an array, found {}"});
  ExpectRejected([](json& j) { j["scores"][3]["successes"] = 21; },
                 {"field 'scores[3].successes': expected an integer in [0, 20], found 21"});
  ExpectRejected([](json& j) { j["scores"][0]["score"] = 1.5; },
                 {"field 'scores[0].score': expected a number in [0, 1], found 1.5"});
}

TEST_F(MalformedLibrary, NonFiniteNumber) {
  // JSON has no NaN or infinity: a number too large for a double is the way in, and the parser
  // refuses it.
  std::string text = good_.dump(1);
  const std::string key = "\"lift_height\": ";
  const size_t at = text.find(key) + key.size();
  text.replace(at, text.find(',', at) - at, "1e999");
  std::ofstream(path_) << text;
  GS_EXPECT_THROW_WITH(ReadGraspLibrary(path_), InputError, path_.string(), "not valid JSON",
                       "1e999");
}

TEST_F(MalformedLibrary, NonUnitQuaternion) {
  ExpectRejected(
      [](json& j) {
        j["entries"][1]["motion"]["waypoints"][2]["quaternion"] = {1.0, 0.01, 0.0, 0.0};
      },
      {"field 'entries[1].motion.waypoints[2].quaternion': expected a unit quaternion",
       "found [1.0,0.01,0.0,0.0]"});
  // within 1e-6 of unit is accepted, and normalized.
  json j = good_;
  json& q = j["entries"][0]["motion"]["waypoints"][1]["quaternion"];
  for (json& c : q) c = c.get<double>() * (1.0 + 5e-7);
  std::ofstream(path_) << j.dump(1);
  const GraspLibrary read = ReadGraspLibrary(path_);
  EXPECT_NEAR(read.entries[0].motion.waypoints[1].q_WH.norm(), 1.0, 1e-15);
}

TEST_F(MalformedLibrary, MotionThatIsNotWellFormed) {
  ExpectRejected([](json& j) { j["entries"][0]["motion"]["waypoints"][0]["t"] = 0.001; },
                 {"field 'entries[0].motion': expected a well-formed grasping motion (",
                  "the first waypoint is not at t = 0"});
  ExpectRejected(
      [](json& j) {
        json& w = j["entries"][0]["motion"]["waypoints"];
        w[4]["t"] = w[3]["t"];
      },
      {"field 'entries[0].motion.waypoints[4].t': expected a time after the previous waypoint's"});
  ExpectRejected(
      [](json& j) {
        json& w = j["entries"][1]["motion"]["waypoints"];
        w.erase(w.begin() + 1, w.end());
      },
      {"field 'entries[1].motion': expected a well-formed grasping motion",
       "at least 2 waypoints"});
  ExpectRejected(
      [](json& j) { j["entries"][1]["motion"]["theta_rad"] = 0.5; },
      {"field 'entries[1].motion.theta_rad': expected the entry's theta_deg", "in rad, found 0.5"});
}

TEST_F(MalformedLibrary, ThetaThatDoesNotIncrease) {
  ExpectRejected([](json& j) { j["entries"][1]["theta_deg"] = 40.0; },
                 {"field 'entries[1].theta_deg': expected a theta above the previous entry's 40.0, "
                  "found 40.0"});
}

TEST(GraspLibrary, DefaultPathIsUnderTheDataDirectory) {
  {
    const testing::DataDirOverride data(nullptr);
    EXPECT_EQ(DefaultGraspLibraryPath(),
              std::filesystem::path(::testing::SourceDir()) / "learning_data" / "library.json");
  }
  const testing::DataDirOverride data("/opt/graspsynth");
  EXPECT_EQ(DefaultGraspLibraryPath(),
            std::filesystem::path("/opt/graspsynth/learning_data/library.json"));
}

}  // namespace
}  // namespace graspsynth
