#!/usr/bin/env bash
# Bonded rock against YADE JCFpm on an identical specimen (issue 20): the same grains, the
# same bonds at cementing, the same strengths, the same unconfined compression (platen
# strain per step, timestep, number of steps), timed on 1 and 2 threads, both stress-strain
# curves to CSV and one chart. Documentation/Benchmarks-Solver.md, "Bonded rock against
# YADE JCFpm", gives the recipe, the mapping of the two bond laws and what cannot be matched.
#
#   scripts/benchmark_yade_jcfpm.sh [--particles 2000] [--steps 8000] [--strain-per-step 5e-7]
#        [--repeat 1] [--threads "1 2"] [--range 1.4] [--modulus 1e10] [--tensile 1e6]
#        [--cohesion 4e6] [--friction-angle 30] [--damping 0.7] [--contact-law Hertz-Mindlin]
#        [--chart FILE.png]
#        [--keep DIR] [--specimen FILE.csv]
#
# 1. Specimen (RockDEM, pvpython): DEM Pack Source + Compact Elements, --particles grains
#    of 1-2 mm (scripts/yade_rockdem.py specimen), written as x,y,z,Radius; --specimen
#    uses a file written before.
# 2. Probe (RockDEM): cement it and read the timestep RockDEM would take at Timestep Safety
#    0.3; 0.9 x that (3 digits) is the timestep of both codes.
# 3. For each thread count, --repeat runs of each code, the median printed:
#    RockDEM: CSV Reader -> Table To Points -> DEM Model From Points -> DEM Cement -> DEM Load
#    Test (Compression), Threads T, OMP_WAIT_POLICY as set (scripts/yade_rockdem.py run);
#    YADE: yade -jT -n -x scripts/yade_jcfpm.py (JCFpm).
# 4. The two stress-strain curves (first run of each code at the first thread count):
#    DIR/rockdem_curve.csv, DIR/yade_curve.csv, and the chart (scripts/yade_plot.py).
#
# YADE is a peer measured against, not a dependency (scripts/install-deps.sh does not
# install it): without `yade` on PATH this script says so and exits 0 without running.
# Environment: ROCKDEM_PLUGIN (default build/lib/paraview-plugins/RockDEM/RockDEM.so),
# PVPYTHON (default pvpython), YADE (default yade). The load average is printed before
# and after: on a shared machine the times are not comparable with idle-machine figures.
set -euo pipefail

PARTICLES=2000
STEPS=8000
SPS=5e-7
REPEAT=1
THREADS="1 2"
RANGE=1.4
MODULUS=1e10
TENSILE=1e6
COHESION=4e6
FRICTION_ANGLE=30
DAMPING=0.7
CONTACT_LAW=Hertz-Mindlin
CHART=""
KEEP=""
SPECIMEN=""
while [ $# -gt 0 ]; do
  case "$1" in
    --particles) PARTICLES="$2"; shift 2 ;;
    --steps) STEPS="$2"; shift 2 ;;
    --strain-per-step) SPS="$2"; shift 2 ;;
    --repeat) REPEAT="$2"; shift 2 ;;
    --threads) THREADS="$2"; shift 2 ;;
    --range) RANGE="$2"; shift 2 ;;
    --modulus) MODULUS="$2"; shift 2 ;;
    --tensile) TENSILE="$2"; shift 2 ;;
    --cohesion) COHESION="$2"; shift 2 ;;
    --friction-angle) FRICTION_ANGLE="$2"; shift 2 ;;
    --damping) DAMPING="$2"; shift 2 ;;
    --contact-law) CONTACT_LAW="$2"; shift 2 ;;
    --chart) CHART="$2"; shift 2 ;;
    --keep) KEEP="$2"; shift 2 ;;
    --specimen) SPECIMEN="$2"; shift 2 ;;
    -h|--help) sed -n '2,31p' "$0"; exit 0 ;;
    *) echo "unknown argument: $1" >&2; exit 2 ;;
  esac
done

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export ROCKDEM_PLUGIN="${ROCKDEM_PLUGIN:-$ROOT/build/lib/paraview-plugins/RockDEM/RockDEM.so}"
PVPYTHON="${PVPYTHON:-pvpython}"
YADE="${YADE:-yade}"
if ! command -v "$YADE" > /dev/null 2>&1; then
  echo "yade not found (YADE is a peer to measure against, not a RockDEM dependency:" \
    "apt-get install yade on Debian 12 to run this comparison); skipped."
  exit 0
fi
[ -f "$ROCKDEM_PLUGIN" ] || { echo "RockDEM plugin not found at $ROCKDEM_PLUGIN: build it or set ROCKDEM_PLUGIN" >&2; exit 1; }
if [ $((STEPS % 10)) -ne 0 ]; then echo "--steps must be a multiple of 10 (RockDEM runs 10 frames)" >&2; exit 2; fi

if [ -n "$KEEP" ]; then
  WORK="$KEEP"; mkdir -p "$WORK"
else
  WORK="$(mktemp -d)"; trap 'rm -rf "$WORK"' EXIT
