#!/usr/bin/env bash
# Runs every benchmark side by side and prints the ratios. Usage: bash bench/run.sh [BUILD_DIR]
# (`make bench` builds Release first). Results go into docs/benchmarks.md by hand, with this command.
set -euo pipefail
build=${1:-build/release}
here=$(cd "$(dirname "$0")" && pwd)
echo "== machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
out=$("$build/bench/bench_hoist")
echo "$out"
py=$(/usr/bin/python3 "$here/scipy_hoist.py" 3 2>/dev/null || echo "hoist scipy    unavailable (apt-get install python3-scipy)")
echo "$py"
if command -v octave >/dev/null 2>&1; then
  oc=$(octave --no-gui --quiet "$here/octave_hoist.m" 2>/dev/null | grep hoist || true)
  echo "$oc"
else
  oc=""
  echo "hoist octave   not installed (ode45 skipped)"
fi
md=$(echo "$out" | awk '/hoist machdyn/{print $3}')
hand=$(echo "$out" | awk '/hoist hand/{print $3}')
sp=$(echo "$py" | awk '/hoist scipy/{print $3}')
echo "== ratios"
awk -v m="$md" -v h="$hand" 'BEGIN{printf "machdyn / hand-written loop: %.2f (goal <= 1.5)\n", m/h}'
[[ "$sp" =~ ^[0-9.]+$ ]] && awk -v m="$md" -v s="$sp" 'BEGIN{printf "scipy / machdyn:             %.0f (goal >= 50)\n", s/m}'
oct=$(echo "$oc" | awk '/hoist octave/{print $3}')
[[ "$oct" =~ ^[0-9.]+$ ]] && awk -v m="$md" -v s="$oct" 'BEGIN{printf "octave / machdyn:            %.0f\n", s/m}'
echo "== travel start-up (paper 001), 2 s: hybrid event-driven run against a hand-written event loop and scipy"
"$build/bench/bench_travel_start" "$here/../examples/travel-start.yaml" 30
/usr/bin/python3 "$here/travel_start_scipy.py" 2>/dev/null || echo "scipy unavailable"
/usr/bin/python3 "$here/travel_start_scipy.py" 1e-10 1e-12 2>/dev/null || true
for f in "$here"/run-*.sh; do [ -e "$f" ] && bash "$f" "$build"; done
exit 0
