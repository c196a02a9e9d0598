#pragma once

#include <CLI/CLI.hpp>

namespace graspsynth::apps {

/// Registers `graspsynth analyze DIR --out report.json [--plot fig.svg] [--table table.md] ...`:
/// the demonstration analysis of the paper's section III-D (Table I, Fig. 8, the wrist line and
/// the radial model). Sets *exit_code to 1 when some log files were rejected (the others are
/// still analyzed and the report is written).
void AddAnalyzeCommand(CLI::App& app, int* exit_code);

}  // namespace graspsynth::apps
