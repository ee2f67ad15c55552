#!/usr/bin/env bash
# Session 27, first call: shaded DVR reusing the exit piece's stencil for the gradient
# (FCC_DVR_SHADE_REUSE, march_fcc.glsl's dvrGradient) on NVIDIA. test_render_dvr's shading and specular
# tests, the shaded engine image with and without the reuse (the same bytes expected), and the frame
# rates at 1080p of the shaded DVR with the reuse (1, main) and without (0, before), beside the
# unshaded one (engine CT inferno, ML 160^3x4 FCC viridis), alternating, two rounds. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard build/bin/test_render_dvr ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session27_call1.sh        (SMALL=1: toy sizes)
source tools/device/prologue.sh
"$B/test_render_dvr" --gtest_filter='*Specular*:*Shading*' 2>&1 | grep -E "^\[  (FAILED|PASSED|     OK) |Failure|Which is|PSNR|highlight" | cut -c1-160 | head -30
W=${W:-/tmp/m27}; source "$HERE/tools/device/bench_data.sh"
source "$HERE/tools/device/dvr_knob_runs.sh"
dvr_reuse_images
for round in 1 2; do
  for v in "0 --shading on" "1 --shading on" "1 --shading off"; do
    set -- $v; reuse=$1; shift; flags="$*"
    run() { FCCVDB_SHADER_DEFINES="FCC_DVR_SHADE_REUSE=$reuse" fccvdb bench render "$@" "${D[@]}" $flags | fps; }
    echo "-- round $round [reuse $reuse $flags]: engine DVR inferno $(run engine.vdb --mode dvr --tf inferno) ML DVR viridis $(run ml.vdb --mode dvr --tf viridis)"
  done
done
true
