#!/usr/bin/env bash
# The other objects and the placements in two engines (issue 45), beside experiments/engines.sh's
# pan study. Parts:
# - mug, sugar_box, saucepan: `graspsynth synthesize --object NAME --theta T` (the object's
#   library, learning_data/objects/NAME/library.json) at 10 orientations, 24-96 deg every 8;
# - placements: the pan at 12 of the placements experiment's 144 held-out placements inside the
#   demonstrated grid (experiments/placements.sh): the inside grid's four corners, x -0.28 and
#   -0.22 m, y 0.82 and 0.88 m (each between demonstrated positions), at 33, 63 and 93 deg;
#   `synthesize --library learning_data/placements/library.json --at X,Y --theta T`.
# Each grasp goes through ODE's default gate (nominal trial and 30 perturbed replays; written
# with --force when it fails, so that the table says why); a grasp the gate passes is replayed
# in MuJoCo's sweep (`simulate --engine mujoco --mujoco-sweep`: 8 contact settings x the stiff
# and soft servo mappings, 16 runs, about 31 CPU-s). Writes experiments/results/engines_objects/
# PART/ (gate_LABEL.json: the gate's verdict, small; sweep_LABEL.json: the sweep; the grasps,
# 340 kB each, stay in BUILD_DIR/engines-grasps/PART/) and the table
# experiments/results/engines_objects.md (experiments/engines_report.py, shared with
# engines.sh) of every part with results there. Deterministic (seed 1).
#
#   experiments/engines_objects.sh [BUILD_DIR] [PART ...]
#       (default: build, then mug sugar_box saucepan placements, one after the other)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-build}"
shift || true
graspsynth="${root}/${build}/apps/graspsynth"
out="${root}/experiments/results"
report="${root}/experiments/engines_report.py"
parts=("$@")
[ ${#parts[@]} -gt 0 ] || parts=(mug sugar_box saucepan placements)
cd "${root}"

# one grasp: PART LABEL then synthesize's arguments; ${object[@]} names the object to both
# commands (a grasp file does not name its object: without --object, simulate would put the
# scene's pan under a mug's grasp). The grasp's path is relative to the root, so that the sweeps
# name their grasp files the same on any clone. A grasp file newer than graspsynth is kept (a
# rerun after a stop only sweeps it again).
grasp() {
  local part="$1" label="$2"
  shift 2
  local dir="${out}/engines_objects/${part}" grasps="${build}/engines-grasps/${part}"
  local name="${label// /_}"
  local g="${grasps}/g_${name}.json"
  mkdir -p "${dir}" "${grasps}"
  echo "== ${part} ${label}" >&2
  rm -f "${dir}/sweep_${name}.json"
  if [ ! "${g}" -nt "${graspsynth}" ]; then
    rm -f "${g}"
    # exit 1: the gate refused the grasp (written all the same, --force, with its verdict).
    "${graspsynth}" synthesize "${object[@]}" "$@" --seed 1 --force --out "${g}" \
      > /dev/null 2>&1 || true
  fi
  if [ ! -e "${g}" ]; then
    echo "${part} ${label}: no grasp written" >&2
    return
  fi
  python3 "${report}" gate "${g}" "${dir}/gate_${name}.json"
  if python3 -c 'import json, sys; sys.exit(0 if json.load(open(sys.argv[1]))["passed"] else 1)' \
    "${dir}/gate_${name}.json"; then
    # exit 1: fewer than 95% of the runs held (a result, not an error).
    "${graspsynth}" simulate "${g}" "${object[@]}" --engine mujoco --mujoco-sweep \
      --out "${dir}/sweep_${name}.json" 2> /dev/null || true
  fi
}

for part in "${parts[@]}"; do
  case "${part}" in
    placements)
      object=()
      for x in -0.28 -0.22; do
        for y in 0.82 0.88; do
          for theta in 33 63 93; do
            grasp placements "${x},${y} ${theta}" --library learning_data/placements/library.json \
              --at "${x},${y}" --theta "${theta}"
          done
        done
      done
      ;;
    *)
      object=(--object "${part}")
      for theta in $(seq 24 8 96); do
        grasp "${part}" "${theta}" --theta "${theta}"
      done
      ;;
  esac
  python3 "${report}" objects "${out}/engines_objects" "${out}/engines_objects.md"
done
