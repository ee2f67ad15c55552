#!/usr/bin/env bash
# Session 18, seventh call: FCC DVR's work group shape (bench render --work-group) now that bricks and
# rounds run in one loop, alternating with the default 4x8; ML 160^3x4 FCC viridis and the engine CT
# inferno at 1080p.
# Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session18_call7.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m18}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; ML=40; FR=5; else RES=1920x1080; ML=320; FR=300; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=${FCC_DATA:-/nonexistent}/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
run() {  # label, work group
  echo "-- $1 ML FCC viridis"; fccvdb bench render ml.vdb --mode dvr --tf viridis --work-group $2 "${D[@]}" | fps
  [ -s engine.vdb ] && { echo "-- $1 engine inferno"; fccvdb bench render engine.vdb --mode dvr --tf inferno --work-group $2 "${D[@]}" | fps; }
}
for g in 4x8 8x4 2x16 8x8 4x4 16x16 4x8; do run "[work group $g]" $g; done
true
