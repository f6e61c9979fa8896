#!/usr/bin/env python3
"""Table and chart of the rock-behaviour series (Documentation/Rock.md).

    scripts/plot_rock.py LOG [LOG ...] [-o chart.png] [--table table.md]

Each LOG is the output of one rockdem_bench_rock run (scripts/rock_series.sh writes one per
Bond Range). Reads the bonded coordination, porosity, UCS, E, nu, direct tensile strength,
UCS / sigma_t, the Mohr-Coulomb fit (friction angle, R^2; when the run had triaxial tests),
the share of broken bonds near the platens and the DFN, and writes a Markdown table and a
chart: UCS / sigma_t (left axis) and friction angle (right axis) against bonded
coordination. Needs matplotlib (Debian: python3-matplotlib).
"""
import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_plotting import pyplot  # noqa: E402

plt = pyplot()

PATTERNS = {
    "particles": r"specimen: (\d+) particles",
    "across": r"([\d.]+) mean diameters across",
    "porosity": r"porosity [\d.]+ -> ([\d.]+)",
    "range": r"cement: Bond Range ([\d.]+)",
    "beta": r"Moment Contribution ([\d.]+)",
    "coordination": r"bonded coordination ([\d.]+)",
    "ucs": r"^UCS ([\d.e+-]+) Pa",
    "E": r"; E ([\d.e+-]+) Pa",
    "nu": r"; nu ([\d.e+-]+);",
    "platens": r"broken within 2 diameters of a platen: ([\d.]+) %",
    "discs": r"DFN: (\d+) discs",
    "disc_width": r"largest radius [\d.e+-]+ m \(([\d.]+) % of the width\)",
    "disc_share": r"([\d.]+) % of broken bonds in discs",
    "tensile": r"^direct tension ([\d.e+-]+) Pa",
    "ratio": r"UCS / sigma_t = ([\d.]+)",
    "phi": r"friction angle ([\d.-]+) deg",
    "r2": r"R\^2 ([\d.-]+)",
}


def parse(path):
    text = open(path).read()
    row = {"log": os.path.basename(path)}
    for key, pattern in PATTERNS.items():
        m = re.search(pattern, text, re.M)
        row[key] = float(m.group(1)) if m else None
    return row


def fmt(v, spec):
    return "-" if v is None else spec % v


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("logs", nargs="+")
    parser.add_argument("-o", "--output", default="rock_chart.png")
    parser.add_argument("--table", default=None)
    args = parser.parse_args()
    rows = sorted((parse(p) for p in args.logs), key=lambda r: r["coordination"] or 0.0)
    lines = ["| Bond Range | beta | particles | across | porosity | bonded coordination | UCS (Pa) | E (Pa) | nu "
             "| sigma_t (Pa) | UCS / sigma_t | phi (deg) | R^2 | broken near platens | DFN discs | largest disc / width "
             "| broken bonds in discs |",
             "|" + "---|" * 17]
    for r in rows:
        lines.append("| " + " | ".join([
            fmt(r["range"], "%.2f"), fmt(r["beta"], "%g"), fmt(r["particles"], "%d"), fmt(r["across"], "%.1f"),
            fmt(r["porosity"], "%.3f"), fmt(r["coordination"], "%.2f"), fmt(r["ucs"], "%.4g"), fmt(r["E"], "%.3g"),
            fmt(r["nu"], "%.3f"), fmt(r["tensile"], "%.4g"), fmt(r["ratio"], "%.2f"), fmt(r["phi"], "%.1f"),
            fmt(r["r2"], "%.3f"), fmt(r["platens"], "%.1f %%"), fmt(r["discs"], "%d"),
            fmt(r["disc_width"], "%.0f %%"), fmt(r["disc_share"], "%.1f %%")]) + " |")
    table = "\n".join(lines) + "\n"
    print(table)
    if args.table:
        with open(args.table, "w") as f:
            f.write(table)
    x = [r["coordination"] for r in rows if r["coordination"] is not None and r["ratio"] is not None]
    y = [r["ratio"] for r in rows if r["coordination"] is not None and r["ratio"] is not None]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(x, y, "o-", color="tab:red", label="UCS / direct tensile strength")
    ax.axhline(10.0, color="tab:red", ls=":", lw=1)
    ax.set_xlabel("bonded coordination (2 x bonds / particles)")
    ax.set_ylabel("UCS / sigma_t", color="tab:red")
    phis = [(r["coordination"], r["phi"]) for r in rows if r["phi"] is not None]
    if phis:
        ax2 = ax.twinx()
        ax2.plot([p[0] for p in phis], [p[1] for p in phis], "s--", color="tab:blue", label="friction angle")
        ax2.axhline(40.0, color="tab:blue", ls=":", lw=1)
        ax2.set_ylabel("friction angle (deg)", color="tab:blue")
    for r in rows:
        if r["coordination"] is not None and r["ratio"] is not None:
            ax.annotate("%.2f" % r["range"], (r["coordination"], r["ratio"]), textcoords="offset points",
                        xytext=(4, -12), fontsize=8)
    ax.set_title("Rock behaviour against bonded coordination (labels: Bond Range)")
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print("chart:", args.output)


if __name__ == "__main__":
    main()
