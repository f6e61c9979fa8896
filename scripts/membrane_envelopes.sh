#!/usr/bin/env bash
# Triaxial envelopes of the same rock in a rigid box and in a membrane cylinder
# (Documentation/Specimens.md, "Envelopes: rigid box and membrane"): rockdem_bench_rock
# --tests envelopes on the stiff-bond rock of the main job (Bond Modulus 1e10, Tensile 1 MPa,
# Cohesion 4 MPa, Moment Contribution 0.5, Bond Range 1.4), then the chart and the picture of
# the membrane specimen after failure (scripts/plot_envelopes.py), and the deformation after
# the peak of the highest-stress membrane test (scripts/plot_localisation.py: OUTDIR/membrane_
# increment.png, membrane_surface.png, membrane_radius.png; its numbers in OUTDIR/localisation.txt).
#
#   bash scripts/membrane_envelopes.sh OUTDIR [rockdem_bench_rock options...]
#
# e.g. nice -n 15 bash scripts/membrane_envelopes.sh results/envelopes --particles 2000 --sigma3 1e6,2e6,4e6
# The options given override the defaults, e.g. one membrane test run on to 60 % of its peak:
#   nice -n 15 bash scripts/membrane_envelopes.sh results/s10 --particles 2000 --specimen cylinder \
#       --sigma3 1e7 --triaxial-stop 0.6 --max-strain 0.04 --threads 1
set -euo pipefail
cd "$(dirname "$0")/.."
out="$1"; shift
bench=build/bin/rockdem_bench_rock
[ -x "$bench" ] || { echo "build first: $bench is missing (bash scripts/build.sh)" >&2; exit 1; }
mkdir -p "$out"
"$bench" --tests envelopes --specimen both --modulus 1e10 --tensile 1e6 --cohesion 4e6 \
  --moment-contribution 0.5 --range 1.4 --dump "$out" "$@" > "$out/envelopes.log.tmp"
mv "$out/envelopes.log.tmp" "$out/envelopes.log"
python3 scripts/plot_envelopes.py "$out/envelopes.log" -o "$out/envelopes.png" \
  --specimen "$out/membrane_failed.csv" --picture "$out/membrane_failed.png"
python3 scripts/plot_localisation.py "$out/membrane_failed.csv" -o "$out/membrane" > "$out/localisation.txt"
cat "$out/localisation.txt"
