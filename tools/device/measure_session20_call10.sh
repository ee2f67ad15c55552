#!/usr/bin/env bash
# Session 20, tenth call: NVIDIA's compiler options by pragma (FCC_NV_OPTIONS: 1 no unrolling, 2 no
# if-conversion, 3 both): each one's occupancy (FCC_WARP_PROBE images in $OUT, engine DVR at 960x540)
# and frame rate (ML 160^3x4 FCC viridis, engine CT inferno, 1080p), alternating with main. The knob
# is in commit d748c0a only (removed after: no effect). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session20_call10.sh
set -u
OUTDIR=${OUT:-/tmp/out20}; mkdir -p "$OUTDIR"
W=${W:-/tmp/m20}; mkdir -p "$W"; cd "$W"
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims 320,320,320 --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet
for o in 1 2 3; do
  FCCVDB_SHADER_DEFINES="FCC_WARP_PROBE=1;FCC_NV_OPTIONS=$o" fccvdb render engine.vdb "$OUTDIR/probe_nv$o.exr" --mode dvr --tf inferno --res 960x540 --force --quiet
done
D=(--variants skip+analytic --layout auto --res 1920x1080 --frames 300 --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for round in 1 2; do
  for o in 0 1 2 3; do
    echo "-- round $round [FCC_NV_OPTIONS=$o] ML DVR viridis"; FCCVDB_SHADER_DEFINES="FCC_NV_OPTIONS=$o" fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
    echo "-- round $round [FCC_NV_OPTIONS=$o] engine DVR inferno"; FCCVDB_SHADER_DEFINES="FCC_NV_OPTIONS=$o" fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
  done
done
true
