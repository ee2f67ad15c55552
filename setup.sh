#!/usr/bin/env bash
# fccvdb set-up: installs what is missing (Debian 12 packages; needs root or sudo), builds in Release,
# then runs the demo or the test suite.
#
#   ./setup.sh demo    install, build, convert a generated Cartesian volume to FCC, describe it and
#                      render its isosurface headless (PNG and EXR)
#   ./setup.sh test    install, build, run the whole test suite (ctest), then each fuzz target of the file
#                      readers for FCC_FUZZ_SECONDS seconds (default 45; 0 skips them; docs/RELIABILITY.md)
#   ./setup.sh build   install and build only
set -euo pipefail
cd "$(dirname "$0")"
mode=${1:-demo}
case "$mode" in demo|test|build) ;; *) echo "setup.sh: unknown mode '$mode' (valid: demo, test, build)" >&2; exit 2 ;; esac

packages=(build-essential cmake pkg-config ccache python3
  libopenvdb-dev libboost-dev libboost-iostreams-dev libtbb-dev zlib1g-dev libblosc-dev
  pocl-opencl-icd ocl-icd-opencl-dev opencl-clhpp-headers
  libglfw3-dev libglm-dev libopenexr-dev libpng-dev libegl-dev libgl1-mesa-dri libegl-mesa0 libepoxy-dev libx11-dev libxrandr-dev
  libinsighttoolkit5-dev libgdcm-tools
  libopenmpi-dev openmpi-bin  # FCC_MPI: mpirun -np N fccvdb render (docs/MPI.md)
  libcli11-dev nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev libimgui-dev xvfb xauth
  clang libclang-rt-14-dev)  # the fuzz targets: clang, and its libFuzzer and sanitizer runtimes

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup.sh: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

build=${FCC_BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j2

case "$mode" in
  demo)
    out=${FCC_DEMO_DIR:-demo-output}
    mkdir -p "$out"
    python3 tools/make_demo_volume.py "$out/torus_64.raw" 64
    "$build/bin/fccvdb" convert "$out/torus_64.raw" "$out/torus_fcc.vdb" --dims 64,64,64 --type u8 --force --quiet
    "$build/bin/fccvdb" info "$out/torus_fcc.vdb"
    "$build/bin/fccvdb" render "$out/torus_fcc.vdb" -o "$out/torus.png" --res 512x512 --iso 128 --force
    "$build/bin/fccvdb" render "$out/torus_fcc.vdb" -o "$out/torus.exr" --res 512x512 --iso 128 --quiet --force
    echo "demo dataset: $(cd "$out" && pwd)/torus_fcc.vdb, images: $(cd "$out" && pwd)/torus.png, torus.exr"
    ;;
  test)
    ctest --test-dir "$build" --output-on-failure -j2
    # The readers' fuzz targets (tests/fuzz), each over a copy of its seed corpus: a crash, leak, hang,
    # sanitizer report or oversized allocation fails the run. A clang build of those few files only.
    fuzz_seconds=${FCC_FUZZ_SECONDS:-45}
    if [ "$fuzz_seconds" -gt 0 ]; then
      fuzz_build=${FCC_FUZZ_BUILD_DIR:-build-fuzz}
      CC=clang CXX=clang++ cmake -S . -B "$fuzz_build" -DFCC_FUZZ=ON -DFCC_BUILD_TESTS=OFF \
        -DFCC_BUILD_BENCHMARKS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
      cmake --build "$fuzz_build" -j2 --target fuzz_all
      tests/fuzz/run_fuzzers.sh "$fuzz_build" "$fuzz_seconds"
    fi
    ;;
esac
