#!/usr/bin/env bash
# Session 20, seventh call: which part of DVR's program sets its registers (FCC_WARP_PROBE images in
# $OUT, engine DVR inferno at 960x540: the largest warp slot + 1 = warps an SM holds), knobs with wrong
# images; and the frame rate of the first (engine inferno, 1080p). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session20_call7.sh
set -u
OUTDIR=${OUT:-/tmp/out20}; mkdir -p "$OUTDIR"
W=${W:-/tmp/m20}; mkdir -p "$W"; cd "$W"
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet
for v in "nofallback:FCC_DVR_CHAIN_PROBE=4" "nofallback_onestep:FCC_DVR_CHAIN_PROBE=4;FCC_DVR_FIXED_STEPS=1" \
         "nojump:FCC_DVR_CHAIN_PROBE=1" "twogathers_onestep:FCC_DVR_CHAIN=0;FCC_DVR_FIXED_STEPS=1" \
         "onefetch_twogathers:FCC_DVR_CHAIN=0;FCC_DVR_ONE_FETCH=1"; do
  echo "-- probe ${v%%:*} (${v#*:})"
  FCCVDB_SHADER_DEFINES="FCC_WARP_PROBE=1;${v#*:}" fccvdb render engine.vdb "$OUTDIR/probe_${v%%:*}.exr" --mode dvr --tf inferno --res 960x540 --force --quiet
done
echo "-- probe shading (--shading on)"
FCCVDB_SHADER_DEFINES="FCC_WARP_PROBE=1" fccvdb render engine.vdb "$OUTDIR/probe_shading.exr" --mode dvr --tf inferno --shading on --res 960x540 --force --quiet
D=(--variants skip+analytic --layout auto --res 1920x1080 --frames 300 --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for v in "main:" "nofallback:FCC_DVR_CHAIN_PROBE=4" "main:"; do
  echo "-- ${v%%:*} engine DVR inferno"; FCCVDB_SHADER_DEFINES=${v#*:} fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
done
true
