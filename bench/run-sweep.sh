#!/usr/bin/env bash
# Sweep throughput (runs/s): `machdyn sweep` on 1 and 2 threads and 2 MPI ranks, against a shell
# loop over `machdyn simulate --set ...` and against scipy doing the same runs.
# Usage: bash bench/run-sweep.sh [BUILD_DIR] [MODEL] [VARY1] [VARY2]
#   defaults: build/release, examples/travel-start.yaml (paper 001: gap and wheel slip, event-driven,
#   2 s at rtol 1e-10), adhesion.mu_k=0.09:0.13:10, P.value=6000:7000:10 (100 runs).
#   The hoist of issue 7's first benchmark: bash bench/run-sweep.sh build examples/hoist-3mass.yaml \
#     c1.stiffness=1e4:5e4:40 I3.inertia=0.2:0.4:25
# Environment: REPEAT (default 3) repetitions of each measurement, the best is printed (the machine
# is shared: the best is the least disturbed); SCIPY_RUNS (default 10) runs done by scipy.
# scipy exists for these two sweeps (bench/scipy_travel_sweep.py, bench/scipy_sweep.py).
# Not a test: numbers depend on the machine. Results go into docs/benchmarks-issue7.md with this command.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-build/release}
model=${2:-$here/../examples/travel-start.yaml}
vary1=${3:-adhesion.mu_k=0.09:0.13:10}
vary2=${4:-P.value=6000:7000:10}
repeat=${REPEAT:-3}
scipy_runs=${SCIPY_RUNS:-10}
bin=$(cd "$build" && pwd)/apps/machdyn/machdyn
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

echo "== sweep throughput: $(basename "$model"), --vary $vary1 --vary $vary2 ($(nproc) cores, load average $(cut -d" " -f1-3 /proc/loadavg)), best of $repeat"
rate() { awk -v n="$1" -v s="$2" 'BEGIN{printf "%6d runs %9.3f s %10.1f runs/s\n", n, s, n/s}'; }
now() { date +%s.%N; }
best=""
keep_best() { best=$(awk -v a="$1" -v b="${best:-1e300}" 'BEGIN{print (a<b)?a:b}'); }

# machdyn sweep: wall time of the whole command (process start, plan, runs, table).
sweep_j() {  # label, dir, jobs, launcher words...
  local label=$1 dir=$2 jobs=$3; shift 3
  local t0 t1 n inside="" r
  best=""
  for r in $(seq 1 "$repeat"); do
    rm -rf "$work/$dir"
    t0=$(now)
    "$@" "$bin" sweep "$model" --vary "$vary1" --vary "$vary2" --jobs "$jobs" -o "$work/$dir" >"$work/$dir.out" 2>/dev/null
    t1=$(now)
    keep_best "$(awk -v a="$t0" -v b="$t1" 'BEGIN{print b-a}')"
    inside="$inside $(grep -o '[0-9.e+]* runs/s' "$work/$dir.out" | cut -d' ' -f1)"
  done
  n=$(($(wc -l <"$work/$dir/sweep.csv") - 1))
  printf "%-13s " "$label"; rate "$n" "$best"
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
best=""
for r in $(seq 1 "$repeat"); do
  t0=$(now); n=0
  for a in $(values "${vary1#*=}"); do
    for b in $(values "${vary2#*=}"); do
      "$bin" simulate "$model" --set "$f1=$a" --set "$f2=$b" -o "$work/loop" >/dev/null
      n=$((n + 1))
    done
  done
  t1=$(now)
  keep_best "$(awk -v a="$t0" -v b="$t1" 'BEGIN{print b-a}')"
done
printf "%-13s " "shell loop"; rate "$n" "$best"

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
