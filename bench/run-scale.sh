#!/usr/bin/env bash
# Scale job (issue 15): `simulate` on a free chain of N masses (one body and one spring-damper
# each, a constant force on the first mass, dopri5, 0.2 s) for N = 1e3, 1e4, 1e5: wall time and
# peak memory (/usr/bin/time -v), so the growth in N shows. Usage: bash bench/run-scale.sh [BUILD_DIR] [N...]
# CONTACTS=1: the same chain with a brake on the last mass and a clutch in the middle (the quasi-static
# loads at every link's extremes with contacts: memory must stay linear in N).
set -euo pipefail
contacts=${CONTACTS:-0}
build=${1:-build/release}
shift || true
sizes=${*:-1000 10000 100000}
cli="$build/apps/machdyn/machdyn"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
if [ "$contacts" = 1 ]; then
  echo "== scale: chain of N masses with a brake and a clutch, simulate 0.2 s (dopri5), time and peak memory"
else
  echo "== scale: free chain of N masses, simulate 0.2 s (dopri5), time and peak memory"
fi
printf "%8s %10s %12s %10s\n" N wall_s peak_MB steps
for n in $sizes; do
  f="$dir/chain-$n.yaml"
  awk -v n="$n" -v contacts="$contacts" 'BEGIN {
    print "name: " (contacts == 1 ? "chain" : "free chain") " of " n " masses"; print "bodies:";
    for (i = 1; i <= n; i++) printf "  m%d: {type: translational, mass: 1 kg}\n", i;
    print "links:";
    for (i = 1; i < n; i++) printf "  c%d: {type: spring-damper, between: [m%d, m%d], stiffness: 1e4 N/m, damping: 1 N*s/m}\n", i, i, i + 1;
    if (contacts == 1) {
      print "contacts:";
      printf "  br: {between: [m%d, ground], static: 50 N, kinetic: 40 N}\n", n;
      printf "  cl: {between: [m%d, m%d], static: 80 N, kinetic: 60 N}\n", int(n / 2), int(n / 2) + 1 }
    print "loads:"; print "  P: {type: constant, body: m1, value: 100 N}";
    print "simulation: {t_end: 0.2 s, dt_out: 0.05 s, integrator: dopri5}" }' > "$f"
  if [ ! -x /usr/bin/time ]; then echo "/usr/bin/time missing (apt-get install time)"; exit 0; fi
  /usr/bin/time -v "$cli" simulate "$f" -o "$dir/out-$n" > "$dir/log-$n" 2> "$dir/time-$n" || { echo "N=$n failed"; tail -3 "$dir/time-$n"; continue; }
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/{n=split($2,a,":"); s=0; for(i=1;i<=n;i++) s=s*60+a[i]; print s}' "$dir/time-$n")
  mem=$(awk -F': ' '/Maximum resident set size/{printf "%.0f", $2/1024}' "$dir/time-$n")
  steps=$(awk '/integrator:/{for(i=1;i<=NF;i++) if ($(i+1) ~ /^steps/) print $i}' "$dir/log-$n" | head -1)
  printf "%8s %10s %12s %10s\n" "$n" "$wall" "$mem" "$steps"
done
