#!/usr/bin/env bash
# Session 22, fourth call: tfZeroOn from the span of the table's non-zero entries (main: for the presets
# no memory read beyond a cell's bounds decides its skip) against the prefix counts always
# (FCC_TF_ZERO_SPAN=0; the same images), alternating, engine CT inferno and ML 160^3x4 FCC viridis at
# 1080p. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session22_call4.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m22}; source "$(dirname "$0")/bench_data.sh"
for round in 1 2 3; do
  for v in "" "FCC_TF_ZERO_SPAN=0"; do
    echo "-- round $round [${v:-main: the span}] engine DVR inferno"; FCCVDB_SHADER_DEFINES="$v" fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
    echo "-- round $round [${v:-main: the span}] ML DVR viridis"; FCCVDB_SHADER_DEFINES="$v" fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
  done
done
true
