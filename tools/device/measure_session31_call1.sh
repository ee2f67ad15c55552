#!/usr/bin/env bash
# Session 31, first call (issue 18): (a) the brick pool's texels in half precision (FCCVDB_POOL_HALF=1,
# viewer/BrickPool.cpp: R16F / RGBA16F, every coefficient rounded; a measurement knob, commit 173aa65, removed since: no difference) against main,
# alternating, two rounds, the engine CT inferno and ML 160^3x4 FCC viridis at 1080p (the pool's bytes
# through L1: what they cost the frame); (b) session 30's third call (measure_session30_call3.sh: the
# final build's projected tetrahedra, which did not run then). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session31_call1.sh        (SMALL=1: toy sizes)
source tools/device/prologue.sh
W=${W:-/tmp/m31}; source "$HERE/tools/device/bench_data.sh"
for round in 1 2; do
  for half in 0 1; do
    run() { FCCVDB_POOL_HALF=$half timeout 200 fccvdb bench render "$@" "${D[@]}" | fps; }
    echo "-- round $round [pool half $half]: engine DVR inferno $(run engine.vdb --mode dvr --tf inferno) ML DVR viridis $(run ml.vdb --mode dvr --tf viridis)"
  done
done
cd "$HERE" && bash tools/device/measure_session30_call3.sh
true
