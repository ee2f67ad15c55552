#!/usr/bin/env bash
# Session 34, first call: where a DVR ray's SM cycles go, by phase (raycast.comp's FCC_DVR_CLOCK: the
# rounds' finds, the gather with its piece in Taylor form, the chord's rule and sub-steps, the rest),
# at 1080p from render's camera (the engine CT inferno, ML 160^3x4 FCC viridis), on main and beside
# knobs that take parts away (no memory reads for the pieces, one sub-step a chord, the SSBO pool);
# then the bench's frame rate with and without the clock's stamps (what they perturb). Run as
#   g++ -O2 -std=c++17 tools/device/dvr_clock_phases.cpp -I/usr/include/OpenEXR -I/usr/include/Imath -lOpenEXR-3_1 -lImath-3_1 -o /tmp/fcc_dvr_clock_phases
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard /tmp/fcc_dvr_clock_phases ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session34_call1.sh        (SMALL=1: toy sizes)
source tools/device/prologue.sh
W=${W:-/tmp/m34}; source "$HERE/tools/device/bench_data.sh"
phases() {  # FILE TF DEFINES [render flags...]
  local file=$1 tf=$2 defs=$3; shift 3
  FCCVDB_SHADER_DEFINES="$defs" fccvdb render "$file" clock.exr --mode dvr --tf "$tf" --res $RES --lookahead 64 \
    --force --quiet "$@" || { echo "render failed"; return; }
  fcc_dvr_clock_phases clock.exr 4 8 "${defs:14:1}"
}
echo "== engine inferno, main";                        phases engine.vdb inferno "FCC_DVR_CLOCK=1"
echo "== ML viridis, main";                            phases ml.vdb viridis "FCC_DVR_CLOCK=1"
echo "== engine inferno, main, the gather's wait apart";  phases engine.vdb inferno "FCC_DVR_CLOCK=2"
echo "== ML viridis, main, the gather's wait apart";      phases ml.vdb viridis "FCC_DVR_CLOCK=2"
echo "== engine inferno, ssbo-scalar, the gather's wait apart"; phases engine.vdb inferno "FCC_DVR_CLOCK=2" --layout ssbo-scalar
echo "== engine inferno, --layout ssbo-scalar";        phases engine.vdb inferno "FCC_DVR_CLOCK=1" --layout ssbo-scalar
echo "== engine inferno, no reads for the pieces (FCC_DVR_CHAIN_PROBE=3, wrong)"; phases engine.vdb inferno "FCC_DVR_CLOCK=1;FCC_DVR_CHAIN_PROBE=3"
echo "== engine inferno, one sub-step a chord (FCC_DVR_FIXED_STEPS=1, wrong)";    phases engine.vdb inferno "FCC_DVR_CLOCK=1;FCC_DVR_FIXED_STEPS=1"
for round in 1 2; do
  for defs in "" "FCC_DVR_CLOCK=1"; do
    run() { FCCVDB_SHADER_DEFINES="$defs" fccvdb bench render "$@" "${D[@]}" | fps; }
    echo "-- round $round [${defs:-main}]: engine DVR inferno $(run engine.vdb --mode dvr --tf inferno) ML DVR viridis $(run ml.vdb --mode dvr --tf viridis)"
  done
done
true
