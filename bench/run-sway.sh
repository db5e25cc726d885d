#!/usr/bin/env bash
# The swinging load's benchmarks (docs/benchmarks.md, "Swinging load"):
#  1. a 60 s trolley move with sway and the drive line on one core: examples/crane/trolley-sway-drive.yaml
#     (case unshaped, t_end 60 s), `machdyn simulate` pinned to CPU 0; the integration's wall time
#     (summary.json solver.wall_time_s) and the whole command's CPU time, best of REPEAT;
#  2. the sway sweep of bench/sway-sweep.yaml: 1000 moves as ONE sweep, rope length 8–16 m (10) ×
#     acceleration time 2–5 s (25) × shaper (none, zv, zvd, two-step), on all cores and on one;
#  3. scipy (bench/scipy_sway.py, the same equations written from docs/sway.md) on SCIPY_RUNS runs of
#     each shaper spread over the grid, and the sweep table's residual sway of the same runs
#     (`rope.residual_sway_rad`) beside scipy's.
# Usage: bash bench/run-sway.sh [BUILD_DIR]   (default build/release; REPEAT=3, SCIPY_RUNS=10)
# Not a test: the numbers depend on the machine and its load (printed). Results go into
# docs/benchmarks.md with this command.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-build/release}
repeat=${REPEAT:-3}
scipy_runs=${SCIPY_RUNS:-10}
bin=$(cd "$build" && pwd)/apps/machdyn/machdyn
model=$here/sway-sweep.yaml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
TIMEFORMAT='%R %U %S'
echo "== swinging load ($(nproc) cores, load average $(cut -d" " -f1-3 /proc/loadavg)), best of $repeat"

# 1. The 60 s move on one core.
best_int="" best_cpu="" all_int=""
for r in $(seq 1 "$repeat"); do
  t=$( { time taskset -c 0 "$bin" simulate "$here/../examples/crane/trolley-sway-drive.yaml" --case unshaped \
           --set simulation.t_end=60 -o "$work/m60" >/dev/null 2>&1; } 2>&1 )
  set -- $t
  cpu=$(awk -v u="$2" -v s="$3" 'BEGIN{print u+s}')
  int=$(/usr/bin/python3 -c "import json,sys; s=json.load(open(sys.argv[1])); print(s['solver']['wall_time_s'], s['solver']['steps'], len(s['events']))" \
        "$work/m60/unshaped/summary.json")
  set -- $int
  all_int="$all_int $(awk -v x="$1" 'BEGIN{printf "%.1f", 1e3*x}')"
  if [ -z "$best_int" ] || awk -v a="$1" -v b="$best_int" 'BEGIN{exit !(a<b)}'; then best_int=$1; steps=$2; events=$3; fi
  if [ -z "$best_cpu" ] || awk -v a="$cpu" -v b="$best_cpu" 'BEGIN{exit !(a<b)}'; then best_cpu=$cpu; fi
done
# The command's own cost (reading, compiling, writing the files) at t_end = 10 ms, to take off.
best_0=""
for r in $(seq 1 "$repeat"); do
  t=$( { time taskset -c 0 "$bin" simulate "$here/../examples/crane/trolley-sway-drive.yaml" --case unshaped \
           --set simulation.t_end=0.01 -o "$work/m0" >/dev/null 2>&1; } 2>&1 )
  set -- $t
  cpu=$(awk -v u="$2" -v s="$3" 'BEGIN{print u+s}')
  if [ -z "$best_0" ] || awk -v a="$cpu" -v b="$best_0" 'BEGIN{exit !(a<b)}'; then best_0=$cpu; fi
done
awk -v i="$best_int" -v c="$best_cpu" -v z="$best_0" -v s="$steps" -v e="$events" -v all="$all_int" 'BEGIN{
  printf "60 s move     %d steps, %d events listed; CPU of the command %.0f ms, of the same at t_end 10 ms %.0f ms: the 60 s %.0f ms\n", s, e, 1e3*c, 1e3*z, 1e3*(c-z)
  printf "              the integration'"'"'s wall time (solver.wall_time_s) %.1f ms (runs:%s ms)\n", 1e3*i, all}'

