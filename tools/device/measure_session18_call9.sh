#!/usr/bin/env bash
# Session 18, ninth call: blobs 2048^3 DVR through the pyramid at 4x the GPU cache on the final build
# (the sub-step rule from the error estimate; the pyramid's walk in rounds, brick by brick), as in
# session 17's third call: first complete frame and frames per second still (goals < 2 s, >= 60 fps).
# Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard
#   source .devbundle/env.sh && bash tools/device/measure_session18_call9.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m18}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; N=128; else RES=1920x1080; N=2048; fi
t0=$(date +%s)
[ -s b2k.vdb ] || fccvdb synth blobs b2k.vdb --dims $N,$N,$N --pyramid --force --quiet
echo "synth: $(( $(date +%s) - t0 )) s"
echo "-- blobs ${N}^3 DVR viridis, pyramid, --gpu-cache 784"
fccvdb bench render b2k.vdb --mode dvr --tf viridis --layout texture-vec4 --variants skip+analytic --gpu-cache 784 \
  --host-cache 8192 --lod-bias 0 --arc 0 --res $RES --frames 60 --warmup 5 --json | grep -oE '"(fps|first_frame_s|first_frame_seconds)": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo
true
