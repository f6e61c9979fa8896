#!/usr/bin/env bash
# Builds RockDEM and runs every test (GoogleTest suites, pvpython scripts, benchmark smoke runs).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
cd build
ctest --output-on-failure --parallel "$(nproc)"
