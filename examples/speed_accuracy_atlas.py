#!/usr/bin/env python3
"""Speed against accuracy: the atlas of Documentation/SpeedAccuracy.md (issue 17).

    python3 examples/speed_accuracy_atlas.py [--bench build/bin/rockdem_bench_rock]
                                             [--out Documentation] [--work DIR] [--quick]

Drives the engine benchmark rockdem_bench_rock (a compacted, cemented specimen: Compact
Elements then DEM Cement over a Bond Range; unconfined compression to past the peak) and
writes, under OUT:
  images/speed_accuracy_rates.png    strain rate 0.25x to 64x the Suggested Strain Rate against
                                     UCS and E (error against the slowest run), the unbalanced
                                     force ratio, the inertial number and the run time;
  images/speed_accuracy_modulus.png  grain and bond modulus 1x to 1000x softer, strengths kept:
                                     run time, error in UCS, strain at peak, UCS / E;
  SpeedAccuracy.md                   the tables between the markers <!-- atlas:NAME --> and
                                     <!-- /atlas:NAME --> (rates, modulus, threads), each with
                                     its command, the machine and the load; the rest of the
                                     page is kept (a new page holds only the tables).
  images/atlas_timestep_bonded.png   Timestep Safety 0.05-0.5 on the cemented specimen: UCS and E
                                     against the smallest, run time and steps;
  images/atlas_stability.png         the stability map: Timestep Safety against the Bond Modulus /
                                     grain Young's modulus ratio (unconfined), Settling Damping
                                     against Servo Alpha (triaxial); unstable, detected, servo
                                     oscillating, drifting runs, the defaults marked;
CPU threads: the same test on 1 and 2 threads, its time and whether the UCS agrees bit for bit.
Contact law (contact_law): the same rock built and tested with Hertz-Mindlin and with linear
contacts (bench --contact-law, set before Compact Elements), the linear one at the same strain
per step and at the same strain rate: porosity, bonds, UCS, E, nu, sigma_t, broken at the peak,
the DFN, steps, particle-steps and run time.
Resolution (resolution): the same rock at 250-17,000 grains (about 5-20 mean diameters across the
width), pack seeds 1-3: UCS, E, nu (unconfined), sigma_t (direct tension) and the friction angle
(triaxial peaks at 10 and 20 % of the UCS with the UCS; up to 8,000 grains), each size's mean and seed spread against the
finest size's, the cost of each test in seconds and particle-steps (images/speed_accuracy_resolution.png),
and where each property converges within 5 %. The runs go in an order that keeps the most useful
ones when the sweep is cut short; --no-new-runs writes the section from the runs already in WORK and
names the missing ones.
Rate against seeds (rate_seeds, not in the default list): the resolution sweep's 700-grain specimens at
4 x and 1 x the Suggested Strain Rate beside their sweep test (the rate effect, paired by seed).
2D against 3D (dims): the same rock as a 2D section of discs, a 3D slab of the same width and height a few
mean diameters thick (bench --depth) and the 3D box of the same width, undamped, at the same strain per
step, pack seeds 1-3: UCS, E, nu, sigma_t, the fracture pattern (broken at the peak, near the platens,
the band statistic of scripts/localisation_index.py after the peak, the DFN), steps, particle-steps and
run time; images/speed_accuracy_dims.png (cost against the difference in UCS, and the cracks of seed 1 of
each: the 2D section, the slab's and the box's mid-plane). Dumps in WORK/dims_dumps (not committed).
CPU threads (threads) also runs the test on the GPU (Vulkan) backend (bench --device gpu; lavapipe here,
a CPU emulation, or the CPU when no device can run it).

--quick (ctest Atlas.Quick): 300 grains, three rates, two moduli, one thread comparison (and the GPU
request), resolution on 120 and 250 grains with two seeds at 4e-7 strain per step, 2D against 3D on one
seed of a 55-disc section, a 175-grain slab and a 300-grain box at 4e-7 per step, into
OUT (a scratch folder); asserts that the charts and tables were written and every number in
them is finite. Each bench run's output is kept in WORK (default OUT/atlas_runs) with its
command on the first line and is reused when the command is the same (delete it to rerun;
--quick always runs).
Needs matplotlib (Debian: python3-matplotlib). SI units.
"""
import argparse
import math
import os
import platform
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "scripts"))
from rockdem_plotting import pyplot  # noqa: E402

plt = pyplot()

# The specimen: the "stiff bonds" rock of Documentation/Rock.md (E = Bond Modulus 1e10 Pa,
# Tensile 1 MPa, Cohesion 4 MPa, Moment Contribution 0.5, Bond Range 1.4).
ROCK = ["--modulus", "1e10", "--tensile", "1e6", "--cohesion", "4e6", "--moment-contribution", "0.5",
        "--range", "1.4", "--max-strain", "0.03"]  # (contact_law_section replaces the last two)
# The strain-rate sweep: (name, factors, inertial target of the suggestion the factors
# multiply, or None for the engine's rule). The full sweep was run at the rule's first
# target, 1e-4 (bench --inertial-target 1e-4): the table and chart give each rate against
# the suggestion of the rule now, CEMENTED_TARGET (the suggestion is proportional to the target).
CEMENTED_TARGET = 2.5e-5  # dem::CementedTargetInertialNumber
FULL = {"particles": 200, "rate_runs": [("rates", [64, 16, 4, 1, 0.5, 0.25], 1e-4),
                                        ("rates_slow", [0.0625], 1e-4)],
        "moduli": [1e10, 1e9, 1e8, 1e7], "modulus_factor": 16, "threads_factor": 64}
FULL["stability"] = {"rate_factor": 64, "ratios": [0.1, 1, 10, 100],
                     "safeties": [0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1, 1.5, 2, 3, 5],
                     "dampings": [0, 0.3, 0.5, 0.7, 0.9, 0.95], "alphas": [0.05, 0.2, 0.5, 1], "servo_safety": 0.1,
                     "sigma3": 1e6, "max_steps": 400000}
QUICK = {"particles": 300, "rate_runs": [("rates", [256, 128, 64], None)], "moduli": [1e10, 1e8], "modulus_factor": 256,
         "threads_factor": 256,
         "stability": {"rate_factor": 256, "ratios": [1], "safeties": [0.3, 3], "dampings": [0.7], "alphas": [0.5, 1],
                       "servo_safety": 0.3, "sigma3": 1e6, "max_steps": 20000}}
# The contact-law comparison: setting C of Documentation/Rock.md on 2,000 grains (run A there).
FULL["contact_law"] = {"particles": 2000, "strain_per_step": 1e-7, "max_strain": 0.004, "tests": "ucs,tension"}
QUICK["contact_law"] = {"particles": 300, "strain_per_step": 4e-7, "max_strain": 0.004, "tests": "ucs"}
FULL["bonded_safeties"] = [0.05, 0.1, 0.2, 0.3, 0.5]
FULL["bonded_factor"] = 16
QUICK["bonded_safeties"] = [0.3, 0.5]
QUICK["bonded_factor"] = 256
# The engine's defaults (Plugin XML): Timestep Safety 0.1, Settling Damping 0.7, Servo Alpha 0.5,
# Bond Modulus 1e9 Pa = Young's Modulus 1e9 Pa (ratio 1).
DEFAULTS = {"safety": 0.1, "ratio": 1.0, "damping": 0.7, "alpha": 0.5}
PROBE = re.compile(r"stability: map (\S+) ratio (\S+) safety (\S+) damping (\S+) alpha (\S+) timestep (\S+) critical (\S+) "
                   r"status (\S+) peak (\S+) strain (\S+) steps (\d+) servo-max (\S+) servo-mean (\S+) max-stress (\S+) "
                   r"max-speed (\S+) wave-speed (\S+) nonfinite (\d+) last-good (\d) settled (\d) peaked (\d) "
                   r"broken-first (\d+) broken (\d+) bonds (\d+) seconds (\S+)")
PROBE_KEYS = ["ratio", "safety", "damping", "alpha", "timestep", "critical", "status", "peak", "strain", "steps",
              "servo_max", "servo_mean", "max_stress", "max_speed", "wave_speed", "nonfinite", "last_good", "settled",
              "peaked", "broken_first", "broken", "bonds", "seconds"]
OSCILLATION = 0.05  # servo: confining stress error above 5 % of the Confining Stress
DRIFT = 0.02        # results more than 2 % from the reference run
SWEEP = re.compile(r"rate-sweep: factor (\S+) strain rate (\S+) 1/s suggested (\S+) 1/s target (\S+) timestep (\S+) s "
                   r"UCS (\S+) Pa strain at peak (\S+) E (\S+) Pa inertial (\S+) ufr (\S+) steps (\d+) "
                   r"seconds (\S+) peaked (\d)")
KEYS = ["factor", "rate", "suggested", "target", "timestep", "ucs", "peak_strain", "E", "inertial", "ufr", "steps",
        "seconds", "peaked"]


def machine():
    cpu = platform.processor() or "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return "%s, %d cores" % (cpu, os.cpu_count() or 0)


def run(bench, args, work, name, reuse=True, parser=None):
    """Runs the bench (or reuses WORK/name.txt written by the same command); its rows."""
    parse_rows = parser or parse
    command = [bench] + args
    text = " ".join(command[1:])
    path = os.path.join(work, name + ".txt")
    if reuse and os.path.exists(path):
        with open(path) as f:
            lines = f.read().splitlines()
        if lines and lines[0] == "# command: " + text:
            return parse_rows(lines), lines[1][2:] if len(lines) > 1 else ""
    load = "load average %.2f %.2f %.2f before the run" % os.getloadavg()
    start = time.time()
    env = dict(os.environ, OMP_WAIT_POLICY="passive")
    partial = path + ".running"  # the output as it comes (a long run can be watched)
    with open(partial, "w") as f:
        code = subprocess.run(command, stdout=f, stderr=subprocess.STDOUT, env=env).returncode
    with open(partial) as f:
        output = f.read()
    os.remove(partial)
    if code != 0:
        sys.exit("%s failed (%d):\n%s" % (" ".join(command), code, output))
    wall = time.time() - start
    note = "%s; %.1f s wall for the whole command" % (load, wall)
    with open(path, "w") as f:
        f.write("# command: %s\n# %s\n%s" % (text, note, output))
    return parse_rows(output.splitlines()), note


def parse(lines):
    rows = []
    for line in lines:
        m = SWEEP.search(line)
        if m:
            row = {k: float(v) for k, v in zip(KEYS, m.groups())}
            row["ucs_text"] = m.group(6)
            rows.append(row)
    if not rows:
        sys.exit("no rate-sweep lines in the bench output")
    return rows


def save_chart(fig, out, name):
    """Writes the figure to OUT/images/NAME (80 dpi) and closes it; its path."""
    fig.tight_layout()
    image = os.path.join(out, "images", name)
    fig.savefig(image, dpi=80)
    plt.close(fig)
    return image


def pct(a, b):
    return 100.0 * (a - b) / b if b else math.nan


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(out)


