#!/usr/bin/env bash
# (Its FCCVDB_BENCH_PRIME knob, in this call's meaning, became `bench stream --prime` after the second call; FCC_DVR_CHORD_STEPS became the default walk: docs/DVR.md.)
# Session 17, second call. (1) FCC DVR (issue 18): a unit cell's chord from its two end pieces,
# sub-stepped as one segment (main now) against every piece gathered and sub-stepped by itself
# (FCC_DVR_GATHER_CENTRAL=1), alternating; then what the sub-step rule and the gather still cost
# (knobs, for the cost alone: coarser entries and depth, one sub-step a chord, one fetch a piece).
# (2) Issue 19's first run: the zoom on blobs 2048^3, each run with a fresh, empty driver shader cache
# directory (as a machine's first run), plain and primed (FCCVDB_BENCH_PRIME="K,M": a throwaway
# raycaster steps K times at the first camera, then M ms of sleep).
# Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session17_call2.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m17}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then N=128; RES=64x64; F=20; ML=40; FR=5; else N=2048; RES=1920x1080; F=120; ML=320; FR=300; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=${FCC_DATA:-/nonexistent}/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
dvr() {  # label, shader defines
  echo "-- $1 ML FCC viridis"; FCCVDB_SHADER_DEFINES=$2 fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
  [ -s engine.vdb ] && { echo "-- $1 engine inferno"; FCCVDB_SHADER_DEFINES=$2 fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps; }
}
for round in 1 2; do
  dvr "round $round [main]" ""
  dvr "round $round [every piece]" "FCC_DVR_GATHER_CENTRAL=1"
done
dvr "[entries x4]" "FCC_DVR_STEP_ENTRIES=4"
dvr "[entries x4, depth 1/4]" "FCC_DVR_STEP_ENTRIES=4;FCC_DVR_STEP_DEPTH=0.25"
dvr "[one sub-step a chord]" "FCC_DVR_FIXED_STEPS=1"
dvr "[one fetch a piece]" "FCC_DVR_ONE_FETCH=1"
dvr "[one fetch, one sub-step]" "FCC_DVR_ONE_FETCH=1;FCC_DVR_FIXED_STEPS=1"
echo "-- ML FCC fog"; fccvdb bench render ml.vdb --mode dvr --tf fog "${D[@]}" | fps
echo "-- ML FCC viridis shaded"; fccvdb bench render ml.vdb --mode dvr --tf viridis --shading on "${D[@]}" | fps
true
[ -s b2k.vdb ] || fccvdb synth blobs b2k.vdb --dims $N,$N,$N --pyramid --force --quiet
S=(--frames $F --lod-bias 0 --gpu-cache 784 --host-cache 1024 --res $RES --iso 0.3 --layout texture-vec4 --force)
summ() { python3 - "$1" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["runs"][0]; f = r["frames"]; s = r["summary"]
print("  p50 %.2f p99 %.2f max %.2f" % (s["p50_frame_ms"], s["p99_frame_ms"], s["max_frame_ms"]))
print("  gpu pass 0-13: " + " ".join("%.1f" % x["gpu_pass_ms"] for x in f[:14]))
PY
}
z() {  # label, then environment assignments for the run (each with a fresh driver cache directory)
  local label=$1; shift
  local cache; cache=$(mktemp -d)
  echo "== $label"; env __GL_SHADER_DISK_CACHE_PATH="$cache" "$@" fccvdb bench stream b2k.vdb --path zoom "${S[@]}" --json /tmp/z.json >/dev/null 2>&1 && summ /tmp/z.json
  echo "  driver cache: $(du -sk "$cache" | cut -f1) KiB"
}
z "zoom, fresh cache"
z "zoom, fresh cache, primed 20 steps" FCCVDB_BENCH_PRIME=20,0
z "zoom, fresh cache, primed 20 steps + 500 ms" FCCVDB_BENCH_PRIME=20,500
z "zoom, fresh cache" 
z "zoom, disk cache off, primed 20 steps" __GL_SHADER_DISK_CACHE=0 FCCVDB_BENCH_PRIME=20,0
true
