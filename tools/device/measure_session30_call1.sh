#!/usr/bin/env bash
# Session 30, first call: paper 002's projected tetrahedra (issue 18's baseline) on the GPU, BCC ML
# 128^3 at 1080p and 512^2, session 15's dataset: main's draw (an instance of 12 vertices a
# tetrahedron, every face rasterized) against one draw of 12 vertices a tetrahedron and faces no ray
# enters dropped in tetra.vert (FCCVDB_TETRA_KNOB of commit a851151, removed since: instanced, nocull), alternating; the
# host's sort from `render --timings`; the ray integration of the same field beside it. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard
#   source .devbundle/env.sh && bash tools/device/measure_session30_call1.sh
source tools/device/prologue.sh
source "$HERE/tools/device/pt_data.sh"
for res in $RESES; do
  P=(--mode dvr --tf viridis --dvr-method tetrahedra --res $res)
  for round in 1 2; do
    for knob in "instanced,nocull" "" "instanced" "nocull"; do
      echo "-- tetrahedra $res [$knob] round $round"
      FCCVDB_TETRA_KNOB="$knob" timeout 300 fccvdb bench render pt_bcc.vdb "${P[@]}" --variants skip+analytic --layout auto --frames $FR --warmup 3 --json | fps
    done
  done
  for knob in "instanced,nocull" ""; do
    echo "-- render --timings $res [$knob]"
    FCCVDB_TETRA_KNOB="$knob" timeout 300 fccvdb render pt_bcc.vdb "${P[@]}" --timings -o pt_$res.exr --force 2>&1 | grep -E "timings|sort|fccvdb:"
  done
  echo "-- ray integration $res"
  timeout 300 fccvdb bench render pt_bcc.vdb --mode dvr --tf viridis --res $res --variants skip+analytic --layout auto --frames 100 --warmup 10 --json | fps
done