def rates_section(bench, cfg, work, out):
    rows, notes, commands = [], [], []
    for name, factors, target in cfg["rate_runs"]:
        args = ["--particles", str(cfg["particles"]), "--threads", "1", "--tests", "rates", "--rate-factors",
                ",".join("%g" % f for f in factors)] + (["--inertial-target", "%g" % target] if target else []) + ROCK
        r, note = run(bench, args, work, name, cfg is FULL)
        rows += r
        notes.append(note)
        commands.append("`rockdem_bench_rock %s`" % " ".join(args))
    for r in rows:
        # Against the suggestion of the rule now (cemented: CEMENTED_TARGET).
        r["suggested_now"] = r["suggested"] * CEMENTED_TARGET / r["target"]
        r["factor"] = r["rate"] / r["suggested_now"]
    rows.sort(key=lambda r: r["factor"])
    ref = rows[0]
    fig, ax = plt.subplots(2, 2, figsize=(10, 7))
    f = [r["factor"] for r in rows]
    ax[0][0].semilogx(f, [pct(r["ucs"], ref["ucs"]) for r in rows], "o-", label="UCS")
    ax[0][0].semilogx(f, [pct(r["E"], ref["E"]) for r in rows], "s--", label="E")
    ax[0][0].axhspan(-1, 1, color="0.9")
    ax[0][0].set_ylabel("difference from %.3gx (%%)" % ref["factor"])
    ax[0][0].legend()
    ax[0][1].loglog(f, [r["ufr"] for r in rows], "o-")
    ax[0][1].axhline(0.01, color="0.5", ls=":")
    ax[0][1].set_ylabel("mean unbalanced force ratio to the peak")
    ax[1][0].loglog(f, [r["inertial"] for r in rows], "o-")
    ax[1][0].axhline(CEMENTED_TARGET, color="0.5", ls=":")
    ax[1][0].set_ylabel("inertial number at the peak")
    ax[1][1].loglog(f, [r["seconds"] for r in rows], "o-")
    ax[1][1].set_ylabel("run time (s)")
    for a in ax.flat:
        a.axvline(1.0, color="r", ls=":")
        a.set_xlabel("strain rate / Suggested Strain Rate")
    fig.suptitle("Unconfined compression, %d grains, stiff-bond rock: strain rate against accuracy" % cfg["particles"])
    image = save_chart(fig, out, "speed_accuracy_rates.png")
    body = table(["rate / suggested", "strain rate (1/s)", "UCS (Pa)", "UCS vs slowest", "E (Pa)", "E vs slowest",
                  "strain at peak", "inertial number at peak", "unbalanced force ratio", "steps", "run time (s)"],
                 [["%.3g" % r["factor"], "%.4g" % r["rate"], "%.5g" % r["ucs"], "%+.2f %%" % pct(r["ucs"], ref["ucs"]),
                   "%.4g" % r["E"], "%+.2f %%" % pct(r["E"], ref["E"]), "%.4g" % r["peak_strain"],
                   "%.3g" % r["inertial"], "%.3g" % r["ufr"], "%d" % r["steps"], "%.1f" % r["seconds"]] for r in rows])
    text = ("Commands: %s (%s; %s).\n\nSuggested Strain Rate %.4g 1/s (inertial number %g at the estimated peak; "
            "the runs' own suggestion at target %s: %s 1/s), timestep %.4g s.\n\n%s") % (
        ", ".join(commands), machine(), "; ".join(notes), ref["suggested_now"], CEMENTED_TARGET,
        "/".join(sorted(set("%g" % r["target"] for r in rows))),
        "/".join(sorted(set("%.4g" % r["suggested"] for r in rows))), ref["timestep"], body)
    return text, rows, [image]


def modulus_section(bench, cfg, work, out):
    rows = []
    notes = []
    commands = []
    for e in cfg["moduli"]:
        args = ["--particles", str(cfg["particles"]), "--threads", "1", "--tests", "rates", "--rate-factors",
                "%g" % cfg["modulus_factor"]] + ROCK
        args[args.index("--modulus") + 1] = "%g" % e
        r, note = run(bench, args, work, "modulus_%g" % e, cfg is FULL)
        r[0]["modulus"] = e
        rows.append(r[0])
        notes.append(note)
        commands.append(" ".join(args))
    ref = rows[0]
    soft = [ref["modulus"] / r["modulus"] for r in rows]
    fig, ax = plt.subplots(2, 2, figsize=(10, 7))
    ax[0][0].loglog(soft, [r["seconds"] for r in rows], "o-")
    ax[0][0].set_ylabel("run time (s)")
    ax[0][1].semilogx(soft, [pct(r["ucs"], ref["ucs"]) for r in rows], "o-")
    ax[0][1].set_ylabel("UCS difference from 1x (%)")
    ax[1][0].loglog(soft, [r["peak_strain"] for r in rows], "o-")
    ax[1][0].set_ylabel("strain at peak")
    ax[1][1].loglog(soft, [r["ucs"] / r["E"] if r["E"] > 0 else math.nan for r in rows], "o-")
    ax[1][1].set_ylabel("UCS / E")
    for a in ax.flat:
        a.set_xlabel("grain and bond modulus: times softer than %g Pa" % ref["modulus"])
    fig.suptitle("Modulus scaling, strengths kept, %d grains, %g x the Suggested Strain Rate"
                 % (cfg["particles"], cfg["modulus_factor"]))
    image = save_chart(fig, out, "speed_accuracy_modulus.png")
    body = table(["modulus (Pa)", "softer", "UCS (Pa)", "UCS vs 1x", "strain at peak", "E (Pa)", "UCS / E",
                  "peak within Max Strain", "timestep (s)", "steps", "run time (s)"],
                 [["%g" % r["modulus"], "%g" % s, "%.5g" % r["ucs"], "%+.2f %%" % pct(r["ucs"], ref["ucs"]),
                   "%.4g" % r["peak_strain"], "%.4g" % r["E"],
                   "%.4g" % (r["ucs"] / r["E"] if r["E"] > 0 else math.nan), "yes" if r["peaked"] else "no",
                   "%.3g" % r["timestep"], "%d" % r["steps"], "%.1f" % r["seconds"]] for r, s in zip(rows, soft)])
    text = "Commands: `rockdem_bench_rock %s` with `--modulus` each of %s (%s; %s).\n\n%s" % (
        commands[0], ", ".join("%g" % e for e in cfg["moduli"]), machine(), "; ".join(notes), body)
    return text, rows, [image]


GPU_PATH = re.compile(r"^rate-sweep-path: factor \S+ (.*)$")


def parse_with_path(lines):
    """parse() and the path the test stepped on (bench --device), in each row's "path"."""
    rows = parse(lines)
    paths = [m.group(1) for m in (GPU_PATH.search(line) for line in lines) if m]
    for row, path in zip(rows, paths):
        row["path"] = path
    return rows


def threads_section(bench, cfg, work, out):
    """The same test on 1 and 2 CPU threads and on the GPU (Vulkan) backend (bench --device gpu: the
    Vulkan device of the machine, lavapipe here, or the CPU when none can run it; the row says which)."""
    rows = []
    notes = []
    for threads, device in ((1, "cpu"), (2, "cpu"), (1, "gpu")):
        args = ["--particles", str(cfg["particles"]), "--threads", str(threads), "--tests", "rates",
                "--rate-factors", "%g" % cfg["threads_factor"]] + ROCK + (["--device", "gpu"] if device == "gpu" else [])
        r, note = run(bench, args, work, "threads_%d" % threads if device == "cpu" else "threads_gpu", cfg is FULL,
                      parse_with_path)
        r[0]["threads"] = threads
        r[0]["device"] = device
        rows.append(r[0])
        notes.append(note)
    cpu1, cpu2, gpu = rows
    same = cpu1["ucs_text"] == cpu2["ucs_text"] and cpu1["steps"] == cpu2["steps"]
    gpu_same = cpu1["ucs_text"] == gpu["ucs_text"] and cpu1["steps"] == gpu["steps"]
    on_gpu = gpu.get("path", "").startswith("GPU Vulkan")
    lavapipe = "llvmpipe" in gpu.get("path", "") or "lavapipe" in gpu.get("path", "")

    def label(r):
        if r["device"] == "cpu":
            return "CPU, %d thread%s" % (r["threads"], "s" if r["threads"] > 1 else "")
        return "GPU requested (`--device gpu`): %s" % r.get("path", "path not printed")
    body = table(["path", "UCS (Pa), all digits", "steps", "run time (s)"],
                 [[label(r), r["ucs_text"], "%d" % r["steps"], "%.1f" % r["seconds"]] for r in rows])
    if on_gpu:
        device_note = ("The GPU row ran on the Vulkan backend%s: UCS and step count against 1 CPU thread bit for bit: "
                       "**%s**; its time against 1 CPU thread: %.2f x." % (
                           " on lavapipe, Mesa's Vulkan driver that runs the compute shaders on the same two CPU cores "
                           "(a CPU emulation of a GPU: its time is not a GPU's time)" if lavapipe else "",
                           "yes" if gpu_same else "NO",
                           gpu["seconds"] / cpu1["seconds"] if cpu1["seconds"] > 0 else math.nan))
    else:
        device_note = ("The GPU request fell back to the CPU (%s): no GPU time was measured; the row only shows that "
                       "the fallback gives the CPU's answer (bit for bit: %s)." % (gpu.get("path", "?"),
                                                                                  "yes" if gpu_same else "NO"))
    text = "Command: `rockdem_bench_rock --particles %d --threads T --tests rates --rate-factors %g %s` with T 1 and 2, " \
        "and with T 1 and `--device gpu` (%s; %s).\n\n%s\n\n" \
        "Bitwise agreement of the UCS and the step count, 1 and 2 CPU threads: **%s**; speed-up %.2f. %s" % (
            cfg["particles"], cfg["threads_factor"], " ".join(ROCK), machine(), "; ".join(notes), body,
            "yes" if same else "NO", cpu1["seconds"] / cpu2["seconds"] if cpu2["seconds"] > 0 else math.nan,
            device_note)
    return text, [{k: v for k, v in r.items() if isinstance(v, float)} for r in rows], []


def parse_probes(lines):
    """The "stability:" lines of the bench (each with the engine's message on the next line when it stopped the run)."""
    rows = []
    for line in lines:
        m = PROBE.search(line)
        if m:
            row = {"map": m.group(1), "message": ""}
            for k, v in zip(PROBE_KEYS, m.groups()[1:]):
                row[k] = v if k == "status" else float(v)
            rows.append(row)
        elif line.startswith("  message: ") and rows:
            rows[-1]["message"] = line[len("  message: "):]
    if not rows:
        sys.exit("no stability lines in the bench output")
    return rows


def classify(rows, reference):
    """Marks each run: unstable (by what the run left, not by whether the engine said so: stopped by the
    engine, a non-finite value, or more than 1 % of the bonds broken in the first 50 steps, where every stable
    run breaks none: the instability of a cemented specimen breaks its bonds before it produces a NaN),
    detected (the engine stopped it with its message and kept the last good state), drift (stable, peak more
    than DRIFT from the reference), oscillating (servo error above OSCILLATION)."""
    for r in rows:
        ref = reference(r)
        r["refused"] = r["status"] == "stopped" and r["message"].startswith("input refused")
        r["diff"] = (r["peak"] - ref["peak"]) / ref["peak"] if ref and ref["peak"] > 0 and r["peak"] > 0 else math.nan
        r["unstable"] = not r["refused"] and (
            r["status"] == "stopped" or r["nonfinite"] > 0 or r["broken_first"] > 0.01 * r["bonds"])
        r["detected"] = r["unstable"] and r["status"] == "stopped" and "went unstable" in r["message"] \
            and r["last_good"] == 1
        r["drift"] = not r["unstable"] and not r["refused"] and abs(r["diff"]) > DRIFT
        r["oscillating"] = r["servo_max"] > OSCILLATION


