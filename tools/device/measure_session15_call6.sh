#!/usr/bin/env bash
# Session 15, sixth call: streaming passes with the request bits read before their atomic
# (FCC_REQUEST_TEST_FIRST, raycast.comp) against the atomic alone, alternating, on blobs 2048^3 with
# levels: the zoom (issue 19's p99), the orbit, and the full turn in 30 frames. Run as
#   source .devbundle/env.sh && bash tools/device/measure_session15_call6.sh      (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m14}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then N=128; RES=64x64; F=20; else N=2048; RES=1920x1080; F=120; fi
[ -s b2k.vdb ] || fccvdb synth blobs b2k.vdb --dims $N,$N,$N --pyramid --force --quiet
S=(--frames $F --lod-bias 0 --gpu-cache 784 --host-cache 1024 --res $RES --iso 0.3 --layout texture-vec4 --force)
summ() { python3 - "$1" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["runs"][0]; f = r["frames"]; s = r["summary"]
print("  p50 %.2f p99 %.2f mean %.2f max %.2f; first 12: %s" % (s["p50_frame_ms"], s["p99_frame_ms"], s["mean_frame_ms"],
      s["max_frame_ms"], " ".join("%.1f" % x["frame_ms"] for x in f[:12])))
slow = sorted(f, key=lambda x: -x["frame_ms"])[:3]
for x in slow:
    print("  frame %d: %.2f ms = upload %.2f + dispatch %.2f + pass %.2f + requests %.2f; %d requested" % (x["frame"],
          x["frame_ms"], x["upload_ms"], x["dispatch_ms"], x["pass_ms"], x["request_ms"], x["bricks_requested"]))
PY
}
for round in 1 2; do
  for v in FCC_REQUEST_TEST_FIRST=1 FCC_REQUEST_TEST_FIRST=0; do
    for p in ${PATHS:-zoom orbit}; do
      echo "== round $round [$v] $p"
      FCCVDB_SHADER_DEFINES=$v fccvdb bench stream b2k.vdb --path $p "${S[@]}" --json /tmp/s6.json >/dev/null 2>&1 && summ /tmp/s6.json
    done
    [ "${TURN:-1}" = 1 ] || continue
    echo "-- [$v] full turn in 30 frames"
    FCCVDB_SHADER_DEFINES=$v fccvdb bench render b2k.vdb --layout texture-vec4 --variants skip+analytic --gpu-cache 784 \
      --host-cache 1024 --iso 0.3 --res $RES --lod-bias 0 --arc 360 --frames 30 --warmup 3 2>&1 | grep -E "texture-vec4 .*skip" | head -2
  done
done
