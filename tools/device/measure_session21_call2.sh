#!/usr/bin/env bash
# Session 21, second call: registers (tools/shader-stats: vkstats over .vk/*.spv, NVIDIA's Vulkan
# compiler) and frame rate of the DVR program with the walk's state kept in shared memory while a cell
# is integrated (FCC_DVR_STASH=1; 2: the flat walk's loop state too), with a fence before the reloads (FCC_DVR_STASH_FENCE=1) so that the compiler cannot keep the values in registers, against main, alternating: ML
# 160^3x4 FCC viridis, engine CT inferno, 1080p. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   call with carry [".devbundle", ".gl", ".vk"]:
#   source .devbundle/env.sh && bash tools/device/measure_session21_call2.sh
set -u
OUTDIR=${OUT:-/tmp/out21}; mkdir -p "$OUTDIR"
[ -d .vk ] && bash tools/shader-stats/run_on_device.sh 2>&1 | grep -E "spv|Register"
W=${W:-/tmp/m21}; mkdir -p "$W"; cd "$W"
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims 320,320,320 --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet
D=(--variants skip+analytic --layout auto --res 1920x1080 --frames 300 --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for round in 1 2; do
  for k in "0" "1;FCC_DVR_STASH_FENCE=1" "2;FCC_DVR_STASH_FENCE=1"; do
    echo "-- round $round [FCC_DVR_STASH=$k] ML DVR viridis"; FCCVDB_SHADER_DEFINES="FCC_DVR_STASH=$k" fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
    echo "-- round $round [FCC_DVR_STASH=$k] engine DVR inferno"; FCCVDB_SHADER_DEFINES="FCC_DVR_STASH=$k" fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
  done
done
true