def stability_section(bench, cfg, work, out):
    st = cfg["stability"]
    common = ["--particles", str(cfg["particles"]), "--threads", "1"] + ROCK + [
        "--rate-factor", "%g" % st["rate_factor"], "--max-steps", "%d" % st["max_steps"]]
    ts_args = common + ["--tests", "tsmap", "--bond-ratios", ",".join("%g" % v for v in st["ratios"]),
                        "--safeties", ",".join("%g" % v for v in st["safeties"])]
    servo_args = common + ["--tests", "servomap", "--safety", "%g" % st["servo_safety"], "--sigma3", "%g" % st["sigma3"],
                           "--dampings", ",".join("%g" % v for v in st["dampings"]),
                           "--servo-alphas", ",".join("%g" % v for v in st["alphas"])]
    ts, ts_note = run(bench, ts_args, work, "stability_timestep", cfg is FULL, parse_probes)
    sv, sv_note = run(bench, servo_args, work, "stability_servo", cfg is FULL, parse_probes)
    # Map 1: the reference of each ratio is its smallest-safety run; map 2: the run at the default damping and alpha.
    smallest = {}
    for r in ts:
        if r["ratio"] not in smallest or r["safety"] < smallest[r["ratio"]]["safety"]:
            smallest[r["ratio"]] = r
    classify(ts, lambda r: smallest[r["ratio"]])
    default = [r for r in sv if r["damping"] == DEFAULTS["damping"] and r["alpha"] == DEFAULTS["alpha"]]
    classify(sv, lambda r: default[0] if default else None)
    rows = ts + sv
    unstable = [r for r in rows if r["unstable"]]
    detected = [r for r in unstable if r["detected"]]
    nonfinite = [r for r in rows if r["nonfinite"] > 0]

    fig, ax = plt.subplots(1, 2, figsize=(12, 5))
    styles = [("stable, within 2 % of the reference", "o", "tab:green"), ("drift above 2 %", "^", "tab:orange"),
              ("servo error above 5 %", "D", "tab:purple"), ("unstable, stopped by the engine", "s", "k"),
              ("unstable, NOT stopped by the engine", "X", "tab:red"), ("refused (input error)", "x", "0.5")]

    def style(r):
        if r["refused"]:
            return 5
        if r["unstable"]:
            return 3 if r["detected"] else 4
        if r["oscillating"]:
            return 2
        return 1 if r["drift"] else 0

    def draw(a, data, x, y):
        for k, (label, marker, colour) in enumerate(styles):
            pts = [r for r in data if style(r) == k]
            if pts:
                a.scatter([r[x] for r in pts], [r[y] for r in pts], marker=marker, color=colour, s=60, label=label)
        for r in data:
            if math.isfinite(r["diff"]) and not r["unstable"]:
                a.annotate("%+.0f" % (100 * r["diff"]), (r[x], r[y]), textcoords="offset points", xytext=(0, 7),
                           ha="center", fontsize=7)

    draw(ax[0], ts, "safety", "ratio")
    ax[0].set_xscale("log")
    ax[0].set_yscale("log")
    ax[0].axvline(1.0, color="0.5", ls=":")
    ax[0].text(1.02, max(st["ratios"]), "largest Timestep Safety\nthe engine accepts", fontsize=7, va="top")
    ax[0].scatter([DEFAULTS["safety"]], [DEFAULTS["ratio"]], marker="*", s=300, facecolors="none", edgecolors="b",
                  label="defaults")
    ax[0].set_xlabel("Timestep Safety (above 1: forced, x the critical timestep)")
    ax[0].set_ylabel("Bond Modulus / grain Young's Modulus")
    ax[0].set_title("unconfined, %g x Suggested Strain Rate; %% = UCS vs smallest safety" % st["rate_factor"], fontsize=9)
    draw(ax[1], sv, "alpha", "damping")
    ax[1].scatter([DEFAULTS["alpha"]], [DEFAULTS["damping"]], marker="*", s=300, facecolors="none", edgecolors="b",
                  label="defaults")
    ax[1].set_xscale("log")
    ax[1].set_xlabel("Servo Alpha")
    ax[1].set_ylabel("Settling Damping")
    ax[1].set_title("triaxial %g Pa, Timestep Safety %g; %% = sigma1 vs defaults" % (st["sigma3"], st["servo_safety"]),
                    fontsize=9)
    ax[0].legend(fontsize=7, loc="lower left")
    fig.suptitle("Stability map, %d grains, stiff-bond rock" % cfg["particles"])
    image = save_chart(fig, out, "atlas_stability.png")

    def cell(r):
        if r["refused"]:
            return "refused"
        if r["unstable"]:
            return "**unstable, stopped**" if r["detected"] else "**UNSTABLE, not stopped** (%d bonds broken in 50 steps)" \
                % r["broken_first"]
        return "%+.1f %%" % (100 * r["diff"]) if math.isfinite(r["diff"]) else "-"

    safeties = sorted(set(r["safety"] for r in ts))
    ts_table = table(["Bond Modulus / Young's Modulus", "critical timestep (s)"] + ["%g" % v for v in safeties],
                     [["%g" % ratio, "%.3g" % smallest[ratio]["critical"]] +
                      [next((cell(r) for r in ts if r["ratio"] == ratio and r["safety"] == v), "") for v in safeties]
                      for ratio in sorted(smallest)])
    alphas = sorted(set(r["alpha"] for r in sv))
    sv_table = table(["Settling Damping"] + ["Servo Alpha %g" % a for a in alphas],
                     [["%g" % d] + [next(("%s; sigma1 %.4g Pa; servo error max %.2f %%, mean %.2f %%; %d steps" % (
                         cell(r), r["peak"], 100 * r["servo_max"], 100 * r["servo_mean"], r["steps"])
                         for r in sv if r["damping"] == d and r["alpha"] == a), "") for a in alphas]
                      for d in sorted(set(r["damping"] for r in sv))])
    # Numbers elided (times, energies, Timestep Safety values), so that one kind of message is listed once.
    messages = sorted(set(re.sub(r"(?<![\w.])[-+]?\d[\d.]*(e[-+]?\d+)?", "...",
                                 re.sub(r"particle \d+", "particle N", r["message"])) for r in detected))
    text = ("Commands: `rockdem_bench_rock %s` and `rockdem_bench_rock %s` (%s; %s; %s).\n\n"
            "**Counts: %d runs, %d unstable, %d of them detected (stopped by the engine with its message, the model "
            "at its last good state), %d runs whose output held a non-finite value.**\n\n"
            "Timestep Safety against the bond-to-contact stiffness ratio (unconfined compression; each cell the UCS "
            "against the smallest Timestep Safety of its row, or what went wrong):\n\n%s\n\n"
            "Settling Damping against Servo Alpha (triaxial, Confining Stress %g Pa; each cell sigma1 at the peak "
            "against the defaults, Settling Damping %g and Servo Alpha %g):\n\n%s\n\n"
            "The engine's messages (numbers elided): %s") % (
        " ".join(ts_args), " ".join(servo_args), machine(), ts_note, sv_note, len(rows), len(unstable), len(detected),
        len(nonfinite), ts_table, st["sigma3"], DEFAULTS["damping"], DEFAULTS["alpha"], sv_table,
        "; ".join("\"%s\"" % m for m in messages) if messages else "none")
    print("atlas: stability: %d runs, %d unstable, %d detected, %d with a non-finite output"
          % (len(rows), len(unstable), len(detected), len(nonfinite)), flush=True)
    if nonfinite:
        sys.exit("atlas: FAILED: a non-finite value reached the output of %d run(s)" % len(nonfinite))
    numbers = [{k: v for k, v in r.items() if k in ("peak", "servo_max", "seconds", "timestep")} for r in rows]
    return text, numbers, [image]


def bonded_args(cfg, factor, extra):
    args = ["--particles", str(cfg["particles"]), "--threads", "1", "--tests", "rates", "--rate-factors",
            "%g" % factor] + extra + ROCK
    return args


def timestep_bonded_section(bench, cfg, work, out):
    """UCS, E, steps and run time at each Timestep Safety on the cemented specimen (error against the smallest)."""
    rows, notes = [], []
    for safety in cfg["bonded_safeties"]:
        args = bonded_args(cfg, cfg["bonded_factor"], ["--safety", "%g" % safety])
        r, note = run(bench, args, work, "timestep_bonded_%g" % safety, cfg is FULL)
        r[0]["safety"] = safety
        rows.append(r[0])
        notes.append(note)
    ref = rows[0]
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    s = [r["safety"] for r in rows]
    ax[0].semilogx(s, [pct(r["ucs"], ref["ucs"]) for r in rows], "o-", label="UCS")
    ax[0].semilogx(s, [pct(r["E"], ref["E"]) for r in rows], "s--", label="E")
    ax[0].axhspan(-2, 2, color="0.9")
    ax[0].axvline(DEFAULTS["safety"], color="b", ls=":")
    ax[0].set_xlabel("Timestep Safety")
    ax[0].set_ylabel("difference from Timestep Safety %g (%%)" % ref["safety"])
    ax[0].legend()
    ax[1].loglog([r["steps"] for r in rows], [r["seconds"] for r in rows], "o-")
    for r in rows:
        ax[1].annotate("%g" % r["safety"], (r["steps"], r["seconds"]), textcoords="offset points", xytext=(4, 4),
                       fontsize=8)
    ax[1].set_xlabel("steps")
    ax[1].set_ylabel("run time (s)")
    fig.suptitle("Timestep Safety on the cemented specimen, %d grains, %g x the Suggested Strain Rate"
                 % (cfg["particles"], cfg["bonded_factor"]))
    image = save_chart(fig, out, "atlas_timestep_bonded.png")
    body = table(["Timestep Safety", "timestep (s)", "UCS (Pa)", "UCS vs smallest", "E (Pa)", "E vs smallest",
                  "strain at peak", "steps", "run time (s)"],
                 [["%g" % r["safety"], "%.3g" % r["timestep"], "%.5g" % r["ucs"], "%+.2f %%" % pct(r["ucs"], ref["ucs"]),
                   "%.4g" % r["E"], "%+.2f %%" % pct(r["E"], ref["E"]), "%.4g" % r["peak_strain"], "%d" % r["steps"],
                   "%.1f" % r["seconds"]] for r in rows])
    text = "Command: `rockdem_bench_rock %s` with `--safety` each of %s (%s; %s).\n\n%s" % (
        " ".join(bonded_args(cfg, cfg["bonded_factor"], ["--safety", "S"])),
        ", ".join("%g" % v for v in cfg["bonded_safeties"]), machine(), "; ".join(notes), body)
    return text, rows, [image]


LAW_PATTERNS = {
    "porosity": r"Compact Elements: porosity \S+ -> (\S+) ",
    "locked_in": r"locked-in isotropic stress (\S+) Pa",
    "compact_steps": r"\d+ stages, (\d+) steps\.",
    "bonds": r"installed (\d+) bonds",
    "coordination": r"bonded coordination (\S+) ",
    "ucs": r"^UCS (\S+) Pa at strain",
    "peak_strain": r"^UCS \S+ Pa at strain (\S+);",
    "E": r"^UCS .*; E (\S+) Pa;",
    "nu": r"^UCS .*; nu (\S+);",
    "ucs_steps": r"^UCS .*\((\d+) steps, \S+ s\)",
    "ucs_seconds": r"^UCS .*\(\d+ steps, (\S+) s\)",
    "rate": r"rate: strain rate (\S+) 1/s",
    "timestep": r"\(timestep (\S+) s\)",
    "broken_peak": r"broken at the peak: \d+ \((\S+) % of bonds\)",
    "near_platens": r"broken within 2 diameters of a platen: (\S+) %",
    "discs": r"^  DFN: (\d+) discs",
    "disc_share": r"^  DFN: .*, (\S+) % of broken bonds in discs",
    "tension": r"^direct tension (\S+) Pa",
    "tension_steps": r"^direct tension .*\((\d+) steps, \S+ s\)",
    "tension_seconds": r"^direct tension .*\(\d+ steps, (\S+) s\)",
    "total": r"^total (\S+) s",
}


def first_matches(patterns, lines):
    """{key: the number the first line matching patterns[key] holds (nan when none does)}."""
    row = {}
    for key, pattern in patterns.items():
        row[key] = math.nan
        for line in lines:
            m = re.search(pattern, line)
            if m:
                row[key] = float(m.group(1))
                break
    return row


