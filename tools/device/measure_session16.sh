#!/usr/bin/env bash
# (Its --gpu-warmup-ms and FCC_GATHER_ALL_SITES were reverted after this call: docs/BENCHMARKS.md, session 16.)
# Session 16, first call: (1) the zoom's p99 on a cold GPU with and without bench stream's new GPU
# warm-up (--gpu-warmup-ms), with the SM clocks logged (nvidia-smi, read only) and each frame's GPU pass
# time (gpu_pass_ms); (2) FCC DVR at 1080p with the 16-fetch gather against all 19 fetches
# (FCC_GATHER_ALL_SITES=1), alternating. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session16.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m16}; mkdir -p "$W"; cd "$W"
O=${OUT:-/tmp/m16out}; mkdir -p "$O"
if [ "${SMALL:-0}" = 1 ]; then N=128; RES=64x64; F=20; ML=40; FR=5; COOL=1; else N=2048; RES=1920x1080; F=120; ML=320; FR=300; COOL=30; fi
if command -v nvidia-smi >/dev/null; then
  nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,pstate,utilization.gpu,power.draw --format=csv,noheader -lms 100 > "$O/clocks.csv" 2>&1 &
  SMI=$!
fi
mark() { echo "$(date +%H:%M:%S.%N | cut -c1-12) $*" | tee -a "$O/marks.txt"; }
mark "synth start"
[ -s b2k.vdb ] || fccvdb synth blobs b2k.vdb --dims $N,$N,$N --pyramid --force --quiet
mark "synth end"
S=(--frames $F --lod-bias 0 --gpu-cache 784 --host-cache 1024 --res $RES --iso 0.3 --layout texture-vec4 --force)
summ() { python3 - "$1" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["runs"][0]; f = r["frames"]; s = r["summary"]
print("  p50 %.2f p99 %.2f mean %.2f max %.2f" % (s["p50_frame_ms"], s["p99_frame_ms"], s["mean_frame_ms"], s["max_frame_ms"]))
print("  frame:    " + " ".join("%5.1f" % x["frame_ms"] for x in f[:14]))
print("  dispatch: " + " ".join("%5.1f" % x["dispatch_ms"] for x in f[:14]))
print("  pass:     " + " ".join("%5.1f" % x["pass_ms"] for x in f[:14]))
print("  gpu pass: " + " ".join("%5.1f" % x["gpu_pass_ms"] for x in f[:14]))
print("  upload:   " + " ".join("%5.1f" % x["upload_ms"] for x in f[:14]))
print("  uploaded: " + " ".join("%5d" % x["bricks_uploaded"] for x in f[:14]))
slow = sorted(f, key=lambda x: -x["frame_ms"])[:3]
for x in slow:
    print("  frame %d: %.2f ms = upload %.2f + dispatch %.2f + pass %.2f (gpu %.2f) + requests %.2f" % (x["frame"],
          x["frame_ms"], x["upload_ms"], x["dispatch_ms"], x["pass_ms"], x["gpu_pass_ms"], x["request_ms"]))
PY
}
i=0
for w in 0 1000 0 1000; do
  i=$((i + 1))
  [ $i -gt 1 ] && { mark "idle ${COOL}s"; sleep $COOL; }
  mark "zoom run $i, --gpu-warmup-ms $w"
  fccvdb bench stream b2k.vdb --path zoom "${S[@]}" --gpu-warmup-ms $w --json "$O/zoom$i.json" >/dev/null 2>&1 && summ "$O/zoom$i.json"
  mark "zoom run $i end"
done
mark "orbit, jumps (warm-up 1000)"
for p in orbit jumps; do
  echo "== $p"; fccvdb bench stream b2k.vdb --path $p "${S[@]}" --json /tmp/p.json >/dev/null 2>&1 && summ /tmp/p.json
done
# DVR (issue 18), 1080p, the gather A/B, alternating.
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=${FCC_DATA:-/nonexistent}/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
mark "DVR"
for round in 1 2; do
  for v in FCC_GATHER_ALL_SITES=0 FCC_GATHER_ALL_SITES=1; do
    echo "-- round $round [$v] ML FCC viridis"; FCCVDB_SHADER_DEFINES=$v fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
    [ -s engine.vdb ] && { echo "-- round $round [$v] engine inferno"; FCCVDB_SHADER_DEFINES=$v fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps; }
    echo "-- round $round [$v] ML FCC iso 0.5"; FCCVDB_SHADER_DEFINES=$v fccvdb bench render ml.vdb --iso 0.5 "${D[@]}" | fps
  done
done
mark "DVR layouts"
for l in texture-vec4 texture-scalar ssbo-vec4 ssbo-scalar; do
  echo "-- layout $l ML FCC viridis"; fccvdb bench render ml.vdb --mode dvr --tf viridis ${D[@]/auto/$l} | fps
done
mark "end"
[ -n "${SMI:-}" ] && kill $SMI
true
