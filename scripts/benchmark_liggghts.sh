#!/usr/bin/env bash
# Runs RockDEM's solver benchmark and LIGGGHTS-PUBLIC (Debian package `liggghts`) side by
# side on the identical problem and prints particle-steps per second for both.
#
#   scripts/benchmark_liggghts.sh [--sizes "10000 100000"] [--packs "poly lattice"]
#                                 [--restitution 0.5] [--bench PATH] [--keep DIR]
#
# For each pack and N, rockdem_bench_solver --write-pack writes the pack (same positions,
# radii, box, timestep, material); this script turns it into a LIGGGHTS data file and
# input deck: pair_style gran model hertz tangential history limitForce on (no-tension
# cut-off, as ours), six fix wall/gran primitive planes on the box faces (a second
# material type 1e6 times stiffer, so that the walls are rigid as ours), fix gravity,
# fix nve/sphere, the same timestep, the same Verlet skin (neighbor SKIN bin,
# neigh_modify delay 0: rebuild when a particle moved half the skin, as ours), the same
# number of steps. Ours runs with Settling Damping 0 (LIGGGHTS has no Cundall local
# damping). Timed: our advance() and LIGGGHTS's "Loop time". Both print the kinetic energy
# at the end (translational + rotational), as a check that they ran the same problem
# (--restitution 1 removes the two codes' different contact damping: then the lattice
# runs, full of contacts, must agree too).
#
# Environment: BENCH (path of rockdem_bench_solver), MPIRUN (default: mpirun
# --allow-run-as-root), NP (processes / threads of the parallel runs; default nproc),
# REPEAT (rounds per configuration, the two codes taking turns, medians reported; default
# 1; each round's figures are printed as "TAG round: ours-1 KE ours-NP KE LIGGGHTS-1-seconds
# KE LIGGGHTS-NP-seconds KE others"). The last column
# says how many cores other processes kept busy during our NP-thread run: on a shared
# machine the threaded figures (ours and LIGGGHTS's) are only meaningful near 0.
set -euo pipefail

SIZES="10000 100000"
PACKS="poly lattice"
BENCH="${BENCH:-}"
KEEP=""
RESTITUTION=0.5
while [ $# -gt 0 ]; do
  case "$1" in
    --sizes) SIZES="$2"; shift 2 ;;
    --packs) PACKS="$2"; shift 2 ;;
    --bench) BENCH="$2"; shift 2 ;;
    --restitution) RESTITUTION="$2"; shift 2 ;;
    --keep) KEEP="$2"; shift 2 ;;
    -h|--help) sed -n '2,27p' "$0"; exit 0 ;;
    *) echo "unknown argument: $1" >&2; exit 2 ;;
  esac
done

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ -z "$BENCH" ]; then
  for candidate in "$ROOT"/build*/Testing/Benchmarks/rockdem_bench_solver "$ROOT"/build*/bin/rockdem_bench_solver; do
    if [ -x "$candidate" ]; then BENCH="$candidate"; break; fi
  done
fi
if [ -z "$BENCH" ] || [ ! -x "$BENCH" ]; then
  echo "rockdem_bench_solver not found: build it (target rockdem_bench_solver) or pass --bench PATH" >&2
  exit 1
fi
LIGGGHTS="$(command -v liggghts || true)"
if [ -z "$LIGGGHTS" ]; then
  echo "liggghts not found: apt-get install -y liggghts" >&2
  exit 1
fi
NP="${NP:-$(nproc)}"
REPEAT="${REPEAT:-1}"
MPIRUN="${MPIRUN:-mpirun --allow-run-as-root}"

if [ -n "$KEEP" ]; then
  WORK="$KEEP"; mkdir -p "$WORK"
else
  WORK="$(mktemp -d)"; trap 'rm -rf "$WORK"' EXIT
fi

default_steps() { # as rockdem_bench_solver's defaults
  if [ "$1" -le 20000 ]; then echo 2000; elif [ "$1" -le 200000 ]; then echo 500; else echo 200; fi
}

# pack file -> LIGGGHTS data file + input deck (scripts/liggghts_deck.py); prints nothing.
make_deck() { # packfile datafile deckfile steps
  python3 "$ROOT/scripts/liggghts_deck.py" deck "$1" "$2" "$3" "$4"
}

# LIGGGHTS log -> "seconds kinetic_energy"
parse_liggghts() {
  python3 - "$1" "$2" <<'PY'
import re, sys
log, steps = open(sys.argv[1]).read(), sys.argv[2]
loop = re.search(r'Loop time of ([0-9.eE+-]+) on', log)
ke = None
for line in log.splitlines():
    parts = line.split()
    if len(parts) == 4 and parts[0] == steps:
        try:
            ke = float(parts[2]) + float(parts[3])
        except ValueError:
            pass
print(loop.group(1) if loop else 'nan', ke if ke is not None else 'nan')
PY
}

