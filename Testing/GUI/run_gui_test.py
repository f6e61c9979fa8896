#!/usr/bin/env python3
"""Runs one of RockDEM's GUI tests: ParaView's GUI under Xvfb replaying an event file.

    run_gui_test.py --paraview paraview --events gui_pack.xml --out DIR [--plugin-dir D]
                    [--baseline-dir B] [--data-dir X] [--checks N] [--load-plugin]

The event file (ParaView's recorded-test XML, `paraview --test-script`) may contain the
words @OUT@ (the output folder), @SOURCE@ (this folder), @BASELINE@, @DATA@ and @PLUGIN@
(the plugin library); they are replaced before the run. ParaView runs with --dr (no
user settings), a 1600x1000 window on a 1600x1000 Xvfb screen, and a style sheet that
widens the Pipeline Browser and Properties panel (readable screenshots). The test passes
when ParaView plays every event and exits with 0, the checks written by rockdem_gui.py
(OUT/checks.txt) are all 'ok', there are at least --checks of them, and the last line
is 'done'. It runs under scripts/run_with_xvfb.sh (a private Xvfb display); a server
that does not come up, or a ParaView that cannot reach it, is retried (up to 3 times).
"""
import argparse
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--paraview", required=True)
    parser.add_argument("--events", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--plugin", required=True, help="the RockDEM plugin library")
    parser.add_argument("--load-plugin", action="store_true",
                        help="do not put the plugin on PV_PLUGIN_PATH: the events load it")
    parser.add_argument("--baseline-dir", default=os.path.join(HERE, "Baseline"))
    parser.add_argument("--data-dir", default="")
    parser.add_argument("--checks", type=int, default=1)
    parser.add_argument("--timeout", type=int, default=600)
    args = parser.parse_args()

    if os.path.isdir(args.out):
        shutil.rmtree(args.out)
    os.makedirs(args.out)
    with open(args.events) as f:
        events = f.read()
    for word, value in (("@OUT@", args.out), ("@SOURCE@", HERE), ("@BASELINE@", args.baseline_dir),
                        ("@DATA@", args.data_dir), ("@PLUGIN@", args.plugin)):
        events = events.replace(word, value)
    script = os.path.join(args.out, os.path.basename(args.events))
    with open(script, "w") as f:
        f.write(events)
    style = os.path.join(args.out, "wide-panels.qss")
    with open(style, "w") as f:
        f.write("QDockWidget#propertiesDock, QDockWidget#pipelineBrowserDock, "
                "QDockWidget#informationDock { min-width: 440px; }\n")

    env = dict(os.environ)
    env["ROCKDEM_GUI_OUT"] = args.out
    env["ROCKDEM_GUI_DATA"] = args.data_dir
    env["PYTHONPATH"] = HERE + os.pathsep + env.get("PYTHONPATH", "")
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    env.pop("PV_PLUGIN_PATH", None)
    if not args.load_plugin:
        env["PV_PLUGIN_PATH"] = os.path.dirname(args.plugin)
    # A private X server (scripts/run_with_xvfb.sh: its own free display, no output pipe
    # held by a server left behind, the server stopped when ParaView ends).
    env["ROCKDEM_XVFB_SCREEN"] = "1600x1000x24"
    command = [os.path.join(HERE, "..", "..", "scripts", "run_with_xvfb.sh"), args.paraview, "--dr",
               "-geometry", "1600x1000+0+0", "-stylesheet", style, "--test-script=" + script,
               "--test-directory=" + args.out, "--exit"]
    start = time.time()
    for attempt in range(3):
        run = subprocess.run(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             universal_newlines=True, timeout=args.timeout)
        if run.returncode != 0 and any(s in run.stdout for s in (
                "bad X server connection", "cannot open display", "Xvfb did not start")):
            print("run_gui_test: X server problem on attempt %d, retrying" % (attempt + 1))
            if os.path.exists(os.path.join(args.out, "checks.txt")):
                os.remove(os.path.join(args.out, "checks.txt"))
            continue
        break
    log = os.path.join(args.out, "paraview.log")
    with open(log, "w") as f:
        f.write(run.stdout)
    # ParaView's log, without the per-batch status lines of a running load test.
    for line in run.stdout.splitlines():
        if "DEM Load Test: t = " not in line and line.strip():
            print(line)
    checks = []
    path = os.path.join(args.out, "checks.txt")
    if os.path.exists(path):
        with open(path) as f:
            checks = [l.rstrip("\n") for l in f]
    print("\n".join(checks))
    failed = [c for c in checks if c.startswith("FAIL")]
    passed = [c for c in checks if c.startswith("ok")]
    problems = []
    if run.returncode != 0:
        problems.append("ParaView exited with %d (an event failed or it crashed; see %s)" % (run.returncode, log))
    if failed:
        problems.append("%d check(s) failed" % len(failed))
    # An image comparison (pqcompareview) that fails does not stop the playback.
    compared = run.stdout.count("The following event FAILED")
    if compared:
        problems.append("%d image comparison(s) or event(s) failed (see %s)" % (compared, log))
    if len(passed) < args.checks:
        problems.append("only %d of the %d expected checks ran" % (len(passed), args.checks))
    if not checks or checks[-1] != "done":
        problems.append("the events did not all play (no 'done' at the end of checks.txt)")
    print("run_gui_test: %d checks passed in %.1f s" % (len(passed), time.time() - start))
    if problems:
        print("run_gui_test: FAILED: " + "; ".join(problems))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
