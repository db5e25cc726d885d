#!/usr/bin/env bash
# The Python module against the C++ call, the CLI's sweep and scipy (bench/python_bench.py).
# Usage: bash bench/run-python.sh [BUILD_DIR]   (run by bench/run.sh with the others)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-build/release}" && pwd)
if [ ! -d "$build/python/machdyn" ]; then
  echo "python module not built (apt-get install pybind11-dev python3-dev, reconfigure)"
  exit 0
fi
PYTHONPATH="$build/python" /usr/bin/python3 "$here/python_bench.py" "$build" "${REPEATS:-300}"
