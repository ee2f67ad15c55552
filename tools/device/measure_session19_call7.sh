#!/usr/bin/env bash
# Session 19, seventh call: the final build against session 18's (commit 9e1dda5, built as fccvdb18),
# alternating: the day's two-gathers rows ran below session 18's final figures; ML 160^3x4 FCC viridis
# and the engine CT inferno at 1080p. Run as
#   git worktree add ../wt18 9e1dda5 && cmake -S ../wt18 -B ../wt18/build -DCMAKE_BUILD_TYPE=Release &&
#   cmake --build ../wt18/build -j2 --target fccvdb && cp ../wt18/build/bin/fccvdb /tmp/fccvdb18
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard /tmp/fccvdb18 ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session19_call7.sh        (SMALL=1: toy sizes)
set -u
W=${W:-/tmp/m19}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; ML=40; FR=5; else RES=1920x1080; ML=320; FR=300; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for round in 1 2 3; do
  for prog in fccvdb fccvdb18; do
    echo "-- round $round [$prog] ML FCC viridis"; $prog bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
    [ -s engine.vdb ] && { echo "-- round $round [$prog] engine inferno"; $prog bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps; }
  done
done
true
