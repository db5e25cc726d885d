#!/usr/bin/env bash
# Installs the Debian 12 packages machdyn builds with, when any is missing. Safe to run again.
set -euo pipefail
packages=(cmake ninja-build g++ make pkg-config
          libeigen3-dev libsundials-dev libyaml-cpp-dev libcli11-dev libfmt-dev nlohmann-json3-dev
          libgtest-dev libgmock-dev)
# MPI sweeps (`mpirun -np N machdyn sweep`) are optional: OpenMPI pulls in ~150 MB (gfortran, UCX,
# libfabric). Opt in with MACHDYN_WITH_MPI=1; without it the MPI test skips with a message.
if [ "${MACHDYN_WITH_MPI:-0}" = 1 ]; then
  packages+=(libopenmpi-dev openmpi-bin)
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
