#!/usr/bin/env bash
# Session 20, fourth call: fewer live values, each build's occupancy (FCC_WARP_PROBE images in $OUT,
# engine DVR at 960x540) and frame rate (ML 160^3x4 FCC viridis, engine CT inferno, 1080p),
# alternating: fccvdb0 (commit with the knobs, as main), fccvdbA (the face jump before the cubic),
# fccvdbB (A + the walk's derivable values and the slot's two offsets dropped). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard /tmp/c20/fccvdb0 /tmp/c20/fccvdbA /tmp/c20/fccvdbB ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session20_call4.sh        (SMALL=1: toy sizes)
set -u
OUTDIR=${OUT:-/tmp/out20}; mkdir -p "$OUTDIR"
W=${W:-/tmp/m20}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; ML=40; FR=5; else RES=1920x1080; ML=320; FR=300; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet
for prog in fccvdb0 fccvdbA fccvdbB; do
  FCCVDB_SHADER_DEFINES="FCC_WARP_PROBE=1" $prog render engine.vdb "$OUTDIR/probe_$prog.exr" --mode dvr --tf inferno --res 960x540 --force --quiet
done
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
both() {  # label, program, extra args...
  local label=$1 prog=$2; shift 2
  echo "-- $label ML FCC viridis"; $prog bench render ml.vdb --mode dvr --tf viridis "${D[@]}" "$@" | fps
  echo "-- $label engine inferno"; $prog bench render engine.vdb --mode dvr --tf inferno "${D[@]}" "$@" | fps
}
for round in 1 2; do
  for prog in fccvdb0 fccvdbA fccvdbB; do both "round $round [$prog]" $prog; done
done
both "[fccvdbB] work group 8x8" fccvdbB --work-group 8x8
true
