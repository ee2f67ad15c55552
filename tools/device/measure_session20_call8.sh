#!/usr/bin/env bash
# Session 20, eighth call: the chain takes chords cut short inside a cell itself (the line's end pieces,
# integrateCellPieces no longer in the flat walk's program) against the build before it (fccvdbB, the
# fourth call's), alternating; ML 160^3x4 FCC viridis and the engine CT inferno at 1080p; the new
# build's occupancy (FCC_WARP_PROBE image in $OUT). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard /tmp/c20/fccvdbB ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session20_call8.sh        (SMALL=1: toy sizes)
set -u
OUTDIR=${OUT:-/tmp/out20}; mkdir -p "$OUTDIR"
W=${W:-/tmp/m20}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; ML=40; FR=5; else RES=1920x1080; ML=320; FR=300; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet
[ "${SMALL:-0}" = 1 ] || FCCVDB_SHADER_DEFINES="FCC_WARP_PROBE=1" fccvdb render engine.vdb "$OUTDIR/probe_cut.exr" --mode dvr --tf inferno --res 960x540 --force --quiet
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for round in 1 2 3; do
  for prog in fccvdb fccvdbB; do
    echo "-- round $round [$prog] ML DVR viridis"; $prog bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
    echo "-- round $round [$prog] engine DVR inferno"; $prog bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
  done
done
true
