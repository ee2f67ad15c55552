# Sourced by the measure scripts of session 30 (projected tetrahedra) after prologue.sh: in $W
# (default /tmp/s30), session 15's BCC dataset pt_bcc.vdb (ML 128^3, made once), the resolutions RESES
# and frame count FR (SMALL=1: toy sizes, to try a script here), and fps (a bench's frame rate from its
# JSON, or its one error line).
W=${W:-/tmp/s30}; mkdir -p "$W"; cd "$W"
if [ "${SMALL:-0}" = 1 ]; then N=32; RESES="64x36"; FR=3; else N=128; RESES="1920x1080 512x512"; FR=20; fi
[ -s pt_bcc.vdb ] || fccvdb synth marschner-lobb pt_bcc.vdb --dims $N,$N,$N --lattice bcc --force --quiet
fps() { grep -oE '"fps": [0-9.e+]+|fccvdb:.*' | tr '\n' ' '; echo; }
