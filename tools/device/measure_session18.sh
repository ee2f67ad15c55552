#!/usr/bin/env bash
# Session 18, first call: the DVR sub-step rule from the midpoint rule's error estimate (issue 18),
# against session 17's rule (FCC_DVR_ENTRY_RULE=1) and one sub-step a chord (the ceiling), ML 160^3x4
# FCC viridis and the engine CT inferno at 1080p; the default also with the texture-vec4 layout.
# Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session18.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m18}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; ML=40; FR=5; else RES=1920x1080; ML=320; FR=300; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=${FCC_DATA:-/nonexistent}/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
run() {  # label, defines, layout
  echo "-- $1 ML FCC viridis"; FCCVDB_SHADER_DEFINES=$2 fccvdb bench render ml.vdb --mode dvr --tf viridis --layout $3 "${D[@]}" | fps
  [ -s engine.vdb ] && { echo "-- $1 engine inferno"; FCCVDB_SHADER_DEFINES=$2 fccvdb bench render engine.vdb --mode dvr --tf inferno --layout $3 "${D[@]}" | fps; }
}
nvidia-smi --query-gpu=name,clocks.sm,clocks.max.sm --format=csv,noheader 2>/dev/null
for round in 1 2; do
  run "round $round [new rule, tolerance 0.01]" "" auto
  run "round $round [session 17 rule]" "FCC_DVR_ENTRY_RULE=1" auto
done
run "[new rule, tolerance 0.001]" "FCC_DVR_TOLERANCE=0.001" auto
run "[one sub-step a chord]" "FCC_DVR_FIXED_STEPS=1" auto
run "[new rule, texture-vec4]" "" texture-vec4
run "[new rule, texture-scalar]" "" texture-scalar
true
