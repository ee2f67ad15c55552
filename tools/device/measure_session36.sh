#!/usr/bin/env bash
# Session 36: session 34's second call, shortened for a small device budget: the flat walk with a ray's
# brick steps first (FCC_DVR_BRICKS_FIRST=1) against main's, the bench's DVR frame rates at 1080p (the
# engine CT inferno, ML 160^3x4 FCC viridis), alternating, ROUNDS rounds (default 2), then the two
# variants' images compared byte for byte. Bundle and run as measure_session34_call2.sh says.
source tools/device/prologue.sh
W=${W:-/tmp/m36}; source "$HERE/tools/device/bench_data.sh"
for round in $(seq 1 "${ROUNDS:-2}"); do
  for defs in "FCC_DVR_BRICKS_FIRST=0" "FCC_DVR_BRICKS_FIRST=1"; do
    run() { FCCVDB_SHADER_DEFINES="$defs" fccvdb bench render "$@" "${D[@]}" | fps; }
    echo "-- round $round [$defs]: engine DVR inferno $(run engine.vdb --mode dvr --tf inferno) ML DVR viridis $(run ml.vdb --mode dvr --tf viridis)"
  done
done
for v in 0 1; do
  for f in engine:inferno ml:viridis; do
    FCCVDB_SHADER_DEFINES="FCC_DVR_BRICKS_FIRST=$v" fccvdb render ${f%%:*}.vdb ${f%%:*}_$v.exr --mode dvr --tf ${f##*:} --res $RES --force --quiet
  done
done
cmp engine_0.exr engine_1.exr && cmp ml_0.exr ml_1.exr && echo "images: the same bytes"
