#!/usr/bin/env bash
# Session 17, third call: issue 19's paths as a machine's first run would see them, each bench stream
# with a fresh, empty driver shader cache directory, with `--prime auto` (the default now: on for a GPU)
# and once with `--prime off`; blobs 2048^3 with its pyramid, budgets 1/4 of the data. Then issue 18's
# blobs 2048^3 DVR through the pyramid at 4x the GPU cache with the chord walk (session 17's default).
# Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard
#   source .devbundle/env.sh && bash tools/device/measure_session17_call3.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m17}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then N=128; RES=64x64; F=20; else N=2048; RES=1920x1080; F=120; fi
[ -s b2k.vdb ] || fccvdb synth blobs b2k.vdb --dims $N,$N,$N --pyramid --force --quiet
S=(--frames $F --lod-bias 0 --gpu-cache 784 --host-cache 1024 --res $RES --iso 0.3 --layout texture-vec4 --force)
summ() { python3 - "$1" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); r = d["runs"][0]; f = r["frames"]; s = r["summary"]
print("  primed %s; p50 %.2f p99 %.2f max %.2f; gpu hit rate %.4f; over budget %s" % (d["primed"], s["p50_frame_ms"],
      s["p99_frame_ms"], s["max_frame_ms"], s["gpu_hit_rate"], s.get("frames_over_budget")))
print("  gpu pass 0-13: " + " ".join("%.1f" % x["gpu_pass_ms"] for x in f[:14]))
slow = sorted(f, key=lambda x: -x["frame_ms"])[:2]
for x in slow:
    print("  frame %d: %.2f ms = upload %.2f + dispatch %.2f + pass %.2f (gpu %.2f) + requests %.2f; %d uploaded" % (x["frame"],
          x["frame_ms"], x["upload_ms"], x["dispatch_ms"], x["pass_ms"], x["gpu_pass_ms"], x["request_ms"], x["bricks_uploaded"]))
PY
}
z() {  # label, path, then more bench stream flags; a fresh driver cache directory each
  local label=$1 path=$2; shift 2
  local cache; cache=$(mktemp -d)
  local t0; t0=$(date +%s.%N)
  echo "== $label"; __GL_SHADER_DISK_CACHE_PATH="$cache" fccvdb bench stream b2k.vdb --path $path "${S[@]}" "$@" --json /tmp/z.json >/dev/null 2>&1 && summ /tmp/z.json
  echo "  wall $(echo "$(date +%s.%N) - $t0" | bc) s"
}
z "zoom, fresh driver cache" zoom
z "zoom, fresh driver cache, --prime off" zoom --prime off
z "zoom, fresh driver cache (again)" zoom
z "orbit, fresh driver cache" orbit
z "jumps, fresh driver cache" jumps
true
echo "-- blobs 2048^3 DVR viridis, pyramid, --gpu-cache 784"
fccvdb bench render b2k.vdb --mode dvr --tf viridis --layout texture-vec4 --variants skip+analytic --gpu-cache 784 \
  --host-cache 8192 --lod-bias 0 --arc 0 --res $RES --frames 60 --warmup 5 --json | grep -oE '"(fps|first_frame_s|first_frame_seconds)": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo
true
