#!/usr/bin/env bash
# (Its FCC_DVR_HERMITE_CELL knob became RenderOptions::dvrCellCubic, off by default: docs/DVR.md.)
# Session 16, third call, on blobs 2048^3 with levels: (1) is the first run's slow start the driver
# compiling the programs? The zoom on a fresh machine, again, then again with the driver's shader disk
# cache off (__GL_SHADER_DISK_CACHE=0: it compiles anew every process), the cache's size logged;
# (2) the zoom's p99 with uploads fitted to the frame budget (--upload-fit on, default) against the
# fixed 4 ms, alternating, and the orbit and jumps twice. A batch of uploads now starts only if it fits.
# Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard
#   source .devbundle/env.sh && bash tools/device/measure_session16_call3.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m16}; mkdir -p "$W"; cd "$W"
O=${OUT:-/tmp/m16out}; mkdir -p "$O"
if [ "${SMALL:-0}" = 1 ]; then N=128; RES=64x64; F=20; else N=2048; RES=1920x1080; F=120; fi
cache() { echo "  GL cache: $(du -sk ~/.nv/GLCache 2>/dev/null | cut -f1) KiB in $(find ~/.nv/GLCache -type f 2>/dev/null | wc -l) files"; }
cache
[ -s b2k.vdb ] || fccvdb synth blobs b2k.vdb --dims $N,$N,$N --pyramid --force --quiet
cache
S=(--frames $F --lod-bias 0 --gpu-cache 784 --host-cache 1024 --res $RES --iso 0.3 --layout texture-vec4 --force)
summ() { python3 - "$1" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["runs"][0]; f = r["frames"]; s = r["summary"]
print("  p50 %.2f p99 %.2f mean %.2f max %.2f; over budget %s" % (s["p50_frame_ms"], s["p99_frame_ms"],
      s["mean_frame_ms"], s["max_frame_ms"], s.get("frames_over_budget")))
print("  gpu pass 0-13: " + " ".join("%.1f" % x["gpu_pass_ms"] for x in f[:14]))
slow = sorted(f, key=lambda x: -x["frame_ms"])[:3]
for x in slow:
    print("  frame %d: %.2f ms = upload %.2f + dispatch %.2f + pass %.2f (gpu %.2f) + requests %.2f; %d uploaded" % (x["frame"],
          x["frame_ms"], x["upload_ms"], x["dispatch_ms"], x["pass_ms"], x["gpu_pass_ms"], x["request_ms"], x["bricks_uploaded"]))
PY
}
z() {  # label, then bench stream flags
  local label=$1; shift
  echo "== $label"; fccvdb bench stream b2k.vdb "${S[@]}" "$@" --json /tmp/z.json >/dev/null 2>&1 && summ /tmp/z.json
  case "$label" in *second*|*"cache 2"*) ;; *) cp /tmp/z.json "$O/$(echo "$label" | tr ' ' '_').json";; esac  # at most 8 come back
}
z "zoom first" --path zoom
cache
z "zoom second" --path zoom
export __GL_SHADER_DISK_CACHE=0
z "zoom no disk cache 1" --path zoom
z "zoom no disk cache 2" --path zoom
unset __GL_SHADER_DISK_CACHE
for round in 1 2; do
  for fit in on off; do z "zoom fit $fit $round" --path zoom --upload-fit $fit; done
done
z "zoom fit on 3" --path zoom
for round in 1 2; do
  for p in orbit jumps; do
    echo "== $p $round"; fccvdb bench stream b2k.vdb --path $p "${S[@]}" --json /tmp/p.json >/dev/null 2>&1 && summ /tmp/p.json
  done
done
true
# (3) FCC DVR with a cell's chord as one Hermite cubic (FCC_DVR_HERMITE_CELL, a knob: one piece
# evaluation a cell instead of 2.5, approximate) against main, alternating.
if [ "${SMALL:-0}" = 1 ]; then ML=40; FR=5; else ML=320; FR=300; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=${FCC_DATA:-/nonexistent}/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for round in 1 2; do
  for v in "" "FCC_DVR_HERMITE_CELL=1"; do
    echo "-- round $round [${v:-main}] ML FCC viridis"; FCCVDB_SHADER_DEFINES=$v fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
    [ -s engine.vdb ] && { echo "-- round $round [${v:-main}] engine inferno"; FCCVDB_SHADER_DEFINES=$v fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps; }
  done
done
true
