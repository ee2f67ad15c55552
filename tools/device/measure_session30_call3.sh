#!/usr/bin/env bash
# Session 30, third call: the final build's projected tetrahedra (faces dropped in tetra.vert, the keys
# sorted by Boost's block_indirect_sort), BCC ML 128^3 as the first call, beside the ray integration
# of the same field. Run as the first call (measure_session30_call1.sh).
source tools/device/prologue.sh
source "$HERE/tools/device/pt_data.sh"
for res in $RESES; do
  P=(--mode dvr --tf viridis --res $res --variants skip+analytic --layout auto)
  for round in 1 2; do
    echo "-- tetrahedra $res round $round"; timeout 300 fccvdb bench render pt_bcc.vdb "${P[@]}" --dvr-method tetrahedra --frames $FR --warmup 3 --json | fps
    echo "-- ray $res round $round"; timeout 300 fccvdb bench render pt_bcc.vdb "${P[@]}" --frames 100 --warmup 10 --json | fps
  done
  timeout 300 fccvdb render pt_bcc.vdb --mode dvr --tf viridis --dvr-method tetrahedra --res $res --timings -o pt_$res.exr --force 2>&1 | grep -E "timings|sort|fccvdb:"
done
