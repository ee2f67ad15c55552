#!/usr/bin/env bash
# Session 28, first call (issue 18): (a) session 27's shaded-DVR stencil reuse (FCC_DVR_SHADE_REUSE):
# the shaded engine and ML EXRs with it on and off (the same bytes expected) and their frame rates;
# (b) the DVR split in two programs (FCCVDB_DVR_SPLIT="K,N": a walk listing K cells a ray, their
# integration, N rounds, then the one program for what is left): the 1080p PNGs against main's
# (pngdiff) and the frame rates, alternating with main, two rounds (engine CT inferno, ML 160^3x4 FCC
# viridis). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard build/bin/test_render_dvr ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session28_call1.sh        (SMALL=1: toy sizes)
# The knobs are removed since (sessions 28, 29): FCC_DVR_SHADE_REUSE is in commit d4f52ac, the split in
# tools/device/session28_dvr_split.patch (against 8d1dd6c).
source tools/device/prologue.sh
W=${W:-/tmp/m28}; source "$HERE/tools/device/bench_data.sh"
source "$HERE/tools/device/dvr_knob_runs.sh"
dvr_reuse_images
for round in 1 2; do
  for reuse in 0 1; do
    run() { FCCVDB_SHADER_DEFINES="FCC_DVR_SHADE_REUSE=$reuse" fccvdb bench render "$@" "${D[@]}" --shading on | fps; }
    echo "-- round $round [shading on, reuse $reuse]: engine DVR inferno $(run engine.vdb --mode dvr --tf inferno) ML DVR viridis $(run ml.vdb --mode dvr --tf viridis)"
  done
done
SPLITS="16,8 32,4 32,8 64,2 64,4 128,2"
dvr_split_images "$SPLITS"
dvr_split_rounds "$SPLITS"
true
