#!/usr/bin/env bash
# The travel start-up's ratio to the hand-written loop over code and stack placements (issue 15).
# One binary measures a few percent faster or slower by where its code and its stack happen to lie
# (docs/benchmarks.md, "Travel start-up"), so one run of bench_travel_start says little
# about a change of 2 %. This relinks bench_travel_start's object with padding objects of 0 … 3080
# bytes before the library (the library's code shifts) and runs each from paths of different length
# (the stack shifts), passes times, interleaved; it prints the median, the quartiles and the range
# of the ratio and of both times. Usage: bash bench/run-placements.sh [BUILD_DIR] [PASSES] [REPEATS]
# (BUILD_DIR configured with -DMACHDYN_BENCH=ON and bench_travel_start built).
set -euo pipefail
build=${1:-build/bench}
passes=${2:-2}
repeats=${3:-60}
here=$(cd "$(dirname "$0")" && pwd)
model="$here/../examples/travel-start.yaml"
obj="$build/bench/CMakeFiles/bench_travel_start.dir/bench_travel_start.cpp.o"
[ -f "$obj" ] || { echo "run-placements: $obj not found (build bench_travel_start in $build first)" >&2; exit 2; }
# The link line CMake uses for the bench, from its build file.
libs=$(awk '/^build bench\/bench_travel_start:/ {f = 1} f && /LINK_LIBRARIES =/ {sub(/.*LINK_LIBRARIES = /, ""); print; exit}' "$build/build.ninja")
[ -n "$libs" ] || { echo "run-placements: no link line for bench_travel_start in $build/build.ninja" >&2; exit 2; }
libs=${libs//libmachdyn.a/$build/libmachdyn.a}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
pads="0 8 24 40 72 136 264 520 1032 2056 3080"
for p in $pads; do
  printf 'void machdyn_bench_pad_%d(void) { __asm__ volatile(".skip %d, 0x90"); }\n' "$p" "$p" > "$dir/pad$p.c"
  cc -O2 -c "$dir/pad$p.c" -o "$dir/pad$p.o" 2> /dev/null
  # shellcheck disable=SC2086  # the link line is a list of words
  c++ -O3 "$obj" "$dir/pad$p.o" -o "$dir/b$p" $libs
done
echo "== travel start-up over placements: ${passes} pass(es) × 11 code layouts × 4 stack placements, ${repeats} repeats each"
out="$dir/times"
for _ in $(seq "$passes"); do
  for p in $pads; do
    for len in 1 5 9 13; do  # the path's length moves the initial stack
      link="$dir/$(printf 'x%.0s' $(seq "$len"))"
      ln -sf "$dir/b$p" "$link"
      "$link" "$model" "$repeats" | awk '/^machdyn simulate/ {m = $4} /^hand-written/ {h = $5} END {print m, h}' >> "$out"
    done
  done
done
python3 - "$out" << 'EOF'
import statistics as s, sys
d = [tuple(map(float, l.split())) for l in open(sys.argv[1]) if l.strip()]
def line(name, v):
    v = sorted(v); q = s.quantiles(v, n=4)
    return f"{name:<16} median {s.median(v):.3f}  quartiles {q[0]:.3f}–{q[2]:.3f}  range {v[0]:.3f}–{v[-1]:.3f}"
print(line("machdyn ms", [a for a, b in d]))
print(line("hand ms", [b for a, b in d]))
print(line("ratio", [a / b for a, b in d]) + f"  ({len(d)} runs)")
EOF
