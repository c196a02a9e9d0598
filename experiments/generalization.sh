#!/usr/bin/env bash
# Experiment 2, generalization: from the shipped grasp library (learning_data/library.json),
# a grasp for every integer orientation from 20 to 100 deg by four methods (the nearest
# demonstration turned with the object, the paper's interpolation, interpolation + refinement,
# the line principle with refinement), each validated in physics (nominal + 10 perturbed
# replays); leave-one-out over the inner demonstrated orientations; extrapolation to 0-19 and
# 101-120 deg with the line principle (and the nearest demonstration for comparison); and the
# plots of success and robustness against orientation. Deterministic from --seed 1.
#
#   experiments/generalization.sh [BUILD_DIR]      (default: build)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
graspsynth="${root}/${1:-build}/apps/graspsynth"
out="${root}/experiments/results"
mkdir -p "${out}"
cd "${root}"
"${graspsynth}" generalize --orientations 20:100:1 \
  --methods nearest,interp,interp+refine,line+refine --perturb 10 --seed 1 \
  --name generalization --out "${out}"
"${graspsynth}" generalize --leave-one-out \
  --methods nearest,interp,interp+refine,line+refine --perturb 10 --seed 1 \
  --name leave_one_out --out "${out}"
"${graspsynth}" generalize --orientations 0:19:1,101:120:1 \
  --methods line+refine,nearest --perturb 10 --seed 1 --name extrapolation --out "${out}"
"${root}/experiments/plot_generalization.sh" "${out}"