# 2. The sweep: the 1000 moves in one `machdyn sweep` (the shaper is a --vary: `shaper: none` is the
# unshaped move), on all cores and on one thread.
vary=(--vary rope.length=8:16:10 --vary travel.reference.signal.end=2:5:25
      --vary travel.reference.shaper=none,zv,zvd,two-step)
sweep() {  # jobs -> "wall cpu"
  local t
  rm -rf "${work:?}/sw"
  t=$( { time "$bin" sweep "$model" "${vary[@]}" --jobs "$1" -o "$work/sw" >/dev/null 2>&1; } 2>&1 )
  set -- $t
  echo "$1 $(awk -v u="$2" -v s="$3" 'BEGIN{print u+s}')"
}
for jobs in 0 1; do
  bw="" bc=""
  for r in $(seq 1 "$repeat"); do
    set -- $(sweep "$jobs")
    if [ -z "$bw" ] || awk -v a="$1" -v b="$bw" 'BEGIN{exit !(a<b)}'; then bw=$1; bc=$2; fi
  done
  n=$(( $(wc -l <"$work/sw/sweep.csv") - 1 ))
  ok=$(grep -c ',ok,$' "$work/sw/sweep.csv" || true)
  slips=$(awk -F, 'FNR==1{for(i=1;i<=NF;i++) if($i=="events_slip") k=i; next} $k!=0{n++} END{print n+0}' "$work/sw/sweep.csv")
  label="sweep all cores"; [ "$jobs" = 1 ] && label="sweep 1 thread "
  awk -v l="$label" -v n="$n" -v w="$bw" -v c="$bc" -v ok="$ok" -v sl="$slips" 'BEGIN{
    printf "%s %5d runs (%d ok, %d with a slip) %8.3f s %8.1f runs/s   CPU %7.3f s %8.1f runs/CPU-s\n", l, n, ok, sl, w, n/w, c, n/c}'
done
awk -F, 'FNR==1{for(i=1;i<=NF;i++){if($i=="rope.residual_sway_rad") k=i; if($i=="travel.reference.shaper") f=i}; next}
  {if(!($f in lo)||$k<lo[$f]) lo[$f]=$k; if(!($f in hi)||$k>hi[$f]) hi[$f]=$k}
  END{for(f in lo) printf "  residual sway from 14 s on, %-8s %.4g–%.4g rad (the table'"'"'s rope.residual_sway_rad)\n", f, lo[f], hi[f]}' \
  "$work/sw/sweep.csv"

# 3. scipy on a sample; the sweep table's residual sway of the same runs beside it (the row of that
# shaper whose rope.length and ramp end are scipy's point, to 1e-9: numpy's linspace and the grid may
# differ in the last bits).
/usr/bin/python3 "$here/scipy_sway.py" 8 16 10 2 5 25 "$scipy_runs" >"$work/scipy.txt"
head -1 "$work/scipy.txt"
grep '^run ' "$work/scipy.txt" | while read -r _ case len ta res; do
  awk -F, -v len="$len" -v ta="$ta" -v res="$res" -v case="$case" '
    FNR==1{for(i=1;i<=NF;i++){if($i=="rope.length")a=i; if($i=="travel.reference.signal.end")b=i;
                              if($i=="travel.reference.shaper")s=i; if($i=="rope.residual_sway_rad")k=i}; next}
    function d(x,y){return x>y?x-y:y-x}
    $s==case && d($a,len)<1e-9 && d($b,ta)<1e-9 {printf "  %-9s L %-6.4g T_a %-6.4g residual sway: machdyn %.9f  scipy %.9f rad  |diff| %.3g\n",
                                     case, len, ta, $k, res, d($k,res); found=1}
    END{if(!found) printf "  %s L %s T_a %s: no row of the sweep\n", case, len, ta}' "$work/sw/sweep.csv"
done | tee "$work/cmp.txt"
awk '/\|diff\|/{d=$NF+0; if(d>w)w=d} END{printf "largest |machdyn sweep − scipy| of the residual sway: %.3g rad\n", w}' "$work/cmp.txt"
