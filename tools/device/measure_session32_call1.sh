#!/usr/bin/env bash
# Session 32, first call: DVR's directional light (--light AZIMUTH,ELEVATION) on NVIDIA. test_render_dvr's
# light, shading, specular and projected-tetrahedra tests (GPU against the CPU reference; the culling far
# from the index origin), then the frame rates at 1080p of the shaded DVR under the headlight and under a
# directional light, beside the unshaded one (engine CT inferno, ML 160^3x4 FCC viridis), alternating,
# two rounds, and the engine's image under each light. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard build/bin/test_render_dvr ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session32_call1.sh        (SMALL=1: toy sizes)
source tools/device/prologue.sh
"$B/test_render_dvr" --gtest_filter='*Light*:*Specular*:*Shading*:*ProjectedTetrahedra*' 2>&1 |
  grep -E "^\[  (FAILED|PASSED|     OK) |Failure|Which is|PSNR|dB|light" | cut -c1-170 | head -40
W=${W:-/tmp/m32}; source "$HERE/tools/device/bench_data.sh"
for l in headlight 30,45; do
  fccvdb render engine.vdb "${OUT:-/tmp}/engine_light_${l/,/_}.png" --mode dvr --tf inferno --shading on --specular 0.5 \
    --light $l --res $RES --force --quiet || echo "render --light $l failed"
done
for round in 1 2; do
  for v in "--shading off" "--shading on --specular 0.5" "--shading on --specular 0.5 --light 30,45"; do
    run() { fccvdb bench render "$@" "${D[@]}" $v | fps; }
    echo "-- round $round [$v]: engine DVR inferno $(run engine.vdb --mode dvr --tf inferno) ML DVR viridis $(run ml.vdb --mode dvr --tf viridis)"
  done
done
true
