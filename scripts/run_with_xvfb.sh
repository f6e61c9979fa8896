#!/usr/bin/env bash
# Runs a rendering command on a private Xvfb display: the main job, the pvbatch tests and
# the GUI tests (Testing/GUI/run_gui_test.py).
#
#   scripts/run_with_xvfb.sh COMMAND [ARG...]      (screen: ROCKDEM_XVFB_SCREEN, default 1280x1024x24)
#
# It starts Xvfb itself rather than through xvfb-run -a:
# - the X server picks a free display number itself (-displayfd), atomically, so that runs
#   started at the same moment (ctest --parallel) never race for one number, as xvfb-run -a
#   does (it looks for a free lock file, then starts the server);
# - the server's standard streams are /dev/null and it inherits none of the command's
#   output pipes: an X server left behind can never keep a caller (ctest, a pipe) waiting
#   for the end of the output. Under xvfb-run the server inherited the pipe of the output
#   copy, and one that outlived its run held a ctest run until the test's timeout;
# - the server is stopped (and waited for) when the command ends, however it ends.
# The command's output goes to this script's output, its exit status is returned. A server
# that does not come up within 20 s, or a command that fails because it could not reach
# the display (Xlib's and Qt's messages), is retried (5 attempts in all; the server's own
# messages are shown when it does not start); any other failure is returned as is.
set -u
screen="${ROCKDEM_XVFB_SCREEN:-1280x1024x24}"
xvfb_pid=""

stop_xvfb() {
  if [ -n "$xvfb_pid" ]; then
    kill "$xvfb_pid" 2>/dev/null
    wait "$xvfb_pid" 2>/dev/null
    xvfb_pid=""
  fi
}
trap stop_xvfb EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
trap 'exit 129' HUP

if ! command -v Xvfb > /dev/null; then
  echo "run_with_xvfb: Xvfb not found (Debian package xvfb; bash scripts/install-deps.sh installs it)" >&2
  exit 127
fi

attempts=5
for attempt in $(seq "$attempts"); do
  numberfile=$(mktemp)
  xvfblog=$(mktemp)
  # fd 3 carries the display number once the server accepts connections; the server's own
  # messages go to a file of their own (never to the command's output pipe) and are shown
  # when it does not come up.
  Xvfb -displayfd 3 -screen 0 "$screen" -nolisten tcp 3> "$numberfile" < /dev/null > "$xvfblog" 2>&1 &
  xvfb_pid=$!
  display=""
  for _ in $(seq 200); do
    display=$(tr -dc '0-9' < "$numberfile")
    if [ -n "$display" ] || ! kill -0 "$xvfb_pid" 2> /dev/null; then
      break
    fi
    sleep 0.1
  done
  rm -f "$numberfile"
  if [ -z "$display" ] || ! kill -0 "$xvfb_pid" 2> /dev/null; then
    echo "run_with_xvfb: Xvfb did not start on attempt $attempt of $attempts; it said:" >&2
    tail -n 5 "$xvfblog" | sed 's/^/  /' >&2
    rm -f "$xvfblog"
    stop_xvfb
    # Servers started at the same moment (ctest --parallel) retry at different moments.
    sleep "$attempt.$((RANDOM % 10))"
    continue
  fi
  rm -f "$xvfblog"
  log=$(mktemp)
  DISPLAY=":$display" "$@" 2>&1 | tee "$log"
  rc=${PIPESTATUS[0]}
  if [ "$rc" -ne 0 ] && grep -q -E "bad X server connection|cannot open display|Can't open display|could not connect to display" "$log"; then
    echo "run_with_xvfb: the command could not reach display :$display on attempt $attempt of $attempts, retrying" >&2
    rm -f "$log"
    stop_xvfb
    sleep "$attempt.$((RANDOM % 10))"
    continue
  fi
  rm -f "$log"
  exit "$rc"
done
exit 1
