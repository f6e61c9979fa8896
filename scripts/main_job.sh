#!/usr/bin/env bash
# Builds RockDEM and runs the main job (examples/main_job.py) on the built-in default
# specimen, writing its results and pictures to results/ (README.md lists them).
# The job renders, so it runs under Xvfb; scripts/run_with_xvfb.sh retries only when the
# X server itself could not be reached.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
export ROCKDEM_PLUGIN="$PWD/build/lib/paraview-plugins/RockDEM/RockDEM.so"
scripts/run_with_xvfb.sh pvbatch examples/main_job.py --output "$PWD/results" "$@"
