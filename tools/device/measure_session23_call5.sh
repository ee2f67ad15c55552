#!/usr/bin/env bash
# Session 23, fifth call: dvr.glsl's tfPosition takes NaN as entry 0 itself (NVIDIA's clamp gave the last
# entry): the NaN test and the skipping test on NVIDIA's driver, and the DVR frame rates with it (engine
# CT inferno, ML 160^3x4 FCC viridis at 1080p, two rounds). Sixth call, NAN_VARIANTS=1: FCC_TF_NAN 0
# (the clamp alone) against 1 (isnan), alternating, three rounds, the NaN test with each (the call also
# ran a variant 2, a comparison instead of isnan, removed since: docs/BENCHMARKS.md). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard build/bin/test_render_dvr ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session23_call5.sh        (SMALL=1: toy sizes)
set -u
HERE=$(pwd)
B=$(dirname "$(command -v fccvdb)")
# The tests run the fccvdb their build names (here, where that is the build, nothing to do).
[ "$B/fccvdb" -ef /work/main/build/bin/fccvdb ] || { mkdir -p /work/main/build/bin && ln -sf "$B/fccvdb" /work/main/build/bin/fccvdb; }
W=${W:-/tmp/m23}; source "$(dirname "$0")/bench_data.sh"
if [ "${NAN_VARIANTS:-0}" = 1 ]; then
  for round in 1 2 3; do
    for k in 0 1; do
      echo "-- round $round FCC_TF_NAN=$k engine DVR inferno"; FCCVDB_SHADER_DEFINES=FCC_TF_NAN=$k fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
      echo "-- round $round FCC_TF_NAN=$k ML DVR viridis"; FCCVDB_SHADER_DEFINES=FCC_TF_NAN=$k fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
      [ $round = 1 ] && (cd "$HERE" && FCCVDB_SHADER_DEFINES=FCC_TF_NAN=$k "$B/test_render_dvr" --gtest_filter='*NanSamples*' 2>&1 | grep -E "opaque")
    done
  done
  exit 0
fi
for round in 1 2; do
  echo "-- round $round engine DVR inferno"; fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
  echo "-- round $round ML DVR viridis"; fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
done
cd "$HERE"
"$B/test_render_dvr" --gtest_filter='*NanSamples*:*SkippingAndSmallCaches*' 2>&1 | grep -E "^\[  (FAILED|PASSED|     OK) |Failure|Which is|dB|changed" | grep -v "^\[  FAILED  \] [0-9]" | cut -c1-200 | head -20
true
