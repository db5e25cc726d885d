#!/usr/bin/env bash
# Benchmark of issue 4 (not part of ctest): crank-slider, 100 revolutions.
#   bench/run-issue4.sh [BUILD_DIR]     (BUILD_DIR with libmachdyn.a, default build)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
OUT=$(mktemp -d)
g++ -std=c++20 -O2 -DNDEBUG -Iinclude -I/usr/include/eigen3 bench/crank_slider_bench.cpp "$BUILD/libmachdyn.a" \
    -lfmt -lyaml-cpp -lsundials_cvode -lsundials_nvecserial -o "$OUT/crank_slider_bench"
"$OUT/crank_slider_bench" examples/crank-slider.yaml
/usr/bin/python3 bench/crank_slider_scipy.py
rm -rf "$OUT"
