#!/usr/bin/env bash
# Session 34, second call: the flat walk with a ray's brick steps first, then the round, in one
# iteration (raycast.comp's FCC_DVR_BRICKS_FIRST=1; the images the same bit for bit on llvmpipe),
# against main's iteration that is a round or a brick step: the bench's DVR frame rates at 1080p
# (the engine CT inferno, ML 160^3x4 FCC viridis), alternating, three rounds, then both variants'
# cycles by phase (FCC_DVR_CLOCK=1) and their images compared. Run as in measure_session34_call1.sh.
# For a small device budget: ROUNDS=N rounds (default 3); CLOCK=0 leaves the cycle phases out.
source tools/device/prologue.sh
W=${W:-/tmp/m34}; source "$HERE/tools/device/bench_data.sh"
for round in $(seq 1 "${ROUNDS:-3}"); do
  for defs in "FCC_DVR_BRICKS_FIRST=0" "FCC_DVR_BRICKS_FIRST=1"; do
    run() { FCCVDB_SHADER_DEFINES="$defs" fccvdb bench render "$@" "${D[@]}" | fps; }
    echo "-- round $round [$defs]: engine DVR inferno $(run engine.vdb --mode dvr --tf inferno) ML DVR viridis $(run ml.vdb --mode dvr --tf viridis)"
  done
done
for v in 0 1; do
  for f in engine:inferno ml:viridis; do
    if [ "${CLOCK:-1}" != 0 ]; then
      echo "== ${f%%:*} ${f##*:}, FCC_DVR_BRICKS_FIRST=$v"
      FCCVDB_SHADER_DEFINES="FCC_DVR_CLOCK=1;FCC_DVR_BRICKS_FIRST=$v" fccvdb render ${f%%:*}.vdb clock.exr --mode dvr --tf ${f##*:} \
        --res $RES --lookahead 64 --force --quiet && fcc_dvr_clock_phases clock.exr 4 8 1
    fi
    FCCVDB_SHADER_DEFINES="FCC_DVR_BRICKS_FIRST=$v" fccvdb render ${f%%:*}.vdb ${f%%:*}_$v.exr --mode dvr --tf ${f##*:} --res $RES --force --quiet
  done
done
cmp engine_0.exr engine_1.exr && cmp ml_0.exr ml_1.exr && echo "images: the same bytes"
true
