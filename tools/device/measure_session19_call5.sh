#!/usr/bin/env bash
# Session 19, fifth call: blobs 2048^3 DVR through the pyramid at 4x the GPU cache, the chain of
# pieces against two gathers (FCC_DVR_CHAIN=0), alternating (the fourth call's 78.3 fps was below
# session 18's 96.5). Run as measure_session19_call4.sh.
set -u
W=${W:-/tmp/m19}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; N=128; else RES=1920x1080; N=2048; fi
t0=$(date +%s)
[ -s b2k.vdb ] || fccvdb synth blobs b2k.vdb --dims $N,$N,$N --pyramid --force --quiet
echo "synth: $(( $(date +%s) - t0 )) s"
for round in 1 2; do
  for v in "chain:" "two gathers:FCC_DVR_CHAIN=0"; do
    echo "-- round $round [${v%%:*}] blobs ${N}^3 DVR viridis, pyramid, --gpu-cache 784"
    FCCVDB_SHADER_DEFINES=${v#*:} fccvdb bench render b2k.vdb --mode dvr --tf viridis --layout texture-vec4 --variants skip+analytic \
      --gpu-cache 784 --host-cache 8192 --lod-bias 0 --arc 0 --res $RES --frames 60 --warmup 5 --json |
      grep -oE '"(fps|first_frame_s|first_frame_seconds)": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo
  done
done
true
