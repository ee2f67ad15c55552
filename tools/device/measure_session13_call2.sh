#!/usr/bin/env bash
# Session 13, second call: the full turn against --lookahead; type6's start-up on NVIDIA.
set -u
W=/tmp/m13; mkdir -p $W; cd $W
R=(--layout texture-vec4 --variants skip+analytic --gpu-cache 784 --host-cache 1024 --iso 0.3 --res 1920x1080)
T() { echo "\$ $*"; /usr/bin/time -f 'time: %e s %M KiB' timeout "$@" 2>&1 | grep -v "^\[" | tail -4; }
[ -s b2k.vdb ] || T 120 fccvdb synth blobs b2k.vdb --dims 2048,2048,2048 --pyramid --force --quiet
[ -s ml_cc.vdb ] || T 60 fccvdb synth marschner-lobb ml_cc.vdb --dims 254,254,254 --lattice cc --force --quiet
for la in 2 0 4 8 16 2 4 8; do
  echo "== lookahead $la"
  T 60 fccvdb bench render b2k.vdb "${R[@]}" --frames 30 --warmup 3 --lookahead $la | grep -E "texture|ssbo|time:"
done
for la in 2 8; do
  echo "== 15 deg drag, lookahead $la"
  T 60 fccvdb bench render b2k.vdb "${R[@]}" --arc 15 --frames 60 --warmup 60 --lookahead $la | grep -E "texture|ssbo|time:"
done
echo "== type6 (one-shot render: set-up is the shader compile), then bench render beside tricubic"
T 200 fccvdb render ml_cc.vdb --reconstruction type6 --iso 0.5 --res 512x512 -o $W/t6.png --timings --force
T 90 fccvdb bench render ml_cc.vdb --reconstruction type6 --iso 0.5 --variants skip+analytic --layout auto --res 512x512 --frames 100 --warmup 10 | grep -E "texture|ssbo|time:"
T 90 fccvdb bench render ml_cc.vdb --reconstruction type6 --iso 0.5 --variants skip+analytic --layout auto --res 1920x1080 --frames 30 --warmup 3 | grep -E "texture|ssbo|time:"
T 60 fccvdb bench render ml_cc.vdb --reconstruction tricubic --iso 0.5 --variants skip+analytic --layout auto --res 512x512 --frames 200 --warmup 20 | grep -E "texture|ssbo|time:"