def parse_law(lines):
    """The figures of one --tests ucs[,tension] bench run (absent ones: nan)."""
    row = first_matches(LAW_PATTERNS, lines)
    if math.isnan(row["ucs"]):
        sys.exit("no UCS line in the bench output")
    return [row]


def law_args(cfg, law, strain_per_step):
    c = cfg["contact_law"]
    return ["--particles", str(c["particles"]), "--threads", "1", "--tests", c["tests"], "--contact-law", law,
            "--strain-per-step", "%.4g" % strain_per_step] + ROCK[:-2] + ["--max-strain", "%g" % c["max_strain"]]


def contact_law_section(bench, cfg, work, out):
    """Hertz-Mindlin against linear contacts on the same rock, each specimen built with its law."""
    c = cfg["contact_law"]
    runs, notes = [], []
    hertz, note = run(bench, law_args(cfg, "hertz", c["strain_per_step"]), work, "contact_law_hertz", cfg is FULL,
                      parse_law)
    runs.append(("Hertz-Mindlin", "%.4g" % c["strain_per_step"], hertz[0]))
    notes.append(note)
    linear, note = run(bench, law_args(cfg, "linear", c["strain_per_step"]), work, "contact_law_linear", cfg is FULL,
                       parse_law)
    runs.append(("linear, same strain per step", "%.4g" % c["strain_per_step"], linear[0]))
    notes.append(note)
    # The same strain rate: the strain per step scaled by the linear specimen's timestep.
    same = c["strain_per_step"] * linear[0]["timestep"] / hertz[0]["timestep"]
    linear_rate, note = run(bench, law_args(cfg, "linear", same), work, "contact_law_linear_same_rate", cfg is FULL,
                            parse_law)
    runs.append(("linear, same strain rate", "%.4g" % same, linear_rate[0]))
    notes.append(note)
    ref = hertz[0]
    n = c["particles"]

    def steps(r):
        return sum(v for v in (r["compact_steps"], r["ucs_steps"], r["tension_steps"]) if math.isfinite(v))

    def fmt(v, f):
        return f % v if math.isfinite(v) else "-"
    rows = []
    for name, sps, r in runs:
        rows.append([name, sps, fmt(r["timestep"], "%.4g"), fmt(r["rate"], "%.3g"), fmt(r["porosity"], "%.3f"),
                     fmt(r["locked_in"] / 1e3, "%.1f kPa"), "%d (%.2f)" % (r["bonds"], r["coordination"]),
                     "%.3g MPa (%+.1f %%)" % (r["ucs"] / 1e6, pct(r["ucs"], ref["ucs"])),
                     "%.3g GPa (%+.1f %%)" % (r["E"] / 1e9, pct(r["E"], ref["E"])), fmt(r["nu"], "%.3f"),
                     fmt(r["tension"] / 1e6, "%.3g MPa") + (" (%+.1f %%)" % pct(r["tension"], ref["tension"])
                                                             if math.isfinite(r["tension"]) else ""),
                     fmt(r["ucs"] / r["tension"], "%.2f"), fmt(r["broken_peak"], "%.1f %%"),
                     fmt(r["near_platens"], "%.1f %%"),
                     "%d discs, %.1f %% of broken bonds" % (r["discs"], r["disc_share"]),
                     "%d / %d / %d" % (r["compact_steps"], r["ucs_steps"], r["tension_steps"] if math.isfinite(
                         r["tension_steps"]) else 0),
                     "%.3g" % (n * steps(r)), fmt(r["total"], "%.1f")])
        r["particle_steps"] = float(n * steps(r))
    body = table(["law", "strain per step", "timestep (s)", "strain rate (1/s)", "porosity", "locked-in",
                  "bonds (coordination)", "UCS (vs Hertz)", "E (vs Hertz)", "nu", "sigma_t (vs Hertz)",
                  "UCS / sigma_t", "broken at the peak", "broken near the platens", "DFN at 70 % of the peak",
                  "steps: compact / UCS / tension", "particle-steps", "wall time (s)"], rows)
    text = "Command: `rockdem_bench_rock %s` with `--contact-law` hertz and linear, and linear again at the " \
        "strain per step that gives Hertz's strain rate (%s; %s).\n\n%s" % (
            " ".join(law_args(cfg, "LAW", c["strain_per_step"])), machine(), "; ".join(notes), body)
    return text, [{k: v for k, v in r.items() if math.isfinite(v)} for _, _, r in runs], []



# The resolution sweep (issue 17 "Resolution"): the same rock at five specimen sizes (grains across
# the width: about 5, 7, 9, 12 and 16), three pack seeds each. Per size and seed two bench runs, each
# building the same specimen from the seed: "ucs" (unconfined, to 70 % of the peak; with "triaxial"
# also two triaxial peaks at 10 and 20 % of that UCS, for the friction angle) and "tension" (direct
# tension). The runs are made in the order of RESOLUTION["order"] (the cheap sizes first, then the
# finest size's unconfined and tension tests, then the triaxial tests of the larger sizes), so that
# a sweep cut short by the clock keeps the most useful runs; --no-new-runs writes the table from the
# runs in WORK and lists the missing ones.
FULL["resolution"] = {
    "sizes": [250, 700, 1500, 3500, 8000, 17000, 47000, 136000], "seeds": [1, 2, 3], "confining": [0.1, 0.2],
    "strain_per_step": 1e-7, "tension_strain_per_step": 1e-8, "ucs_max_strain": 0.006, "triaxial_max_strain": 0.01,
    "tension_max_strain": 0.0003,
    # (size, seed, kind): "ucs_triaxial" replaces "ucs" where it is planned (the same unconfined test).
    "order": ([(n, s, k) for n in (250, 700, 1500) for s in (1, 2, 3) for k in ("ucs_triaxial", "tension")]
              + [(8000, s, k) for s in (1, 2, 3) for k in ("ucs", "tension")]
              + [(3500, s, k) for s in (1, 2, 3) for k in ("ucs_triaxial", "tension")]
              # (fifteenth session: a sixth size, 20 across, unconfined and tension only: its triaxial
              # tests would take about 50 minutes per seed on one thread)
              + [(17000, s, k) for s in (1, 2, 3) for k in ("ucs", "tension")]
              + [(8000, s, "ucs_triaxial") for s in (1, 2, 3)]
              # (sixteenth session: the friction angle at 20 across, seed 1 only: about an hour)
              + [(17000, 1, "ucs_triaxial")]
              # (nineteenth session: 40 and 28 across, seed 1, unconfined only, on two threads - the same
              # bits as one, Determinism - about 3.5e9 and 1.3e9 particle-steps)
              + [(136000, 1, "ucs"), (47000, 1, "ucs")]
              # (twentieth session: the friction angle at 20 across for seeds 2 and 3, one thread each,
              # run side by side)
              + [(17000, 2, "ucs_triaxial"), (17000, 3, "ucs_triaxial")]),
    "threads": {136000: 2, 47000: 2}}
# The same sweep undamped (nineteenth session): is the UCS's rise with the size, which does not level off
# by 20 across under Settling Damping 0.7, the damping's? The unconfined test at Settling Damping 0 and
# 5e-8 per step (the recipe of "2D section against a 3D slab", whose 8,000-grain boxes are these
# specimens: the same seeds give the same UCS to the last digit), tension at 1e-8 per step as above.
FULL["resolution_undamped"] = {
    "sizes": [250, 700, 1500, 3500, 8000, 17000, 47000], "seeds": [1, 2, 3], "confining": [],
    "strain_per_step": 5e-8, "tension_strain_per_step": 1e-8, "ucs_max_strain": 0.005, "tension_max_strain": 0.0003,
    "triaxial_max_strain": 0.01, "extra": ["--damping", "0"], "ucs_extra": ["--min-peak-strain", "2e-05"],
    "title": ", undamped (Settling Damping 0)",
    # The unconfined tests first (the question), the finest size before 8,000; then tension; then
    # (added once the damped 28-across run had shown a denser pack there) 28 across, seed 1, on two threads.
    "order": ([(n, s, "ucs") for n in (250, 700, 1500, 3500, 17000, 8000) for s in (1, 2, 3)]
              + [(n, s, "tension") for n in (250, 700, 1500, 3500, 8000, 17000) for s in (1, 2, 3)]
              + [(47000, 1, "ucs")]),
    "threads": {47000: 2}}
QUICK["resolution_undamped"] = {
    "sizes": [120, 250], "seeds": [1, 2], "confining": [],
    "strain_per_step": 4e-7, "tension_strain_per_step": 4e-7, "ucs_max_strain": 0.006, "tension_max_strain": 0.0004,
    "triaxial_max_strain": 0.01, "extra": ["--damping", "0"], "ucs_extra": ["--min-peak-strain", "6e-05"],
    "title": ", undamped (Settling Damping 0)",
    "order": [(n, s, k) for n in (120, 250) for s in (1, 2) for k in ("ucs", "tension")]}
QUICK["resolution"] = {
    "sizes": [120, 250], "seeds": [1, 2], "confining": [0.2],
    "strain_per_step": 4e-7, "tension_strain_per_step": 4e-7, "ucs_max_strain": 0.006, "triaxial_max_strain": 0.01,
    "tension_max_strain": 0.0004,
    "order": [(n, s, k) for n in (120, 250) for s in (1, 2) for k in ("ucs_triaxial", "tension")]}
# The resolution runs' figures: those of the contact-law runs and the specimen's size, the
# build time, the rate against the suggestion and the tensile strain.
RES_PATTERNS = dict(
    LAW_PATTERNS,
    across=r"^specimen: \d+ particles, .* (\S+) mean diameters across",
    particles=r"^specimen: (\d+) particles",
    build_seconds=r"^cement: .*\((\S+) s\)$",
    rate_factor=r"rate: strain rate \S+ 1/s = (\S+) x Suggested",
    tension_strain=r"^direct tension \S+ Pa at strain (\S+);",
)
TRIAXIAL = re.compile(r"^triaxial sigma3 \S+ Pa \((\d+) % UCS\): (peak|no peak within Max Strain: largest) sigma1 (\S+) "
                      r"Pa at strain (\S+) \((\d+) steps, (\S+) s\)")


def parse_resolution(lines):
    """The figures of one resolution run (absent ones: nan); triaxial: [(fraction of UCS, sigma1, peaked, steps)]."""
    row = first_matches(RES_PATTERNS, lines)
    row["triaxial"] = []
    for line in lines:
        m = TRIAXIAL.search(line)
        if m:
            row["triaxial"].append((float(m.group(1)) / 100.0, float(m.group(3)), m.group(2) == "peak",
                                    float(m.group(5)), float(m.group(6))))
    if math.isnan(row["particles"]) or math.isnan(row["total"]):
        sys.exit("resolution: an incomplete bench output (no specimen or total line)")
    return [row]


def resolution_args(c, n, seed, kind):
    tests = {"ucs": "ucs", "ucs_triaxial": "ucs,triaxial", "tension": "tension"}[kind]
    strain = {"ucs": c["ucs_max_strain"], "ucs_triaxial": c["triaxial_max_strain"],
              "tension": c["tension_max_strain"]}[kind]
    return (["--particles", str(n), "--seed", str(seed), "--threads", str(c.get("threads", {}).get(n, 1)),
             "--tests", tests]
            + (["--confining", ",".join("%g" % f for f in c["confining"])] if kind == "ucs_triaxial" else [])
            + c.get("extra", [])
            + ["--strain-per-step", "%g" % (c["tension_strain_per_step"] if kind == "tension" else c["strain_per_step"])]
            + ROCK[:-2] + ["--max-strain", "%g" % strain]
            + (c.get("ucs_extra", []) if kind != "tension" else []))


