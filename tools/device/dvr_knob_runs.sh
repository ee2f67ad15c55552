# Sourced by the measure scripts of sessions 27 and 28 after bench_data.sh: the loops they share over a
# DVR measurement knob, on the engine CT (inferno) and ML 160^3x4 FCC (viridis) at $RES in $W.
#
# dvr_reuse_images: the shaded EXRs with FCC_DVR_SHADE_REUSE 0 and 1 (removed after session 28), and
#   whether each pair is the same bytes.
# dvr_split_images SPLITS: the PNGs with FCCVDB_DVR_SPLIT="K,N" for each of SPLITS against main's
#   (pngdiff's first line).
# dvr_split_rounds SPLITS: two rounds of the bench's frame rates, main and then each of SPLITS.
dvr_reuse_images() {
  for v in 0 1; do
    FCCVDB_SHADER_DEFINES="FCC_DVR_SHADE_REUSE=$v" fccvdb render engine.vdb --mode dvr --tf inferno --shading on --res $RES -o "$W/engine_shaded_$v.exr" --force --quiet
    FCCVDB_SHADER_DEFINES="FCC_DVR_SHADE_REUSE=$v" fccvdb render ml.vdb --mode dvr --tf viridis --shading on --res $RES -o "$W/ml_shaded_$v.exr" --force --quiet
  done
  cmp "$W/engine_shaded_0.exr" "$W/engine_shaded_1.exr" && echo "engine shaded EXR: the same bytes"
  cmp "$W/ml_shaded_0.exr" "$W/ml_shaded_1.exr" && echo "ML shaded EXR: the same bytes"
}

dvr_split_images() {
  fccvdb render engine.vdb --mode dvr --tf inferno --res $RES -o "$W/engine_main.png" --force --quiet
  fccvdb render ml.vdb --mode dvr --tf viridis --res $RES -o "$W/ml_main.png" --force --quiet
  for s in $1; do
    FCCVDB_DVR_SPLIT=$s fccvdb render engine.vdb --mode dvr --tf inferno --res $RES -o "$W/engine_split.png" --force --quiet
    FCCVDB_DVR_SPLIT=$s fccvdb render ml.vdb --mode dvr --tf viridis --res $RES -o "$W/ml_split.png" --force --quiet
    echo "split $s engine: $(python3 "$HERE/tools/device/pngdiff.py" "$W/engine_main.png" "$W/engine_split.png" | head -1 | cut -c1-120)"
    echo "split $s ML: $(python3 "$HERE/tools/device/pngdiff.py" "$W/ml_main.png" "$W/ml_split.png" | head -1 | cut -c1-120)"
  done
}

dvr_split_rounds() {
  for round in 1 2; do
    for s in main $1; do
      if [ $s = main ]; then run() { fccvdb bench render "$@" "${D[@]}" | fps; }
      else run() { FCCVDB_DVR_SPLIT=$s fccvdb bench render "$@" "${D[@]}" | fps; }; fi
      echo "-- round $round [split $s]: engine DVR inferno $(run engine.vdb --mode dvr --tf inferno) ML DVR viridis $(run ml.vdb --mode dvr --tf viridis)"
    done
  done
}
