#!/usr/bin/env bash
# Session 17, fourth call: issue 19's paths with the default `--prime auto` on a fresh machine (its
# driver has compiled none of our programs: the first zoom is a machine's first run), each path more
# than once; blobs 2048^3 with its pyramid, budgets 1/4 of the data; the first zoom's plots come back.
# Then issue 18's DVR on the final build (the chord's knots now skip crossings rounding adds near its
# ends; 192 sub-steps a chord at most), main against every piece.
# Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session17_call4.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m17}; mkdir -p "$W"; cd "$W"
O=${OUT:-/tmp/m17out}; mkdir -p "$O"
if [ "${SMALL:-0}" = 1 ]; then N=128; RES=64x64; F=20; else N=2048; RES=1920x1080; F=120; fi
[ -s b2k.vdb ] || fccvdb synth blobs b2k.vdb --dims $N,$N,$N --pyramid --force --quiet
S=(--frames $F --lod-bias 0 --gpu-cache 784 --host-cache 1024 --res $RES --iso 0.3 --layout texture-vec4 --force)
summ() { python3 - "$1" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); r = d["runs"][0]; f = r["frames"]; s = r["summary"]
print("  primed %s; p50 %.2f p99 %.2f max %.2f; gpu hit rate %.4f; over budget %s; budget_ok %s" % (d["primed"],
      s["p50_frame_ms"], s["p99_frame_ms"], s["max_frame_ms"], s["gpu_hit_rate"], s.get("frames_over_budget"), s.get("budget_ok")))
slow = sorted(f, key=lambda x: -x["frame_ms"])[:2]
for x in slow:
    print("  frame %d: %.2f ms = upload %.2f + dispatch %.2f + pass %.2f (gpu %.2f) + requests %.2f; %d uploaded" % (x["frame"],
          x["frame_ms"], x["upload_ms"], x["dispatch_ms"], x["pass_ms"], x["gpu_pass_ms"], x["request_ms"], x["bricks_uploaded"]))
PY
}
z() {  # label, path, more flags
  local label=$1 path=$2; shift 2
  echo "== $label"; fccvdb bench stream b2k.vdb --path $path "${S[@]}" "$@" --json /tmp/z.json >/dev/null 2>&1 && summ /tmp/z.json
}
z "zoom 1 (the machine's first)" zoom --plots "$O"
for i in 2 3 4; do z "zoom $i" zoom; done
for i in 1 2; do z "orbit $i" orbit; z "jumps $i" jumps; done
true
if [ "${SMALL:-0}" = 1 ]; then ML=40; FR=5; else ML=320; FR=300; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=${FCC_DATA:-/nonexistent}/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for round in 1 2; do
  for v in "" "FCC_DVR_GATHER_CENTRAL=1"; do
    echo "-- round $round [${v:-main}] ML FCC viridis"; FCCVDB_SHADER_DEFINES=$v fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
    [ -s engine.vdb ] && { echo "-- round $round [${v:-main}] engine inferno"; FCCVDB_SHADER_DEFINES=$v fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps; }
  done
done
true
