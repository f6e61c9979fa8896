#!/usr/bin/env python3
"""Chart and summary of the RockDEM / YADE JCFpm stress-strain curves (scripts/benchmark_yade_jcfpm.sh).

    scripts/yade_plot.py ROCKDEM.csv YADE.csv [-o chart.png] [--title TEXT]

Each CSV has the columns step, axial_strain, axial_stress_pa, broken_tension, broken_shear
(written by scripts/yade_rockdem.py run and scripts/yade_jcfpm.py). Prints, for each code,
the peak stress and its strain, the secant modulus between 10 % and 50 % of the peak (as
rockdem.elastic_constants) and the broken bonds at the end; with -o, draws both curves
(stress in MPa against strain in %) and the broken bonds on one chart. Needs matplotlib
(Debian: python3-matplotlib).
"""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("%s holds no rows" % path)
    cols = {k: [float(r[k]) for r in rows] for k in rows[0]}
    return cols


def summary(name, c):
    stress, strain = c["axial_stress_pa"], c["axial_strain"]
    ipeak = max(range(len(stress)), key=lambda i: stress[i])
    peak = stress[ipeak]
    pts = [(e, s) for e, s in zip(strain[:ipeak + 1], stress[:ipeak + 1]) if 0.1 * peak <= s <= 0.5 * peak]
    if len(pts) >= 2:
        (e1, s1), (e2, s2) = pts[0], pts[-1]
        modulus = (s2 - s1) / (e2 - e1) if e2 > e1 else float("nan")
    else:
        modulus = float("nan")
    broken = int(c["broken_tension"][-1] + c["broken_shear"][-1])
    print("%-8s peak %.4g Pa at strain %.5f (step %d); modulus (10-50 %% of the peak) %.4g Pa; stress at the "
          "end %.4g Pa (strain %.5f); broken bonds at the end %d (%d tension, %d shear)"
          % (name, peak, strain[ipeak], c["step"][ipeak], modulus, stress[-1], strain[-1], broken,
             c["broken_tension"][-1], c["broken_shear"][-1]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("rockdem")
    ap.add_argument("yade")
    ap.add_argument("-o", "--output", help="chart PNG")
    ap.add_argument("--title", default="")
    a = ap.parse_args()
    plt = None
    if a.output:  # first: pyplot() may run the script again under /usr/bin/python3
        from rockdem_plotting import pyplot
        plt = pyplot()
    ours, theirs = read(a.rockdem), read(a.yade)
    summary("RockDEM", ours)
    summary("YADE", theirs)
    if plt is None:
        return
    fig, ax = plt.subplots(figsize=(8, 5))
    for c, label, colour in ((ours, "RockDEM (parallel bond, Moment Contribution 0)", "tab:blue"),
                             (theirs, "YADE 2023.02a JCFpm", "tab:red")):
        ax.plot([100 * e for e in c["axial_strain"]], [s / 1e6 for s in c["axial_stress_pa"]], color=colour,
                label=label)
    ax.set_xlabel("axial strain (%)")
    ax.set_ylabel("axial stress (MPa)")
    ax.grid(alpha=0.3)
    right = ax.twinx()
    for c, colour in ((ours, "tab:blue"), (theirs, "tab:red")):
        right.plot([100 * e for e in c["axial_strain"]],
                   [t + s for t, s in zip(c["broken_tension"], c["broken_shear"])], color=colour, ls=":")
    right.set_ylabel("broken bonds (dotted)")
    ax.legend(loc="upper left")
    ax.set_title("Unconfined compression, identical specimen and bonds" + (": " + a.title if a.title else ""))
    fig.tight_layout()
    tmp = a.output + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, a.output)
    print("chart: %s" % a.output)


if __name__ == "__main__":
    main()
