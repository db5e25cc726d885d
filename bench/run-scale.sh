#!/usr/bin/env bash
# Scale job (issue 15): `simulate` on a free chain of N masses (one body and one spring-damper
# each, a constant force on the first mass, dopri5, 0.2 s) for N = 1e3, 1e4, 1e5: wall time and
# peak memory (/usr/bin/time -v), so the growth in N shows. Usage: bash bench/run-scale.sh [BUILD_DIR] [N...]
set -euo pipefail
build=${1:-build/release}
shift || true
sizes=${*:-1000 10000 100000}
cli="$build/apps/machdyn/machdyn"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
echo "== scale: free chain of N masses, simulate 0.2 s (dopri5), time and peak memory"
printf "%8s %10s %12s %10s\n" N wall_s peak_MB steps
for n in $sizes; do
  f="$dir/chain-$n.yaml"
  awk -v n="$n" 'BEGIN {
    print "name: free chain of " n " masses"; print "bodies:";
    for (i = 1; i <= n; i++) printf "  m%d: {type: translational, mass: 1 kg}\n", i;
    print "links:";
    for (i = 1; i < n; i++) printf "  c%d: {type: spring-damper, between: [m%d, m%d], stiffness: 1e4 N/m, damping: 1 N*s/m}\n", i, i, i + 1;
    print "loads:"; print "  P: {type: constant, body: m1, value: 100 N}";
    print "simulation: {t_end: 0.2 s, dt_out: 0.05 s, integrator: dopri5}" }' > "$f"
  if [ ! -x /usr/bin/time ]; then echo "/usr/bin/time missing (apt-get install time)"; exit 0; fi
  /usr/bin/time -v "$cli" simulate "$f" -o "$dir/out-$n" > "$dir/log-$n" 2> "$dir/time-$n" || { echo "N=$n failed"; tail -3 "$dir/time-$n"; continue; }
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/{n=split($2,a,":"); s=0; for(i=1;i<=n;i++) s=s*60+a[i]; print s}' "$dir/time-$n")
  mem=$(awk -F': ' '/Maximum resident set size/{printf "%.0f", $2/1024}' "$dir/time-$n")
  steps=$(awk '/integrator:/{for(i=1;i<=NF;i++) if ($(i+1) ~ /^steps/) print $i}' "$dir/log-$n" | head -1)
  printf "%8s %10s %12s %10s\n" "$n" "$wall" "$mem" "$steps"
done