def friction_angle(ucs, triaxial):
    """Least-squares sigma1 = a + b sigma3 through (0, UCS) and the triaxial peaks; phi in degrees (nan if a
    test reached no peak or none ran)."""
    if not triaxial or not all(peaked for _, _, peaked, _, _ in triaxial):
        return math.nan
    s3 = [0.0] + [f * ucs for f, _, _, _, _ in triaxial]
    s1 = [ucs] + [v for _, v, _, _, _ in triaxial]
    m3, m1 = sum(s3) / len(s3), sum(s1) / len(s1)
    b = sum((x - m3) * (y - m1) for x, y in zip(s3, s1)) / sum((x - m3) ** 2 for x in s3)
    return math.degrees(math.asin((b - 1.0) / (b + 1.0)))


def mean_sd(values):
    v = [x for x in values if math.isfinite(x)]
    if not v:
        return math.nan, math.nan, 0
    m = sum(v) / len(v)
    sd = math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1)) if len(v) > 1 else math.nan
    return m, sd, len(v)


def resolution_runs(bench, cfg, work, new_runs, key="resolution"):
    """Runs (or reuses) the sweep's bench runs in their order; {(size, seed, kind): figures}, the missing runs."""
    c = cfg[key]
    done, missing = {}, []
    for n, seed, kind in c["order"]:
        args = resolution_args(c, n, seed, kind)
        name = "%s_%d_s%d_%s" % (key, n, seed, kind)
        path = os.path.join(work, name + ".txt")
        have = False
        if cfg is FULL and os.path.exists(path):
            with open(path) as f:
                have = f.readline().rstrip("\n") == "# command: " + " ".join(args)
        if not have and not new_runs:
            missing.append((n, seed, kind))
            continue
        if not have:
            print("atlas: resolution: %s (started %s, load average %.2f)"
                  % (name, time.strftime("%H:%M:%S UTC", time.gmtime()), os.getloadavg()[0]), flush=True)
        r, note = run(bench, args, work, name, cfg is FULL, parse_resolution)
        r[0]["wall"] = float(re.search(r"(\S+) s wall for the whole command", note).group(1))
        r[0]["load"] = float(re.search(r"load average (\S+) ", note).group(1))
        r[0]["args"] = args
        done[(n, seed, kind)] = r[0]
    return done, missing



RES_PROPS = [("ucs", "UCS", 1e6, "MPa", "%.2f"), ("E", "E", 1e9, "GPa", "%.2f"), ("nu", "nu", 1.0, "", "%.3f"),
             ("tension", "sigma_t", 1e6, "MPa", "%.3f"), ("phi", "friction angle", 1.0, "deg", "%.1f")]
CONVERGED = 0.05  # within 5 % of the finest size


def resolution_records(cfg, done):
    """One record per size and seed: the unconfined figures (from "ucs_triaxial" where it ran, else "ucs"),
    sigma_t, the friction angle, and the cost of each (seconds the bench measured: the specimen's
    compaction and cementing plus the test(s); particle-steps)."""
    per = {}
    for (n, seed, kind), r in sorted(done.items(), key=lambda kv: kv[0][2] != "ucs_triaxial"):
        rec = per.setdefault((n, seed), {"n": n, "seed": seed, "commands": {}})
        rec["commands"][kind] = r
        build = r["build_seconds"]
        if kind in ("ucs", "ucs_triaxial"):
            if "ucs" in rec:  # both ran: the same specimen and test, so the same figures
                rec["ucs_twice"] = (rec["ucs"], r["ucs"])
                continue
            for k in ("across", "porosity", "bonds", "coordination", "ucs", "peak_strain", "E", "nu", "timestep",
                      "rate", "rate_factor"):
                rec[k] = r[k]
            rec["sec_ucs"] = build + r["ucs_seconds"]
            rec["ps_ucs"] = n * (r["compact_steps"] + r["ucs_steps"])
            if kind == "ucs_triaxial":
                rec["phi"] = friction_angle(r["ucs"], r["triaxial"])
                rec["triaxial"] = r["triaxial"]
                rec["sec_phi"] = rec["sec_ucs"] + sum(t[4] for t in r["triaxial"])
                rec["ps_phi"] = rec["ps_ucs"] + n * sum(t[3] for t in r["triaxial"])
        else:
            rec["tension"] = r["tension"]
            rec["tension_strain"] = r["tension_strain"]
            rec["sec_tension"] = build + r["tension_seconds"]
            rec["ps_tension"] = n * (r["compact_steps"] + r["tension_steps"])
    return per


def resolution_stats(cfg, per, key="resolution"):
    c = cfg[key]
    stats = {}
    for n in c["sizes"]:
        recs = [per[(n, s)] for s in c["seeds"] if (n, s) in per]
        if not recs:
            continue
        st = {"n": n, "across": mean_sd([r.get("across", math.nan) for r in recs])[0],
              "porosity": mean_sd([r.get("porosity", math.nan) for r in recs])[0],
              "coordination": mean_sd([r.get("coordination", math.nan) for r in recs])[0],
              "rate_factor": mean_sd([r.get("rate_factor", math.nan) for r in recs])[0]}
        for key, _, _, _, _ in RES_PROPS:
            st[key] = mean_sd([r.get(key, math.nan) for r in recs])
            st[key + "_values"] = [r.get(key, math.nan) for r in recs if math.isfinite(r.get(key, math.nan))]
        for cost in ("sec_ucs", "ps_ucs", "sec_tension", "ps_tension", "sec_phi", "ps_phi"):
            st[cost] = mean_sd([r.get(cost, math.nan) for r in recs])[0]
        stats[n] = st
    return stats


def convergence(stats, key):
    """(the finest size with this property, the smallest size from which every size's mean lies within 5 % of
    the finest's, the smallest size from which every seed of every size does) - None where none does."""
    sizes = [n for n in sorted(stats) if stats[n][key][2] > 0]
    if len(sizes) < 2:
        return None, None, None
    ref = stats[sizes[-1]][key][0]
    mean_ok = [abs(stats[n][key][0] - ref) <= CONVERGED * abs(ref) for n in sizes[:-1]]
    seed_ok = [all(abs(v - ref) <= CONVERGED * abs(ref) for v in stats[n][key + "_values"]) for n in sizes[:-1]]

    def first(ok):
        for i in range(len(ok)):
            if all(ok[i:]):
                return sizes[i]
        return None
    return sizes[-1], first(mean_ok), first(seed_ok)