RESULTS="$WORK/results.txt"
: > "$RESULTS"
echo "RockDEM vs LIGGGHTS: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p' | head -1)"
echo "bench: $BENCH"
echo "liggghts: $LIGGGHTS ($(dpkg-query -W -f='${Version}' liggghts 2>/dev/null || echo '?'))"
for pack in $PACKS; do
  for n in $SIZES; do
    steps="$(default_steps "$n")"
    tag="$pack-$n"
    "$BENCH" --write-pack "$WORK/$tag.pack" --pack "$pack" --sizes "$n" --restitution "$RESTITUTION" > /dev/null
    natoms="$(sed -n 's/^# particles //p' "$WORK/$tag.pack")"
    make_deck "$WORK/$tag.pack" "$WORK/$tag.data" "$WORK/$tag.in" "$steps"
    # REPEAT rounds, the two codes taking turns (ours on 1 and NP threads, then LIGGGHTS on
    # 1 and NP ranks): on a machine whose speed drifts over minutes, a slow spell slows
    # runs of both codes instead of one code's. Ours without Cundall damping (LIGGGHTS has
    # none). The medians of the rounds are reported; every run is in $tag.runs.
    : > "$WORK/$tag.runs"
    for r in $(seq "$REPEAT"); do
      "$BENCH" --sizes "$n" --packs "$pack" --threads "1,$NP" --steps "$steps" --damping 0 \
        --restitution "$RESTITUTION" --repeat 1 --csv "$WORK/$tag.ours.$r.csv" > "$WORK/$tag.ours.$r.log"
      ours1="$(awk -F, 'NR>1 && $3==1 {print $8, $13}' "$WORK/$tag.ours.$r.csv")"
      oursN="$(awk -F, -v np="$NP" 'NR>1 && $3==np {print $8, $13, $14}' "$WORK/$tag.ours.$r.csv")"
      (cd "$WORK" && "$LIGGGHTS" -in "$tag.in" -log "$tag.lig1.$r.log" > /dev/null)
      lig1="$(parse_liggghts "$WORK/$tag.lig1.$r.log" "$steps")"
      (cd "$WORK" && $MPIRUN -np "$NP" "$LIGGGHTS" -in "$tag.in" -log "$tag.ligN.$r.log" > /dev/null 2>&1) || true
      ligN="$(parse_liggghts "$WORK/$tag.ligN.$r.log" "$steps" 2>/dev/null || echo 'nan nan')"
      read -r o1 oke1 <<< "$ours1"
      read -r oN okeN obusy <<< "$oursN"
      echo "$o1 $oke1 $oN $okeN $lig1 $ligN $obusy" >> "$WORK/$tag.runs"
    done
    echo "$pack $natoms $steps $(python3 - "$WORK/$tag.runs" <<'PY'
import statistics, sys
runs = [l.split() for l in open(sys.argv[1]) if l.strip()]
def med(c):
    values = [float(r[c]) for r in runs]
    return statistics.median(values) if all(v == v for v in values) else float('nan')
# ours 1 (p-steps/s), its KE, ours NP, its KE, LIGGGHTS 1 (s), its KE, LIGGGHTS NP (s), its KE, others
print(med(0), runs[-1][1], med(2), runs[-1][3], med(4), runs[-1][5], med(6), runs[-1][7], max(float(r[8]) for r in runs))
PY
)" >> "$RESULTS"
    sed "s/^/  $tag round: /" "$WORK/$tag.runs"
  done
done

python3 - "$RESULTS" "$NP" <<'PY'
import sys, math
np_ = sys.argv[2]
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
print()
print(f"{'pack':8} {'N':>8} {'steps':>6} | {'ours 1 thr':>11} {'ours '+np_+' thr':>11} | "
      f"{'LIGGGHTS 1':>11} {'LIGGGHTS '+np_:>11} | {'1: ours/L':>9} {np_+': ours/L':>9} | KE end ours / LIGGGHTS (J) | others")
for r in rows:
    pack, n, steps = r[0], int(r[1]), int(r[2])
    o1, ke1, oN, keN = float(r[3]), r[4], float(r[5]), r[6]
    l1t, lke1, lNt, lkeN = float(r[7]), r[8], float(r[9]), r[10]
    l1 = n * steps / l1t if l1t == l1t and l1t > 0 else float('nan')
    lN = n * steps / lNt if lNt == lNt and lNt > 0 else float('nan')
    print(f"{pack:8} {n:8d} {steps:6d} | {o1:11.3e} {oN:11.3e} | {l1:11.3e} {lN:11.3e} | "
          f"{o1 / l1:9.2f} {oN / lN:9.2f} | {float(ke1):.4e} / {float(lke1):.4e} | {r[11]}")
print("\nparticle-steps per second (higher is better); ratios < 1: RockDEM slower.")
PY
