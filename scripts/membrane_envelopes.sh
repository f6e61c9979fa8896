#!/usr/bin/env bash
# Triaxial envelopes of the same rock in a rigid box and in a membrane cylinder
# (Documentation/Specimens.md, "Envelopes: rigid box and membrane"): rockdem_bench_rock
# --tests envelopes on the stiff-bond rock of the main job (Bond Modulus 1e10, Tensile 1 MPa,
# Cohesion 4 MPa, Moment Contribution 0.5, Bond Range 1.4), then the chart and the picture of
# the membrane specimen after failure (scripts/plot_envelopes.py).
#
#   bash scripts/membrane_envelopes.sh OUTDIR [rockdem_bench_rock options...]
#
# e.g. nice -n 15 bash scripts/membrane_envelopes.sh results/envelopes --particles 2000 --sigma3 1e6,2e6,4e6
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
