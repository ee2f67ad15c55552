#!/usr/bin/env bash
# Session 20, second call: where the DVR frame's limit lies. (1) The raycaster's program binary as
# NVIDIA's driver gives it (FCCVDB_DUMP_PROGRAMS), searched for an embedded ELF (a cubin, whose
# resource usage cuobjdump prints) and brought back in $OUT. (2) Occupancy: FCC_OCCUPANCY_PAD floats
# of shared memory a work group holds (14, 28, 48 KiB: at most 16, 8, 4 groups an SM; 48 KiB is what NVIDIA's GL lets a group hold), ML
# 160^3x4 FCC viridis and the engine CT inferno at 1080p. Run as
#   ../shared/tools/device-bundle build/bin/fccvdb build/bin/fccvdb-guard ../shared/data/engine_256x256x128_uint8.raw.gz
#   source .devbundle/env.sh && bash tools/device/measure_session20_call2.sh        (SMALL=1: toy sizes)
set -u
OUTDIR=${OUT:-/tmp/out20}; mkdir -p "$OUTDIR/dump"
W=${W:-/tmp/m20}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; ML=40; FR=5; else RES=1920x1080; ML=320; FR=300; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
echo "-- program binaries"
FCCVDB_DUMP_PROGRAMS="$OUTDIR/dump" fccvdb render engine.vdb "$OUTDIR/e.exr" --mode dvr --tf inferno --res 64x64 --force --quiet
ls -la "$OUTDIR/dump"
for f in "$OUTDIR"/dump/*raycast*.bin; do
  python3 - "$f" <<'PY'
import sys, zlib
b = open(sys.argv[1], 'rb').read()
print(sys.argv[1], len(b), 'bytes; head', b[:16].hex())
i = b.find(b'\x7fELF')
print('ELF at', i)
if i >= 0:
    open(sys.argv[1] + '.elf', 'wb').write(b[i:])
for z in (b'\x78\x9c', b'\x78\xda', b'\x28\xb5\x2f\xfd'):
    print('magic', z.hex(), 'at', b.find(z))
PY
  [ -f "$f.elf" ] && { /usr/local/cuda/bin/cuobjdump --dump-resource-usage "$f.elf" 2>&1 | head -20; /usr/local/cuda/bin/nvdisasm --print-code "$f.elf" 2>&1 | head -5; }
done
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
both() {  # label, extra args...
  local label=$1; shift
  echo "-- $label ML FCC viridis"; fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" "$@" | fps
  [ -s engine.vdb ] && { echo "-- $label engine inferno"; fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" "$@" | fps; }
}
both "main"
for pad in 3584 7168 12288; do FCCVDB_SHADER_DEFINES="FCC_OCCUPANCY_PAD=$pad" both "pad $pad floats"; done
both "work group 8x8" --work-group 8x8
FCCVDB_SHADER_DEFINES="FCC_OCCUPANCY_PAD=7168" both "work group 8x8, pad 7168 floats" --work-group 8x8
both "main again"
nvidia-smi -q -d PERFORMANCE | sed -n '1,40p' | grep -vi "^$"
true
