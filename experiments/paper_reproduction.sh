#!/usr/bin/env bash
# Experiment 1, paper reproduction: Table I of the shipped demonstrations beside the paper's
# values with the differences, the paper's Fig. 8 (gnuplot), and the wrist-line and radial fits
# (analysis.json). Deterministic: the shipped logs are fixed, the analysis has no randomness.
#
# Run from the project root with the demonstrations named learning_data/demos, the analysis is
# the bytes of `graspsynth run`'s analysis.json and fig8.svg on any clone (a test compares
# `run --quick`'s with these: tests/apps/run_command_test.cpp).
#
#   experiments/paper_reproduction.sh [BUILD_DIR]      (default: build, relative to the root)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
graspsynth="${root}/${1:-build}/apps/graspsynth"
out="experiments/results"
cd "${root}"
mkdir -p "${out}"
"${graspsynth}" analyze learning_data/demos \
  --out "${out}/analysis.json" --table "${out}/table1.md" --plot "${out}/fig8.svg"
echo "wrote ${out}/analysis.json, table1.md and fig8.svg"
