#!/usr/bin/env bash
# Session 19, third call: is the FCC DVR frame bound by the latency of its memory reads? Two cells a
# round where the chain continues (FCC_DVR_PAIRS=1: two gathers read together); sub-steps two at a time
# (FCC_DVR_SUBSTEP_PAIRS=1: two table reads together). The chain (one
# gather a cell) ran no faster than two gathers (second call), as if a round's cost were its waits, not
# its work. Variants: no memory reads for the pieces (FCC_DVR_CHAIN_PROBE=3, wrong images); fixed 2 and
# 3 sub-steps a chord (no table reads for the rule); and the registers the programs use, from the
# driver's program binaries (FCCVDB_DUMP_PROGRAMS). ML 160^3x4 FCC viridis, engine CT inferno, 1080p.
# Run as measure_session19.sh.
set -u
W=${W:-/tmp/m19}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then RES=64x64; ML=40; FR=5; else RES=1920x1080; ML=320; FR=300; fi
[ -s ml.vdb ] || fccvdb synth marschner-lobb ml.vdb --dims $ML,$ML,$ML --force --quiet
ENGINE=$(cd "${FCC_DATA:-/nonexistent}" 2>/dev/null && pwd)/engine_256x256x128_uint8.raw.gz
[ -s engine.vdb ] || { [ -f "$ENGINE" ] && fccvdb convert "$ENGINE" engine.vdb --dims 256,256,128 --type u8 --force --quiet; }
D=(--variants skip+analytic --layout auto --res $RES --frames $FR --warmup 30 --json)
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
run() {  # label, defines
  echo "-- $1 ML FCC viridis"; FCCVDB_SHADER_DEFINES=$2 fccvdb bench render ml.vdb --mode dvr --tf viridis "${D[@]}" | fps
  [ -s engine.vdb ] && { echo "-- $1 engine inferno"; FCCVDB_SHADER_DEFINES=$2 fccvdb bench render engine.vdb --mode dvr --tf inferno "${D[@]}" | fps; }
}
echo "profilers: $(command -v ncu nsys nv-nsight-cu-cli 2>/dev/null | tr '\n' ' ')"
for v in "chain:" "two:FCC_DVR_CHAIN=0" "pairs:FCC_DVR_PAIRS=1" "iso:"; do
  name=${v%%:*}; defs=${v#*:}; mkdir -p "dump_$name"
  mode=dvr; [ "$name" = iso ] && mode=iso
  FCCVDB_DUMP_PROGRAMS=$PWD/dump_$name FCCVDB_SHADER_DEFINES=$defs fccvdb render engine.vdb --mode $mode --tf inferno \
    --res 64x64 -o "dump_$name/x.png" --force --quiet 2>&1 | tail -1
  echo "-- registers [$name]: $(strings dump_$name/*raycast* 2>/dev/null | grep -iE 'regs|registers|R-regs' | head -3 | tr '\n' ' ')"
done
run "[chain]" ""
run "[pairs]" "FCC_DVR_PAIRS=1"
run "[chain, no memory reads for pieces]" "FCC_DVR_CHAIN_PROBE=3"
run "[chain, no memory reads for pieces, 1 sub-step]" "FCC_DVR_CHAIN_PROBE=3;FCC_DVR_FIXED_STEPS=1"
run "[chain, 2 sub-steps a chord]" "FCC_DVR_FIXED_STEPS=2"
run "[chain, 3 sub-steps a chord]" "FCC_DVR_FIXED_STEPS=3"
run "[chain, 1 sub-step]" "FCC_DVR_FIXED_STEPS=1"
run "[pairs, 1 sub-step]" "FCC_DVR_PAIRS=1;FCC_DVR_FIXED_STEPS=1"
run "[two gathers]" "FCC_DVR_CHAIN=0"
run "[pairs again]" "FCC_DVR_PAIRS=1"
run "[chain, sub-steps two at a time]" "FCC_DVR_SUBSTEP_PAIRS=1"
run "[pairs, sub-steps two at a time]" "FCC_DVR_PAIRS=1;FCC_DVR_SUBSTEP_PAIRS=1"
true
