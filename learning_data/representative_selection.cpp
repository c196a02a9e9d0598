#include "learning_data/representative_selection.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include "common/byte_codec.hpp"
#include "common/errors.hpp"
#include "common/field_codec.hpp"
#include "common/parallel.hpp"
#include "common/valid_options.hpp"
#include "learning_data/demo_replay.hpp"
#include "learning_data/learning_data_fields.hpp"
#include "simulation/random.hpp"
#include "simulation/robustness.hpp"

namespace graspsynth {
namespace {

// The layouts of the selection's job results (JobStage::payload): a nominal replay's success,
// and an orientation's perturbed scores. Change them with EncodeScores and RunNominal.
constexpr const char* kNominalLayout = "selection-nominal/1";
constexpr const char* kScoresLayout = "selection-scores/2";

std::string FileName(const std::string& source) {
  return std::filesystem::path(source).filename().string();
}

// A segmented, successful demonstration and what its replays gave.
struct Scored {
  const DemoLog* log = nullptr;
  SegmentedTrial segmented;
  DemoReplay replay;                    // the robot's replay of the log (PrepareNominal)
  std::optional<SelectionIssue> issue;  // why it could not be replayed (PrepareNominal)
  SelectionCandidate candidate;
};

}  // namespace

bool SelectionOptions::IsValid(std::string* why) const {
  const auto fail = [why](const std::string& text) {
    if (why) *why = text;
    return false;
  };
  if (robustness.trials < 1) {
    return fail("perturbations must be >= 1, not " + std::to_string(robustness.trials));
  }
  if (robustness.threads < 0) {
    return fail("threads must be >= 0, not " + std::to_string(robustness.threads));
  }
  if (!(min_score >= 0.0 && min_score < 1.0)) {
    std::ostringstream s;
    s << "min_score must be in [0, 1), not " << min_score;
    return fail(s.str());
  }
  std::string nested;
  if (!segmentation.IsValid(&nested)) return fail("segmentation: " + nested);
  if (!robustness.trial.IsValid(&nested)) return fail("trial: " + nested);
  if (!robustness.perturbation.IsValid(&nested)) return fail("perturbation: " + nested);
  return true;
}

const char* ToString(SelectionIssueKind kind) {
  switch (kind) {
    case SelectionIssueKind::kUnreadable:
      return "unreadable";
    case SelectionIssueKind::kNotSegmented:
      return "not segmented";
    case SelectionIssueKind::kNotReplayable:
      return "not replayable";
  }
  return "?";
}

uint64_t DemoSeed(uint64_t seed, std::string_view file_name) {
  // FNV-1a, 64 bit: a fixed, portable hash of the name (std::hash is neither).
  uint64_t h = 0xcbf29ce484222325ull;
  for (const char c : file_name) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ull;
  }
  return SplitMix64::ForStream(seed, h).Next();
}

namespace {

// kTieRule's keys after the score: a successful nominal replay, the shorter motion, the file
// name. They are known before any perturbed replay runs (the early stop orders by them).
bool PreferredOnTies(const SelectionCandidate& a, const SelectionCandidate& b) {
  if (a.score.nominal_success != b.score.nominal_success) return a.score.nominal_success;
  if (a.motion_duration != b.motion_duration) return a.motion_duration < b.motion_duration;
  return a.score.file < b.score.file;
}

}  // namespace

bool PreferredRepresentative(const SelectionCandidate& a, const SelectionCandidate& b) {
  if (a.score.score != b.score.score) return a.score.score > b.score.score;
  if (a.score.ci_low != b.score.ci_low) return a.score.ci_low > b.score.ci_low;
  return PreferredOnTies(a, b);
}

