#!/usr/bin/env bash
# Session 22, second call: with sub-steps at mean values (about one a chord on the engine), what a
# work group's size does to the DVR program (the driver must fit a whole group on an SM, so 512
# threads cap a thread at 128 registers, 768 at 85 and 1024 at 64: more warps an SM, values spilled),
# one sub-step a chord and the walk alone, engine CT inferno and ML 160^3x4 FCC viridis at 1080p; then
# blobs 2048^3 DVR through the pyramid at 4x the GPU cache, main against FCC_DVR_MIDPOINT=1. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session22_call2.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m22}; source "$(dirname "$0")/bench_data.sh"
if [ "${SMALL:-0}" = 1 ]; then N=128; else N=2048; fi
for round in 1 2; do
  for wg in 4x8 16x32 32x24 32x32; do
    echo "-- round $round [work group $wg] engine DVR inferno"; fccvdb bench render engine.vdb --mode dvr --tf inferno --work-group $wg "${D[@]}" | fps
    echo "-- round $round [work group $wg] ML DVR viridis"; fccvdb bench render ml.vdb --mode dvr --tf viridis --work-group $wg "${D[@]}" | fps
  done
done
for v in "FCC_DVR_FIXED_STEPS=1" "FCC_DVR_WALK_ONLY=1"; do
  echo "-- [$v, wrong images] engine DVR inferno"; FCCVDB_SHADER_DEFINES="$v" fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
  echo "-- [$v, wrong images] ML DVR viridis"; FCCVDB_SHADER_DEFINES="$v" fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
done
[ -s b2k.vdb ] || fccvdb synth blobs b2k.vdb --dims $N,$N,$N --pyramid --force --quiet
for v in "" "FCC_DVR_MIDPOINT=1" ""; do
  echo "-- [${v:-main}] blobs ${N}^3 DVR viridis, pyramid, --gpu-cache 784"
  FCCVDB_SHADER_DEFINES="$v" fccvdb bench render b2k.vdb --mode dvr --tf viridis --layout texture-vec4 --variants skip+analytic --gpu-cache 784 \
    --host-cache 8192 --lod-bias 0 --arc 0 --res $RES --frames 60 --warmup 5 --json | grep -oE '"(fps|first_frame_s|first_frame_seconds)": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo
done
true
