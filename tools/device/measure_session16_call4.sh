#!/usr/bin/env bash
# (FCC_DVR_CELL_CUBIC_OFF was removed after the fifth call; the cubic is off by default.)
# Session 16, fourth call: FCC DVR with the certified cell cubic (docs/DVR.md, "One cubic a cell"; the
# default now) against every cell by its pieces (FCC_DVR_CELL_CUBIC_OFF), alternating, at 1080p on ML
# 160^3x4 FCC and the engine CT, beside the isosurface and the Cartesian trilinear DVR of the same sample
# count; then blobs 2048^3 DVR through the pyramid at 4x the GPU cache. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session16_call4.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m16}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then ML=40; MLC=32; FR=5; RES=64x64; N=128; else ML=320; MLC=254; FR=300; RES=1920x1080; N=2048; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
[ -s ml_cc.vdb ] || fccvdb synth marschner-lobb ml_cc.vdb --dims $MLC,$MLC,$MLC --lattice cc --force --quiet
ENGINE=${FCC_DATA:-/nonexistent}/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for round in 1 2; do
  for v in "" "FCC_DVR_CELL_CUBIC_OFF=1"; do
    echo "-- round $round [${v:-cell cubic}] ML FCC viridis"; FCCVDB_SHADER_DEFINES=$v fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
    [ -s engine.vdb ] && { echo "-- round $round [${v:-cell cubic}] engine inferno"; FCCVDB_SHADER_DEFINES=$v fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps; }
  done
done
echo "-- ML FCC viridis, shading on"; fccvdb bench render ml.vdb --mode dvr --tf viridis --shading on "${D[@]}" | fps
echo "-- ML FCC fog"; fccvdb bench render ml.vdb --mode dvr --tf fog "${D[@]}" | fps
echo "-- ML FCC isosurface 0.5"; fccvdb bench render ml.vdb --iso 0.5 "${D[@]}" | fps
[ -s engine.vdb ] && { echo "-- engine isosurface 100"; fccvdb bench render engine.vdb --iso 100 "${D[@]}" | fps; }
echo "-- ML CC trilinear DVR (same sample count)"; fccvdb bench render ml_cc.vdb --reconstruction trilinear --mode dvr --tf viridis "${D[@]}" | fps
# Blobs 2048^3 DVR through the pyramid at 4x the GPU cache (session 15: first frame 0.431 s, 62.9 fps).
[ -s b2k.vdb ] || fccvdb synth blobs b2k.vdb --dims $N,$N,$N --pyramid --force --quiet
echo "-- blobs 2048^3 DVR viridis, pyramid, --gpu-cache 784"
fccvdb bench render b2k.vdb --mode dvr --tf viridis --layout texture-vec4 --variants skip+analytic --gpu-cache 784 \
  --host-cache 8192 --lod-bias 0 --arc 0 --res $RES --frames 60 --warmup 5 --json | grep -oE '"(fps|first_frame_s|first_frame_seconds)": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo
true
