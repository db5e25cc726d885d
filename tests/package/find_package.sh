#!/usr/bin/env bash
# The installed CMake package works for an outside project: `cmake --install` into a scratch prefix,
# configure and build tests/package/external with find_package(machdyn), run it on the hoist and
# compare its link maxima with the installed CLI's summary.json (bit for bit).
# Usage: find_package.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 src=$2
work=$build/package-test/find_package
rm -rf "$work" && mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
test -f "$work/prefix/lib/cmake/machdyn/machdynConfig.cmake"
cmake -S "$src/tests/package/external" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build" -j 2 >/dev/null
model=$src/examples/hoist-3mass.yaml
"$work/prefix/bin/machdyn" simulate "$model" -o "$work/cli" --quiet >/dev/null
"$work/build/peaks" "$model" | /usr/bin/python3 "$src/tests/package/compare_peaks.py" "$work/cli/summary.json"
