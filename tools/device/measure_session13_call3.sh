#!/usr/bin/env bash
# Session 13, third call: --lookahead 0 against 2 on every camera (full turn, drags, still, streams).
set -u
W=/tmp/m13; mkdir -p $W; cd $W
R=(--layout texture-vec4 --variants skip+analytic --gpu-cache 784 --host-cache 1024 --iso 0.3 --res 1920x1080)
S=(--gpu-cache 784 --host-cache 1024 --res 1920x1080 --iso 0.3 --layout texture-vec4 --frames 120 --lod-bias 0)
T() { echo "\$ $*"; /usr/bin/time -f 'time: %e s %M KiB' timeout "$@" 2>&1 | grep -v "^\[" | tail -4; }
[ -s b2k.vdb ] || T 120 fccvdb synth blobs b2k.vdb --dims 2048,2048,2048 --pyramid --force --quiet
for la in 0 2 0 2 0; do
  echo "== full turn, lookahead $la"; T 60 fccvdb bench render b2k.vdb "${R[@]}" --frames 30 --warmup 3 --lookahead $la | grep -E "texture|time:"
done
for la in 0 2 0; do
  echo "== 15 deg drag, lookahead $la"; T 60 fccvdb bench render b2k.vdb "${R[@]}" --arc 15 --frames 60 --warmup 60 --lookahead $la | grep -E "texture|time:"
done
for la in 0 2; do
  echo "== 5 deg drag and still, lookahead $la"
  T 60 fccvdb bench render b2k.vdb "${R[@]}" --arc 5 --frames 60 --warmup 60 --lookahead $la | grep -E "texture|time:"
  T 60 fccvdb bench render b2k.vdb "${R[@]}" --arc 0 --frames 60 --warmup 60 --lookahead $la | grep -E "texture|time:"
  echo "== levels: full turn, lookahead $la"; T 60 fccvdb bench render b2k.vdb "${R[@]}" --frames 30 --warmup 3 --lod-bias 0 --lookahead $la | grep -E "texture|time:"
done
for la in 0 2; do
  for p in orbit zoom jumps; do
    echo "== stream $p with levels, lookahead $la"
    T 60 fccvdb bench stream b2k.vdb --path $p "${S[@]}" --lookahead $la --json $W/s_${p}_$la.json --force | grep -E "p50|p99|hit|fps" | head -4
    python3 -c "import json;d=json.load(open('$W/s_${p}_$la.json'));s=d['runs'][0]['summary'];print('summary', '$p', $la, s['p50_frame_ms'], s['p99_frame_ms'], s['gpu_hit_rate'], s['complete_frames'], s['budget_ok'])" 2>&1 | tail -1
  done
done
for la in 0 2; do
  echo "== first complete frame, lookahead $la"; T 60 fccvdb render b2k.vdb -o $W/f.png --layout texture-vec4 --gpu-cache 784 --host-cache 1024 --iso 0.3 --res 1920x1080 --timings --force --lookahead $la | grep -E "timings|wrote"
done
