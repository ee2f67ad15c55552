#!/usr/bin/env bash
# Session 19, second call: the chain of pieces with the face jump from the exit piece's stencil (one more
# coefficient; the first call's 15 fetches ran slower than two gathers), and where it loses or gains:
# without the face jump (FCC_DVR_CHAIN_PROBE=1, wrong images), and without rounds that
# gather an entry piece alone (FCC_DVR_CHAIN_PROBE=2, wrong images); ML 160^3x4 FCC viridis and the
# engine CT inferno at 1080p. Run as measure_session19.sh.
set -u
W=${W:-/tmp/m19}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; ML=40; FR=5; else RES=1920x1080; ML=320; FR=300; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
run() {  # label, defines
  echo "-- $1 ML FCC viridis"; FCCVDB_SHADER_DEFINES=$2 fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
  [ -s engine.vdb ] && { echo "-- $1 engine inferno"; FCCVDB_SHADER_DEFINES=$2 fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps; }
}
run "[chain]" ""
run "[chain, no jump]" "FCC_DVR_CHAIN_PROBE=1"
run "[chain, no entry rounds]" "FCC_DVR_CHAIN_PROBE=2"
run "[two gathers]" "FCC_DVR_CHAIN=0"
run "[chain again]" ""
run "[chain, 1 sub-step]" "FCC_DVR_FIXED_STEPS=1"
run "[two gathers, 1 sub-step]" "FCC_DVR_CHAIN=0;FCC_DVR_FIXED_STEPS=1"
true