def resolution_section(bench, cfg, work, out, new_runs=True, sweep="resolution"):
    """Grains across the width against UCS, E, nu, sigma_t and the friction angle over pack seeds: error against
    the finest size, cost (seconds, particle-steps) against error, and where each property converges within 5 %.
    sweep: the sweep's configuration (cfg[sweep]), also its runs' and chart's name."""
    c = cfg[sweep]
    done, missing = resolution_runs(bench, cfg, work, new_runs, sweep)
    if not done:
        sys.exit("%s: no runs" % sweep)
    per = resolution_records(cfg, done)
    stats = resolution_stats(cfg, per, sweep)
    sizes = sorted(stats)
    charted = [p for p in RES_PROPS if p[0] != "nu"]
    cost_of = {"ucs": "ucs", "E": "ucs", "nu": "ucs", "tension": "tension", "phi": "phi"}
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.6))
    markers = {"ucs": "o", "E": "s", "tension": "^", "phi": "D"}
    for key, label, _, _, _ in charted:
        ns = [n for n in sizes if stats[n][key][2] > 0]
        if len(ns) < 1:
            continue
        ref = stats[ns[-1]][key][0]
        if ns[-1] != sizes[-1] or stats[ns[-1]][key][2] < len(c["seeds"]):
            label = "%s (against %d grains, %d seed%s)" % (label, ns[-1], stats[ns[-1]][key][2],
                                                          "" if stats[ns[-1]][key][2] == 1 else "s")
        err = [pct(stats[n][key][0], ref) for n in ns]
        bar = [100.0 * stats[n][key][1] / abs(ref) if math.isfinite(stats[n][key][1]) else 0.0 for n in ns]
        across = [stats[n]["across"] for n in ns]
        ax[0].errorbar(across, err, yerr=bar, marker=markers[key], capsize=3, label=label)
        ax[1].errorbar([stats[n]["sec_" + cost_of[key]] for n in ns], err, yerr=bar, marker=markers[key], capsize=3,
                       label=label)
        ax[2].errorbar([stats[n]["ps_" + cost_of[key]] for n in ns], err, yerr=bar, marker=markers[key], capsize=3,
                       label=label)
        for n, x, y in zip(ns, [stats[n]["sec_" + cost_of[key]] for n in ns], err):
            if key == "ucs":
                ax[1].annotate("%.1f" % stats[n]["across"], (x, y), textcoords="offset points", xytext=(4, 6),
                               fontsize=7)
    ax[0].set_xlabel("mean grain diameters across the width")
    two = sorted(n for n, t in c.get("threads", {}).items() if t == 2 and n in stats)
    ax[1].set_xlabel("seconds per specimen (compaction, cement, test(s); 1 thread%s)"
                     % ("; %s grains: 2" % " and ".join("%d" % n for n in two) if two else ""))
    ax[2].set_xlabel("particle-steps per specimen")
    for a in ax:
        a.axhspan(-100 * CONVERGED, 100 * CONVERGED, color="0.9")
        a.axhline(0.0, color="0.5", lw=0.5)
        a.set_ylabel("difference from the finest size (%)")
        a.legend(fontsize=7)
    ax[0].set_title("mean over seeds, bars: seed standard deviation", fontsize=9)
    ax[1].set_xscale("log")
    ax[1].set_title("cost against error (labels: grains across)", fontsize=9)
    ax[2].set_xscale("log")
    fig.suptitle("Resolution: stiff-bond rock, %s grains, seeds %s, %g strain per step%s"
                 % ("/".join("%d" % n for n in sizes), ",".join("%d" % s for s in c["seeds"]), c["strain_per_step"],
                    c.get("title", "")))
    image = save_chart(fig, out, "speed_accuracy_%s.png" % sweep)

    ref_size = {key: max([n for n in sizes if stats[n][key][2] > 0] or [0]) for key, _, _, _, _ in RES_PROPS}
    ref = {key: stats[ref_size[key]][key][0] if ref_size[key] else math.nan for key, _, _, _, _ in RES_PROPS}

    def cell(st, key, scale, fmt):
        m, sd, k = st[key]
        if k == 0:
            return "-"
        text = (fmt % (m / scale)) + (" +- " + fmt % (sd / scale) if k > 1 else "")
        if key != "nu" and math.isfinite(ref[key]) and st["n"] != ref_size[key]:
            # The difference of the means with its standard error (both sizes' seed spreads).
            rm, rsd, rk = stats[ref_size[key]][key]
            se = math.sqrt((sd ** 2 / k if k > 1 else math.nan) + (rsd ** 2 / rk if rk > 1 else math.nan))
            text += " (%+.1f" % pct(m, ref[key]) + (" +- %.1f" % (100.0 * se / abs(rm)) if math.isfinite(se) else "") \
                + " %)"
        return text + ("" if k == len(c["seeds"]) else " [%d seed%s]" % (k, "" if k == 1 else "s"))
    rows = []
    for n in sizes:
        st = stats[n]
        seeds_ucs = [s for s in c["seeds"] if math.isfinite(per.get((n, s), {}).get("ucs", math.nan))]
        rows.append(["%d" % n, "%.1f" % st["across"], ",".join("%d" % s for s in seeds_ucs),
                     "%.3f / %.2f" % (st["porosity"], st["coordination"]), "%.1f" % st["rate_factor"]]
                    + [cell(st, key, scale, fmt) for key, _, scale, _, fmt in RES_PROPS]
                    + [" / ".join("%.1f" % st[k] if math.isfinite(st[k]) else "-"
                                  for k in ("sec_ucs", "sec_tension", "sec_phi")),
                       " / ".join("%.3g" % st[k] if math.isfinite(st[k]) else "-"
                                  for k in ("ps_ucs", "ps_tension", "ps_phi"))])
    body = table(["grains", "across", "seeds", "porosity / bonded coordination",
                  "compression strain rate / Suggested Strain Rate", "UCS (MPa)", "E (GPa)", "nu", "sigma_t (MPa)", "friction angle (deg)",
                  "seconds per specimen: unconfined / tension / triaxial", "particle-steps: unconfined / tension / "
                  "triaxial"], rows)
    # Every specimen (seed) on its own line.
    seed_rows = []
    for (n, s) in sorted(per):
        r = per[(n, s)]

        def f(key, scale, fmt):
            v = r.get(key, math.nan)
            return fmt % (v / scale) if math.isfinite(v) else "-"
        tri = ", ".join("%.3g" % (v / 1e6) + ("" if peaked else " (no peak)") for _, v, peaked, _, _ in r.get("triaxial", []))
        seed_rows.append(["%d" % n, "%d" % s, f("across", 1, "%.1f"), f("porosity", 1, "%.3f"),
                          "%s (%s)" % (f("bonds", 1, "%d"), f("coordination", 1, "%.2f")), f("ucs", 1e6, "%.3f"),
                          f("peak_strain", 1, "%.5f"), f("E", 1e9, "%.3f"), f("nu", 1, "%.3f"), f("tension", 1e6, "%.4f"),
                          tri or "-", f("phi", 1, "%.2f"), f("sec_ucs", 1, "%.1f"), f("sec_tension", 1, "%.1f"),
                          f("sec_phi", 1, "%.1f")])
    seed_table = table(["grains", "seed", "across", "porosity", "bonds (coordination)", "UCS (MPa)", "strain at peak",
                        "E (GPa)", "nu", "sigma_t (MPa)", "triaxial sigma1 at 10 / 20 % UCS (MPa)", "phi (deg)",
                        "s unconfined", "s tension", "s triaxial"], seed_rows)
    conv = []
    for key, label, _, _, _ in RES_PROPS:
        finest, mean_from, seed_from = convergence(stats, key)
        if finest is None:
            conv.append("%s: fewer than two sizes measured" % label)
            continue
        def name(n):
            return "%d grains (%.1f across)" % (n, stats[n]["across"])
        conv.append("%s: the mean within 5 %% of %s's %s; every seed within 5 %% %s" % (
            label, name(finest), ("from " + name(mean_from)) if mean_from else "at no smaller size",
            ("from " + name(seed_from)) if seed_from else "at no smaller size"))
    loads = sorted(r["load"] for r in done.values())
    walls = sum(r["wall"] for r in done.values())
    compression = [r for (_, _, k), r in done.items() if k != "tension"]
    kinds = {"ucs_triaxial": "unconfined and triaxial", "ucs": "unconfined", "tension": "tension"}
    commands = "; ".join("%s: `rockdem_bench_rock %s`" % (
        kinds[k], " ".join(resolution_args(c, "N", "S", k))) for k in
        ("ucs_triaxial", "ucs", "tension") if any(kind == k for _, _, kind in c["order"]))
    runs_by_kind = {}
    for (n, s, k) in sorted(done):
        runs_by_kind.setdefault(k, []).append("%d/%d" % (n, s))
    text = ("Commands (N grains, seed S): %s (%s; load average %.2f-%.2f before the runs, %d runs, %.0f s wall in all; "
            "each run's command, load and output in `atlas_runs/%s_N_sS_KIND.txt`). Runs made (grains/seed): %s. "
            "Compression tests: timestep %.3g-%.3g s (the smallest grain is smaller in a larger pack), strain rate "
            "%.3g-%.3g 1/s = %.3g-%.3g x the Suggested Strain Rate.\n\n"
            "Mean over the seeds +- their standard deviation, and (in brackets) the difference of the mean from the "
            "finest size's (the reference) +- its standard error (from both sizes' seed spreads):\n\n%s\n\n"
            "Within 5 %% of the finest size (the mean over the seeds; each seed on its own):\n\n%s\n\n%s\n\n%s") % (
        commands, machine(), loads[0], loads[-1], len(done), walls, sweep,
        "; ".join("%s %s" % (kinds[k], ", ".join(v)) for k, v in runs_by_kind.items()),
        min(comp["timestep"] for comp in compression), max(comp["timestep"] for comp in compression),
        min(comp["rate"] for comp in compression), max(comp["rate"] for comp in compression),
        min(comp["rate_factor"] for comp in compression), max(comp["rate_factor"] for comp in compression), body, "\n".join("- " + line for line in conv),
        "Each specimen:\n\n" + seed_table + "".join(
            "\n\nThe unconfined test of %d grains, seed %d, ran twice (alone and before the triaxial tests): UCS %.4g "
            "and %.4g Pa (%s)." % (n, seed, a, b, "the same" if a == b else "NOT the same")
            for (n, seed), rec in sorted(per.items()) if "ucs_twice" in rec for a, b in [rec["ucs_twice"]]),
        ("**Not run** (grains/seed/kind): %s." % ", ".join("%d/%d/%s" % m for m in missing)) if missing
        else "Every planned run finished.")
    numbers = [{k: v for k, v in r.items() if isinstance(v, float)} for r in per.values()]
    # Non-finite figures: a missing test leaves nan on purpose; only the measured ones are checked.
    numbers = [{k: v for k, v in d.items() if math.isfinite(v) or k not in ("phi", "tension", "sec_phi", "ps_phi",
                                                                             "sec_tension", "ps_tension", "tension_strain")}
               for d in numbers]
    return text, numbers, [image]



# The strain-rate effect against the seed spread (SpeedAccuracy.md "Strain rate": is the rate effect
# separable from the path noise at a larger size?): the resolution sweep's 700-grain specimens (7 across,
# seeds 1-3) loaded at 4 x and 1 x the Suggested Strain Rate, beside their unconfined test of the sweep
# (1e-7 per step). Each specimen is the same at every rate: the differences are paired.
FULL["rate_seeds"] = {"particles": 700, "seeds": [1, 2, 3], "factors": [4, 1], "max_strain": 0.006}


def rate_seeds_section(bench, cfg, work, out, new_runs=True):
    c = cfg["rate_seeds"]
    r = cfg["resolution"]
    rows, notes = [], []
    for seed in c["seeds"]:
        args = ["--particles", str(c["particles"]), "--seed", str(seed), "--threads", "1", "--tests", "rates",
                "--rate-factors", ",".join("%g" % f for f in c["factors"])] + ROCK[:-2] + ["--max-strain",
                                                                                          "%g" % c["max_strain"]]
        name = "rate_seeds_%d_s%d" % (c["particles"], seed)
        path = os.path.join(work, name + ".txt")
        if not os.path.exists(path) and not new_runs:
            continue  # not run (the clock)
        sweep, note = run(bench, args, work, name, True)
        base = os.path.join(work, "resolution_%d_s%d_ucs_triaxial.txt" % (c["particles"], seed))
        with open(base) as f:
            b = parse_resolution(f.read().splitlines())[0]
        rows.append({"seed": seed, "sweep": sweep, "base": b})
        notes.append(note)
    if not rows:
        return "Not run.", [], []
    slow = min(c["factors"])

    def at(row, factor):
        return next(x for x in row["sweep"] if x["factor"] == factor)
    lines = []
    diffs = {f: [] for f in c["factors"] if f != slow}
    diffs["sweep"] = []
    ediffs = {k: [] for k in diffs}
    for row in rows:
        ref = at(row, slow)
        cells = ["%d" % row["seed"], "%.3f (%.1f x, %d steps)" % (row["base"]["ucs"] / 1e6, row["base"]["rate_factor"],
                                                                  row["base"]["ucs_steps"])]
        d = pct(row["base"]["ucs"], ref["ucs"])
        diffs["sweep"].append(d)
        ediffs["sweep"].append(pct(row["base"]["E"], ref["E"]))
        for f in sorted(c["factors"], reverse=True):
            x = at(row, f)
            cells.append("%.3f (%d steps)" % (x["ucs"] / 1e6, x["steps"]))
            if f != slow:
                diffs[f].append(pct(x["ucs"], ref["ucs"]))
                ediffs[f].append(pct(x["E"], ref["E"]))
        cells += ["%+.1f %%" % diffs[f][-1] for f in sorted(c["factors"], reverse=True) if f != slow]
        cells.append("%+.1f %%" % d)
        cells.append("%.2f / %.2f / %.2f" % (row["base"]["E"] / 1e9, at(row, max(c["factors"]))["E"] / 1e9,
                                             ref["E"] / 1e9))
        lines.append(cells)
    header = (["seed", "UCS (MPa) at the sweep's 1e-7 per step"]
              + ["UCS (MPa) at %g x" % f for f in sorted(c["factors"], reverse=True)]
              + ["%g x vs %g x" % (f, slow) for f in sorted(c["factors"], reverse=True) if f != slow]
              + ["1e-7 per step vs %g x" % slow, "E (GPa): 1e-7 per step / %g x / %g x" % (max(c["factors"]), slow)])
    summary = []
    for k in diffs:
        m, sd, n = mean_sd(diffs[k])
        em, esd, _ = mean_sd(ediffs[k])
        summary.append("%s against %g x: UCS %+.1f %% +- %.1f %% (mean +- standard deviation of the %d paired "
                       "differences), E %+.1f %% +- %.1f %%" % ("the sweep's 1e-7 per step" if k == "sweep" else
                                                              "%g x" % k, slow, m, sd, n, em, esd))
    text = ("Commands: `rockdem_bench_rock %s` with `--seed` %s (%s; %s), beside the resolution sweep's "
            "unconfined test of the same specimens.\n\n%s\n\n%s.") % (
        " ".join(["--particles", str(c["particles"]), "--seed", "S", "--threads", "1", "--tests", "rates",
                  "--rate-factors", ",".join("%g" % f for f in c["factors"])] + ROCK[:-2]
                 + ["--max-strain", "%g" % c["max_strain"]]),
        ", ".join("%d" % row["seed"] for row in rows), machine(), "; ".join(notes), table(header, lines),
        "; ".join(summary))
    return text, [{"d": v} for k in diffs for v in diffs[k]], []

# 2D against 3D (issue 17, "Contact law and 2D against 3D"): the same rock as a 2D section of
# discs (bench --dimension 2: discs in the XY plane, slab 2 mm, loaded along Y), as a 3D slab of
# the same width and height and a few mean diameters thick (bench --depth D: Y = D nominal mean
# diameters, loaded along Z), and as the usual 3D box of the same width (square cross-section).
# Undamped test (--damping 0: Settling Damping 0.7 during a test acts as a strength, "The defaults
# justified"), the same platen strain per step for every specimen, unconfined compression then direct
# tension on a fresh copy of the same specimen; --dump writes the unconfined specimen at 70 % of the
# peak (the pictures and the band statistic of scripts/localisation_index.py). The particle counts
# give every specimen the nominal width of the box of "box" grains, by the bench's own sizing
# (buildSpecimen: the box holds N grains of mean volume V at --porosity, 0.36 in 3D, 0.16 in 2D).
FULL["dims"] = {"box": 8000, "depth": 4, "seeds": [1, 2, 3], "strain_per_step": 5e-8, "max_strain": 0.005,
                "min_peak_strain": 2e-5,
                # the order: seed 1 of every kind first, then the cheap kinds' other seeds, then the boxes'
                "order": [("2d", 1), ("slab", 1), ("box", 1), ("2d", 2), ("2d", 3), ("slab", 2), ("slab", 3),
                          ("box", 2), ("box", 3), ("thick", 1), ("thick", 2), ("thick", 3)], "directions": 2000,
                # a slab twice as thick (run after the others): where a slab approaches the box
                "thick_depth": 8}
