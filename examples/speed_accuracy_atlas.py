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
CPU threads: the same test on 1 and 2 threads, its time and whether the UCS agrees bit for bit.

--quick (ctest Atlas.Quick): 300 grains, three rates, two moduli, one thread comparison, into
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
        "--range", "1.4", "--max-strain", "0.03"]
# The strain-rate sweep: (name, factors, inertial target of the suggestion the factors
# multiply, or None for the engine's rule). The full sweep was run at the rule's first
# target, 1e-4 (bench --inertial-target 1e-4): the table and chart give each rate against
# the suggestion of the rule now, CEMENTED_TARGET (the suggestion is proportional to the target).
CEMENTED_TARGET = 2.5e-5  # dem::CementedTargetInertialNumber
FULL = {"particles": 200, "rate_runs": [("rates", [64, 16, 4, 1, 0.5, 0.25], 1e-4),
                                        ("rates_slow", [0.0625], 1e-4)],
        "moduli": [1e10, 1e9, 1e8, 1e7], "modulus_factor": 16, "threads_factor": 64}
QUICK = {"particles": 300, "rate_runs": [("rates", [256, 128, 64], None)], "moduli": [1e10, 1e8], "modulus_factor": 256,
         "threads_factor": 256}
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


def run(bench, args, work, name, reuse=True):
    """Runs the bench (or reuses WORK/name.txt written by the same command); its rows."""
    command = [bench] + args
    text = " ".join(command[1:])
    path = os.path.join(work, name + ".txt")
    if reuse and os.path.exists(path):
        with open(path) as f:
            lines = f.read().splitlines()
        if lines and lines[0] == "# command: " + text:
            return parse(lines), lines[1][2:] if len(lines) > 1 else ""
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
    return parse(output.splitlines()), note


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
    fig.tight_layout()
    image = os.path.join(out, "images", "speed_accuracy_rates.png")
    fig.savefig(image, dpi=80)
    plt.close(fig)
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
    fig.tight_layout()
    image = os.path.join(out, "images", "speed_accuracy_modulus.png")
    fig.savefig(image, dpi=80)
    plt.close(fig)
    body = table(["modulus (Pa)", "softer", "UCS (Pa)", "UCS vs 1x", "strain at peak", "E (Pa)", "UCS / E",
                  "peak within Max Strain", "timestep (s)", "steps", "run time (s)"],
                 [["%g" % r["modulus"], "%g" % s, "%.5g" % r["ucs"], "%+.2f %%" % pct(r["ucs"], ref["ucs"]),
                   "%.4g" % r["peak_strain"], "%.4g" % r["E"],
                   "%.4g" % (r["ucs"] / r["E"] if r["E"] > 0 else math.nan), "yes" if r["peaked"] else "no",
                   "%.3g" % r["timestep"], "%d" % r["steps"], "%.1f" % r["seconds"]] for r, s in zip(rows, soft)])
    text = "Commands: `rockdem_bench_rock %s` with `--modulus` each of %s (%s; %s).\n\n%s" % (
        commands[0], ", ".join("%g" % e for e in cfg["moduli"]), machine(), "; ".join(notes), body)
    return text, rows, [image]


def threads_section(bench, cfg, work, out):
    rows = []
    notes = []
    for threads in (1, 2):
        args = ["--particles", str(cfg["particles"]), "--threads", str(threads), "--tests", "rates",
                "--rate-factors", "%g" % cfg["threads_factor"]] + ROCK
        r, note = run(bench, args, work, "threads_%d" % threads, cfg is FULL)
        r[0]["threads"] = threads
        rows.append(r[0])
        notes.append(note)
    same = rows[0]["ucs_text"] == rows[1]["ucs_text"] and rows[0]["steps"] == rows[1]["steps"]
    body = table(["threads", "UCS (Pa), all digits", "steps", "run time (s)"],
                 [["%d" % r["threads"], r["ucs_text"], "%d" % r["steps"], "%.1f" % r["seconds"]] for r in rows])
    text = "Command: `rockdem_bench_rock --particles %d --threads T --tests rates --rate-factors %g %s` (%s; %s).\n\n%s\n\n" \
        "Bitwise agreement of the UCS and the step count: **%s**; speed-up %.2f." % (
            cfg["particles"], cfg["threads_factor"], " ".join(ROCK), machine(), "; ".join(notes), body,
            "yes" if same else "NO", rows[0]["seconds"] / rows[1]["seconds"] if rows[1]["seconds"] > 0 else math.nan)
    return text, rows, []


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
    parser.add_argument("--only", default="rates,modulus,threads", help="sections to run (comma list)")
    o = parser.parse_args()
    cfg = QUICK if o.quick else FULL
    work = o.work or os.path.join(o.out, "atlas_runs")
    os.makedirs(os.path.join(o.out, "images"), exist_ok=True)
    os.makedirs(work, exist_ok=True)
    sections, numbers, images = {}, [], []
    makers = {"rates": rates_section, "modulus": modulus_section, "threads": threads_section}
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
