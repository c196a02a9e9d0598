#!/usr/bin/env bash
# The fuzz regression of the test suite: TARGET replays every input of its seed corpus, then
# runs 2000 fuzzing iterations from a fixed seed (new inputs go to WORK_DIR, never into the
# repository). A crash, a sanitizer report, a leak or an exception other than InputError fails.
#
#   fuzz/regression.sh TARGET CORPUS_DIR WORK_DIR
set -euo pipefail
target=$1 corpus=$2 work=$3
rm -rf "${work}"
mkdir -p "${work}/new" "${work}/artifacts"
exec "${target}" "${work}/new" "${corpus}" -runs=2000 -seed=1 -max_len=65536 -timeout=30 \
  -rss_limit_mb=2048 -artifact_prefix="${work}/artifacts/" -print_final_stats=1
