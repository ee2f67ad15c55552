# Sourced first by the measure scripts (tools/device/measure_session27_call1.sh and later), run from the
# repository root on the device after `source .devbundle/env.sh`: HERE (the root), B (the folder of the
# bundle's binaries; build/bin/fccvdb made to point at its fccvdb, where the tests look for it), and
# the GPU's name and driver as the output's first line.
set -u
HERE=$(pwd)
B=$(dirname "$(command -v fccvdb)")
[ "$B/fccvdb" -ef /work/main/build/bin/fccvdb ] || { mkdir -p /work/main/build/bin && ln -sf "$B/fccvdb" /work/main/build/bin/fccvdb; }
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null
