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
for d in libyaml-cpp libsundials-cvode libstdc++6 python3-numpy; do
  grep -q "$d" <<<"$depends" || { echo "missing dependency $d"; exit 1; }
done
dpkg -x "$deb" "$work/root"
with_python=0
[ -f "$build/python/machdyn/__init__.py" ] && with_python=1  # MACHDYN_PYTHON=OFF or no pybind11: no module
files=(usr/bin/machdyn usr/include/machdyn/analysis/simulate.hpp usr/lib/libmachdyn.a usr/lib/cmake/machdyn/machdynConfig.cmake
       usr/share/doc/machdyn/README.md usr/share/doc/machdyn/model-files.md usr/share/doc/machdyn/crane-factors.md)
[ $with_python = 1 ] && files+=(usr/lib/python3/dist-packages/machdyn/__init__.py)
for f in "${files[@]}"; do
  test -e "$work/root/$f" || { echo "missing $f"; exit 1; }
done
"$work/root/usr/bin/machdyn" simulate "$src/examples/hoist-3mass.yaml" -o "$work/out" --quiet >/dev/null
test -s "$work/out/summary.json"
# The installed CLI finds its installed examples, not the source tree it was built from.
# (The listing is read whole: `| head -n 1` would close the pipe under a long list, and pipefail
# would count the CLI's SIGPIPE as a failure.) Its sub-folders are listed too.
listing=$("$work/root/usr/bin/machdyn" examples)
head -n 1 <<<"$listing" | grep -qF "$work/root/usr/share/machdyn/examples" ||
  { echo "installed CLI does not list its installed examples:"; head -n 1 <<<"$listing"; exit 1; }
grep -qF "crane/main-hoist.yaml" <<<"$listing" || { echo "the installed examples list lacks crane/"; exit 1; }
(cd "$work" && "$work/root/usr/bin/machdyn" demo -o "$work/demo" >/dev/null) && test -s "$work/demo/summary.json"
[ $with_python = 1 ] || { echo "no Python module in this build: CLI checked only"; exit 0; }
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
