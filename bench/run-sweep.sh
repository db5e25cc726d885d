#!/usr/bin/env bash
# Sweep throughput (runs/s): `machdyn sweep` on 1 and 2 threads and 2 MPI ranks, against a shell
# loop over `machdyn simulate --set ...` and against scipy doing the same runs.
# Usage: bash bench/run-sweep.sh [BUILD_DIR] [MODEL] [VARY1] [VARY2]
#   defaults: build/release, examples/hoist-3mass.yaml, c1.stiffness=1e4:5e4:40, I3.inertia=0.2:0.4:25
# The model and the two varied fields are parameters (e.g. the travel start-up example); the scipy
# comparison exists only for the hoist (its right-hand side is written out in bench/scipy_sweep.py).
# Not a test: numbers depend on the machine. Results go into docs/benchmarks.md with this command.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-build/release}
model=${2:-$here/../examples/hoist-3mass.yaml}
vary1=${3:-c1.stiffness=1e4:5e4:40}
vary2=${4:-I3.inertia=0.2:0.4:25}
bin=$(cd "$build" && pwd)/apps/machdyn/machdyn
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

echo "== sweep throughput: $(basename "$model"), --vary $vary1 --vary $vary2 ($(nproc) cores, load average $(cut -d" " -f1-3 /proc/loadavg))"
rate() { awk -v n="$1" -v a="$2" -v b="$3" 'BEGIN{printf "%6d runs %9.3f s %10.1f runs/s\n", n, b-a, n/(b-a)}'; }
now() { date +%s.%N; }

# machdyn sweep: wall time of the whole command (process start, plan, runs, table).
sweep_j() {  # label, dir, jobs, launcher words...
  local label=$1 dir=$2 jobs=$3; shift 3
  local t0 t1 n
  t0=$(now)
  "$@" "$bin" sweep "$model" --vary "$vary1" --vary "$vary2" --jobs "$jobs" -o "$work/$dir" >"$work/$dir.out" 2>/dev/null
  t1=$(now)
  n=$(($(wc -l <"$work/$dir/sweep.csv") - 1))
  printf "%-13s " "$label"; rate "$n" "$t0" "$t1"
  echo "              (inside the sweep: $(grep -o '[0-9.e+]* runs/s' "$work/$dir.out"))"
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
t0=$(now); n=0
for a in $(values "${vary1#*=}"); do
  for b in $(values "${vary2#*=}"); do
    "$bin" simulate "$model" --set "$f1=$a" --set "$f2=$b" -o "$work/loop" >/dev/null
    n=$((n + 1))
  done
done
t1=$(now)
printf "%-13s " "shell loop"; rate "$n" "$t0" "$t1"

if [ "$(basename "$model")" = "hoist-3mass.yaml" ] && [ "$vary1" = "c1.stiffness=1e4:5e4:40" ] &&
   [ "$vary2" = "I3.inertia=0.2:0.4:25" ]; then
  /usr/bin/python3 "$here/scipy_sweep.py" 1e4 5e4 40 0.2 0.4 25 50 2>/dev/null ||
    echo "scipy         unavailable (apt-get install python3-scipy)"
else
  echo "scipy         only for the default hoist sweep"
fi