QUICK["dims"] = {"box": 300, "depth": 3, "seeds": [1], "strain_per_step": 4e-7, "max_strain": 0.005,
                 "min_peak_strain": 2e-5, "order": [("2d", 1), ("slab", 1), ("box", 1)], "directions": 100,
                 "thick_depth": 6}
DIMS_KINDS = [("2d", "2D section"), ("slab", "3D slab"), ("thick", "3D slab, thicker"), ("box", "3D box")]
DIMS_RMIN, DIMS_RMAX, DIMS_SLAB, DIMS_ASPECT = 0.001, 0.002, 0.002, 2.0  # the bench's defaults
DIMS_PATTERNS = dict(
    RES_PATTERNS,
    particles=r"^specimen: .*?(\d+) particles, ",
    across=r"^specimen: .* (\S+) mean diameters across",
    size_y=r"^specimen: .*particles, \S+ x (\S+) x",
    near_platens=r"^UCS .*broken within 2 diameters of a platen: (\S+) %",
    depth_across=r"along Y = (\S+) mean diameters",
    broken_70=r"^UCS .*; broken \d+ \((\S+) % of bonds\); 70 % of peak",
    tension_steps=r"^direct tension .*\((\d+) steps, \S+ s\)",
    skin_broken=r"outer grain layer .*?: (\S+) % of the broken bonds",
    skin_all=r"outer grain layer .*?: \S+ % of the broken bonds, (\S+) % of all bonds",
)
DIMS_BAND_LINE = re.compile(r"^dims-band: excess (\S+) control (\S+) plane (\S+) deg cracks (\d+)", re.M)

def dims_counts(box, depth, thick_depth):
    """The nominal width (m) of a 3D box of `box` grains, and {kind: particles} giving the 2D section and the
    slab (`depth` nominal mean diameters thick) that width (and twice it as height), by the bench's sizing."""
    a, b = DIMS_RMIN, DIMS_RMAX
    v3 = 4.0 / 3.0 * math.pi * (a + b) * (a * a + b * b) / 4.0  # mean sphere volume
    a2 = math.pi * (a * a + a * b + b * b) / 3.0                 # mean disc area (x the slab: its volume)
    width = (box * v3 / (1.0 - 0.36) / DIMS_ASPECT) ** (1.0 / 3.0)
    return width, {"box": box, "2d": int(round(width * width * DIMS_ASPECT * (1.0 - 0.16) / a2)),
                   "slab": int(round(width * width * DIMS_ASPECT * depth * (a + b) * (1.0 - 0.36) / v3)),
                   "thick": int(round(width * width * DIMS_ASPECT * thick_depth * (a + b) * (1.0 - 0.36) / v3))}


def dims_args(c, kind, seed, counts):
    n = counts[kind]
    extra = {"2d": ["--dimension", "2"], "slab": ["--depth", "%g" % c["depth"]],
             "thick": ["--depth", "%g" % c["thick_depth"]], "box": []}[kind]
    return (["--particles", str(n)] + extra + ["--seed", str(seed), "--threads", "1", "--tests", "ucs,tension",
                                               "--damping", "0", "--strain-per-step", "%g" % c["strain_per_step"]]
            + ROCK[:-2] + ["--max-strain", "%g" % c["max_strain"], "--min-peak-strain", "%g" % c["min_peak_strain"]])


def dims_band(dump, count):
    """The band statistic of the cracks formed after the peak (scripts/localisation_index.py: the strip or
    slab 4 mean diameters wide, over `count` directions in 3D, every degree in 2D, holding the largest excess
    of the cracks' share over its share of the specimen): (excess, the control's excess, the plane's angle
    from the loading axis in degrees, cracks)."""
    import numpy as np
    from localisation_index import band_excess, directions, dip
    from failed_dump import read_dump
    g, b = read_dump(dump)
    flat = np.ptp(g[:, 2]) == 0.0
    after = b[b[:, 3] == 1][:, 0:3]
    if len(after) < 10:
        return math.nan, math.nan, math.nan, len(after)
    box = (g[:, 0:3].min(axis=0), g[:, 0:3].max(axis=0))
    (e, _, _, n), (ec, _, _, _) = band_excess(after, box, directions(2 if flat else 3, count),
                                              4.0 * 2.0 * g[:, 3].mean(), np.random.default_rng(1))
    return e, ec, dip(n, 1 if flat else 2), len(after)


def dims_runs(bench, cfg, work, new_runs, only=None):
    """Runs (or reuses) the section's bench runs in their order (only those named in `only`, KIND:SEED, when
    given: to split the runs over processes); {(kind, seed): figures}, the missing runs, counts, width."""
    c = cfg["dims"]
    width, counts = dims_counts(c["box"], c["depth"], c["thick_depth"])
    done, missing = {}, []
    for kind, seed in c["order"]:
        name = "dims_%s_s%d" % (kind, seed)
        dump = os.path.join(work, "dims_dumps", name)
        args = dims_args(c, kind, seed, counts) + ["--dump", dump]
        path = os.path.join(work, name + ".txt")
        have = False
        if cfg is FULL and os.path.exists(path):
            with open(path) as f:
                have = f.readline().rstrip("\n") == "# command: " + " ".join(args)
        if not have and (not new_runs or (only and "%s:%d" % (kind, seed) not in only)):
            missing.append((kind, seed))
            continue
        if not have:
            os.makedirs(dump, exist_ok=True)
            print("atlas: dims: %s (started %s, load average %.2f)"
                  % (name, time.strftime("%H:%M:%S UTC", time.gmtime()), os.getloadavg()[0]), flush=True)
        r, note = run(bench, args, work, name, have, parse_resolution_like)
        row = r[0]
        row["wall"] = float(re.search(r"(\S+) s wall for the whole command", note).group(1))
        row["load"] = float(re.search(r"load average (\S+) ", note).group(1))
        # The band statistic: computed from the dump once and kept as a "dims-band:" line at the end of the
        # run's file (the dumps are not committed), read from there afterwards.
        with open(path) as f:
            kept = DIMS_BAND_LINE.search(f.read())
        row["dump"] = os.path.join(dump, "ucs_failed.csv")
        if kept:
            row["band"], row["band_control"], row["band_plane"] = (float(v) for v in kept.groups()[:3])
            row["band_cracks"] = int(kept.group(4))
        elif os.path.exists(row["dump"]):
            row["band"], row["band_control"], row["band_plane"], row["band_cracks"] = dims_band(
                row["dump"], c["directions"])
            with open(path, "a") as f:
                f.write("dims-band: excess %.6g control %.6g plane %.4g deg cracks %d (the cracks after the peak of "
                        "%s, %d directions)\n" % (row["band"], row["band_control"], row["band_plane"],
                                                   row["band_cracks"], row["dump"], c["directions"]))
        else:
            row["band"] = row["band_control"] = row["band_plane"] = math.nan
            row["band_cracks"] = 0
        row["args"] = args
        done[(kind, seed)] = row
    return done, missing, counts, width


def parse_resolution_like(lines):
    row = first_matches(DIMS_PATTERNS, lines)
    if math.isnan(row["particles"]) or math.isnan(row["total"]) or math.isnan(row["ucs"]):
        sys.exit("dims: an incomplete bench output (no specimen, UCS or total line)")
    return [row]


def dims_picture(ax, dump, kind, title):
    """The specimen at 70 % of the peak: the grains (2D: all; 3D: those within one mean diameter of the
    mid-plane XZ) in light grey, the bonds broken before the peak as grey dots, after it as red dots."""
    from matplotlib.collections import PatchCollection
    from matplotlib.patches import Circle
    grains, cracks = [], []
    with open(dump) as f:
        header = f.readline().strip().split(",")
        ix = {k: i for i, k in enumerate(header)}
        for line in f:
            v = line.rstrip("\n").split(",")
            x, y, z = float(v[ix["x"]]), float(v[ix["y"]]), float(v[ix["z"]])
            if v[0] == "particle":
                grains.append((x, y, z, float(v[ix["radius"]])))
            else:
                cracks.append((x, y, z, int(v[ix["after_peak"]])))
    planar = kind == "2d"
    d = 2.0 * sum(g[3] for g in grains) / len(grains)
    cy = sum(g[1] for g in grains) / len(grains)

    def keep(p):
        return planar or abs(p[1] - cy) <= d

    def xy(p):
        return (p[0] * 1e3, (p[1] if planar else p[2]) * 1e3)
    ax.add_collection(PatchCollection([Circle(xy(g), g[3] * 1e3) for g in grains if keep(g)], facecolor="0.88",
                                      edgecolor="0.75", linewidth=0.2))
    for after, colour, label in ((0, "0.45", "broken before the peak"), (1, "red", "after the peak")):
        pts = [xy(p) for p in cracks if keep(p) and p[3] == after]
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], ".", color=colour, markersize=1.6,
                    label="%s (%d)" % (label, len(pts)))
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("%s (mm, loading axis)" % ("y" if planar else "z"))
    ax.set_title(title, fontsize=9)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), fontsize=7, markerscale=4, frameon=False)


