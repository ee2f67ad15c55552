#!/usr/bin/env bash
# Session 26, first call: the DVR highlight (--specular K --specular-power P) on NVIDIA. test_render_dvr's
# shading and specular tests (GPU against the CPU reference) and the frame rates at 1080p of the shaded
# DVR with and without the highlight beside the unshaded one (engine CT inferno, ML 160^3x4 FCC viridis),
# alternating, two rounds. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard build/bin/test_render_dvr ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session26_call1.sh        (SMALL=1: toy sizes)
set -u
HERE=$(pwd)
B=$(dirname "$(command -v fccvdb)")
[ "$B/fccvdb" -ef /work/main/build/bin/fccvdb ] || { mkdir -p /work/main/build/bin && ln -sf "$B/fccvdb" /work/main/build/bin/fccvdb; }
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null
"$B/test_render_dvr" --gtest_filter='*Specular*:*Shading*' 2>&1 | grep -E "^\[  (FAILED|PASSED|     OK) |Failure|Which is|PSNR|highlight" | cut -c1-160 | head -30
W=${W:-/tmp/m26}; source "$HERE/tools/device/bench_data.sh"
fccvdb render engine.vdb --mode dvr --tf inferno --shading on --specular 0.5 --res $RES -o "${OUT:-/tmp}/engine_specular.png" --force --quiet
for round in 1 2; do
  for v in "--shading off" "--shading on" "--shading on --specular 0.5 --specular-power 20"; do
    run() { fccvdb bench render "$@" "${D[@]}" $v | fps; }
    echo "-- round $round [$v]: engine DVR inferno $(run engine.vdb --mode dvr --tf inferno) ML DVR viridis $(run ml.vdb --mode dvr --tf viridis)"
  done
done
true
