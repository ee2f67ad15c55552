#!/usr/bin/env bash
# Session 21, third call: how much of session 20's slowdown with shared memory held by each work group
# (FCC_OCCUPANCY_PAD floats a group) is the L1 cache it takes rather than the warps an SM then holds:
# pads too small to limit the 16 warps the DVR program holds (256, 1024 and 2048 floats: 1, 4 and 8
# KiB a group, 16 groups an SM) against none and 3584 (14 KiB: 12 warps), engine CT inferno and ML
# 160^3x4 FCC viridis at 1080p, alternating; then the walk alone (28 warps an SM) without
# and with 14 KiB a group. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session21_call3.sh
set -u
W=${W:-/tmp/m21}; mkdir -p "$W"; cd "$W"
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims 320,320,320 --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet
D=(--variants skip+analytic --layout auto --res 1920x1080 --frames 200 --warmup 20 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for round in 1 2; do
  for pad in 0 256 1024 2048 3584; do
    echo "-- round $round [FCC_OCCUPANCY_PAD=$pad] engine DVR inferno"; FCCVDB_SHADER_DEFINES="FCC_OCCUPANCY_PAD=$pad" fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
    echo "-- round $round [FCC_OCCUPANCY_PAD=$pad] ML DVR viridis"; FCCVDB_SHADER_DEFINES="FCC_OCCUPANCY_PAD=$pad" fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
  done
done
for pad in 0 3584; do
  echo "-- [FCC_DVR_WALK_ONLY=1;FCC_OCCUPANCY_PAD=$pad] engine DVR inferno, the walk alone"; FCCVDB_SHADER_DEFINES="FCC_DVR_WALK_ONLY=1;FCC_OCCUPANCY_PAD=$pad" fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
done
true
