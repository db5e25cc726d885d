#!/usr/bin/env bash
# Sweep throughput (runs/s): `machdyn sweep` on 1 and 2 threads and 2 MPI ranks, against a shell
# loop over `machdyn simulate --set ...` and against scipy doing the same runs.
# Usage: bash bench/run-sweep.sh [BUILD_DIR] [MODEL] [VARY1] [VARY2]
#   defaults: build/release, examples/travel-start.yaml (paper 001: gap and wheel slip, event-driven,
#   2 s at rtol 1e-10), adhesion.mu_k=0.09:0.13:40, P.value=6000:7000:25 (1000 runs).
#   The hoist of issue 7's first benchmark: bash bench/run-sweep.sh build examples/hoist-3mass.yaml \
#     c1.stiffness=1e4:5e4:40 I3.inertia=0.2:0.4:25
# Environment: REPEAT (default 3) repetitions of each measurement, the best is printed (the machine
# is shared: the best is the least disturbed); SCIPY_RUNS (default 10) runs done by scipy.
# scipy exists for these two sweeps (bench/scipy_travel_sweep.py, bench/scipy_sweep.py).
# Not a test: numbers depend on the machine. Results go into docs/benchmarks.md with this command.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-build/release}
model=${2:-$here/../examples/travel-start.yaml}
vary1=${3:-adhesion.mu_k=0.09:0.13:40}
vary2=${4:-P.value=6000:7000:25}
repeat=${REPEAT:-3}
scipy_runs=${SCIPY_RUNS:-10}
bin=$(cd "$build" && pwd)/apps/machdyn/machdyn
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

echo "== sweep throughput: $(basename "$model"), --vary $vary1 --vary $vary2 ($(nproc) cores, load average $(cut -d" " -f1-3 /proc/loadavg)), best of $repeat"
# Each measurement: the wall time of the best repetition, and the CPU time (user + sys, all
# processes) of that repetition: on a shared machine the CPU time per run is the steadier figure.
rate() { awk -v n="$1" -v w="$2" -v c="$3" 'BEGIN{printf "%6d runs %8.3f s %9.1f runs/s   CPU %7.3f s %8.1f runs/CPU-s\n", n, w, n/w, c, n/c}'; }
TIMEFORMAT='%R %U %S'
best_wall="" best_cpu=""
timed() {  # command...: runs it, keeps the best wall time and its CPU time
  local t
  t=$( { time "$@" >/dev/null 2>&1; } 2>&1 )
  set -- $t
  if [ -z "$best_wall" ] || awk -v a="$1" -v b="$best_wall" 'BEGIN{exit !(a<b)}'; then
    best_wall=$1; best_cpu=$(awk -v u="$2" -v s="$3" 'BEGIN{print u+s}')
  fi
}

# machdyn sweep: wall time of the whole command (process start, plan, runs, table).
sweep_j() {  # label, dir, jobs, launcher words...
  local label=$1 dir=$2 jobs=$3; shift 3
  local n inside="" r
  best_wall="" best_cpu=""
  for r in $(seq 1 "$repeat"); do
    rm -rf "${work:?}/$dir"
    timed sh -c '"$@" >"$0" 2>/dev/null' "$work/$dir.out" "$@" "$bin" sweep "$model" --vary "$vary1" --vary "$vary2" --jobs "$jobs" -o "$work/$dir"
    inside="$inside $(grep -o '[0-9.e+]* runs/s' "$work/$dir.out" | cut -d' ' -f1)"
  done
  n=$(($(wc -l <"$work/$dir/sweep.csv") - 1))
  printf "%-13s " "$label"; rate "$n" "$best_wall" "$best_cpu"
  echo "              (inside the sweep, runs/s of each repetition:$inside)"
}
sweep_j "sweep 1 thr" j1 1
sweep_j "sweep 2 thr" j2 2
cmp -s "$work/j1/sweep.csv" "$work/j2/sweep.csv" && echo "              tables of 1 and 2 threads identical"
if command -v mpirun >/dev/null 2>&1; then
  sweep_j "mpirun -np 2" mpi2 1 mpirun -np 2 --oversubscribe
  cmp -s "$work/j1/sweep.csv" "$work/mpi2/sweep.csv" && echo "              table of 2 ranks identical"
else
  echo "mpirun -np 2  skipped (apt-get install openmpi-bin libopenmpi-dev, rebuild)"
fi

# The same runs as a shell loop over `machdyn simulate` (a process, files and a table per run).
values() {  # SPEC a:b:n -> n values
  echo "$1" | awk -F: '{n=$3; for(k=0;k<n;k++) printf "%.17g\n", (n==1)?$1:$1+($2-$1)*k/(n-1)}'
}
f1=${vary1%%=*}; f2=${vary2%%=*}
loop() {
  local a b
  for a in $(values "${vary1#*=}"); do
    for b in $(values "${vary2#*=}"); do
      "$bin" simulate "$model" --set "$f1=$a" --set "$f2=$b" -o "$work/loop" >/dev/null
    done
  done
}
best_wall="" best_cpu=""
for r in $(seq 1 "$repeat"); do timed loop; done
n=$(( $(values "${vary1#*=}" | wc -l) * $(values "${vary2#*=}" | wc -l) ))
printf "%-13s " "shell loop"; rate "$n" "$best_wall" "$best_cpu"

split() { echo "${1#*=}" | tr ':' ' '; }
if [ "$(basename "$model")" = "travel-start.yaml" ] && [ "$f1" = adhesion.mu_k ] && [ "$f2" = P.value ]; then
  # shellcheck disable=SC2046
  /usr/bin/python3 "$here/scipy_travel_sweep.py" $(split "$vary1") $(split "$vary2") "$scipy_runs" 2>/dev/null ||
    echo "scipy         unavailable (apt-get install python3-scipy)"
elif [ "$(basename "$model")" = "hoist-3mass.yaml" ] && [ "$f1" = c1.stiffness ] && [ "$f2" = I3.inertia ]; then
  # shellcheck disable=SC2046
  /usr/bin/python3 "$here/scipy_sweep.py" $(split "$vary1") $(split "$vary2") "$scipy_runs" 2>/dev/null ||
    echo "scipy         unavailable (apt-get install python3-scipy)"
else
  echo "scipy         only for the travel start-up (adhesion.mu_k × P.value) and hoist (c1.stiffness × I3.inertia) sweeps"
fi
