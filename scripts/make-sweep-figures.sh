#!/usr/bin/env bash
# The sweep figures of docs/sweeps.md (docs/img/sweep_*.png), made by exactly the commands shown there.
# Usage: bash scripts/make-sweep-figures.sh [BUILD_DIR]   (default build; needs gnuplot)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=$(cd "${1:-build}" && pwd)/apps/machdyn/machdyn
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$root"
"$bin" sweep examples/hoist-modes.yaml --all-cases --vary "MB.value=-330 N*m:-210 N*m:5" \
  --plot c1.peak_dynamic_factor -o "$work/modes" >/dev/null
cp "$work/modes/plot-c1.peak_dynamic_factor-vs-MB.value-vs-case.png" docs/img/sweep_hoist_modes.png
"$bin" sweep examples/travel-start.yaml --vary adhesion.mu_k=0.09:0.13:21 --vary P.value=6000:7000:11 \
  --plot adhesion.c_max_over_static_limit -o "$work/travel" >/dev/null
cp "$work/travel/plot-adhesion.c_max_over_static_limit-vs-adhesion.mu_k-vs-P.value.png" docs/img/sweep_travel_map.png
echo "wrote docs/img/sweep_hoist_modes.png docs/img/sweep_travel_map.png"
