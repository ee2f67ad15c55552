#!/usr/bin/env bash
# Session 22, fourth call: tfZeroOn from the span of the table's non-zero entries (main: for the presets
# no memory read beyond a cell's bounds decides its skip) against the prefix counts always
# (FCC_TF_ZERO_SPAN=0; the same images), alternating, engine CT inferno and ML 160^3x4 FCC viridis at
# 1080p. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session22_call4.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m22}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; ML=40; FR=5; else RES=1920x1080; ML=320; FR=200; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 20 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for round in 1 2 3; do
  for v in "" "FCC_TF_ZERO_SPAN=0"; do
    echo "-- round $round [${v:-main: the span}] engine DVR inferno"; FCCVDB_SHADER_DEFINES="$v" fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
    echo "-- round $round [${v:-main: the span}] ML DVR viridis"; FCCVDB_SHADER_DEFINES="$v" fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
  done
done
true
