#!/usr/bin/env bash
# Runs each fuzz target over a copy of its seed corpus (tests/fuzz/corpus/<target>/, never written to) for
# SECONDS, one target after another, one process each, with the memory caps docs/RELIABILITY.md gives.
# Prints one line per target; at the first crash, leak, hang, sanitizer report or allocation beyond the
# cap, prints the end of its log and exits 1, leaving the log and the input in the work folder.
#
#   tests/fuzz/run_fuzzers.sh BUILD_DIR SECONDS [TARGET...]
#       (targets: vdb_leaf_reader nrrd nifti raw cartesian_range_cache transfer_function)
#
# FCC_FUZZ_SEED (default 1) seeds libFuzzer's mutations: with a fixed seed the same binary and corpus try
# the same inputs in the same order, so a run is reproducible and CI's verdict does not depend on luck
# (a faster machine only gets further along the same sequence). FCC_FUZZ_SEED=0 draws a random seed:
# use it for the long runs that look for new bugs (docs/RELIABILITY.md).
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: $0 BUILD_DIR SECONDS [TARGET...]" >&2
  exit 2
fi
build=$1
seconds=$2
shift 2
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(vdb_leaf_reader nrrd nifti raw cartesian_range_cache transfer_function)
seed=${FCC_FUZZ_SEED:-1}
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/fccvdb-fuzz.XXXXXX")

for t in "${targets[@]}"; do
  mkdir -p "$work/$t/corpus" "$work/$t/artifacts"
  cp "$here/corpus/$t/"* "$work/$t/corpus/"
  log="$work/$t/log.txt"
  # -timeout: one input running longer is a hang. -rss_limit_mb/-malloc_limit_mb: a reader must refuse an
  # absurd size before allocating it.
  if ! "$build/fuzz/fuzz_$t" "$work/$t/corpus" -seed="$seed" -max_total_time="$seconds" -timeout=25 -rss_limit_mb=2048 \
      -malloc_limit_mb=1024 -print_final_stats=1 -artifact_prefix="$work/$t/artifacts/" >"$log" 2>&1; then
    echo "fuzz_$t: FAILED; its log and input are in $work/$t" >&2
    tail -n 40 "$log" >&2
    exit 1
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  done_line=$(grep -E '^#[0-9]+[[:space:]]+DONE' "$log" | tail -n 1)
  cov=$(echo "$done_line" | grep -o 'cov: [0-9]*' || true)
  ft=$(echo "$done_line" | grep -o 'ft: [0-9]*' || true)
  corp=$(echo "$done_line" | grep -o 'corp: [0-9]*/[0-9]*[a-zA-Z]*' || true)
  echo "fuzz_$t: clean for ${seconds} s (seed $seed): $runs runs, $cov, $ft, $corp"
done
rm -rf "$work"
