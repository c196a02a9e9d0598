#pragma once

/// @file
/// Robust representative selection (paper III-C): every successful demonstration is replayed
/// as the operator made it - reach, grasping motion and lift, through the arm's IK
/// (demo_replay.hpp) - once unperturbed and options.robustness.trials times under time scaling,
/// waypoint noise and perturbed physics (simulation/robustness.hpp); its score is the success
/// fraction. The most robust demonstration of each orientation becomes that orientation's library
/// entry (grasp_library.hpp). Demonstrations at several object positions (the logs'
/// object_position) are grouped by placement (position and orientation): "orientation" below reads
/// "placement".
///
/// Determinism: the perturbation stream of a demonstration is seeded by
/// DemoSeed(options.robustness.seed, file name) - a function of the file's name, never of the
/// order in which files are processed or of the number of threads - and every replay is
/// bit-for-bit independent of the thread count, so the same options give the same library
/// whatever options.robustness.threads is.
///
/// Tie rule (kTieRule): among the demonstrations of one orientation the representative has the
/// highest score; on equal scores the higher lower bound of the Wilson interval (it differs
/// only when the numbers of replays differ), then a successful nominal replay, then the
/// shorter grasping motion (pre-grasp to grasp, s), then the file name in byte order.
///
/// Early stop (SelectionOptions::early_stop, the default): an orientation's demonstrations are
/// scored one after another in the order in which the tie rule breaks ties, so one scored later
/// needs strictly more successes than the best one scored in full; its replays stop at the
/// first failure that makes that impossible. The representatives and every fully scored
/// demonstration's figures are those of a selection that runs every replay.
///
/// Threads: the nominal replays run side by side, then the orientations (each one's
/// demonstrations in turn, as the early stop needs), the largest orientation first; with fewer
/// orientations than threads, each orientation's replays share the threads left over.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "common/job_runner.hpp"
#include "learning_data/demo_directory.hpp"
#include "learning_data/demo_log.hpp"
#include "learning_data/grasp_library.hpp"
#include "learning_data/segmentation.hpp"
#include "simulation/perturbation.hpp"
#include "simulation/robustness.hpp"
#include "simulation/simulation_model.hpp"
#include "simulation/trial.hpp"

namespace graspsynth {

/// The tie rule in words, as the library records it.
inline constexpr std::string_view kTieRule =
    "highest score, then highest Wilson lower bound, then a successful nominal replay, then the "
    "shortest grasping motion (pre-grasp to grasp), then the file name in byte order";

/// Inputs of SelectRepresentatives().
struct SelectionOptions {
  /// The perturbed replays of each demonstration, passed down whole: `trials` per
  /// demonstration, >= 1; `seed` of the whole selection (each demonstration's stream is
  /// DemoSeed(seed, file name)); `threads` (0: one per hardware thread; changes no result);
  /// `perturbation`, the time scaling, waypoint noise and physics ranges; `trial`, the nominal
  /// and the perturbed replays' trial settings. 20 replays under the evaluator's default
  /// perturbation (time scale U[0.7, 1.3], wrist noise 5 mm and 2 deg, finger noise 2 deg per
  /// knot, and the physics perturbation) separate a robust grasp from a fragile one (Wilson 95%
  /// interval [0.30, 0.70] at 10 of 20, [0.84, 1] at 20 of 20) for 21 kFast trials per
  /// demonstration; raise it for a finer ranking.
  RobustnessOptions robustness = RobustnessOptions::WithTrials(20);
  /// Spend replays only where they can change the selection: the demonstrations of an
  /// orientation are scored in the tie rule's order of ties, and one stops replaying once it
  /// has failed so often that it cannot win over the best fully scored one (DemoScore::stopped).
  /// The representatives and their scores are the same as with every replay run; only the
  /// losers' scores count fewer replays. False: every replay of every demonstration.
  bool early_stop = true;
  /// Pre-grasp region and success label (commands take the region from the scene).
  SegmentationOptions segmentation;
  /// An orientation gets a library entry only when its best demonstration scores above this
  /// (strictly), in [0, 1): by default at least one perturbed replay must succeed.
  double min_score = 0.0;
  /// Where the replays run (common/job_runner.hpp): the nominal replays (stage
  /// "selection-nominal", a job per demonstration) and the orientations' perturbed replays
  /// (stage "selection", a job per placement, its demonstrations in turn for the early stop);
  /// nullptr: on this process's threads. Not owned.
  JobRunner* runner = nullptr;

