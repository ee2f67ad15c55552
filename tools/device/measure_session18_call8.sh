#!/usr/bin/env bash
# Session 18, eighth call: the sub-step rule after review (kinks only where crossed, a term for the value
# curving along a segment: FCC_DVR_BEND_TERM) against it without that term and with tolerance 0.02,
# alternating; ML 160^3x4 FCC viridis and the engine CT inferno at 1080p (and the engine at 8x8).
# Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session18_call8.sh        (SMALL=1: toy sizes)
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
for round in 1 2; do
  run "round $round [main]" ""
  run "round $round [no bend term]" "FCC_DVR_BEND_TERM=0"
  run "round $round [tolerance 0.02]" "FCC_DVR_TOLERANCE=0.02"
done
echo "-- [work group 8x8] engine inferno"; fccvdb bench render engine.vdb --mode dvr --tf inferno --work-group 8x8 "${D[@]}" | fps
true
