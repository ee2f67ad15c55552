#!/usr/bin/env bash
# Session 24, second call (branch tile-queue-fix): where the tile queue's isosurface differs from the
# grid dispatch's on NVIDIA (pixels, tools/device/pngdiff.py) with the full queue, static tiles several
# a group (FCC_TQ_DIRECT=4, no atomics), the queue in row-major order, one tile a group (=2); the DVR
# tests against the CPU reference with the queue (the default on NVIDIA) and without. Run as call 1.
set -u
HERE=$(pwd)
B=$(dirname "$(command -v fccvdb)")
[ "$B/fccvdb" -ef /work/main/build/bin/fccvdb ] || { mkdir -p /work/main/build/bin && ln -sf "$B/fccvdb" /work/main/build/bin/fccvdb; }
W=${W:-/tmp/m24}; source "$(dirname "$0")/bench_data.sh"
DIFF="python3 $HERE/tools/device/pngdiff.py"
for job in "engine.vdb" "ml.vdb --iso 0.5"; do
  FCCVDB_TILE_QUEUE=0 fccvdb render $job --res $RES -o grid.png --force --quiet
  FCCVDB_TILE_QUEUE=0 fccvdb render $job --res $RES -o grid2.png --force --quiet
  echo "render $job, grid twice: $($DIFF grid.png grid2.png | cut -c1-400)"
  fccvdb render $job --res $RES -o q.png --force --quiet
  echo "render $job, queue: $($DIFF grid.png q.png | cut -c1-400)"
  FCCVDB_SHADER_DEFINES=FCC_TQ_DIRECT=4 fccvdb render $job --res $RES -o s.png --force --quiet
  echo "render $job, static tiles: $($DIFF grid.png s.png | cut -c1-400)"
  FCCVDB_SHADER_DEFINES=FCC_TQ_ROWMAJOR=1 fccvdb render $job --res $RES -o r.png --force --quiet
  echo "render $job, row-major queue: $($DIFF grid.png r.png | cut -c1-400)"
  FCCVDB_SHADER_DEFINES=FCC_TQ_DIRECT=2 FCCVDB_TILE_QUEUE=1000000 fccvdb render $job --res $RES -o d.png --force --quiet
  echo "render $job, one tile a group: $($DIFF grid.png d.png | cut -c1-400)"
done
cd "$HERE"
F='*MatchesTheCpuReference*:*TileQueue*:*ShadingDarkens*'
for q in 0 -1; do
  echo "== FCCVDB_TILE_QUEUE=$q"
  [ "$q" = -1 ] && unset FCCVDB_TILE_QUEUE || export FCCVDB_TILE_QUEUE=$q
  "$B/test_render_dvr" --gtest_filter="$F" 2>&1 | grep -E "^\[  (FAILED|     OK) |Failure|Which is|dB" | grep -v "^\[  FAILED  \] [0-9]" | cut -c1-160 | head -30
done
true
