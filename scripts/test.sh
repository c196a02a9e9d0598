#!/usr/bin/env bash
# Runs the whole test suite: the Release build in build/, the same tests built with
# AddressSanitizer + UndefinedBehaviorSanitizer in build-asan/, and the fuzz regression: every
# libFuzzer target of fuzz/ (clang, ASan + UBSan, build-fuzz/) replays its seed corpus and
# fuzzes 2000 inputs more. Any failure or sanitizer report fails the run.
#
#   scripts/test.sh          all three
#   scripts/test.sh --fast   the Release build only
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
# ccache keys on paths below this folder relative to it, so clones elsewhere share the cache.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$(cd .. && pwd)}

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build
ctest --test-dir build --output-on-failure -j "$jobs"

if [[ ${1:-} == --fast ]]; then exit 0; fi

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# -O1 -g1 (line tables only): the sanitizers' usual level, and about half the compile time of
# -O2 -g on this template-heavy code (Eigen, CGAL, Ceres); reports still name file and line.
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGRASPSYNTH_SANITIZE=ON \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DGRASPSYNTH_BUILD_BENCHMARKS=OFF
cmake --build build-asan
ctest --test-dir build-asan --output-on-failure -j "$jobs"

# the fuzz regression (scripts/fuzz.sh fuzzes for longer).
scripts/fuzz.sh --build-only
ctest --test-dir build-fuzz --output-on-failure -j "$jobs"
