#!/usr/bin/env bash
# Session 24, first call (branch tile-queue-fix: the tile queue's diagnostic knobs FCC_TQ_DIRECT and
# FCC_TQ_ROWMAJOR, not on main): (1) the queue's tricubic scratch test on NVIDIA with the full queue, one
# tile a group (FCC_TQ_DIRECT=2), tiles assigned statically several a group (=4, no atomics) and the
# queue in row-major order; (2) the images of `fccvdb render` grid against queue, EXR and PNG bytes;
# (3) FCC_TF_NAN=2 (min then max: NaN as entry 0 through the drivers' minNum/maxNum) against 1 (isnan):
# the NaN test and the frame rates, alternating, two rounds. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard build/bin/test_render_dvr ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session24_call1.sh        (SMALL=1: toy sizes)
set -u
HERE=$(pwd)
B=$(dirname "$(command -v fccvdb)")
[ "$B/fccvdb" -ef /work/main/build/bin/fccvdb ] || { mkdir -p /work/main/build/bin && ln -sf "$B/fccvdb" /work/main/build/bin/fccvdb; }
scratch() {  # $1: shader defines, $2: groups
  (cd "$HERE" && FCCVDB_SHADER_DEFINES="$1" SCRATCH_GROUPS=$2 "$B/test_render_dvr" --gtest_filter='*ScratchTricubicQueue*' 2>&1 | grep -E "^bad|rror" | head -3)
}
for v in "FCC_TQ_DIRECT=0:64" "FCC_TQ_DIRECT=0:1" "FCC_TQ_DIRECT=2:1000" "FCC_TQ_DIRECT=4:7" "FCC_TQ_DIRECT=4:1" "FCC_TQ_ROWMAJOR=1:1000" "FCC_TQ_ROWMAJOR=1:1"; do
  echo "-- scratch ${v%%:*} groups ${v##*:}: $(scratch "${v%%:*}" "${v##*:}")"
done
W=${W:-/tmp/m24}; source "$(dirname "$0")/bench_data.sh"
for job in "engine.vdb" "ml.vdb --iso 0.5" "engine.vdb --mode dvr --tf inferno"; do
  FCCVDB_TILE_QUEUE=0 fccvdb render $job --res $RES -o grid.exr --force --quiet
  FCCVDB_TILE_QUEUE=0 fccvdb render $job --res $RES -o grid.png --force --quiet
  fccvdb render $job --res $RES -o queue.exr --force --quiet
  fccvdb render $job --res $RES -o queue.png --force --quiet
  FCCVDB_SHADER_DEFINES=FCC_TQ_DIRECT=2 FCCVDB_TILE_QUEUE=1000000 fccvdb render $job --res $RES -o direct.exr --force --quiet
  echo "render $job: queue exr $(cmp -s grid.exr queue.exr && echo same || echo DIFFERENT), png $(cmp -s grid.png queue.png && echo same || echo DIFFERENT); one tile a group exr $(cmp -s grid.exr direct.exr && echo same || echo DIFFERENT)"
done
for round in 1 2; do
  for k in 1 2; do
    echo "-- round $round FCC_TF_NAN=$k engine DVR inferno $(FCCVDB_TILE_QUEUE=0 FCCVDB_SHADER_DEFINES=FCC_TF_NAN=$k fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps)"
    echo "-- round $round FCC_TF_NAN=$k ML DVR viridis $(FCCVDB_TILE_QUEUE=0 FCCVDB_SHADER_DEFINES=FCC_TF_NAN=$k fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps)"
  done
done
cd "$HERE"
for k in 1 2; do
  echo "-- NaN test FCC_TF_NAN=$k"
  FCCVDB_TILE_QUEUE=0 FCCVDB_SHADER_DEFINES=FCC_TF_NAN=$k "$B/test_render_dvr" --gtest_filter='*NanSamples*:*SkippingAndSmallCaches*' 2>&1 | grep -E "^\[  (FAILED|     OK) |dB|changed|Which is" | grep -v "^\[  FAILED  \] [0-9]" | cut -c1-200 | head -12
done
true
