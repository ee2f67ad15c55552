#!/usr/bin/env bash
# (Its FCCVDB_BENCH_PRIME knob, in this call's meaning, became `bench stream --prime` after the second call; FCC_DVR_CHORD_STEPS became the default walk: docs/DVR.md.)
# Session 17, first call. (1) FCC DVR (issue 18) with a chord's central piece taken from its
# neighbours (main now) against gathering it (FCC_DVR_GATHER_CENTRAL=1, session 16's walk) and against
# a chord sub-stepped as one segment (FCC_DVR_CHORD_STEPS=1) and against sub-steps of up to 1/8 and 1/4
# of optical depth (FCC_DVR_STEP_DEPTH; 1/16 in main), alternating, ML 160^3x4 FCC viridis
# and the engine CT inferno at 1080p. (2) Issue 19's first run: the zoom on blobs 2048^3 with the
# driver's shader disk cache off (every process compiles anew, as a machine's first run does), plain
# and primed (FCCVDB_BENCH_PRIME="K,M": K steps looking away from the data, then M ms of sleep).
# Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session17.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m17}; mkdir -p "$W"; cd "$W"
O=${OUT:-/tmp/m17out}; mkdir -p "$O"
if [ "${SMALL:-0}" = 1 ]; then N=128; RES=64x64; F=20; ML=40; FR=5; else N=2048; RES=1920x1080; F=120; ML=320; FR=300; fi
nvidia-smi --query-gpu=name,driver_version,clocks.sm --format=csv,noheader 2>/dev/null
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=${FCC_DATA:-/nonexistent}/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for round in 1 2; do
  for v in "" "FCC_DVR_GATHER_CENTRAL=1" "FCC_DVR_CHORD_STEPS=1" "FCC_DVR_STEP_DEPTH=0.125" "FCC_DVR_STEP_DEPTH=0.25"; do
    echo "-- round $round [${v:-main}] ML FCC viridis"; FCCVDB_SHADER_DEFINES=$v fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
    [ -s engine.vdb ] && { echo "-- round $round [${v:-main}] engine inferno"; FCCVDB_SHADER_DEFINES=$v fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps; }
  done
done
echo "-- ML isosurface 0.5"; fccvdb bench render ml.vdb --iso 0.5 "${D[@]}" | fps
echo "-- ML FCC fog"; fccvdb bench render ml.vdb --mode dvr --tf fog "${D[@]}" | fps
true
# (2) The first run's slow start.
[ -s b2k.vdb ] || fccvdb synth blobs b2k.vdb --dims $N,$N,$N --pyramid --force --quiet
S=(--frames $F --lod-bias 0 --gpu-cache 784 --host-cache 1024 --res $RES --iso 0.3 --layout texture-vec4 --force)
summ() { python3 - "$1" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["runs"][0]; f = r["frames"]; s = r["summary"]
print("  p50 %.2f p99 %.2f max %.2f" % (s["p50_frame_ms"], s["p99_frame_ms"], s["max_frame_ms"]))
print("  gpu pass 0-13: " + " ".join("%.1f" % x["gpu_pass_ms"] for x in f[:14]))
PY
}
z() {  # label, then environment assignments for the run
  local label=$1; shift
  echo "== $label"; env "$@" fccvdb bench stream b2k.vdb --path zoom "${S[@]}" --json /tmp/z.json >/dev/null 2>&1 && summ /tmp/z.json
}
z "zoom, disk cache on (after the DVR runs)"
z "zoom, disk cache off" __GL_SHADER_DISK_CACHE=0
z "zoom, disk cache off, primed 20 passes" __GL_SHADER_DISK_CACHE=0 FCCVDB_BENCH_PRIME=20,0
z "zoom, disk cache off, primed 1 pass + 1000 ms" __GL_SHADER_DISK_CACHE=0 FCCVDB_BENCH_PRIME=1,1000
z "zoom, disk cache off, primed 40 passes + 500 ms" __GL_SHADER_DISK_CACHE=0 FCCVDB_BENCH_PRIME=40,500
z "zoom, disk cache off, again" __GL_SHADER_DISK_CACHE=0
z "zoom, disk cache on" 
true
