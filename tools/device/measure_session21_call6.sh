#!/usr/bin/env bash
# Session 21, sixth call (the fifth was tools/shader-stats/run_on_device.sh with no core Vulkan feature):
# the slots' cell bounds as two halves rounded outwards (FCC_SLOT_BOUNDS_HALF=1: half their bytes in
# the caches; the images bit for bit the same on llvmpipe) against main, alternating, engine CT
# inferno and ML 160^3x4 FCC viridis at 1080p. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session21_call6.sh
set -u
W=${W:-/tmp/m21}; mkdir -p "$W"; cd "$W"
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims 320,320,320 --force --quiet
D=(--variants skip+analytic --layout auto --res 1920x1080 --frames 200 --warmup 20 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for round in 1 2 3; do
  for k in 0 1; do
    echo "-- round $round [FCC_SLOT_BOUNDS_HALF=$k] engine DVR inferno"; FCCVDB_SHADER_DEFINES="FCC_SLOT_BOUNDS_HALF=$k" fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
  done
done
for k in 0 1; do
  echo "-- [FCC_SLOT_BOUNDS_HALF=$k] ML DVR viridis"; FCCVDB_SHADER_DEFINES="FCC_SLOT_BOUNDS_HALF=$k" fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
done
true
