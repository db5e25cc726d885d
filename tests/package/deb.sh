#!/usr/bin/env bash
# The Debian package (CPack): builds it, checks its declared dependencies, unpacks it into a scratch
# root with `dpkg -x` and runs the installed CLI and the installed Python module on the hoist.
# Usage: deb.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 src=$2
work=$build/package-test/deb
rm -rf "$work" && mkdir -p "$work"
cpack --config "$build/CPackConfig.cmake" -B "$work/cpack" >/dev/null
deb=$(ls "$work"/cpack/machdyn_*.deb)
depends=$(dpkg-deb -f "$deb" Depends)
echo "Depends: $depends"
for d in libyaml-cpp libsundials-cvode python3-numpy libstdc++6; do
  grep -q "$d" <<<"$depends" || { echo "missing dependency $d"; exit 1; }
done
dpkg -x "$deb" "$work/root"
for f in usr/bin/machdyn usr/include/machdyn/analysis/simulate.hpp usr/lib/libmachdyn.a \
         usr/lib/cmake/machdyn/machdynConfig.cmake usr/lib/python3/dist-packages/machdyn/__init__.py; do
  test -e "$work/root/$f" || { echo "missing $f"; exit 1; }
done
"$work/root/usr/bin/machdyn" simulate "$src/examples/hoist-3mass.yaml" -o "$work/out" --quiet >/dev/null
PYTHONPATH="$work/root/usr/lib/python3/dist-packages" /usr/bin/python3 - "$work/out/summary.json" "$src" <<'PY'
import json, sys
import machdyn
assert "dist-packages" in machdyn.__file__, machdyn.__file__
cli = json.load(open(sys.argv[1]))
r = machdyn.simulate(machdyn.load(sys.argv[2] + "/examples/hoist-3mass.yaml"))
for name, s in cli["links"].items():
    assert r.summary["links"][name]["max"] == s["max"], name
print("installed CLI and Python module agree on", len(cli["links"]), "link maxima")
PY
