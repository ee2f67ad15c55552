#!/usr/bin/env bash
# Session 28, second call (issue 18): the DVR split (FCCVDB_DVR_SPLIT="K,N") with its lists laid out a
# work group's at a time (a warp's k-th entries one run of memory; the first call's were a frame's k-th
# entries, pixels apart): the 1080p PNGs against main's (pngdiff) and the frame rates, alternating with
# main, two rounds (engine CT inferno, ML 160^3x4 FCC viridis). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session28_call2.sh        (SMALL=1: toy sizes)
# The knob is removed since (session 29); to run this again, apply tools/device/session28_dvr_split.patch
# to commit 8d1dd6c first.
source tools/device/prologue.sh
W=${W:-/tmp/m28}; source "$HERE/tools/device/bench_data.sh"
SPLITS=${SPLITS:-"16,6 32,3 32,4 64,2 128,1 256,1"}
source "$HERE/tools/device/dvr_knob_runs.sh"
dvr_split_images "$SPLITS"
dvr_split_rounds "$SPLITS"
true
