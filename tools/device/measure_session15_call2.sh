#!/usr/bin/env bash
# Session 15, second call: the FCC DVR after the cell gather and the sparse table of extinction maxima
# (issue 18), and the streaming paths with each frame's upload time (issue 19, the zoom's p99). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session15_call2.sh
# PART=dvr|stream runs one part; SMALL=1 the same commands at toy sizes. FCC_DVR_CELL_GATHER was a knob
# of the build this call measured (a unit cell's 28 coefficients gathered once); it was slower and is
# gone, so that define now changes nothing.
set -u
HERE=$(cd "$(dirname "$0")" && pwd)
OUTDIR=${OUT:-/tmp/m15out}; mkdir -p "$OUTDIR"
W=${W:-/tmp/m14}; mkdir -p "$W"; cd "$W"
T() { echo "\$ $*"; /usr/bin/time -f 'time: %e s %M KiB' timeout "$@" 2>&1 | grep -v "^\[" | tail -8; }
if [ "${SMALL:-0}" = 1 ]; then ML=40; MLC=32; B2K=128; RES=64x64; FR=5; SF=20; else ML=320; MLC=254; B2K=2048; RES=1920x1080; FR=300; SF=120; fi
PART=${PART:-all}
fps() { grep -oE '"fps": [0-9.e+]+|time:.*|fccvdb:.*' | tr '\n' ' '; echo; }
if [ "$PART" = all ] || [ "$PART" = dvr ]; then
  [ -s ml.vdb ] || T 120 fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
  [ -s ml_cc.vdb ] || T 120 fccvdb synth marschner-lobb ml_cc.vdb --dims $MLC,$MLC,$MLC --lattice cc --force --quiet
  ENGINE=${FCC_DATA:-$HERE/../../../shared/data}/engine_256x256x128_uint8.raw.gz
  [ -s engine.vdb ] || { [ -f "$ENGINE" ] && T 60 fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
  D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
  echo "== DVR, ML FCC viridis $RES"
  for v in "" "FCC_DVR_CELL_GATHER=0" "FCC_DVR_FIXED_STEPS=1" "" ; do
    echo "-- [$v]"; FCCVDB_SHADER_DEFINES="$v" T 60 fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
  done
  for g in 8x4 8x8 16x8; do echo "-- work group $g"; T 60 fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" --work-group $g | fps; done
  echo "-- fog"; T 60 fccvdb bench render ml.vdb --mode dvr --tf fog "${D[@]}" | fps
  echo "-- shading on"; T 60 fccvdb bench render ml.vdb --mode dvr --tf viridis --shading on "${D[@]}" | fps
  echo "-- CC trilinear"; T 60 fccvdb bench render ml_cc.vdb --reconstruction trilinear --mode dvr --tf viridis "${D[@]}" | fps
  if [ -s engine.vdb ]; then
    for v in "" "FCC_DVR_CELL_GATHER=0"; do
      echo "-- engine inferno [$v]"; FCCVDB_SHADER_DEFINES="$v" T 60 fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
    done
  fi
fi
if [ "$PART" = all ] || [ "$PART" = stream ]; then
  [ -s b2k.vdb ] || T 120 fccvdb synth blobs b2k.vdb --dims $B2K,$B2K,$B2K --pyramid --force --quiet
  S=(--frames $SF --lod-bias 0 --gpu-cache 784 --host-cache 1024 --res $RES --iso 0.3 --layout texture-vec4)
  for p in ${PATHS:-zoom orbit jumps}; do
    echo "== bench stream $p"
    T 120 fccvdb bench stream b2k.vdb --path $p "${S[@]}" --json "$OUTDIR/stream_$p.json" --force | tail -4
    python3 - "$OUTDIR/stream_$p.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["runs"][0]
f = r["frames"]; s = r["summary"]
ms = sorted(x["frame_ms"] for x in f)
print("p50 %.2f p99 %s max %.2f" % (ms[len(ms)//2], s.get("p99_frame_ms"), ms[-1]))
worst = sorted(f, key=lambda x: -x["frame_ms"])[:8]
for x in worst:
    print("  frame %d: %.2f ms, upload %.2f, dispatch %.2f, pass %.2f, requests %.2f ms, %d uploaded, %d requested, restarted %s" % (
        x["frame"], x["frame_ms"], x.get("upload_ms", 0), x.get("dispatch_ms", 0), x.get("pass_ms", 0), x.get("request_ms", 0),
        x["bricks_uploaded"], x["bricks_requested"], x["restarted"]))
print("  mean upload %.2f ms, mean frame %.2f ms" % (sum(x.get("upload_ms", 0) for x in f) / len(f), sum(x["frame_ms"] for x in f) / len(f)))
PY
  done
fi
