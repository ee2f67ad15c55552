#!/usr/bin/env bash
# Session 19, first call: FCC DVR with one gather a cell (the chain of pieces across cube faces,
# docs/DVR.md "One gather a cell") against session 18's two (FCC_DVR_CHAIN=0), alternating, also with
# one sub-step a chord; ML 160^3x4 FCC viridis and the engine CT inferno at 1080p (issue 18).
# Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session19.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m19}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; ML=40; FR=5; else RES=1920x1080; ML=320; FR=300; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=${FCC_DATA:-/nonexistent}/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
run() {  # label, defines
  echo "-- $1 ML FCC viridis"; FCCVDB_SHADER_DEFINES=$2 fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
  [ -s engine.vdb ] && { echo "-- $1 engine inferno"; FCCVDB_SHADER_DEFINES=$2 fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps; }
}
for round in 1 2; do
  run "round $round [main: chain]" ""
  run "round $round [two gathers]" "FCC_DVR_CHAIN=0"
done
run "[chain, 1 sub-step]" "FCC_DVR_FIXED_STEPS=1"
run "[two gathers, 1 sub-step]" "FCC_DVR_CHAIN=0;FCC_DVR_FIXED_STEPS=1"
true
