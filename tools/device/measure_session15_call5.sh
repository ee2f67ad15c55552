#!/usr/bin/env bash
# Session 15, fifth call: the zoom path's slow first frames, A/B against session 13's last build
# (92ad9c7) on the same blobs 2048^3 file, alternating. Run as
#   cp <92ad9c7's build>/bin/fccvdb /tmp/fccvdb_old
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard /tmp/fccvdb_old
#   source .devbundle/env.sh && bash tools/device/measure_session15_call5.sh
set -u
OLD=${OLD:-/opt/fcc/bin/fccvdb_old}
[ -f "${FCC_DATA:-}/fccvdb_old" ] && cp "$FCC_DATA/fccvdb_old" "$OLD" && chmod +x "$OLD"
W=${W:-/tmp/m14}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then N=128; RES=64x64; F=20; else N=2048; RES=1920x1080; F=120; fi
[ -s b2k.vdb ] || fccvdb synth blobs b2k.vdb --dims $N,$N,$N --pyramid --force --quiet
S=(--frames $F --lod-bias 0 --gpu-cache 784 --host-cache 1024 --res $RES --iso 0.3 --layout texture-vec4 --force)
summ() { python3 - "$1" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["runs"][0]; f = r["frames"]; s = r["summary"]
print("  p50 %.2f p99 %.2f mean %.2f; first 12: %s" % (s["p50_frame_ms"], s["p99_frame_ms"], s["mean_frame_ms"],
      " ".join("%.1f" % x["frame_ms"] for x in f[:12])))
print("  requested: %s" % " ".join(str(x["bricks_requested"]) for x in f[:12]))
print("  uploaded:  %s" % " ".join(str(x["bricks_uploaded"]) for x in f[:12]))
PY
}
for round in 1 2; do
  for b in fccvdb "$OLD"; do
    [ -x "$(command -v $b)" ] || continue
    for p in zoom ${EXTRA_PATHS:-}; do
      echo "== round $round $(basename $b) $p"; $b bench stream b2k.vdb --path $p "${S[@]}" --json /tmp/ab.json >/dev/null 2>&1 && summ /tmp/ab.json
    done
  done
done
echo "== new, zoom, --lookahead 0"; fccvdb bench stream b2k.vdb --path zoom "${S[@]}" --lookahead 0 --json /tmp/ab.json >/dev/null 2>&1 && summ /tmp/ab.json
# The DVR figures of the final build (no cell gather; the sparse table of extinction maxima).
if [ "${DVR:-1}" = 1 ]; then
  if [ "${SMALL:-0}" = 1 ]; then ML=40; MLC=32; FR=5; else ML=320; MLC=254; FR=300; fi
  [ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
  [ -s ml_cc.vdb ] || fccvdb synth marschner-lobb ml_cc.vdb --dims $MLC,$MLC,$MLC --lattice cc --force --quiet
  ENGINE=${FCC_DATA:-/nonexistent}/engine_256x256x128_uint8.raw.gz
  [ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
  D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
  fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
  echo "== DVR $RES"
  echo "-- ML FCC viridis"; fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
  echo "-- ML FCC viridis"; fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
  echo "-- ML FCC fog"; fccvdb bench render ml.vdb --mode dvr --tf fog "${D[@]}" | fps
  echo "-- ML FCC viridis shading"; fccvdb bench render ml.vdb --mode dvr --tf viridis --shading on "${D[@]}" | fps
  echo "-- ML CC trilinear"; fccvdb bench render ml_cc.vdb --reconstruction trilinear --mode dvr --tf viridis "${D[@]}" | fps
  echo "-- ML CC tricubic"; fccvdb bench render ml_cc.vdb --reconstruction tricubic --mode dvr --tf viridis "${D[@]}" --frames 100 | fps
  [ -s engine.vdb ] && { echo "-- engine inferno"; fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps; }
fi