def dims_section(bench, cfg, work, out, new_runs=True, only=None):
    c = cfg["dims"]
    done, missing, counts, width = dims_runs(bench, cfg, work, new_runs, only)
    names = dict(DIMS_KINDS, slab="3D slab, %g diameters" % c["depth"], thick="3D slab, %g diameters" % c["thick_depth"])
    kinds = [(k, names[k]) for k, _ in DIMS_KINDS]
    for r in done.values():
        steps = r["compact_steps"] + r["ucs_steps"] + (r["tension_steps"] if math.isfinite(r["tension_steps"]) else 0)
        r["particle_steps"] = r["particles"] * steps
        r["ratio"] = r["ucs"] / r["tension"] if r["tension"] > 0 else math.nan
        r["broken_peak_share"] = r["broken_peak"]
    stats = {}
    for kind, _ in kinds:
        recs = [done[(kind, s)] for s in c["seeds"] if (kind, s) in done]
        if recs:
            stats[kind] = {k: mean_sd([r[k] for r in recs]) for k in (
                "ucs", "E", "nu", "tension", "ratio", "across", "porosity", "coordination", "bonds", "particles",
                "broken_peak", "near_platens", "band", "band_control", "disc_share", "discs", "total", "wall",
                "particle_steps", "ucs_steps", "peak_strain", "skin_broken", "skin_all", "timestep", "rate_factor", "rate")}
            stats[kind]["seeds"] = [s for s in c["seeds"] if (kind, s) in done]
    ref = stats.get("box")

    def diff(kind, key):
        """The difference of the mean from the box's (%) +- its standard error from both seed spreads."""
        if not ref or kind == "box" or key not in stats[kind]:
            return ""
        m, sd, n = stats[kind][key]
        rm, rsd, rn = ref[key]
        if not (math.isfinite(m) and math.isfinite(rm) and rm):
            return ""
        se = math.sqrt((sd ** 2 / n if n > 1 and math.isfinite(sd) else 0.0)
                       + (rsd ** 2 / rn if rn > 1 and math.isfinite(rsd) else 0.0))
        return " (%+.1f +- %.1f %%)" % (100.0 * (m - rm) / rm, 100.0 * se / abs(rm)) if se > 0 else \
            " (%+.1f %%)" % (100.0 * (m - rm) / rm)

    def ms(kind, key, scale, fmt):
        m, sd, n = stats[kind][key]
        if not math.isfinite(m):
            return "-"
        return (fmt % (m / scale)) + ((" +- " + fmt % (sd / scale)) if n > 1 and math.isfinite(sd) else "")
    summary = []
    for kind, label in kinds:
        if kind not in stats:
            continue
        st = stats[kind]
        summary.append([
            label, ",".join("%d" % s for s in st["seeds"]), "%d" % st["particles"][0], "%.1f" % st["across"][0],
            "%.3f / %.2f" % (st["porosity"][0], st["coordination"][0]),
            "%.3g s, %.3g 1/s (%.1f x)" % (st["timestep"][0], st["rate"][0], st["rate_factor"][0]),
            ms(kind, "ucs", 1e6, "%.2f") + diff(kind, "ucs"), ms(kind, "E", 1e9, "%.2f") + diff(kind, "E"),
            ms(kind, "nu", 1.0, "%.3f"), ms(kind, "tension", 1e6, "%.3f") + diff(kind, "tension"),
            ms(kind, "ratio", 1.0, "%.2f"), ms(kind, "broken_peak", 1.0, "%.1f %%"),
            ms(kind, "near_platens", 1.0, "%.1f %%"),
            ms(kind, "band", 1.0, "%.3f") + " (%.3f)" % st["band_control"][0],
            "%.1f / %.1f %%" % (st["discs"][0], st["disc_share"][0]),
            "%.0f" % st["ucs_steps"][0], "%.3g" % st["particle_steps"][0], "%.1f" % st["total"][0]])
    head = ["specimen", "seeds", "particles", "across", "porosity / bonded coordination",
            "timestep, strain rate (x Suggested Strain Rate)", "UCS (MPa)", "E (GPa)", "nu",
            "sigma_t (MPa)", "UCS / sigma_t", "bonds broken at the peak", "broken near the platens",
            "band excess after the peak (control)", "DFN: discs / broken bonds in discs", "steps to 70 % of the peak",
            "particle-steps (compaction, UCS, tension)", "seconds (whole run)"]
    per = []
    for (kind, seed), r in sorted(done.items(), key=lambda kv: ([k for k, _ in kinds].index(kv[0][0]), kv[0][1])):
        per.append([names[kind], "%d" % seed, "%d" % r["particles"], "%.1f" % r["across"],
                    "%.1f" % r["depth_across"] if kind in ("slab", "thick") else "-",
                    "%.3f" % r["porosity"], "%d (%.2f)" % (r["bonds"], r["coordination"]), "%.3f" % (r["ucs"] / 1e6),
                    "%.5f" % r["peak_strain"], "%.2f" % (r["E"] / 1e9), "%.3f" % r["nu"],
                    "%.3f" % (r["tension"] / 1e6), "%.2f" % r["ratio"], "%.1f / %.1f %%" % (r["broken_peak"], r["broken_70"]),
                    "%.1f %%" % r["near_platens"], "%.3f (%.3f), %.0f deg" % (r["band"], r["band_control"],
                                                                           r["band_plane"]),
                    "%d / %.1f %%" % (r["discs"], r["disc_share"]), "%.1f / %.1f %%" % (r["skin_broken"], r["skin_all"]),
                    "%d / %d" % (r["ucs_steps"], r["tension_steps"]), "%.3g" % r["particle_steps"],
                    "%.1f" % r["total"], "%.2f" % r["load"]])
    per_head = ["specimen", "seed", "particles", "across", "depth (mean diameters)", "porosity",
                "bonds (coordination)", "UCS (MPa)", "strain at peak", "E (GPa)", "nu", "sigma_t (MPa)",
                "UCS / sigma_t", "bonds broken at the peak / at 70 % of it", "broken near the platens", "band excess after the peak (control), "
                "plane from the axis", "DFN discs / share", "outer layer: share of broken / of all bonds",
                "steps UCS / tension", "particle-steps", "seconds", "load average before"]
    # The chart: cost against the difference in UCS from the box's mean (each seed, and the means), and the
    # fracture pattern of seed 1 of each kind.
    import matplotlib.gridspec as gridspec
    first_seed = c["seeds"][0]
    pics = [(k, done[(k, first_seed)]) for k in ("2d", "slab", "box")
            if (k, first_seed) in done and os.path.exists(done[(k, first_seed)]["dump"])]
    fig = plt.figure(figsize=(4.2 + 3.0 * len(pics), 6.4))
    grid = gridspec.GridSpec(1, 1 + len(pics), width_ratios=[1.5] + [1.0] * len(pics), figure=fig)
    ax = fig.add_subplot(grid[0, 0])
    colours = {"2d": "tab:blue", "slab": "tab:orange", "thick": "tab:red", "box": "tab:green"}
    if ref:
        for kind, label in kinds:
            recs = [done[(kind, s)] for s in c["seeds"] if (kind, s) in done]
            if not recs:
                continue
            ax.semilogx([r["total"] for r in recs], [pct(r["ucs"], ref["ucs"][0]) for r in recs], "o",
                        color=colours[kind], alpha=0.45)
            m = stats[kind]
            ax.errorbar([m["total"][0]], [pct(m["ucs"][0], ref["ucs"][0])],
                        yerr=[100.0 * m["ucs"][1] / ref["ucs"][0] if m["ucs"][2] > 1 else 0.0], fmt="s",
                        color=colours[kind], markersize=8, capsize=4,
                        label="%s (%d particles; mean +- sd)" % (label, m["particles"][0]))
        ax.axhline(0.0, color="0.6", linewidth=0.8)
        from matplotlib.ticker import NullFormatter
        ax.xaxis.set_minor_formatter(NullFormatter())
        seconds = [r["total"] for r in done.values()]
        ax.set_xlim(10 ** math.floor(math.log10(min(seconds))), 10 ** math.ceil(math.log10(max(seconds))))
        ax.set_xlabel("seconds per specimen, whole run (one thread)")
        ax.set_ylabel("UCS against the 3D box's mean (%)")
        ax.set_title("Cost against the difference in UCS\n(dots: seeds; squares: means)", fontsize=9)
        ax.legend(fontsize=7, loc="best")
    else:
        ax.axis("off")
        ax.text(0.5, 0.5, "no 3D box run yet:\nno reference for the UCS", ha="center", va="center")
    for i, (kind, r) in enumerate(pics):
        a = fig.add_subplot(grid[0, 1 + i])
        dims_picture(a, r["dump"], kind, "%s, seed %d, at 70 %% of the peak\n%s" % (
            names[kind], first_seed, "all discs" if kind == "2d" else "mid-plane XZ, +- one mean diameter"))
    image = save_chart(fig, out, "speed_accuracy_dims.png")
    example = {k: " ".join(dims_args(c, k, first_seed, counts)) for k, _ in kinds}
    loads = [r["load"] for r in done.values()]
    thick = any(k == "thick" for k, _ in done) or any(k == "thick" for k, _ in missing)
    text = ("Commands (seed S; the same rock, options and strain per step for all, `--dump DIR` besides): "
            "2D section: `rockdem_bench_rock %s`; 3D slab: `rockdem_bench_rock %s`%s; 3D box: `rockdem_bench_rock %s`, "
            "with `--seed` %s (%s; load average %.2f-%.2f before the runs, %d runs, %.0f s wall in all; each run's "
            "command, load and output in `atlas_runs/dims_KIND_sS.txt`). The particle counts give each specimen the "
            "nominal width of the box of %d grains (%.2f mm); the band statistic is that of "
            "`scripts/localisation_index.py DIR/ucs_failed.csv` (4 mean diameters wide) on each run's dump.\n\n"
            "Mean over the seeds +- their standard deviation, and (in brackets) the difference of the mean from the 3D "
            "box's +- its standard error:\n\n%s\n\nEach specimen:\n\n%s%s") % (
        example["2d"].replace("--seed %d" % first_seed, "--seed S"),
        example["slab"].replace("--seed %d" % first_seed, "--seed S"),
        (" (the thicker slab: the same with `--particles %d --depth %g`)" % (counts["thick"], c["thick_depth"])
         if thick else ""),
        example["box"].replace("--seed %d" % first_seed, "--seed S"),
        ", ".join("%d" % s for s in c["seeds"]), machine(), min(loads) if loads else math.nan,
        max(loads) if loads else math.nan, len(done), sum(r["wall"] for r in done.values()), c["box"], width * 1e3,
        table(head, summary), table(per_head, per),
        ("\n\n**Not run** (kind/seed): %s." % ", ".join("%s/%d" % m for m in missing)) if missing else "")
    rows = [{k: r[k] for k in ("ucs", "E", "tension", "total", "particle_steps", "wall")} for r in done.values()]
    return text, rows, [image]


def write_page(path, sections):
    """Replaces the text between <!-- atlas:NAME --> and <!-- /atlas:NAME --> (or writes a page)."""
    page = ""
    if os.path.exists(path):
        with open(path) as f:
            page = f.read()
    for name, text in sections.items():
        start, end = "<!-- atlas:%s -->" % name, "<!-- /atlas:%s -->" % name
        block = "%s\n%s\n%s" % (start, text, end)
        if start in page and end in page:
            page = page[:page.index(start)] + block + page[page.index(end) + len(end):]
        else:
            page += "\n## %s\n\n%s\n" % (name, block)
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(page)
    os.replace(tmp, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bench", default=os.path.join(HERE, "..", "build", "bin", "rockdem_bench_rock"))
    parser.add_argument("--out", default=os.path.join(HERE, "..", "Documentation"))
    parser.add_argument("--work", default=None)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--no-new-runs", action="store_true",
                        help="resolution: write the table from the runs in WORK only, listing the missing ones")
    parser.add_argument("--dims-runs", default="",
                        help="dims: run only these of its runs (KIND:SEED comma list; to split them over processes)")
    parser.add_argument("--only", default="rates,modulus,threads,stability,timestep_bonded,contact_law,resolution,"
                        "resolution_undamped,dims",
                        help="sections to run (comma list)")
    o = parser.parse_args()
    cfg = QUICK if o.quick else FULL
    work = o.work or os.path.join(o.out, "atlas_runs")
    os.makedirs(os.path.join(o.out, "images"), exist_ok=True)
    os.makedirs(work, exist_ok=True)
    sections, numbers, images = {}, [], []
    makers = {"rates": rates_section, "modulus": modulus_section, "threads": threads_section,
              "stability": stability_section, "timestep_bonded": timestep_bonded_section,
              "contact_law": contact_law_section,
              "resolution": lambda *a: resolution_section(*a, new_runs=not o.no_new_runs),
              "resolution_undamped": lambda *a: resolution_section(*a, new_runs=not o.no_new_runs,
                                                                   sweep="resolution_undamped"),
              "rate_seeds": lambda *a: rate_seeds_section(*a, new_runs=not o.no_new_runs),
              "dims": lambda *a: dims_section(*a, new_runs=not o.no_new_runs,
                                              only=o.dims_runs.split(",") if o.dims_runs else None)}
    for name in o.only.split(","):
        text, rows, files = makers[name](o.bench, cfg, work, o.out)
        sections[name] = text
        numbers += [v for r in rows for k, v in r.items() if isinstance(v, float)]
        images += files
        print("atlas: %s done" % name, flush=True)
    page = os.path.join(o.out, "SpeedAccuracy.md")
    write_page(page, sections)
    bad = [v for v in numbers if not math.isfinite(v)]
    missing = [p for p in images + [page] if not os.path.exists(p) or os.path.getsize(p) == 0]
    print("atlas: %d numbers (%d not finite), %d files written (%d missing): %s"
          % (len(numbers), len(bad), len(images) + 1, len(missing), ", ".join(images + [page])))
    if bad or missing:
        sys.exit("atlas: FAILED (non-finite numbers or missing files)")


if __name__ == "__main__":
    main()
