#!/usr/bin/env bash
# Session 21, fourth call: what the DVR program keeps in the L1 cache. Each variant without and with
# 8 KiB of shared memory a work group (FCC_OCCUPANCY_PAD=2048: the L1 cache shrinks by 128 KiB at 16
# groups an SM; the third call: main 200 -> 115 fps): main; no memory reads for the pieces
# (FCC_DVR_CHAIN_PROBE=3, wrong images); one sub-step a chord (wrong); the walk's and loop's state in
# shared memory while a cell is integrated (FCC_DVR_STASH=2 with its fence: 115 registers against
# 127, commit 9b2a891); the walk alone (52 registers, 28 warps: 4 KiB a group there so that the pad does
# not limit its groups). Engine CT inferno at 1080p. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session21_call4.sh
set -u
W=${W:-/tmp/m21}; mkdir -p "$W"; cd "$W"
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet
D=(--variants skip+analytic --layout auto --res 1920x1080 --frames 200 --warmup 20 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
for round in 1 2; do
  for v in "" "FCC_DVR_CHAIN_PROBE=3" "FCC_DVR_FIXED_STEPS=1" "FCC_DVR_STASH=2;FCC_DVR_STASH_FENCE=1"; do
    for pad in 0 2048; do
      echo "-- round $round [$v;FCC_OCCUPANCY_PAD=$pad] engine DVR inferno"; FCCVDB_SHADER_DEFINES="$v;FCC_OCCUPANCY_PAD=$pad" fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
    done
  done
  for pad in 0 1024; do
    echo "-- round $round [FCC_DVR_WALK_ONLY=1;FCC_OCCUPANCY_PAD=$pad] engine DVR inferno, the walk alone"; FCCVDB_SHADER_DEFINES="FCC_DVR_WALK_ONLY=1;FCC_OCCUPANCY_PAD=$pad" fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps
  done
done
for tf in grayscale viridis inferno ct-bone fog; do
  echo "-- preset $tf: engine DVR"; fccvdb bench render engine.vdb --mode dvr --tf $tf "${D[@]}" | fps
done
true