namespace {

// The order of placements (grasp_library.hpp), and one placement.
bool Before(const DemoScore& a, const DemoScore& b) {
  return PlacementBefore(a.xy, a.theta_deg, b.xy, b.theta_deg);
}
bool SamePlacement(const DemoScore& a, const DemoScore& b) {
  return !Before(a, b) && !Before(b, a);
}

// Segments every log; only successful, segmented trials are ranked (the others are counted
// unsuccessful or listed as issues in `result`).
std::vector<Scored> SegmentLogs(const std::vector<DemoLog>& logs, const SelectionOptions& options,
                                SelectionResult* result) {
  std::vector<Scored> scored;
  for (const DemoLog& log : logs) {
    SegmentedTrial segmented = Segment(log, options.segmentation);
    if (!segmented.success) {
      ++result->unsuccessful;
      continue;
    }
    if (!segmented.ok()) {
      result->issues.push_back(
          {FileName(log.source), SelectionIssueKind::kNotSegmented, segmented.message});
      continue;
    }
    Scored s;
    s.log = &log;
    s.segmented = std::move(segmented);
    scored.push_back(std::move(s));
  }
  return scored;
}

// Replays demonstration `s` unperturbed (its nominal trial). A demonstration the robot cannot
// play keeps its issue in s->issue.
// What a demonstration's score knows before any trial: its file, placement and seed, and the
// robot's replay of its log (or why there is none: it then scores 0, its replays counted).
void PrepareNominal(const SimulationModel& model, const SelectionOptions& options, Scored* s,
                    ProgressCounter* counter) {
  const DemoLog& log = *s->log;
  DemoScore& score = s->candidate.score;
  score.file = FileName(log.source);
  score.trial = log.metadata.trial.value_or("");
  score.theta_deg = log.metadata.theta_deg;
  score.xy = log.metadata.object_position.head<2>();
  score.seed = DemoSeed(options.robustness.seed, score.file);
  s->candidate.motion_duration = s->segmented.motion.duration();

  s->replay = ReplayDemoLog(model.robot(), log);
  if (!s->replay.ok) {
    // a demonstration the robot cannot play scores 0; nothing is known about it.
    score.failures = "not replayable: " + s->replay.message;
    score.ci_low = 0.0;
    score.ci_high = 1.0;
    s->issue = SelectionIssue{score.file, SelectionIssueKind::kNotReplayable, s->replay.message};
    counter->Add(options.robustness.trials + 1, score.file);
  }
}

// The nominal replay's success, as a job's result bytes.
std::string RunNominal(const SimulationModel& model, const SelectionOptions& options,
                       const Scored& s, ProgressCounter* counter) {
  ByteWriter w;
  w.Bool(s.replay.ok && RunTrial(model, s.replay.trajectory, options.robustness.trial).success());
  if (s.replay.ok) counter->Add(1, s.candidate.score.file);
  return w.Take();
}

// Whether nominal replay i succeeded, from its job's result bytes.
bool DecodeNominal(std::string_view bytes, int i) {
  ByteReader r(bytes, "nominal replay " + std::to_string(i));
  const bool success = r.Bool();
  r.Finish();
  return success;
}

// The scores of an orientation's demonstrations (`order`) after their perturbed replays, as a
// job's result bytes: every field of each (learning_data/learning_data_fields.hpp).
std::string EncodeScores(const std::vector<Scored*>& order) {
  std::vector<DemoScore> scores;
  for (const Scored* s : order) scores.push_back(s->candidate.score);
  return EncodeFields(scores);
}

// Decodes into `scores`, one per demonstration of the orientation, in order. Throws InputError
// naming `source` for bytes that hold the scores of other demonstrations.
void DecodeScores(std::string_view bytes, const std::string& source,
                  const std::vector<DemoScore*>& scores) {
  const auto read = DecodeFields<std::vector<DemoScore>>(bytes, source);
  if (read.size() != scores.size()) {
    throw InputError(source + ": " + std::to_string(read.size()) +
                     " scores where the orientation has " + std::to_string(scores.size()) +
                     " demonstrations");
  }
  for (size_t k = 0; k < read.size(); ++k) {
    if (read[k].file != scores[k]->file) {
      throw InputError(source + ": the scores of '" + read[k].file + "' where '" + scores[k]->file +
                       "' was expected");
    }
    *scores[k] = read[k];
  }
}

// Scores demonstration `s` by its perturbed replays. With `rival` (a demonstration of the same
// orientation whose replays have all run and that kTieRule prefers on every tie) the replays
// stop once `s` has failed so often that it cannot score above the rival.
void ScorePerturbed(const SimulationModel& model, const SelectionOptions& options,
                    RobustnessOptions robustness, const DemoScore* rival, Scored* s,
                    ProgressCounter* counter) {
  DemoScore& score = s->candidate.score;
  if (!s->replay.ok) return;
  const int n = options.robustness.trials;
  StopRule stop;
  if (rival) {
    const int needed = rival->successes + 1;  // ties go to the rival
    stop = [n, needed](int, int failures) { return n - failures < needed; };
  }
  if (rival && rival->successes >= n) {
    // the rival succeeded in every replay: nothing can win over it.
    score.stopped = "no replays: " + rival->file + " succeeded in all " + std::to_string(n) +
                    " of its replays and wins every tie";
    counter->Add(n, score.file);
    return;
  }
  robustness.seed = score.seed;
  int reported = 0;  // replays counted so far
  const RobustnessResult r =
      EvaluateRobustnessUntil(model, s->replay.trajectory, robustness, stop, [&](int k, int) {
        if (k <= reported) return;  // a stop leaves finished replays past it uncounted
        counter->Add(k - reported, score.file);
        reported = k;
      });
  counter->Add(n - reported, score.file);  // those the stop skipped
  score.trials = static_cast<int>(r.trials.size());
  score.successes = r.successes;
  score.score = r.score;
  score.ci_low = r.ci95.lo;
  score.ci_high = r.ci95.hi;
  score.failures = FailureSummary(r);
  if (score.trials < n) {
    std::ostringstream why;
    why << "stopped after " << score.trials << " of " << n
        << " replays: " << score.trials - score.successes << " failed, so at most "
        << n - (score.trials - score.successes) << " of " << n << ", which cannot win over "
        << rival->file << " (" << rival->successes << " of " << n << ")";
    score.stopped = why.str();
  }
}

// Scores every demonstration of one orientation (`order`, in the order in which kTieRule breaks
// ties) and, with options.early_stop, spends replays only while a demonstration can still
// become the representative.
void ScoreOrientation(const SimulationModel& model, const SelectionOptions& options,
                      const RobustnessOptions& robustness, const std::vector<Scored*>& order,
                      ProgressCounter* counter) {
  const DemoScore* best = nullptr;  // the preferred one of those whose replays all ran
  for (Scored* s : order) {
    ScorePerturbed(model, options, robustness, options.early_stop ? best : nullptr, s, counter);
    if (!s->candidate.score.stopped.empty()) continue;
    if (!best || s->candidate.score.successes > best->successes) best = &s->candidate.score;
  }
}

// The library entry of a selected demonstration.
LibraryEntry EntryOf(const Scored& best) {
  const DemoScore& b = best.candidate.score;
  const DemoLog& log = *best.log;
  const SegmentedTrial& seg = best.segmented;
  LibraryEntry entry;
  entry.theta_deg = b.theta_deg;
  entry.file = b.file;
  entry.trial = b.trial;
  entry.score = b.score;
  entry.motion = seg.motion;
  entry.lift_height = log.samples[seg.end].p_WH.z() - log.samples[seg.grasp].p_WH.z();
  entry.lift_duration = log.samples[seg.end].t - log.samples[seg.grasp].t;
  return entry;
}

// Sorts the scores by placement, then file, and picks the representative of each placement by
// the tie rule (a placement whose best score is not above min_score is left unselected).
void PickRepresentatives(const SelectionOptions& options, std::vector<Scored>* scored,
                         SelectionResult* result) {
  std::sort(scored->begin(), scored->end(), [](const Scored& a, const Scored& b) {
    if (!SamePlacement(a.candidate.score, b.candidate.score)) {
      return Before(a.candidate.score, b.candidate.score);
    }
    return a.candidate.score.file < b.candidate.score.file;
  });
  std::vector<Scored>& all = *scored;
  for (size_t begin = 0; begin < all.size();) {
    size_t end = begin;
    Scored* best = &all[begin];
    while (end < all.size() &&
           SamePlacement(all[end].candidate.score, all[begin].candidate.score)) {
      // a demonstration whose replays stopped early cannot win (ScorePerturbed).
      if (all[end].candidate.score.stopped.empty() &&
          PreferredRepresentative(all[end].candidate, best->candidate)) {
        best = &all[end];
      }
      ++end;
    }
    const DemoScore& b = best->candidate.score;
    if (b.score > options.min_score) {
      best->candidate.score.selected = true;
      result->library.entries.push_back(EntryOf(*best));
    } else {
      result->unselected_thetas.push_back(b.theta_deg);
    }
    begin = end;
  }
}

// The demonstrations of `scored` by placement, each placement's in kTieRule's order of ties (a
// successful nominal replay, the shorter motion, the file name, so that a later one needs more
// successes to win); the placements with the most demonstrations first: they are independent
// jobs that run side by side, so that a small one ends the stage.
std::vector<std::vector<Scored*>> GroupByPlacement(std::vector<Scored>* scored) {
  std::vector<Scored*> order;
  for (Scored& s : *scored) order.push_back(&s);
  std::sort(order.begin(), order.end(), [](const Scored* a, const Scored* b) {
    if (!SamePlacement(a->candidate.score, b->candidate.score)) {
      return Before(a->candidate.score, b->candidate.score);
    }
    return PreferredOnTies(a->candidate, b->candidate);
  });
  std::vector<std::vector<Scored*>> placements;
  for (Scored* s : order) {
    if (placements.empty() ||
        !SamePlacement(placements.back().front()->candidate.score, s->candidate.score)) {
      placements.emplace_back();
    }
    placements.back().push_back(s);
  }
  std::stable_sort(placements.begin(), placements.end(),
                   [](const auto& a, const auto& b) { return a.size() > b.size(); });
  return placements;
}

// Pointers to the elements of `scores`.
std::vector<DemoScore*> Pointers(std::vector<DemoScore>* scores) {
  std::vector<DemoScore*> out;
  for (DemoScore& d : *scores) out.push_back(&d);
  return out;
}

}  // namespace

