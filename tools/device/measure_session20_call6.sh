#!/usr/bin/env bash
# Session 20, sixth call: the brick pool's layout (bench render --layout) for DVR, ML 160^3x4 FCC
# viridis and the engine CT inferno at 1080p, alternating; and the isosurface's occupancy
# (FCC_WARP_PROBE images in $OUT, 960x540). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session20_call6.sh        (SMALL=1: toy sizes)
set -u
OUTDIR=${OUT:-/tmp/out20}; mkdir -p "$OUTDIR"
W=${W:-/tmp/m20}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; ML=40; FR=5; else RES=1920x1080; ML=320; FR=300; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet
if [ "${SMALL:-0}" != 1 ]; then
  FCCVDB_SHADER_DEFINES="FCC_WARP_PROBE=1" fccvdb render engine.vdb "$OUTDIR/probe_engine_iso.exr" --res 960x540 --force --quiet
  FCCVDB_SHADER_DEFINES="FCC_WARP_PROBE=1" fccvdb render ml.vdb "$OUTDIR/probe_ml_iso.exr" --iso 0.5 --res 960x540 --force --quiet
fi
D=(--variants skip+analytic --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for round in 1 2; do
  for layout in auto texture-vec4 ssbo-scalar ssbo-vec4; do
    echo "-- round $round [$layout] ML DVR viridis"; fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" --layout $layout | fps
    echo "-- round $round [$layout] engine DVR inferno"; fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" --layout $layout | fps
  done
done
true
