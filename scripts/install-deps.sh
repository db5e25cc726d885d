#!/usr/bin/env bash
# Installs the Debian 12 packages machdyn builds with, when any is missing. Safe to run again.
#   gnuplot-nox, fonts-dejavu-core: the static figures of --plot (SVG, PNG)
#   nodejs, npm: CMake installs the report's charting library (uPlot, report/package-lock.json) with
#                `npm ci` at configure time; installed only when no npm is on PATH already
#   pybind11-dev, python3-dev: the Python module (python/, built for Debian's /usr/bin/python3);
#   python3-pytest, -numpy, -pandas, -matplotlib, -nbconvert, -ipykernel: its tests and the notebook
#   chromium:    the browser test of the HTML report; installed unless MACHDYN_WITH_CHROMIUM=0 (large;
#                without it that test is skipped, and says so)
#   clang-14, libclang-rt-14-dev: the sanitizer build and the libFuzzer harnesses of `make test`
#   libsuitesparse-dev: KLU, CVODE's sparse linear solver for large models
#   ccache:      keeps rebuilds of unchanged sources cheap (the Makefile uses it when present)
# `install-deps.sh demo` (make demo) installs only what the library and the CLI build and run with:
# the compilers, the libraries, gnuplot and npm (the CLI's --plot and report); no test, Python,
# sanitizer, MPI or browser packages.
set -euo pipefail
packages=(cmake ninja-build g++ make pkg-config ccache
          libeigen3-dev libsundials-dev libsuitesparse-dev libyaml-cpp-dev libcli11-dev libfmt-dev nlohmann-json3-dev
          gnuplot-nox fonts-dejavu-core)
command -v npm >/dev/null 2>&1 || packages+=(nodejs npm)
if [ "${1:-}" = demo ]; then
  MACHDYN_WITH_MPI=0 MACHDYN_WITH_CHROMIUM=0
else
  packages+=(libgtest-dev libgmock-dev clang-14 libclang-rt-14-dev
             pybind11-dev python3-dev python3-pytest python3-numpy python3-pandas python3-matplotlib
             python3-nbconvert python3-ipykernel)
fi
# MPI sweeps (`mpirun -np N machdyn sweep`): OpenMPI is installed unless MACHDYN_WITH_MPI=0 (it pulls
# in ~150 MB: gfortran, UCX, libfabric); without it the MPI test skips with a message.
if [ "${MACHDYN_WITH_MPI:-1}" = 1 ]; then
  packages+=(libopenmpi-dev openmpi-bin)
fi
# The report's browser test needs Chromium (large): installed by default, opt out with MACHDYN_WITH_CHROMIUM=0.
if [ "${MACHDYN_WITH_CHROMIUM:-1}" = 1 ] && ! command -v chromium >/dev/null 2>&1; then
  packages+=(chromium)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "machdyn: installing missing Debian packages: ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
