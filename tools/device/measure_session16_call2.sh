#!/usr/bin/env bash
# Session 16, second call: (1) the zoom with uploads fitted to the frame budget (bench stream
# --upload-fit on, the new default) against the fixed 4 ms (off), alternating, on blobs 2048^3 with
# levels; the orbit and jumps with it; (2) where FCC DVR's time goes: one fetch for a piece's 19
# coefficients (FCC_DVR_ONE_FETCH) with and without one sub-step a piece. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard
#   source .devbundle/env.sh && bash tools/device/measure_session16_call2.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m16}; mkdir -p "$W"; cd "$W"
O=${OUT:-/tmp/m16out}; mkdir -p "$O"
if [ "${SMALL:-0}" = 1 ]; then N=128; RES=64x64; F=20; ML=40; FR=5; else N=2048; RES=1920x1080; F=120; ML=320; FR=300; fi
[ -s b2k.vdb ] || fccvdb synth blobs b2k.vdb --dims $N,$N,$N --pyramid --force --quiet
S=(--frames $F --lod-bias 0 --gpu-cache 784 --host-cache 1024 --res $RES --iso 0.3 --layout texture-vec4 --force)
summ() { python3 - "$1" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["runs"][0]; f = r["frames"]; s = r["summary"]
print("  p50 %.2f p99 %.2f mean %.2f max %.2f; over budget %s; first complete frame %s" % (s["p50_frame_ms"], s["p99_frame_ms"],
      s["mean_frame_ms"], s["max_frame_ms"], s.get("frames_over_budget"), next((x["frame"] for x in f if x["complete"]), None)))
print("  frames 14-34: " + " ".join("%.1f" % x["frame_ms"] for x in f[14:34]))
print("  upload:       " + " ".join("%.1f" % x["upload_ms"] for x in f[14:34]))
print("  gpu pass:     " + " ".join("%.1f" % x["gpu_pass_ms"] for x in f[14:34]))
slow = sorted(f, key=lambda x: -x["frame_ms"])[:3]
for x in slow:
    print("  frame %d: %.2f ms = upload %.2f + dispatch %.2f + pass %.2f (gpu %.2f) + requests %.2f; %d uploaded" % (x["frame"],
          x["frame_ms"], x["upload_ms"], x["dispatch_ms"], x["pass_ms"], x["gpu_pass_ms"], x["request_ms"], x["bricks_uploaded"]))
PY
}
# A first run of the program on this machine (shader cache, file pages) before the measured ones.
fccvdb bench stream b2k.vdb --path orbit "${S[@]}" --frames 10 --json /tmp/first.json >/dev/null 2>&1
for round in 1 2; do
  for fit in on off; do
    echo "== round $round zoom --upload-fit $fit"
    fccvdb bench stream b2k.vdb --path zoom "${S[@]}" --upload-fit $fit --json /tmp/z.json >/dev/null 2>&1 && summ /tmp/z.json
    cp /tmp/z.json "$O/zoom_${fit}_$round.json"
  done
done
for p in orbit jumps; do
  echo "== $p --upload-fit on"; fccvdb bench stream b2k.vdb --path $p "${S[@]}" --json /tmp/p.json >/dev/null 2>&1 && summ /tmp/p.json
  cp /tmp/p.json "$O/${p}_on.json"
done
# DVR: the gather's share.
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for v in "" "FCC_DVR_ONE_FETCH=1" "FCC_DVR_FIXED_STEPS=1" "FCC_DVR_FIXED_STEPS=1;FCC_DVR_ONE_FETCH=1"; do
  echo "-- [${v:-main}] ML FCC viridis"; FCCVDB_SHADER_DEFINES=$v fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
done
true
