#!/usr/bin/env bash
# Session 30, second call: where a projected-tetrahedra frame goes (BCC ML 128^3, 1080p), by the
# diagnostic knob FCCVDB_TETRA_KNOB of commit ee6b9e2 (removed since; wrong images): flat (no
# integration in tetra.frag), half (an RGBA16F target), nosort (the first frame's order kept), noblend
# (no blending), against main, alternating. Run as call 1 (measure_session30_call1.sh).
source tools/device/prologue.sh
source "$HERE/tools/device/pt_data.sh"
for round in 1 2; do
  for knob in "" flat half nosort noblend; do
    echo "-- tetrahedra 1080p [$knob] round $round"
    FCCVDB_TETRA_KNOB="$knob" timeout 300 fccvdb bench render pt_bcc.vdb --mode dvr --tf viridis --dvr-method tetrahedra \
      --res 1920x1080 --variants skip+analytic --layout auto --frames $FR --warmup 3 --json | fps
  done
done
