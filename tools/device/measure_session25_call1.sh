#!/usr/bin/env bash
# Session 25, first call (written in session 24 as its fifth, not run then; needs
# tools/device/session25_persistent_groups.patch applied: `git am` it on main, measured there, not kept):
# persistent work groups (RenderOptions::persistentGroups, the default on NVIDIA with the patch:
# group g draws tiles g, g + G, ...; no queue) against one group a tile: DVR and isosurfaces at 1080p,
# G automatic (SMs x warp slots: 8 448 on the H200), 4 224 and 2 112, alternating, two rounds; the
# images of `fccvdb render` against one group a tile's (pixels, tools/device/pngdiff.py, and the EXR's
# bytes); test_render_dvr on NVIDIA (persistent groups by default). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard build/bin/test_render_dvr ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session25_call1.sh        (SMALL=1: toy sizes)
set -u
HERE=$(pwd)
B=$(dirname "$(command -v fccvdb)")
[ "$B/fccvdb" -ef /work/main/build/bin/fccvdb ] || { mkdir -p /work/main/build/bin && ln -sf "$B/fccvdb" /work/main/build/bin/fccvdb; }
W=${W:-/tmp/m24}; source "$(dirname "$0")/bench_data.sh"
DIFF="python3 $HERE/tools/device/pngdiff.py"
for job in "engine.vdb" "ml.vdb --iso 0.5" "engine.vdb --mode dvr --tf inferno" "ml.vdb --mode dvr --tf viridis"; do
  FCCVDB_PERSISTENT_GROUPS=0 fccvdb render $job --res $RES -o grid.png --force --quiet
  FCCVDB_PERSISTENT_GROUPS=0 fccvdb render $job --res $RES -o grid.exr --force --quiet
  fccvdb render $job --res $RES -o p.png --force --quiet
  fccvdb render $job --res $RES -o p.exr --force --quiet
  echo "render $job: $($DIFF grid.png p.png | cut -c1-200); exr $(cmp -s grid.exr p.exr && echo same || echo DIFFERENT)"
done
for round in 1 2; do
  for g in 0 -1 4224 2112; do
    run() { fccvdb bench render "$@" "${D[@]}" --persistent-groups $g | fps; }
    echo "-- round $round groups $g: engine DVR $(run engine.vdb --mode dvr --tf inferno) ML DVR $(run ml.vdb --mode dvr --tf viridis) engine iso $(run engine.vdb) ML iso $(run ml.vdb --iso 0.5)"
  done
done
cd "$HERE"
"$B/test_render_dvr" 2>&1 | grep -E "^\[  (FAILED|PASSED) |Failure|Which is|changed" | grep -v "^\[  FAILED  \] [0-9]" | cut -c1-160 | head -20
true
