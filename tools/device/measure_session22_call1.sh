#!/usr/bin/env bash
# Session 22, first call: DVR sub-steps at the field's mean value (docs/DVR.md, "The value a sub-step
# takes"; the rule without its curvature term) against session 21's midpoint values with the term
# (FCC_DVR_MIDPOINT=1), alternating, ML 160^3x4 FCC viridis and the engine CT inferno at 1080p; then,
# on main, gradient shading, the presets, the isosurfaces and the Cartesian trilinear DVR of the same
# sample count (the baseline ratio). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session22_call1.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m22}; source "$(dirname "$0")/bench_data.sh"
if [ "${SMALL:-0}" = 1 ]; then MLC=32; else MLC=254; fi
[ -s ml_cc.vdb ] || fccvdb synth marschner-lobb ml_cc.vdb --dims $MLC,$MLC,$MLC --lattice cc --force --quiet
for round in 1 2 3; do
  for v in "" "FCC_DVR_MIDPOINT=1"; do
    echo "-- round $round [${v:-main: mean values}] engine DVR inferno"; FCCVDB_SHADER_DEFINES="$v" fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
    echo "-- round $round [${v:-main: mean values}] ML DVR viridis"; FCCVDB_SHADER_DEFINES="$v" fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
  done
done
echo "-- [one sub-step a chord, FCC_DVR_FIXED_STEPS=1, wrong images] engine DVR inferno"; FCCVDB_SHADER_DEFINES="FCC_DVR_FIXED_STEPS=1" fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
for tf in grayscale viridis fog; do
  echo "-- preset $tf: engine DVR"; fccvdb bench render engine.vdb --mode dvr --tf $tf "${D[@]}" | fps
done
echo "-- engine DVR inferno, shading on"; fccvdb bench render engine.vdb --mode dvr --tf inferno --shading on "${D[@]}" | fps
echo "-- ML DVR viridis, shading on"; fccvdb bench render ml.vdb --mode dvr --tf viridis --shading on "${D[@]}" | fps
echo "-- ML isosurface 0.5"; fccvdb bench render ml.vdb --iso 0.5 "${D[@]}" | fps
echo "-- engine isosurface (suggested value)"; fccvdb bench render engine.vdb "${D[@]}" | fps
echo "-- ML CC trilinear DVR viridis (same sample count)"; fccvdb bench render ml_cc.vdb --reconstruction trilinear --mode dvr --tf viridis "${D[@]}" | fps
true