  /// True when every value is in range (and the nested options are valid); otherwise false
  /// with the reason in `why` (if given).
  bool IsValid(std::string* why) const;
};

/// Why a file of the demonstration set has no say in the selection.
enum class SelectionIssueKind {
  kUnreadable,     ///< the log reader rejected the file
  kNotSegmented,   ///< the trial could not be segmented (no grasping motion)
  kNotReplayable,  ///< the robot cannot play the log (IK); it is scored 0 all the same
};

/// Short name of a kind ("unreadable", "not segmented", "not replayable").
const char* ToString(SelectionIssueKind kind);

/// A file that was rejected or could not be replayed, with the reason.
struct SelectionIssue {
  std::string file;  ///< the file name (a path for unreadable files, as the reader names it)
  SelectionIssueKind kind = SelectionIssueKind::kUnreadable;
  std::string reason;
};

/// What SelectRepresentatives() found.
struct SelectionResult {
  /// Every scored demonstration (by placement, then file), one entry per placement whose best
  /// demonstration passed min_score (theta increasing), seed, perturbations and tie rule.
  GraspLibrary library;
  std::vector<SelectionIssue> issues;  ///< by file name
  int logs = 0;                        ///< logs read
  int unsuccessful = 0;                ///< logs labelled unsuccessful (kept out of the ranking)
  /// Orientations with successful demonstrations but no entry (best score <= min_score), deg.
  std::vector<double> unselected_thetas;
};

/// Progress of a selection: replays done so far (nominal and perturbed, over all
/// demonstrations), their total, and the file being replayed. Called from worker threads, one
/// call at a time.
using SelectionProgress = std::function<void(int done, int total, const std::string& file)>;

/// The seed of the perturbation stream of the demonstration in file `file_name` (the name
/// without folders) for a selection with `seed`: SplitMix64 stream FNV-1a-64(file_name) of
/// `seed`, so it depends on the name alone.
uint64_t DemoSeed(uint64_t seed, std::string_view file_name);

/// Scores used by the tie rule, for one candidate.
struct SelectionCandidate {
  DemoScore score;
  double motion_duration = 0.0;  ///< grasping motion, pre-grasp to grasp, s
};

/// True when `a` is preferred to `b` as a representative by kTieRule.
bool PreferredRepresentative(const SelectionCandidate& a, const SelectionCandidate& b);

/// Scores `logs` (file names: the last component of each log's `source`, which must be unique)
/// and selects one representative per orientation; model.robot() replays them. `logs` must pass
/// the log reader's rules (ReadDemoLog: at least one sample, one grasp event, the end event
/// last; Segment aborts otherwise). `directory` is recorded in the library.
/// Throws InputError for invalid options or duplicate file names; logs that are unsuccessful,
/// unsegmentable or not replayable are results (`unsuccessful`, `issues`).
SelectionResult SelectRepresentatives(const SimulationModel& model,
                                      const std::vector<DemoLog>& logs,
                                      const std::string& directory, const SelectionOptions& options,
                                      const SelectionProgress& progress = {});

/// Reads `directory` (ReadDemoDirectory: bad files become kUnreadable issues) and selects.
/// Throws InputError when the folder cannot be read or the options are invalid.
SelectionResult SelectRepresentatives(const SimulationModel& model,
                                      const std::filesystem::path& directory,
                                      const SelectionOptions& options,
                                      const SelectionProgress& progress = {});

/// Selects from the logs of `demos` (a ReadDemoDirectory result: its rejected files become
/// kUnreadable issues, its `directory` name is recorded in the library).
/// Throws InputError when the options are invalid.
SelectionResult SelectRepresentatives(const SimulationModel& model, const DemoDirectory& demos,
                                      const SelectionOptions& options,
                                      const SelectionProgress& progress = {});

}  // namespace graspsynth
