#!/usr/bin/env bash
# Scale-out, measured on this machine and projected (issue 20): `graspsynth generalize` over
# 20-100 deg every 5 deg, two methods (interp+refine, nearest), a nominal trial and 5 perturbed
# replays per grasp (the physics perturbed), one worker thread per process:
# - as a single process, under `mpirun -n 2` (one rank per core), as one process with two
#   worker threads (the local runner: what this machine's two cores give without MPI), and as
#   two independent processes side by side, each on half of the orientations (no MPI: what
#   two processes on this machine's two cores cost each grasp, whatever runs them);
# - the three CSV files compared byte for byte;
# - from each grasp's own wall time (the markdown's synthesis and gate columns): the time per
#   grasp and per trial, the share of the wall time outside the grasps (start-up, library,
#   gather, writing), the speed-up from 1 to 2 ranks;
# - rank 0's cost per result and the cost of a job run on another rank
#   (build/benchmarks/job_runner_benchmark, alone and under `mpirun -n 2`);
# - a model of the speed-up at 64 and 1,024 ranks (scaling_report.py).
# Writes experiments/results/scaling/ (scaling.md, the two runs' CSV and markdown, times.json,
# the benchmarks' JSON). About 12 minutes on 2 cores; needs the build's MPI runner
# (scripts/setup.sh builds it when Open MPI is installed) and an otherwise idle machine: the
# speed-up of two ranks on two cores is only measured right when nothing else runs.
#
#   experiments/scaling.sh [BUILD_DIR]     (default: build)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${root}/${1:-build}"
graspsynth="${build}/apps/graspsynth"
out="${root}/experiments/results/scaling"
cd "${root}"
mkdir -p "${out}"
command -v mpirun > /dev/null || {
  echo "scaling.sh: mpirun not found (scripts/setup.sh installs Open MPI)" >&2
  exit 2
}
mpirun_flags=(--oversubscribe)
[[ "$(id -u)" == 0 ]] && mpirun_flags+=(--allow-run-as-root)
common=(--methods interp+refine,nearest --perturb 5 --seed 1)
args=(generalize --orientations 20:100:5 "${common[@]}")

now() { date +%s.%N; }
echo "== one process"
t0=$(now)
"${graspsynth}" "${args[@]}" --threads 1 --name ranks1 --out "${out}" > /dev/null
t1=$(now)
echo "== mpirun -n 2"
mpirun "${mpirun_flags[@]}" -n 2 "${graspsynth}" "${args[@]}" --threads 1 --name ranks2 \
  --out "${out}" > /dev/null
t2=$(now)
echo "== one process, two threads"
"${graspsynth}" "${args[@]}" --threads 2 --name threads2 --out "${out}" > /dev/null
t3=$(now)
echo "== two independent processes side by side, one thread each (20-60 deg and 65-100 deg)"
"${graspsynth}" generalize --orientations 20:60:5 "${common[@]}" --threads 1 --name procs2a \
  --out "${out}" > /dev/null &
first=$!
"${graspsynth}" generalize --orientations 65:100:5 "${common[@]}" --threads 1 --name procs2b \
  --out "${out}" > /dev/null
wait "${first}"
t4=$(now)
cmp "${out}/ranks1.csv" "${out}/ranks2.csv"
cmp "${out}/ranks1.csv" "${out}/threads2.csv"
echo "the CSV files are the same bytes"
echo "== rank 0's cost per job (job_runner_benchmark, alone and under mpirun -n 2)"
"${build}/benchmarks/job_runner_benchmark" --benchmark_out="${out}/bench_local.json" \
  --benchmark_out_format=json > /dev/null
mpirun "${mpirun_flags[@]}" -n 2 "${build}/benchmarks/job_runner_benchmark" \
  --benchmark_out="${out}/bench_mpi2.json" --benchmark_out_format=json > /dev/null
machine="$(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores"
python3 - "${out}/times.json" "${t0}" "${t1}" "${t2}" "${t3}" "${t4}" "${machine}" "${args[*]}" <<'PY'
import datetime, json, sys
path, t0, t1, t2, t3, t4, machine, args = sys.argv[1], *map(float, sys.argv[2:7]), *sys.argv[7:]
with open(path, "w") as f:
    json.dump({"ranks1_s": t1 - t0, "ranks2_s": t2 - t1, "threads2_s": t3 - t2,
               "procs2_s": t4 - t3, "machine": machine,
               "date": datetime.date.today().isoformat(), "args": args[len("generalize "):] + " --threads 1"},
              f, indent=2)
PY
python3 "${root}/experiments/scaling_report.py" "${out}"
