#!/usr/bin/env bash
# Session 20, third call: the warps an SM holds at once (FCC_WARP_PROBE: each pixel's warp slot,
# GL_NV_shader_thread_group), DVR and the isosurface at 960x540 (work group 4x8: at most 32 groups an
# SM), images in $OUT for tools' reading (the largest slot + 1 = the occupancy). Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session20_call3.sh
set -u
OUTDIR=${OUT:-/tmp/out20}; mkdir -p "$OUTDIR"
W=${W:-/tmp/m20}; mkdir -p "$W"; cd "$W"
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims 320,320,320 --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet
probe() {  # name, defines, file, args...
  local name=$1 defs=$2 file=$3; shift 3
  echo "-- $name ($defs)"
  FCCVDB_SHADER_DEFINES="FCC_WARP_PROBE=1${defs:+;$defs}" fccvdb render "$file" "$OUTDIR/$name.exr" --res 960x540 --force --quiet "$@"
}
probe engine_dvr "" engine.vdb --mode dvr --tf inferno
probe ml_dvr "" ml.vdb --mode dvr --tf viridis
probe engine_dvr_pad3584 "FCC_OCCUPANCY_PAD=3584" engine.vdb --mode dvr --tf inferno
probe engine_dvr_twogathers "FCC_DVR_CHAIN=0" engine.vdb --mode dvr --tf inferno
probe engine_dvr_walkonly "FCC_DVR_WALK_ONLY=1" engine.vdb --mode dvr --tf inferno
probe engine_dvr_onestep "FCC_DVR_FIXED_STEPS=1" engine.vdb --mode dvr --tf inferno
probe engine_dvr_nobend "FCC_DVR_BEND_TERM=0" engine.vdb --mode dvr --tf inferno
probe engine_iso "" engine.vdb
probe ml_iso "" ml.vdb --iso 0.5
ls -la "$OUTDIR"
true
