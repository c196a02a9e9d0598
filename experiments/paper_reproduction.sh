#!/usr/bin/env bash
# Experiment 1, paper reproduction: Table I of the shipped demonstrations beside the paper's
# values with the differences, the paper's Fig. 8 (gnuplot), and the wrist-line and radial fits
# (analysis.json). Deterministic: the shipped logs are fixed, the analysis has no randomness.
#
#   experiments/paper_reproduction.sh [BUILD_DIR]      (default: build)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
graspsynth="${root}/${1:-build}/apps/graspsynth"
out="${root}/experiments/results"
mkdir -p "${out}"
"${graspsynth}" analyze "${root}/learning_data/demos" \
  --out "${out}/analysis.json" --table "${out}/table1.md" --plot "${out}/fig8.svg"
echo "wrote ${out}/analysis.json, table1.md and fig8.svg"
