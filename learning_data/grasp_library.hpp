#pragma once

/// @file
/// The grasp library: the robustness score of every successful demonstration of a directory,
/// the most robust demonstration per placement (paper III-C: per orientation), and where each
/// came from. `graspsynth select` writes it; `graspsynth synthesize` reads it.
///
/// Formats: `graspsynth-library/1` holds demonstrations of one object position (the paper's
/// setting: one entry per orientation, theta strictly increasing); `graspsynth-library/2` holds
/// demonstrations at several positions, and every score and entry carries
/// `"placement": {"x": m, "y": m, "theta_deg": deg}`, entries strictly increasing in (x, y,
/// theta). The writer uses version 1 whenever every entry stands at one position, so that a
/// library of the fixed position keeps its bytes; the reader reads both.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "motion/grasping_motion.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth {

/// The robustness score of one successful demonstration.
struct DemoScore {
  std::string file;        ///< the log's file name, relative to the library's demo directory
  std::string trial;       ///< the log's `trial` metadata (empty when absent)
  double theta_deg = 0.0;  ///< object orientation, deg
  /// The object centre on the table in its log, world, m (the log's object_position); version-1
  /// files do not record it (zero when read from one).
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();
  int trials = 0;       ///< perturbed replays
  int successes = 0;    ///< of which succeeded
  double score = 0.0;   ///< successes / trials
  double ci_low = 0.0;  ///< Wilson 95% interval of the success probability
  double ci_high = 1.0;
  bool nominal_success = false;  ///< the unperturbed replay succeeded
  uint64_t seed = 0;             ///< seed of this demonstration's perturbation stream
  std::string failures;          ///< failure outcomes and counts, e.g. "dropped 3, not_lifted 1"
  bool selected = false;         ///< the representative of its orientation
  /// Empty when all the selection's replays ran; otherwise why its replays stopped early (it
  /// could no longer win its orientation): `trials`, `successes` and `score` then count the
  /// replays that ran, and the full score would be at most (successes + the replays left) /
  /// the library's `perturbations`.
  std::string stopped;
};

/// The representative (most robust) demonstration of one placement.
struct LibraryEntry {
  double theta_deg = 0.0;  ///< deg
  std::string file;        ///< as in DemoScore
  std::string trial;
  double score = 0.0;
  /// Its grasping motion, pre-grasp to grasp (segmentation.hpp), times from the pre-grasp.
  GraspingMotion motion;
  /// The wrist's lift after the grasp as the operator made it: wrist height gained from the
  /// grasp sample to the end of the trial, m, and the time it took, s.
  double lift_height = 0.0;
  double lift_duration = 0.0;

  /// Where the object stood: theta_deg in rad at the motion's object centre.
  Placement placement() const { return {theta_deg * kDeg, Eigen::Vector2d(motion.p_WO.head<2>())}; }
};

/// The order of placements in a library: x, then y, then theta (for one position: theta).
bool PlacementBefore(const Eigen::Vector2d& xy_a, double theta_a, const Eigen::Vector2d& xy_b,
                     double theta_b);

/// A grasp library.
struct GraspLibrary {
  /// The file it was read from (ReadGraspLibrary), for error messages; empty when the library
  /// was built in memory. Not written.
  std::string source;
  std::string demo_directory;  ///< the directory the demonstrations were read from
  uint64_t seed = 0;           ///< seed of the selection
  int perturbations = 0;       ///< perturbed replays per demonstration
  std::string tie_rule;        ///< how ties in score were broken, in words
  /// Every successful demonstration, by placement (PlacementBefore) then file.
  std::vector<DemoScore> scores;
  /// One per placement, strictly increasing by PlacementBefore (one position: by theta).
  std::vector<LibraryEntry> entries;

  /// True when the entries, or the scored demonstrations, stand at more than one object
  /// position (format version 2: a selection over several positions stays one even when only
  /// one of them has a representative).
  bool HasPositions() const;
};

/// The text of `library` as a graspsynth-library/1 file, or /2 when it HasPositions() (pretty
/// JSON), what WriteGraspLibrary writes.
std::string GraspLibraryToJson(const GraspLibrary& library);

/// Writes GraspLibraryToJson(library) to `path`, atomically.
void WriteGraspLibrary(const GraspLibrary& library, const std::filesystem::path& path);

/// The selection's perturbed replays: those that ran (the sum of the scores' `trials`), those
/// that every replay would have been (scores x `perturbations`), and the scores whose replays
/// stopped early (DemoScore::stopped).
struct SelectionReplays {
  int ran = 0;
  int all = 0;
  int stopped = 0;
};
SelectionReplays CountSelectionReplays(const GraspLibrary& library);

/// Reads a library file. Throws InputError naming the file and the field for a missing file,
/// malformed JSON, another format or version, a missing or ill-typed field, non-finite numbers,
/// non-unit quaternions, a motion that breaks IsWellFormed, entries whose theta (version 1) or
/// placement (version 2) does not strictly increase, or a version-2 placement that disagrees
/// with its motion's object position or theta.
GraspLibrary ReadGraspLibrary(const std::filesystem::path& path);
/// The same from the text of a library; `source` names it in messages.
GraspLibrary ParseGraspLibrary(std::string_view json_text, const std::string& source);

/// Path of the shipped library of `object_name`: library.json in its learning-data folder
/// (learning_data/library.json for the pan; ObjectLearningDataDirectory), in the source tree or
/// the data directory.
std::filesystem::path DefaultGraspLibraryPath(const std::string& object_name = "pan");

}  // namespace graspsynth
