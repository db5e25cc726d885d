#!/usr/bin/env bash
# Siconos on the travel start-up of issue 3 (paper 001), beside machdyn's event-driven run.
#   bash bench/run-siconos.sh [BUILD_DIR]      (default build/release; bench/run.sh calls it)
# Skipped with one line when Debian's python3 cannot import siconos (apt-get install python3-siconos).
# Not a test: the times depend on the machine. Results go into docs/benchmarks.md.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-build/release}
model=$here/../examples/travel-start.yaml
if ! /usr/bin/python3 -c "import siconos.kernel" >/dev/null 2>&1; then
  echo "travel siconos skipped: python3 cannot import siconos.kernel (apt-get install python3-siconos)"
  exit 0
fi
echo "== travel start-up, Siconos $(dpkg-query -W -f='${Version}' python3-siconos 2>/dev/null || echo '?')" \
     "($(nproc) cores, load average $(cut -d" " -f1-3 /proc/loadavg))"
args=(--model "$model" --h 1e-3 1e-4 1e-5)
bin=$build/apps/machdyn/machdyn
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [ -x "$bin" ] && "$bin" simulate "$model" --json -o "$tmp" >/dev/null 2>&1; then
  args+=(--machdyn "$bin")
else
  echo "(no machdyn comparison: $bin missing or too old for $(basename "$model"))"
fi
/usr/bin/python3 "$here/siconos_travel_start.py" "${args[@]}"
