#!/usr/bin/env bash
# Session 14's measurements, for the next H200 call (this session had no device time): BCC rendering at
# equal samples (issue 17), projected tetrahedra against the ray integration and DVR through the pyramid
# (issue 18). Bounded: about 6 minutes on a fresh machine. Run as
#   source .devbundle/env.sh && bash tools/device/measure_session14.sh
# Figures go to docs/BENCHMARKS.md with these commands; SMALL=1 runs the same commands at toy sizes
# (a syntax and flag check on any machine).
set -u
W=${W:-/tmp/m14}; mkdir -p "$W"; cd "$W"
T() { echo "\$ $*"; /usr/bin/time -f 'time: %e s %M KiB' timeout "$@" 2>&1 | grep -v "^\[" | tail -8; }
if [ "${SMALL:-0}" = 1 ]; then ML=40; MLB=50; PTD=32; B2K=128; RES=64x64; FR=2; BUDGETS=4000
else ML=320; MLB=403; PTD=128; B2K=2048; RES=1920x1080; FR=300; BUDGETS=20000,160000,1280000; fi
# ML 160^3 x 4 FCC (16.4 M sites) and the BCC set of the same count (403^3 / 4).
[ -s ml.vdb ] || T 120 fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
[ -s ml_bcc.vdb ] || T 120 fccvdb synth marschner-lobb ml_bcc.vdb --dims $MLB,$MLB,$MLB --lattice bcc --force --quiet
B=(--variants skip+analytic --layout auto --frames $FR --warmup 30 --json)
echo "== issue 17: isosurface at equal samples, 512^2 and $RES"
for res in 512x512 $RES; do
  T 90 fccvdb bench render ml.vdb --iso 0.5 --res $res "${B[@]}" | grep -oE '"fps": [0-9.e+]+|time:.*'
  for r in barycentric sheared-trilinear bilinear-spatial bilinear; do
    echo "-- $r $res"; T 90 fccvdb bench render ml_bcc.vdb --reconstruction $r --iso 0.5 --res $res "${B[@]}" | grep -oE '"fps": [0-9.e+]+|time:.*'
  done
done
echo "== issue 17: compare's fps column, every lattice"
mkdir -p cmp; T 240 fccvdb compare --field marschner-lobb --budget $BUDGETS --res 512x512 --points 20000 -o cmp --force
grep -oE '"lattice": "[a-z]+", "reconstruction": "[a-z0-9-]+"|"budget": [0-9]+|"fps": [0-9.e+null]+' cmp/compare.json | paste - - -
echo "== issue 18: DVR, ray against projected tetrahedra (BCC barycentric, in core)"
[ -s pt_bcc.vdb ] || T 60 fccvdb synth marschner-lobb pt_bcc.vdb --dims $PTD,$PTD,$PTD --lattice bcc --force --quiet
for m in ray tetrahedra; do
  echo "-- $m"; T 120 fccvdb bench render pt_bcc.vdb --mode dvr --tf viridis --dvr-method $m --res $RES --frames 60 --warmup 5 --variants skip+analytic --layout auto --json | grep -oE '"fps": [0-9.e+]+|"first_frame_seconds": [0-9.e+]+|time:.*'
done
echo "== issue 18: DVR of blobs ${B2K}^3 through the pyramid, 4x the GPU cache"
[ -s b2k.vdb ] || T 120 fccvdb synth blobs b2k.vdb --dims $B2K,$B2K,$B2K --pyramid --force --quiet
D=(--mode dvr --tf viridis --gpu-cache 784 --host-cache 1024 --res $RES)
T 60 fccvdb render b2k.vdb out_dvr_lod.png "${D[@]}" --lod-bias 0 --timings --force
T 60 fccvdb render b2k.vdb out_dvr_full.png "${D[@]}" --timings --force
T 120 fccvdb bench render b2k.vdb "${D[@]}" --lod-bias 0 --variants skip+analytic --layout texture-vec4 --arc 0 --frames 10 --warmup 2 | grep -E "first|texture|time:"
T 120 fccvdb bench render b2k.vdb "${D[@]}" --lod-bias 1 --variants skip+analytic --layout texture-vec4 --arc 0 --frames 10 --warmup 2 | grep -E "first|texture|time:"
