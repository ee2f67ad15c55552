#!/usr/bin/env bash
# Session 28, second call (issue 18): the DVR split (FCCVDB_DVR_SPLIT="K,N") with its lists laid out a
# work group's at a time (a warp's k-th entries one run of memory; the first call's were a frame's k-th
# entries, pixels apart): the 1080p PNGs against main's (pngdiff) and the frame rates, alternating with
# main, two rounds (engine CT inferno, ML 160^3x4 FCC viridis). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session28_call2.sh        (SMALL=1: toy sizes)
source tools/device/prologue.sh
W=${W:-/tmp/m28}; source "$HERE/tools/device/bench_data.sh"
SPLITS=${SPLITS:-"16,6 32,3 32,4 64,2 128,1 256,1"}
fccvdb render engine.vdb --mode dvr --tf inferno --res $RES -o "$W/engine_main.png" --force --quiet
fccvdb render ml.vdb --mode dvr --tf viridis --res $RES -o "$W/ml_main.png" --force --quiet
for s in $SPLITS; do
  FCCVDB_DVR_SPLIT=$s fccvdb render engine.vdb --mode dvr --tf inferno --res $RES -o "$W/engine_split.png" --force --quiet
  FCCVDB_DVR_SPLIT=$s fccvdb render ml.vdb --mode dvr --tf viridis --res $RES -o "$W/ml_split.png" --force --quiet
  echo "split $s engine: $(python3 "$HERE/tools/device/pngdiff.py" "$W/engine_main.png" "$W/engine_split.png" | head -1 | cut -c1-100)"
  echo "split $s ML: $(python3 "$HERE/tools/device/pngdiff.py" "$W/ml_main.png" "$W/ml_split.png" | head -1 | cut -c1-100)"
done
for round in 1 2; do
  for s in main $SPLITS; do
    if [ $s = main ]; then run() { fccvdb bench render "$@" "${D[@]}" | fps; }
    else run() { FCCVDB_DVR_SPLIT=$s fccvdb bench render "$@" "${D[@]}" | fps; }; fi
    echo "-- round $round [split $s]: engine DVR inferno $(run engine.vdb --mode dvr --tf inferno) ML DVR viridis $(run ml.vdb --mode dvr --tf viridis)"
  done
done
true
