#!/usr/bin/env bash
# Session 13, fifth call: the host cache's hit counter per shard (was one atomic all loader threads wrote).
set -u
W=/tmp/m13; mkdir -p $W; cd $W
R=(--layout texture-vec4 --variants skip+analytic --gpu-cache 784 --host-cache 1024 --iso 0.3 --res 1920x1080)
T() { echo "\$ $*"; /usr/bin/time -f 'time: %e s %M KiB' timeout "$@" 2>&1 | grep -v "^\[" | tail -6; }
[ -s b2k.vdb ] || T 120 fccvdb synth blobs b2k.vdb --dims 2048,2048,2048 --pyramid --force --quiet
for i in 1 2 3 4; do echo "== bench bricks $i"; T 60 fccvdb bench bricks b2k.vdb --bricks 400000 --layout texture-vec4 | grep -E "blocks|decode|open|time:"; done
echo "== full turn"; T 60 fccvdb bench render b2k.vdb "${R[@]}" --frames 30 --warmup 3 | grep -E "texture|time:"
echo "== 15 deg drag"; T 60 fccvdb bench render b2k.vdb "${R[@]}" --arc 15 --frames 60 --warmup 60 | grep -E "texture|time:"
