# Sourced by the measure scripts (tools/device/measure_session22_call*.sh and later) after they set W:
# in the working folder $W, the two DVR datasets of issue 18 (ML 160^3x4 FCC as ml.vdb, the engine CT
# from $FCC_DATA as engine.vdb, each made once), the sizes (SMALL=1: toy sizes, to try a script here),
# the bench's common flags D and fps (a bench's frame rate from its JSON, or its one error line).
mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; ML=40; FR=5; else RES=1920x1080; ML=320; FR=200; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 20 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
