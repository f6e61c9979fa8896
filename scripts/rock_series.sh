#!/usr/bin/env bash
# The rock-behaviour series of Documentation/Rock.md: rockdem_bench_rock (the engine's
# laboratory tests on a compacted, cemented specimen) at several Bond Ranges, one log per
# range, then the chart of UCS / tensile strength and friction angle against bonded
# coordination (scripts/plot_rock.py).
#
#   bash scripts/rock_series.sh OUTDIR "1.0 1.2 1.4 1.6" [rockdem_bench_rock options...]
#
# e.g. bash scripts/rock_series.sh results/rock "1.0 1.2 1.4 1.6" --particles 2000 \
#        --moment-contribution 0 --strain-per-step 1e-6 --tests ucs,tension,triaxial
# Run it under nice on a shared machine; every range is an independent run.
set -euo pipefail
cd "$(dirname "$0")/.."
out="$1"; ranges="$2"; shift 2
bench=build/bin/rockdem_bench_rock
[ -x "$bench" ] || { echo "build first: $bench is missing (bash scripts/build.sh)" >&2; exit 1; }
mkdir -p "$out"
for r in $ranges; do
  log="$out/range_$r.log"
  echo "Bond Range $r -> $log"
  "$bench" --range "$r" "$@" > "$log.tmp"
  mv "$log.tmp" "$log"
done
python3 scripts/plot_rock.py "$out"/range_*.log -o "$out/rock_chart.png" --table "$out/rock_table.md"
