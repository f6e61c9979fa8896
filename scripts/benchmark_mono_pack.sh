#!/usr/bin/env bash
# The issue-20 comparison with LIGGGHTS-PUBLIC on the peers' settled mono pack, regenerated
# with their recipe, and timed through RockDEM's user path.
#
#   scripts/benchmark_mono_pack.sh [--cells "20 20 25"] [--settle 0.06] [--steps 2000]
#                                  [--repeat 3] [--threads "1 2"] [--keep DIR]
#
# 1. Pack: a simple cubic lattice of NX x NY x NZ spheres of radius 1 mm, centres 2.2 mm
#    apart (each moved by up to 0.05 mm per axis, fixed seed, so that the columns buckle
#    as they settle), in a box of NX x NY x 1.5 NZ spacings with rigid walls; Hertz-Mindlin
#    with history and the no-tension cut-off, E 1e8 Pa, nu 0.25, e 0.5, mu 0.5,
#    2650 kg/m^3, gravity 9.81 m/s^2, dt 5e-6 s, skin 0.2 mm. Settled in LIGGGHTS for
#    --settle seconds (0.06 s = 12,000 steps); the settled positions (at rest, no history)
#    are the pack both codes are timed on. --cells "43 43 54" is the 100k version (99,846
#    spheres, the same proportions).
# 2. Timed, --steps steps, --repeat runs each, the two codes taking turns, the medians
#    printed: LIGGGHTS on 1 and 2 MPI ranks ("Loop time"), RockDEM through pvpython (CSV
#    Reader -> Table To Points -> DEM Model From Points -> DEM Load Test, Mode Off, Settling
#    Damping 0; the second of two frames of --steps steps is timed;
#    scripts/time_pack_pvpython.py) on 1 and 2 threads.
#
# Environment: ROCKDEM_PLUGIN (default: build/lib/paraview-plugins/RockDEM/RockDEM.so),
# PVPYTHON (default pvpython), MPIRUN (default mpirun --allow-run-as-root). The load
# average is printed before and after: the times are only meaningful on an idle machine.
# Set OMP_WAIT_POLICY as you run ParaView (the table prints it).
set -euo pipefail

CELLS="20 20 25"
SETTLE=0.06
STEPS=2000
REPEAT=3
THREADS="1 2"
KEEP=""
while [ $# -gt 0 ]; do
  case "$1" in
    --cells) CELLS="$2"; shift 2 ;;
    --settle) SETTLE="$2"; shift 2 ;;
    --steps) STEPS="$2"; shift 2 ;;
    --repeat) REPEAT="$2"; shift 2 ;;
    --threads) THREADS="$2"; shift 2 ;;
    --keep) KEEP="$2"; shift 2 ;;
    -h|--help) sed -n '2,25p' "$0"; exit 0 ;;
    *) echo "unknown argument: $1" >&2; exit 2 ;;
  esac
done

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DECK="$ROOT/scripts/liggghts_deck.py"
export ROCKDEM_PLUGIN="${ROCKDEM_PLUGIN:-$ROOT/build/lib/paraview-plugins/RockDEM/RockDEM.so}"
PVPYTHON="${PVPYTHON:-pvpython}"
MPIRUN="${MPIRUN:-mpirun --allow-run-as-root}"
LIGGGHTS="$(command -v liggghts || true)"
[ -n "$LIGGGHTS" ] || { echo "liggghts not found: apt-get install -y liggghts" >&2; exit 1; }
[ -f "$ROCKDEM_PLUGIN" ] || { echo "RockDEM plugin not found at $ROCKDEM_PLUGIN: build it or set ROCKDEM_PLUGIN" >&2; exit 1; }

if [ -n "$KEEP" ]; then
  WORK="$KEEP"; mkdir -p "$WORK"
else
  WORK="$(mktemp -d)"; trap 'rm -rf "$WORK"' EXIT
fi
echo "RockDEM vs LIGGGHTS on the settled mono pack: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores," \
  "load average $(cut -d' ' -f1-3 /proc/loadavg), OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-unset}"

