#!/usr/bin/env bash
# Linear analysis (issue 12): machdyn's modal analysis and frequency response against scipy on the
# same matrices (bench/bench_linear.cpp writes them, bench/linear_scipy.py reads them).
# Usage: bash bench/run-linear.sh [BUILD_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-build/release}" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/bench/bench_linear" "$work" "${REPEATS:-5}"
if /usr/bin/python3 -c "import scipy" 2>/dev/null; then
  /usr/bin/python3 "$here/linear_scipy.py" "$work" "${REPEATS:-5}"
else
  echo "scipy not installed (apt-get install python3-scipy): no side-by-side"
fi
