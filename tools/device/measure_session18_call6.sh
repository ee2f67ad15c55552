#!/usr/bin/env bash
# Session 18, sixth call: one piece a round (FCC_DVR_PIECE_ROUNDS, docs/RENDERER.md): a two-piece chord
# takes two rounds, against the default (both pieces in one round), alternating; ML 160^3x4 FCC viridis and
# the engine CT inferno at 1080p. (The knob was measured slower and removed afterwards: this script
# runs as recorded only on that commit, 599538e.)
# Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session18_call6.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m18}; mkdir -p "$W"; cd "$W"
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
for round in 1 2 3; do
  run "round $round [default]" ""
  run "round $round [piece rounds]" "FCC_DVR_PIECE_ROUNDS=1"
done
run "[piece rounds, one sub-step a chord]" "FCC_DVR_PIECE_ROUNDS=1;FCC_DVR_FIXED_STEPS=1"
true
