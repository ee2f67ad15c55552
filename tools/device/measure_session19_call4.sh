#!/usr/bin/env bash
# Session 19, fourth call (and sixth, on the final build): the build (the chain of pieces, the walk left on a cell until it is
# integrated) against session 18's two gathers (FCC_DVR_CHAIN=0), alternating; ML 160^3x4 FCC viridis
# and the engine CT inferno at 1080p, their isosurfaces beside; then blobs 2048^3 DVR through the
# pyramid at 4x the GPU cache (first complete frame, frames per second still), as session 18's ninth.
# Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session19_call4.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m19}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; ML=40; FR=5; N=128; else RES=1920x1080; ML=320; FR=300; N=2048; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
run() {  # label, defines
  echo "-- $1 ML FCC viridis"; FCCVDB_SHADER_DEFINES=$2 fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
  [ -s engine.vdb ] && { echo "-- $1 engine inferno"; FCCVDB_SHADER_DEFINES=$2 fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps; }
}
for round in 1 2; do
  run "round $round [main: chain]" ""
  run "round $round [two gathers]" "FCC_DVR_CHAIN=0"
done
echo "-- isosurface ML"; fccvdb bench render ml.vdb "${D[@]}" | fps
[ -s engine.vdb ] && { echo "-- isosurface engine"; fccvdb bench render engine.vdb "${D[@]}" | fps; }
t0=$(date +%s)
[ -s b2k.vdb ] || fccvdb synth blobs b2k.vdb --dims $N,$N,$N --pyramid --force --quiet
echo "synth: $(( $(date +%s) - t0 )) s"
echo "-- blobs ${N}^3 DVR viridis, pyramid, --gpu-cache 784"
fccvdb bench render b2k.vdb --mode dvr --tf viridis --layout texture-vec4 --variants skip+analytic --gpu-cache 784 \
  --host-cache 8192 --lod-bias 0 --arc 0 --res $RES --frames 60 --warmup 5 --json | grep -oE '"(fps|first_frame_s|first_frame_seconds)": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo
true
