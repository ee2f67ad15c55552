#!/usr/bin/env bash
# Session 24, third call (branch tile-queue-fix): the engine's isosurface at 1080p with the tile queue,
# the tiles each pass processed (FCC_TQ_COUNT, TQ_DEBUG) against the queue's tiles (65 280 with the
# 8x8 blocks' padding), and the pixels that differ from the grid dispatch's (tools/device/pngdiff.py)
# for the queue, one counter instead of regions (FCC_TQ_SIMPLE), and static tiles with a barrier
# after each (FCC_TQ_DIRECT=4, FCC_TQ_BARRIER). Run as call 1.
set -u
HERE=$(pwd)
W=${W:-/tmp/m24}; source "$(dirname "$0")/bench_data.sh"
DIFF="python3 $HERE/tools/device/pngdiff.py"
FCCVDB_TILE_QUEUE=0 fccvdb render engine.vdb --res $RES -o grid.png --force --quiet
echo "-- queue, counted"
TQ_DEBUG=1 FCCVDB_SHADER_DEFINES="FCC_TQ_COUNT=1" fccvdb render engine.vdb --res $RES -o q.png --force --quiet 2>&1 | head -20
echo "queue: $($DIFF grid.png q.png | cut -c1-300)"
echo "-- one counter, counted"
TQ_DEBUG=1 FCCVDB_SHADER_DEFINES="FCC_TQ_COUNT=1;FCC_TQ_SIMPLE=1" fccvdb render engine.vdb --res $RES -o s.png --force --quiet 2>&1 | head -20
echo "one counter: $($DIFF grid.png s.png | cut -c1-300)"
FCCVDB_SHADER_DEFINES="FCC_TQ_DIRECT=4;FCC_TQ_BARRIER=1" fccvdb render engine.vdb --res $RES -o b.png --force --quiet
echo "static tiles with a barrier: $($DIFF grid.png b.png | cut -c1-300)"
true