fi
echo "RockDEM vs YADE JCFpm, bonded rock: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores," \
  "load average $(cut -d' ' -f1-3 /proc/loadavg), OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-unset}," \
  "$("$YADE" --version 2>/dev/null | sed -n 's/^Yade version: *//p' | head -1 | sed 's/^/YADE /')"

# 1. The specimen.
if [ -n "$SPECIMEN" ]; then
  cp "$SPECIMEN" "$WORK/specimen.csv"
else
  "$PVPYTHON" "$ROOT/scripts/yade_rockdem.py" specimen "$WORK/specimen.csv" --particles "$PARTICLES"
fi
N="$(($(wc -l < "$WORK/specimen.csv") - 1))"

# 2. The shared parameters, and the timestep from RockDEM's probe.
cat > "$WORK/params.json" <<EOF
{"density": 2650.0, "grain_modulus": $MODULUS, "grain_poisson": 0.25, "grain_friction": 0.5,
 "bond_modulus": $MODULUS, "bond_stiffness_ratio": 0.4, "tensile_strength": $TENSILE,
 "cohesion": $COHESION, "friction_angle": $FRICTION_ANGLE, "bond_range": $RANGE,
 "moment_contribution": 0.0, "damping": $DAMPING, "strain_per_step": $SPS, "steps": $STEPS,
 "sample": 100, "timestep_safety": 0.3, "contact_law": "$CONTACT_LAW"}
EOF
"$PVPYTHON" "$ROOT/scripts/yade_rockdem.py" probe "$WORK/specimen.csv" "$WORK/params.json"

# 3. Timed runs.
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
field() { awk -v k="$1" '$1 == "run" {for (i = 2; i < NF; i++) if ($i == k) print $(i + 1)}'; }
declare -A OURS THEIRS LOAD
FIRST=""
for t in $THREADS; do
  [ -n "$FIRST" ] || FIRST="$t"
  curve=()
  [ "$t" = "$FIRST" ] && curve=(--history "$WORK/rockdem_curve.csv")
  LOAD[$t]="$(cut -d' ' -f1 /proc/loadavg)"
  "$PVPYTHON" "$ROOT/scripts/yade_rockdem.py" run "$WORK/specimen.csv" "$WORK/params.json" --threads "$t" \
    --repeat "$REPEAT" "${curve[@]}" > "$WORK/rockdem$t.log"
  grep -E '^(run|warning)' "$WORK/rockdem$t.log" | sed 's/^/  RockDEM: /'
  : > "$WORK/yade$t.log"
  for r in $(seq "$REPEAT"); do
    out="$WORK/yade_curve$t.$r.csv"
    "$YADE" -j"$t" -n -x "$ROOT/scripts/yade_jcfpm.py" "$WORK/specimen.csv" "$WORK/params.json" "$out" \
      2> "$WORK/yade$t.$r.err" | grep '^run ' >> "$WORK/yade$t.log" || {
        echo "YADE run failed; its log: $WORK/yade$t.$r.err" >&2; tail -5 "$WORK/yade$t.$r.err" >&2; exit 1; }
  done
  sed 's/^/  YADE:    /' "$WORK/yade$t.log"
  [ "$t" = "$FIRST" ] && cp "$WORK/yade_curve$t.1.csv" "$WORK/yade_curve.csv"
  OURS[$t]="$(field pstep_s < "$WORK/rockdem$t.log" | median)"
  THEIRS[$t]="$(field pstep_s < "$WORK/yade$t.log" | median)"
  LOAD[$t]="${LOAD[$t]}-$(cut -d' ' -f1 /proc/loadavg)"
done

BONDS_OURS="$(field bonds < "$WORK/rockdem$FIRST.log" | head -1)"
BONDS_YADE="$(field bonds < "$WORK/yade$FIRST.log" | head -1)"
BONDS_KD="$(field kdtree < "$WORK/yade$FIRST.log" | head -1)"
echo
echo "grains $N; bonds at cementing: RockDEM $BONDS_OURS, YADE JCFpm $BONDS_YADE, independent count (cKDTree) $BONDS_KD"
printf '%-8s %8s %6s | %14s %14s | %7s | %s\n' threads N steps "RockDEM (p-s/s)" "YADE JCFpm" ratio "load average (start-end)"
for t in $THREADS; do
  /usr/bin/env python3 -c "
import sys
t, n, s, o, y, load = sys.argv[1:]
print('%-8s %8d %6d | %14.3e %14.3e | %7.2f | %s' % (t, int(n), int(s), float(o), float(y), float(o) / float(y), load))
" "$t" "$N" "$STEPS" "${OURS[$t]}" "${THEIRS[$t]}" "${LOAD[$t]}"
done
echo "medians of $REPEAT; particle-steps per second over the $STEPS compression steps; ratio > 1: RockDEM faster." \
  "Load average now: $(cut -d' ' -f1-3 /proc/loadavg)"

# 4. The curves.
PLOT=(python3 "$ROOT/scripts/yade_plot.py" "$WORK/rockdem_curve.csv" "$WORK/yade_curve.csv" --title "$N grains, $STEPS steps of $SPS")
[ -n "$CHART" ] && PLOT+=(-o "$CHART")
"${PLOT[@]}"
