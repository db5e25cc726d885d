#!/usr/bin/env bash
# Regenerates the figures of docs/figures.md (docs/img/*.png) with the commands shown there.
# Usage: scripts/make-doc-figures.sh [path/to/machdyn]   (default build/release/apps/machdyn/machdyn)
set -euo pipefail
cd "$(dirname "$0")/.."
machdyn=${1:-build/release/apps/machdyn/machdyn}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$machdyn" simulate examples/hoist-3mass.yaml --plot -o "$tmp/hoist" >/dev/null
"$machdyn" modes examples/hoist-3mass.yaml --plot -o "$tmp/hoist" >/dev/null
"$machdyn" gears examples/walking-drive-gears.yaml --plot -o "$tmp/gears" >/dev/null
"$machdyn" report examples/hoist-3mass.yaml -o "$tmp/report.html" >/dev/null
mkdir -p docs/img
cp "$tmp"/hoist/{link_loads,body_speeds,mode_shapes}.png "$tmp"/gears/{pitch_curves,ratio}.png docs/img/
if command -v chromium >/dev/null; then
  chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking \
    --disable-component-update --disable-sync --user-data-dir="$tmp/profile" --virtual-time-budget=5000 \
    --hide-scrollbars --window-size=1100,2750 --screenshot="$PWD/docs/img/report.png" "file://$tmp/report.html" 2>/dev/null
fi
ls -la docs/img
