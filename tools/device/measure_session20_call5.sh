#!/usr/bin/env bash
# Session 20, fifth call: the raycaster's work group shape (bench render --work-group) for DVR and the
# isosurface, ML 160^3x4 FCC (viridis; isosurface 0.5) and the engine CT (inferno; isosurface at its
# suggested value) at 1080p, on the build with the walk's derivable values dropped; then blobs 2048^3
# DVR through the pyramid at 4x the GPU cache (4x8 and 8x8). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session20_call5.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m20}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; ML=40; FR=5; N=128; else RES=1920x1080; ML=320; FR=300; N=2048; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for round in 1 2; do
  for wg in 4x8 8x8 4x16 8x16 16x8; do
    echo "-- round $round [$wg] ML DVR viridis"; fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" --work-group $wg | fps
    echo "-- round $round [$wg] engine DVR inferno"; fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" --work-group $wg | fps
    echo "-- round $round [$wg] ML isosurface 0.5"; fccvdb bench render ml.vdb --iso 0.5 "${D[@]}" --work-group $wg | fps
    echo "-- round $round [$wg] engine isosurface"; fccvdb bench render engine.vdb "${D[@]}" --work-group $wg | fps
  done
done
t0=$(date +%s)
[ -s b2k.vdb ] || fccvdb synth blobs b2k.vdb --dims $N,$N,$N --pyramid --force --quiet
echo "synth: $(( $(date +%s) - t0 )) s"
for wg in 4x8 8x8; do
  echo "-- [$wg] blobs ${N}^3 DVR viridis, pyramid, --gpu-cache 784"
  fccvdb bench render b2k.vdb --mode dvr --tf viridis --layout texture-vec4 --variants skip+analytic --work-group $wg \
    --gpu-cache 784 --host-cache 8192 --lod-bias 0 --arc 0 --res $RES --frames 60 --warmup 5 --json |
    grep -oE '"(fps|first_frame_s|first_frame_seconds)": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo
done
true