# 1. The lattice, settled in LIGGGHTS.
read -r NX NY NZ <<< "$CELLS"
python3 "$DECK" lattice "$WORK/lattice.pack" --cells "$NX" "$NY" "$NZ" --radius 0.001 --spacing 0.0022 \
  --jitter 0.00005 --seed 20
SETTLE_STEPS="$(python3 -c "print(round($SETTLE / 5e-6))")"
python3 "$DECK" deck "$WORK/lattice.pack" "$WORK/settle.data" "$WORK/settle.in" "$SETTLE_STEPS" --dump "$WORK/settled.dump"
(cd "$WORK" && $MPIRUN -np 2 "$LIGGGHTS" -in settle.in -log settle.log > /dev/null 2>&1)
python3 "$DECK" pack "$WORK/settled.dump" "$WORK/lattice.pack" "$WORK/settled.pack"
N="$(sed -n 's/^# particles //p' "$WORK/settled.pack")"
echo "pack: $N spheres ($NX x $NY x $NZ lattice), settled $SETTLE s ($SETTLE_STEPS steps) in LIGGGHTS: $WORK/settled.pack"

# 2. Timed runs.
python3 "$DECK" deck "$WORK/settled.pack" "$WORK/timed.data" "$WORK/timed.in" "$STEPS"
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
loop_time() { sed -n 's/^Loop time of \([0-9.eE+-]*\) on.*/\1/p' "$1" | tail -1; }
declare -A LIG OURS CONTACTS
for np in $THREADS; do
  : > "$WORK/lig$np.times"
  : > "$WORK/ours$np.log"
  # The two codes take turns (LIGGGHTS, RockDEM, LIGGGHTS, ...): on a machine whose speed
  # drifts over minutes, a slow spell then slows runs of both instead of one code's three.
  for r in $(seq "$REPEAT"); do
    if [ "$np" = 1 ]; then
      (cd "$WORK" && "$LIGGGHTS" -in timed.in -log "timed1.$r.log" > /dev/null)
    else
      (cd "$WORK" && $MPIRUN -np "$np" "$LIGGGHTS" -in timed.in -log "timed$np.$r.log" > /dev/null 2>&1)
    fi
    loop_time "$WORK/timed$np.$r.log" >> "$WORK/lig$np.times"
    "$PVPYTHON" "$ROOT/scripts/time_pack_pvpython.py" "$WORK/settled.pack" --steps "$STEPS" --threads "$np" \
      --repeat 1 | sed "s/^run 0 /run $((r - 1)) /" >> "$WORK/ours$np.log"
  done
  LIG[$np]="$(median < "$WORK/lig$np.times")"
  OURS[$np]="$(awk '$1 == "run" {print $8}' "$WORK/ours$np.log" | median)"
  CONTACTS[$np]="$(awk '$1 == "run" {c = $12} END {print c}' "$WORK/ours$np.log")"
  sed 's/^/  ours: /' "$WORK/ours$np.log"
  sed 's/^/  LIGGGHTS seconds: /' "$WORK/lig$np.times" | paste -sd' '
done

echo
printf '%-16s %8s %6s | %14s %14s | %8s | %s\n' "threads / ranks" N steps "RockDEM (p-s/s)" "LIGGGHTS" ratio "contacts (ours, end)"
for np in $THREADS; do
  python3 - "$np" "$N" "$STEPS" "${OURS[$np]}" "${LIG[$np]}" "${CONTACTS[$np]}" <<'PY'
import sys
np_, n, steps, ours, lig, contacts = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5]), sys.argv[6]
o, l = n * steps / ours, n * steps / lig
print(f"{np_:16} {n:8d} {steps:6d} | {o:14.3e} {l:14.3e} | {o / l:8.2f} | {contacts}")
PY
done
echo "medians of $REPEAT; particle-steps per second; ratio > 1: RockDEM faster. Load average now: $(cut -d' ' -f1-3 /proc/loadavg)"
