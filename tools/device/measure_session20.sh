#!/usr/bin/env bash
# Session 20, first call: DVR's flat walk with the brick steps folded into the rounds (commit fc6d687, every
# iteration integrates a cell) against session 19's final build (commit deb1eef, built as fccvdb19),
# alternating; ML 160^3x4 FCC viridis and the engine CT inferno at 1080p, plus knobs on the new build.
# Run as
#   git stash; make fccvdb; cp build/bin/fccvdb /tmp/c20/fccvdb19; git stash pop   (or a worktree at deb1eef)
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard /tmp/c20/fccvdb19 ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session20.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m20}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; ML=40; FR=5; else RES=1920x1080; ML=320; FR=300; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
both() {  # label, program, extra args...
  local label=$1 prog=$2; shift 2
  echo "-- $label ML FCC viridis"; $prog bench render ml.vdb --mode dvr --tf viridis "${D[@]}" "$@" | fps
  [ -s engine.vdb ] && { echo "-- $label engine inferno"; $prog bench render engine.vdb --mode dvr --tf inferno "${D[@]}" "$@" | fps; }
}
for round in 1 2; do
  both "round $round [folded]" fccvdb
  both "round $round [fccvdb19]" fccvdb19
done
FCCVDB_SHADER_DEFINES="FCC_DVR_FIXED_STEPS=1" both "folded, one sub-step a chord (wrong)" fccvdb
both "folded, work group 8x8" fccvdb --work-group 8x8
both "folded, work group 8x4" fccvdb --work-group 8x4
both "round 3 [folded]" fccvdb
true
