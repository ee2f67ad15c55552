#!/usr/bin/env bash
# (FCC_DVR_CELL_CUBIC_OFF was removed after the fifth call; the cubic is off by default.)
# Session 16, fifth call: the cell cubic with its bound corrected and tightened (type 4's rates at most
# 1.5 |d|_1, not 2.5; the constant 1/4), against every cell by its pieces, alternating. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session16_call5.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m16}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then ML=40; FR=5; RES=64x64; else ML=320; FR=300; RES=1920x1080; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=${FCC_DATA:-/nonexistent}/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for round in 1 2; do
  for v in "" "FCC_DVR_CELL_CUBIC_OFF=1"; do
    echo "-- round $round [${v:-cell cubic}] ML FCC viridis"; FCCVDB_SHADER_DEFINES=$v fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
    [ -s engine.vdb ] && { echo "-- round $round [${v:-cell cubic}] engine inferno"; FCCVDB_SHADER_DEFINES=$v fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps; }
  done
done
true
