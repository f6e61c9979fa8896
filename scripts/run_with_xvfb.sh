#!/usr/bin/env bash
# Runs a rendering command under xvfb-run (the main job, the pvbatch tests). xvfb-run -a
# occasionally fails to bring up or reach its X server ("bad X server connection"); that
# is retried (up to 3 times), any other failure is returned as is.
set -u
for attempt in 1 2 3; do
  log=$(mktemp)
  xvfb-run -a "$@" > >(tee "$log") 2>&1
  rc=$?
  if [ $rc -ne 0 ] && grep -q -E "bad X server connection|cannot open display|Xvfb failed to start" "$log"; then
    echo "run_with_xvfb: X server problem on attempt $attempt, retrying" >&2
    rm -f "$log"
    sleep 1
    continue
  fi
  rm -f "$log"
  exit $rc
done
exit 1
