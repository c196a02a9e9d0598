#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang with ASan and UBSan) in build-fuzz/ and fuzzes
# each for SECONDS (default 60) on its seed corpus, one target after another. New inputs that
# reach new code go to build-fuzz/corpus/NAME/ (kept between runs; copy the useful ones into
# fuzz/corpus/NAME/), crashes to build-fuzz/findings/NAME/. Prints per target the executions,
# the coverage reached and the findings; exits 1 when any target found something.
#
#   scripts/fuzz.sh [--jobs N] [SECONDS] [TARGET ...]
#       every target by default; --jobs N runs N targets at a time (default 1), e.g.
#       scripts/fuzz.sh --jobs 2 600      scripts/fuzz.sh 60 gstp http
#   scripts/fuzz.sh --build-only
set -euo pipefail
jobs=1
if [[ ${1:-} == --jobs ]]; then
  jobs=$2
  shift 2
fi
cd "$(dirname "$0")/.."
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$(cd .. && pwd)}
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DGRASPSYNTH_FUZZ=ON -DGRASPSYNTH_BUILD_TESTS=OFF -DGRASPSYNTH_BUILD_BENCHMARKS=OFF > /dev/null
cmake --build build-fuzz --target graspsynth_fuzz
if [[ ${1:-} == --build-only ]]; then exit 0; fi

seconds=${1:-60}
shift || true
targets=("$@")
if ((${#targets[@]} == 0)); then
  for f in fuzz/*_fuzz.cpp; do targets+=("$(basename "${f}" _fuzz.cpp)"); done
fi
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# one target: its run, then one line with what it did (and its findings).
fuzz_one() {
  local t=$1
  local corpus=build-fuzz/corpus/${t} findings=build-fuzz/findings/${t}
  local log=build-fuzz/fuzz_${t}.log result=0
  mkdir -p "${corpus}" "${findings}"
  "build-fuzz/fuzz/${t}_fuzz" "${corpus}" "fuzz/corpus/${t}" -max_total_time="${seconds}" \
    -max_len=65536 -timeout=30 -rss_limit_mb=2048 -artifact_prefix="${findings}/" \
    -print_final_stats=1 > "${log}" 2>&1 || result=1
  local runs cov
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "${log}" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "${log}" | tail -1)
  echo "== ${t}: ${seconds} s, ${runs:-?} executions, ${cov:-cov: ?} edges, $(ls "${corpus}" | wc -l) inputs kept" >&2
  if ((result)); then echo "   FOUND: $(ls "${findings}")  (log: ${log})" >&2; fi
  return ${result}
}

status=0
running=0
for t in "${targets[@]}"; do
  if ((running >= jobs)); then
    wait -n || status=1
    running=$((running - 1))
  fi
  fuzz_one "${t}" &
  running=$((running + 1))
done
while ((running > 0)); do
  wait -n || status=1
  running=$((running - 1))
done
exit ${status}
