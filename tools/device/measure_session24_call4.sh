#!/usr/bin/env bash
# Session 24, fourth call. (1) Which part of the tile queue changes the engine's isosurface at 1080p on
# NVIDIA (pixels against the grid dispatch's, tools/device/pngdiff.py), with `fccvdb-tq`, the branch
# tile-queue-fix's build (tools/device/session24_tile_queue.patch): static tiles handed through shared
# memory and barriers (FCC_TQ_DIRECT=5), static tiles beside an atomic on the queue's buffer (=6), the
# queue with request() taking the atomic alone (FCC_REQUEST_TEST_FIRST=0), the queue handing the tile
# through a subgroup broadcast (FCC_TQ_SUBGROUP); one differing pixel's passes (TQ_PIXEL). (In the call
# fccvdb-tq was a broken build: this part printed nothing.) (2) dvrChord3's lookup before the sub-step
# rule (FCC_DVR_SPECULATE 1, commit 019e30f, reverted since) against after it (0), alternating, two
# rounds. (3) Work groups of K 4x8 tiles (FCCVDB_GROUP_TILES, commit 6418783, reverted since: the
# group's size caps a thread's registers, 512 threads 128, 768 85, 1024 64, while each warp keeps one
# tile's rays), two rounds.
# Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-tq build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session24_call4.sh        (SMALL=1: toy sizes)
set -u
HERE=$(pwd)
W=${W:-/tmp/m24}; source "$(dirname "$0")/bench_data.sh"
DIFF="python3 $HERE/tools/device/pngdiff.py"
if command -v fccvdb-tq > /dev/null; then
  FCCVDB_TILE_QUEUE=0 fccvdb-tq render engine.vdb --res $RES -o grid.png --force --quiet
  for v in FCC_TQ_DIRECT=5 FCC_TQ_DIRECT=6 FCC_REQUEST_TEST_FIRST=0 FCC_TQ_SUBGROUP=1; do
    FCCVDB_SHADER_DEFINES="$v" fccvdb-tq render engine.vdb --res $RES -o v.png --force --quiet 2>&1 | head -3
    echo "$v: $($DIFF grid.png v.png | cut -c1-200)"
  done
  echo "-- pixel 907,247, grid then queue"
  TQ_PIXEL=907,247 FCCVDB_TILE_QUEUE=0 fccvdb-tq render engine.vdb --res $RES -o g.png --force --quiet 2>&1 | head -12
  TQ_PIXEL=907,247 fccvdb-tq render engine.vdb --res $RES -o q.png --force --quiet 2>&1 | head -12
fi
for round in 1 2; do
  for k in 0 1; do
    echo "-- round $round FCC_DVR_SPECULATE=$k engine DVR inferno $(FCCVDB_SHADER_DEFINES=FCC_DVR_SPECULATE=$k fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps)"
    echo "-- round $round FCC_DVR_SPECULATE=$k ML DVR viridis $(FCCVDB_SHADER_DEFINES=FCC_DVR_SPECULATE=$k fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps)"
  done
done
for round in 1 2; do
  for k in 1 16 24 32; do
    echo "-- round $round FCCVDB_GROUP_TILES=$k engine DVR inferno $(FCCVDB_GROUP_TILES=$k fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps)"
    echo "-- round $round FCCVDB_GROUP_TILES=$k ML DVR viridis $(FCCVDB_GROUP_TILES=$k fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps)"
  done
done
true
