#!/usr/bin/env bash
# Session 15, first call: where the FCC DVR frame goes (issue 18: ML 160^3x4 at 1080p >= 300 fps), by
# shader variants through FCCVDB_SHADER_DEFINES (docs/RENDERER.md), then session 14's measurements
# (tools/device/measure_session14.sh). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session15.sh
set -u
HERE=$(cd "$(dirname "$0")" && pwd)
W=${W:-/tmp/m14}; mkdir -p "$W"; cd "$W"
T() { echo "\$ $*"; /usr/bin/time -f 'time: %e s %M KiB' timeout "$@" 2>&1 | grep -v "^\[" | tail -8; }
if [ "${SMALL:-0}" = 1 ]; then ML=40; MLC=32; RES=64x64; FR=5; else ML=320; MLC=254; RES=1920x1080; FR=300; fi
[ -s ml.vdb ] || T 120 fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
[ -s ml_cc.vdb ] || T 120 fccvdb synth marschner-lobb ml_cc.vdb --dims $MLC,$MLC,$MLC --lattice cc --force --quiet
ENGINE=${FCC_DATA:-$HERE/../../../shared/data}/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && T 60 fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|time:.*|fccvdb:.*' | tr '\n' ' '; echo; }
echo "== DVR variants, ML FCC viridis $RES"
for v in "" "FCC_DVR_STEP_ENTRIES=4" "FCC_DVR_STEP_ENTRIES=16" "FCC_DVR_FIXED_STEPS=1" "FCC_DVR_FIXED_STEPS=2"; do
  echo "-- [$v]"; FCCVDB_SHADER_DEFINES="$v" T 60 fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
done
echo "-- fog"; T 60 fccvdb bench render ml.vdb --mode dvr --tf fog "${D[@]}" | fps
echo "-- iso 0.5"; T 60 fccvdb bench render ml.vdb --iso 0.5 "${D[@]}" | fps
for v in "" "FCC_DVR_STEP_ENTRIES=4" "FCC_DVR_FIXED_STEPS=1"; do
  echo "-- CC trilinear [$v]"; FCCVDB_SHADER_DEFINES="$v" T 60 fccvdb bench render ml_cc.vdb --reconstruction trilinear --mode dvr --tf viridis "${D[@]}" | fps
done
if [ -s engine.vdb ]; then
  for v in "" "FCC_DVR_STEP_ENTRIES=4" "FCC_DVR_FIXED_STEPS=1"; do
    echo "-- engine inferno [$v]"; FCCVDB_SHADER_DEFINES="$v" T 60 fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
  done
fi
echo "== session 14's script"
bash "$HERE/measure_session14.sh"