SelectionResult SelectRepresentatives(const SimulationModel& model,
                                      const std::vector<DemoLog>& logs,
                                      const std::string& directory, const SelectionOptions& options,
                                      const SelectionProgress& progress) {
  RequireValid(options, "bad selection option");
  std::set<std::string> names;
  for (const DemoLog& log : logs) {
    if (!names.insert(FileName(log.source)).second) {
      throw InputError(log.source + ": another log has the same file name '" +
                       FileName(log.source) + "'");
    }
  }

  SelectionResult result;
  result.logs = static_cast<int>(logs.size());
  GraspLibrary& library = result.library;
  library.demo_directory = directory;
  library.seed = options.robustness.seed;
  library.perturbations = options.robustness.trials;
  library.tie_rule = std::string(kTieRule);

  std::vector<Scored> scored = SegmentLogs(logs, options, &result);
  RobustnessOptions robustness = options.robustness;  // its seed is each demonstration's
  ProgressCounter counter(static_cast<int>(scored.size()) * (options.robustness.trials + 1),
                          progress);
  ParallelFor(static_cast<int>(scored.size()), options.robustness.threads, [&](int i) {
    PrepareNominal(model, options, &scored[static_cast<size_t>(i)], &counter);
  });
  LocalJobRunner local;
  JobRunner& runner = options.runner ? *options.runner : local;
  JobStage nominal;
  nominal.name = "selection-nominal";
  nominal.count = static_cast<int>(scored.size());
  nominal.threads = options.robustness.threads;
  nominal.run = [&](int i) {
    return RunNominal(model, options, scored[static_cast<size_t>(i)], &counter);
  };
  nominal.payload = kNominalLayout;
  nominal.check = [](int i, std::string_view bytes) { DecodeNominal(bytes, i); };
  nominal.finished = [&](int i, bool here) {
    const Scored& s = scored[static_cast<size_t>(i)];
    if (!here && s.replay.ok) counter.Add(1, s.candidate.score.file);
  };
  const std::vector<std::string> nominal_results = runner.Run(nominal);
  for (size_t i = 0; i < scored.size(); ++i) {
    scored[i].candidate.score.nominal_success =
        DecodeNominal(nominal_results[i], static_cast<int>(i));
  }
  for (const Scored& s : scored) {
    if (s.issue) result.issues.push_back(*s.issue);
  }
  const std::vector<std::vector<Scored*>> orientations = GroupByPlacement(&scored);
  // each orientation on its share of the threads (one, when there are more orientations than
  // threads; a replay never depends on the thread that runs it).
  const ThreadSplit split =
      SplitThreads(options.robustness.threads, static_cast<int>(orientations.size()));
  robustness.threads = split.inner;
  JobStage perturbed;
  perturbed.name = "selection";
  perturbed.count = static_cast<int>(orientations.size());
  perturbed.threads = split.outer;
  perturbed.run = [&](int k) {
    const std::vector<Scored*>& order = orientations[static_cast<size_t>(k)];
    ScoreOrientation(model, options, robustness, order, &counter);
    return EncodeScores(order);
  };
  perturbed.payload = kScoresLayout;
  // job k's scores from its bytes into `scores`: a kept one is checked with it (into scratch
  // scores), and every one read back.
  const auto decode = [](int k, std::string_view bytes, const std::vector<DemoScore*>& scores) {
    DecodeScores(bytes, "selection job " + std::to_string(k), scores);
  };
  perturbed.check = [&](int k, std::string_view bytes) {
    std::vector<DemoScore> scratch;
    for (const Scored* s : orientations[static_cast<size_t>(k)]) {
      scratch.push_back(s->candidate.score);
    }
    decode(k, bytes, Pointers(&scratch));
  };
  perturbed.finished = [&](int k, bool here) {
    if (here) return;
    for (const Scored* s : orientations[static_cast<size_t>(k)]) {
      if (s->replay.ok) counter.Add(options.robustness.trials, s->candidate.score.file);
    }
  };
  const std::vector<std::string> perturbed_results = runner.Run(perturbed);
  for (size_t k = 0; k < orientations.size(); ++k) {
    std::vector<DemoScore*> scores;
    for (Scored* s : orientations[k]) scores.push_back(&s->candidate.score);
    decode(static_cast<int>(k), perturbed_results[k], scores);
  }

  PickRepresentatives(options, &scored, &result);
  for (const Scored& s : scored) library.scores.push_back(s.candidate.score);
  std::stable_sort(
      result.issues.begin(), result.issues.end(),
      [](const SelectionIssue& a, const SelectionIssue& b) { return a.file < b.file; });
  return result;
}

SelectionResult SelectRepresentatives(const SimulationModel& model,
                                      const std::filesystem::path& directory,
                                      const SelectionOptions& options,
                                      const SelectionProgress& progress) {
  RequireValid(options, "bad selection option");
  return SelectRepresentatives(model, ReadDemoDirectory(directory), options, progress);
}

SelectionResult SelectRepresentatives(const SimulationModel& model, const DemoDirectory& demos,
                                      const SelectionOptions& options,
                                      const SelectionProgress& progress) {
  SelectionResult result =
      SelectRepresentatives(model, demos.logs, demos.directory, options, progress);
  for (const RejectedDemoFile& rejected : demos.rejected) {
    result.issues.push_back(
        {FileName(rejected.file), SelectionIssueKind::kUnreadable, rejected.reason});
  }
  std::stable_sort(
      result.issues.begin(), result.issues.end(),
      [](const SelectionIssue& a, const SelectionIssue& b) { return a.file < b.file; });
  return result;
}

}  // namespace graspsynth
