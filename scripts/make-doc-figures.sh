#!/usr/bin/env bash
# Regenerates the figures of docs/figures.md (docs/img/*.png) with the commands shown there.
# Usage: scripts/make-doc-figures.sh [path/to/machdyn]   (default build/release/apps/machdyn/machdyn)
# The PNGs are scaled to 1200 px wide and reduced to a palette when ImageMagick and pngquant are
# installed (apt-get install imagemagick pngquant), which keeps docs/img near 1 MB.
set -euo pipefail
cd "$(dirname "$0")/.."
machdyn=${1:-build/release/apps/machdyn/machdyn}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$machdyn" simulate examples/hoist-3mass.yaml --plot -o "$tmp/hoist" >/dev/null
"$machdyn" modes examples/hoist-3mass.yaml --plot -o "$tmp/hoist" >/dev/null
"$machdyn" modes examples/chain-20.yaml --plot -o "$tmp/chain" >/dev/null
"$machdyn" modes examples/hoist-3mass.yaml --plot -o "$tmp/linear" --frf Msp --output c1.load --output c2.load \
  --campbell 0:1500 --order pole=2 --order mesh=5 >/dev/null
"$machdyn" gears examples/walking-drive-gears.yaml --plot -o "$tmp/gears" >/dev/null
"$machdyn" simulate examples/travel-start.yaml --plot -o "$tmp/travel" >/dev/null
"$machdyn" simulate examples/hoist-modes.yaml --case brake_I2_lifting --plot -o "$tmp/modes" >/dev/null
"$machdyn" simulate examples/chain-20.yaml --plot -o "$tmp/chain" >/dev/null
for k in 1 2 3; do
  "$machdyn" energy examples/rolling-wheel-$k.yaml --plot -o "$tmp/wheel-$k" >/dev/null
done
"$machdyn" energy examples/crank-slider.yaml --plot -o "$tmp/crank" >/dev/null
"$machdyn" report examples/travel-start.yaml --quiet -o "$tmp/report.html" >/dev/null
"$machdyn" report examples/hoist-modes.yaml --all-cases --quiet -o "$tmp/cases.html" >/dev/null
mkdir -p docs/img
# Only the images made here are replaced (the sweep figures of docs/sweeps.md are made by their own
# commands, the report screenshots only when chromium is installed).
cp "$tmp"/hoist/{link_loads,mode_shapes}.png "$tmp"/gears/{pitch_curves,ratio}.png docs/img/
cp "$tmp"/modes/brake_I2_lifting/link_loads.png docs/img/link_loads_brake_case.png
cp "$tmp"/chain/link_loads.png docs/img/link_loads_chain20.png
cp "$tmp"/travel/load_cyclogram.png docs/img/load_cyclogram.png
cp "$tmp"/travel/contacts.png docs/img/contacts.png
cp "$tmp"/chain/mode_shapes.png docs/img/mode_shapes_chain20.png
for k in 1 2 3; do cp "$tmp/wheel-$k/speed_distance.png" "docs/img/speed_distance_$k.png"; done
cp "$tmp"/crank/{speed_angle,inertia_moments}.png docs/img/
cp "$tmp"/linear/{bode_magnitude,campbell}.png docs/img/
shot() {  # shot HTML PNG HEIGHT: a screenshot of the top of a report
  chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking \
    --disable-component-update --disable-sync --user-data-dir="$tmp/profile-$(basename "$2")" --virtual-time-budget=8000 \
    --hide-scrollbars --window-size=1100,"$3" --screenshot="$PWD/$2" "file://$1" 2>/dev/null
}
made=(docs/img/{link_loads,mode_shapes,pitch_curves,ratio,link_loads_brake_case,link_loads_chain20,load_cyclogram}.png
      docs/img/{contacts,mode_shapes_chain20,speed_distance_1,speed_distance_2,speed_distance_3,speed_angle,inertia_moments}.png
      docs/img/{bode_magnitude,campbell}.png)
if command -v chromium >/dev/null; then
  shot "$tmp/report.html" docs/img/report.png 2600
  shot "$tmp/cases.html" docs/img/report_cases.png 1500
  made+=(docs/img/report.png docs/img/report_cases.png)
fi
if command -v convert >/dev/null && convert -version 2>/dev/null | grep -q ImageMagick; then
  for f in "${made[@]}"; do convert "$f" -resize '1200x>' -strip "$f"; done
fi
if command -v pngquant >/dev/null; then
  for f in "${made[@]}"; do pngquant --force --skip-if-larger --quality 70-95 --output "$f" "$f" || true; done
fi
ls -la docs/img
du -sh docs/img
# The duty figures of docs/duty.md (issue 30): the rope of the 32 t main hoist's worked example.
"$machdyn" duty examples/duty/hoist-32t.yaml examples/duty/hoist-32t.duty.yaml --plot -o "$tmp/duty" >/dev/null
cp "$tmp"/duty/duty_{exceedance,heatmap}_rope.png docs/img/
