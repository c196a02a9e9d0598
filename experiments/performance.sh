#!/usr/bin/env bash
# Experiment 4, performance, on this machine: the analytic IK against orocos KDL, the speed of a
# simulated trial against real time, the synthesis latency against the 60 Hz tick (scripted
# and shipped libraries) and the physics gate, and the wall time of `graspsynth run` with 1 and
# 2 threads (its scaling). Timings depend on the machine; the script records it.
# Writes experiments/results/performance.md, the raw Google Benchmark JSON (perf_*.json), and
# the 2-thread study's report.md and summary (study_report.md, study_summary.txt). No file keeps
# a path of this machine: the benchmarks run from the project root by a relative path and their
# JSON goes through experiments/benchmark_context.py; the study reads the shipped demonstrations
# (named learning_data/demos) and writes into study_N of the temporary folder, its working folder.
#
#   experiments/performance.sh [BUILD_DIR]      (default: build, relative to the project root)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build_arg="${1:-build}"
build="${root}/${build_arg}"
out="${root}/experiments/results"
tmp="$(mktemp -d)"
trap 'rm -rf "${tmp}"' EXIT
mkdir -p "${out}"
cd "${root}"
bench() {
  local name="$1"
  shift
  "${build_arg}/benchmarks/${name}" --benchmark_out="${out}/perf_${name}.json" \
    --benchmark_out_format=json "$@" >"${tmp}/${name}.txt"
  python3 "${root}/experiments/benchmark_context.py" --root "${root}" "${out}/perf_${name}.json"
}
echo "benchmarks (several minutes)..." >&2
bench ik_benchmark
bench simulation_benchmark
bench synthesis_benchmark
study_time() {
  local threads="$1"
  (cd "${tmp}" && "${build}/apps/graspsynth" run --threads "${threads}" --out "study_${threads}" \
    >"study_${threads}.txt" 2>/dev/null)
  grep -o '"total_s": [0-9.]*' "${tmp}/study_${threads}/timing.json" | awk '{printf "%.1f", $2}'
}
echo "graspsynth run with 2 threads, then 1 thread (about 20 minutes)..." >&2
t2="$(study_time 2)"
t1="$(study_time 1)"
cp "${tmp}/study_2/report.md" "${out}/study_report.md"
cp "${tmp}/study_2.txt" "${out}/study_summary.txt"
{
  echo "# Performance (experiment 4)"
  echo
  echo "Machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc)" \
    "cores, $(free -g | awk '/Mem:/ {print $2}') GB, $(. /etc/os-release && echo "${PRETTY_NAME}")," \
    "$(g++ --version | head -1); $(date -u +%Y-%m-%d). Written by experiments/performance.sh;" \
    "benchmarks/README.md explains every benchmark."
  echo
  echo "## graspsynth run (the main job, shipped demonstrations, defaults)"
  echo
  echo "| threads | wall time (s) |"
  echo "|---|---|"
  echo "| 1 | ${t1} |"
  echo "| 2 | ${t2} |"
  echo
  echo "Speed-up from 1 to 2 threads: $(awk -v a="${t1}" -v b="${t2}" 'BEGIN {printf "%.2f", a / b}')x."
  for name in ik_benchmark simulation_benchmark synthesis_benchmark; do
    echo
    echo "## ${name}"
    echo
    echo '```'
    cat "${tmp}/${name}.txt"
    echo '```'
  done
} >"${out}/performance.md.tmp"
mv "${out}/performance.md.tmp" "${out}/performance.md"
echo "wrote ${out}/performance.md"
