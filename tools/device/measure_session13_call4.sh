#!/usr/bin/env bash
# Session 13, fourth call: the defaults after the automatic look-ahead (no --lookahead).
set -u
W=/tmp/m13; mkdir -p $W; cd $W
R=(--layout texture-vec4 --variants skip+analytic --gpu-cache 784 --host-cache 1024 --iso 0.3 --res 1920x1080)
T() { echo "\$ $*"; /usr/bin/time -f 'time: %e s %M KiB' timeout "$@" 2>&1 | grep -v "^\[" | tail -4; }
[ -s b2k.vdb ] || T 120 fccvdb synth blobs b2k.vdb --dims 2048,2048,2048 --pyramid --force --quiet
for i in 1 2 3 4; do echo "== full turn $i"; T 60 fccvdb bench render b2k.vdb "${R[@]}" --frames 30 --warmup 3 | grep -E "texture|time:"; done
for i in 1 2; do echo "== 15 deg drag $i"; T 60 fccvdb bench render b2k.vdb "${R[@]}" --arc 15 --frames 60 --warmup 60 | grep -E "texture|time:"; done
echo "== 5 deg drag"; T 60 fccvdb bench render b2k.vdb "${R[@]}" --arc 5 --frames 60 --warmup 60 | grep -E "texture|time:"
echo "== still"; T 60 fccvdb bench render b2k.vdb "${R[@]}" --arc 0 --frames 60 --warmup 60 | grep -E "texture|time:"
for i in 1 2; do echo "== levels, full turn $i"; T 60 fccvdb bench render b2k.vdb "${R[@]}" --frames 30 --warmup 3 --lod-bias 0 | grep -E "texture|time:"; done
echo "== first complete frame"; T 60 fccvdb render b2k.vdb -o $W/f.png --layout texture-vec4 --gpu-cache 784 --host-cache 1024 --iso 0.3 --res 1920x1080 --timings --force | grep -E "timings|wrote"
