#!/usr/bin/env bash
# Runs the libFuzzer target of the state file reader for a bounded time and fails on any
# crash, sanitizer report, leak in RockDEM code, timeout or unexpected exception.
#
#   scripts/fuzz_state_reader.sh [FUZZER] [SEED_MAKER] [WORKDIR] [SECONDS] [--no-checksum]
#
# Defaults: build/bin/fuzz_state_reader, build/bin/rockdem_make_fuzz_seeds, build/fuzz, 60.
# The corpus grows in WORKDIR/corpus (seeded with small valid state files); crashing inputs
# are kept in WORKDIR as crash-*. With --no-checksum the reader's checksum check is off
# (ROCKDEM_FUZZ_NO_CHECKSUM=1), so mutated files reach HDF5's own parser.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
fuzzer="${1:-$here/build/bin/fuzz_state_reader}"
seeder="${2:-$here/build/bin/rockdem_make_fuzz_seeds}"
work="${3:-$here/build/fuzz}"
seconds="${4:-60}"
mode="${5:-}"
mkdir -p "$work/seeds" "$work/corpus"
fuzzer="$(realpath "$fuzzer")"
seeder="$(realpath "$seeder")"
work="$(realpath "$work")"
"$seeder" "$work/seeds" >/dev/null
if [ "$mode" = "--no-checksum" ]; then
  export ROCKDEM_FUZZ_NO_CHECKSUM=1
  echo "fuzz_state_reader: checksum check OFF: mutated files reach HDF5"
fi
# HDF5 1.10 keeps some allocations on its error paths until the library closes (and on
# some damaged files never frees them: "HDF5: infinite loop closing library" at exit).
# libFuzzer's per-input leak check is off (-detect_leaks=0: it would report every
# rejected file); the leak check at exit stays on for RockDEM code and suppresses leaks
# allocated inside libhdf5 (ASan still reports every invalid access).
log="$work/fuzz.log"
supp="$work/lsan.supp"
printf 'leak:libhdf5\n' >"$supp"
export LSAN_OPTIONS="suppressions=$supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
set +e
(cd "$work" && "$fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -detect_leaks=0 \
   -max_len=65536 -print_final_stats=1 corpus seeds) >"$log" 2>&1
rc=$?
set -e
grep -E "^(#[0-9]+ +DONE|Done [0-9]+ runs|stat::number_of_executed_units|stat::peak_rss_mb)" "$log" || true
if [ $rc -ne 0 ]; then
  echo "fuzz_state_reader: FAILED (exit $rc); the end of the log ($log):"
  tail -40 "$log"
  exit 1
fi
echo "fuzz_state_reader: no crash in ${seconds} s; corpus $(ls "$work/corpus" | wc -l) inputs"
