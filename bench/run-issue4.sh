#!/usr/bin/env bash
# Benchmark of issue 4 (not part of ctest): crank-slider, 100 revolutions, against its hand-written
# loop and scipy.   bench/run-issue4.sh [BUILD_DIR]   (BUILD_DIR configured with -DMACHDYN_BENCH=ON;
# the target crank_slider_bench is built there, with the library's own link line).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build/release}
cmake --build "$BUILD" --target crank_slider_bench > /dev/null
"$BUILD/bench/crank_slider_bench" examples/crank-slider.yaml
/usr/bin/python3 bench/crank_slider_scipy.py
