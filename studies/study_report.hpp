#pragma once

/// @file
/// The reports of the study (studies/study.hpp): the synthesis table as CSV, JSON and markdown,
/// the wall times as JSON, and the study's markdown report. Each builder is a pure function of
/// the study's results; the command decides where the text goes.

#include <cstdio>
#include <string>
#include <vector>

#include "common/format.hpp"
#include "studies/study.hpp"

namespace graspsynth {

/// Text helpers shared by the study and its reports.
namespace study_text {

/// A markdown table cell: pipes escaped, line breaks turned into spaces.
std::string Cell(const std::string& text);

/// A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break.
std::string CsvField(const std::string& text);

}  // namespace study_text

/// The row's status as the files write it: ToString(SynthesisStatus), or "no_library" when
/// the synthesis did not run (StudyRow::status unset).
std::string StatusName(const StudyRow& row);

/// The row's method used as the files write it: ToString(SynthesisMethod), or "" when the
/// synthesis did not succeed (StudyRow::used unset).
std::string UsedName(const StudyRow& row);

/// The row's nominal outcome as the files write it: ToString(TrialOutcome), or "" when the
/// gate did not run (StudyRow::nominal_outcome unset).
std::string NominalOutcomeName(const StudyRow& row);

/// The synthesis table as markdown: one line per row (method used, nominal outcome,
/// robustness with its interval, gate, epsilon, synthesis and gate times), then the fallbacks.
std::string SynthesisTableMarkdown(const std::vector<StudyRow>& rows);

/// Per-method summary as markdown: rows, synthesized, nominal successes (and %), mean
/// robustness, gate passes, fallbacks.
std::string SummaryMarkdown(const std::vector<StudyRow>& rows);

/// The nominal trial's hold quality (end and largest tilt, slip, load-bearing fingers) and the
/// sensitivity table (successes at the low · high end of each physics factor's range) of every
/// row whose gate ran, as a Markdown table.
std::string HoldAndSensitivityMarkdown(const std::vector<StudyRow>& rows);

/// ODE and MuJoCo side by side, one line per row whose gate ran MuJoCo (StudyRow::mujoco): the
/// nominal ODE outcome and robustness, MuJoCo's k/n runs held, its slip (median and worst, mm
/// and deg, over the runs that held) and the runs that failed, as a Markdown table; "" when no
/// row has MuJoCo's figures.
std::string EnginesMarkdown(const std::vector<StudyRow>& rows);
/// The thresholds of `options` with their reasons, then the nominal hold's margin of every row
/// whose gate ran (slip, end tilt, contacts per finger and palm, load-bearing links, epsilon at
/// the measured forces, friction use, squeeze, the thresholds missed), as Markdown.
std::string HoldMarginMarkdown(const std::vector<StudyRow>& rows, const HoldMarginOptions& options);

/// "Where a method falls short": every row that did not pass the gate with its reason from the
/// simulator.
std::string ShortfallMarkdown(const std::vector<StudyRow>& rows);

/// The synthesis table as CSV: kStudySynthesisCsvHeader, then one line per row (numbers with 17
/// significant digits, text fields quoted when they hold a comma or a quote). Rows at positions
/// of their own (StudyRow::at) add the columns x and y (m) in front.
std::string StudySynthesisCsv(const std::vector<StudyRow>& rows);

/// The synthesis table as JSON (format kStudySynthesisFormat): `format`, `seed`, `orientations`
/// [deg], `methods`, `gate` {perturbations, min_robustness}, `summary` [per method], `rows`
/// [one per orientation and method, without wall times].
std::string StudySynthesisJson(const StudyResult& result);

/// The per-method summary and the rows of a synthesis table, as StudySynthesisJson writes them:
/// {"summary": [...], "rows": [...]} (`graspsynth generalize`'s table for the Python module).
std::string StudyRowsJson(const std::vector<StudyRow>& rows);

/// The wall times (format kStudyTimingFormat): stages, total, per row synthesis and gate.
std::string StudyTimingJson(const StudyResult& result);

/// The report (markdown): options, Table I beside the paper with differences, Fig. 8, the wrist
/// line and radial residuals, the kinematics check, the library, the synthesis table per
/// orientation and method, per-method summary lines and the failure reasons.
std::string StudyReportMarkdown(const StudyResult& result);

}  // namespace graspsynth
