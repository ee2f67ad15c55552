#!/usr/bin/env bash
# Session 15, third call: issue 19's largest file, `synth blobs --dims 4096,4096,4096 --half --pyramid`,
# orbited with a 1 GiB GPU pool and a 4 GiB host cache at 1920x1080 (goal: >= 60 fps). Run as
#   source .devbundle/env.sh && bash tools/device/measure_session15_call3.sh     (SMALL=1: toy sizes)
set -u
OUTDIR=${OUT:-/tmp/m15out}; mkdir -p "$OUTDIR"
W=${W:-/tmp/m15c3}; mkdir -p "$W"; cd "$W"
T() { echo "\$ $*"; /usr/bin/time -f 'time: %e s %M KiB' timeout "$@" 2>&1 | grep -v "^\[" | tail -8; }
if [ "${SMALL:-0}" = 1 ]; then N=128; RES=64x64; else N=4096; RES=1920x1080; fi
df -h . | tail -1
T 480 fccvdb synth blobs b4k.vdb --dims $N,$N,$N --half --pyramid --force --quiet
ls -l b4k.vdb; df -h . | tail -1
T 30 fccvdb info b4k.vdb | head -12
S=(--lod-bias 0 --gpu-cache 1024 --host-cache 4096 --res $RES --iso 0.3 --layout texture-vec4)
for p in orbit zoom; do
  echo "== bench stream $p"
  plots=(); [ $p = orbit ] && plots=(--plots "$OUTDIR")  # at most 8 files come back
  T 150 fccvdb bench stream b4k.vdb --path $p --frames 120 "${S[@]}" --json "$OUTDIR/b4k_$p.json" "${plots[@]}" --force | grep -v "^plot:" | tail -6
done
