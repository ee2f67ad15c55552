#!/usr/bin/env bash
# Session 33, first call: DVR's light kit (--light kit) on NVIDIA. test_render_dvr's light tests (the
# kit and the directional light against the CPU reference, live setters) and the projected tetrahedra
# under them, then the frame rates at 1080p of the shaded DVR under the headlight and under the kit,
# beside the unshaded one (engine CT inferno, ML 160^3x4 FCC viridis), alternating, two rounds, and the
# engine's image under the kit. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard build/bin/test_render_dvr ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session33_call1.sh        (SMALL=1: toy sizes)
source tools/device/prologue.sh
"$B/test_render_dvr" --gtest_filter='*Light*:*ProjectedTetrahedraMatch*' 2>&1 |
  grep -E "^\[  (FAILED|PASSED|     OK) |Failure|Which is|PSNR|dB|light" | cut -c1-170 | head -40
W=${W:-/tmp/m33}; source "$HERE/tools/device/bench_data.sh"
fccvdb render engine.vdb "${OUT:-/tmp}/engine_light_kit.png" --mode dvr --tf inferno --shading on --specular 0.5 \
  --light kit --res $RES --force --quiet || echo "render --light kit failed"
for round in 1 2; do
  for v in "--shading off" "--shading on --specular 0.5" "--shading on --specular 0.5 --light kit"; do
    run() { fccvdb bench render "$@" "${D[@]}" $v | fps; }
    echo "-- round $round [$v]: engine DVR inferno $(run engine.vdb --mode dvr --tf inferno) ML DVR viridis $(run ml.vdb --mode dvr --tf viridis)"
  done
done
fccvdb bench render engine.vdb --mode dvr --tf inferno --shading on --light kit --res 64x36 --frames 2 --warmup 0 \
  --variants skip+analytic --layout auto --json |
  grep -oE '"shading": \{[^}]*\}'
true
