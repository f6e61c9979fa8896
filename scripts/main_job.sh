#!/usr/bin/env bash
# Builds RockDEM and runs the main job on the built-in default specimen:
# results/pack.png (the pack drawn as spheres) and results/pack_summary.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
export ROCKDEM_PLUGIN="$PWD/build/lib/paraview-plugins/RockDEM/RockDEM.so"
xvfb-run -a pvbatch examples/main_job.py --output "$PWD/results" "$@"
