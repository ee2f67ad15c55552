#!/usr/bin/env bash
# Session 22, third call: the sub-step rule's kink and colour sums from two reads of the prefix table
# instead of four (main; FCC_DVR_RULE_FOUR_READS=1 the old reads, the same sub-steps), alternating, engine
# CT inferno and ML 160^3x4 FCC viridis at 1080p; then both at the orbit's first view alone (--arc 0:
# the view llvmpipe's counts were taken from) against the whole orbit. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session22_call3.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m22}; source "$(dirname "$0")/bench_data.sh"
for round in 1 2 3; do
  for v in "" "FCC_DVR_RULE_FOUR_READS=1"; do
    echo "-- round $round [${v:-main: two reads}] engine DVR inferno"; FCCVDB_SHADER_DEFINES="$v" fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
    echo "-- round $round [${v:-main: two reads}] ML DVR viridis"; FCCVDB_SHADER_DEFINES="$v" fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
  done
done
# The default camera turned about the vertical through the engine's centre (127.5, 127.5, 53.5) by 0,
# 90, 180 and 270 degrees (frameBox's eye: distance 570.3 along (0.55, 0.45, 0.75) normalized).
for view in "0 431.302,376.065,467.776" "90 541.776,376.065,-250.302" "180 -176.302,376.065,-360.776" "270 -286.776,376.065,357.302"; do
  set -- $view
  echo "-- view at $1 degrees alone (--arc 0): engine DVR inferno"
  fccvdb bench render engine.vdb --mode dvr --tf inferno --eye $2 --variants skip+analytic --layout auto --res $RES --frames $FR --warmup 20 --json --arc 0 2>&1 | fps
done
echo "-- first view alone: ML DVR viridis"; fccvdb bench render ml.vdb --mode dvr --tf viridis --variants skip+analytic --layout auto --res $RES --frames $FR --warmup 20 --json --arc 0 | fps
true
