#!/usr/bin/env python3
"""Triaxial envelopes of the same rock in a rigid box and in a membrane cylinder, on one
chart, and a picture of the membrane specimen after failure (Documentation/Specimens.md).

    scripts/plot_envelopes.py LOG [-o envelopes.png] [--specimen DIR/membrane_failed.csv
                              --picture membrane_failed.png]

LOG is the output of `rockdem_bench_rock --tests envelopes --specimen both --sigma3 ...`
(scripts/membrane_envelopes.sh). Reads its "envelope" and "envelope-fit" lines and plots peak
sigma1 against sigma3 for both specimens with their Mohr-Coulomb lines. The picture is a
slice through the cylinder's axis (grains within one mean diameter of the XZ plane through
the axis, coloured by their radial displacement during the test) with the broken bonds of
that slab (tension black, shear gold). Needs
matplotlib (Debian: python3-matplotlib).
"""
import argparse
import csv
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_plotting import pyplot  # noqa: E402

plt = pyplot()
from matplotlib.collections import PatchCollection  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402

POINT = re.compile(r"^envelope (\w+) sigma3 (\S+) sigma1 (\S+)")
FIT = re.compile(r"^envelope-fit (\w+): sigma1 = (\S+) \+ (\S+) sigma3; friction angle (\S+) deg, cohesion (\S+) Pa")
LABELS = {"box": "rigid box (six servo faces)", "cylinder": "cylinder in a membrane"}


def read_log(path):
    points, fits = {}, {}
    with open(path) as f:
        for line in f:
            m = POINT.match(line)
            if m:
                points.setdefault(m.group(1), []).append((float(m.group(2)), float(m.group(3))))
            m = FIT.match(line)
            if m:
                fits[m.group(1)] = tuple(float(m.group(k)) for k in range(2, 6))
    return points, fits


def envelope_chart(points, fits, out):
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    for kind, marker in (("box", "s"), ("cylinder", "o")):
        if kind not in points:
            continue
        s3 = [p[0] / 1e6 for p in points[kind]]
        s1 = [p[1] / 1e6 for p in points[kind]]
        line = ax.plot(s3, s1, marker, label=LABELS[kind])[0]
        if kind in fits and all(math.isfinite(v) for v in fits[kind]):  # a single test has no fit
            a, b, phi, c = fits[kind]
            xs = [0.0, max(s3) * 1.1]
            ax.plot(xs, [a / 1e6 + b * x for x in xs], "-", color=line.get_color(),
                    label="%s fit: phi %.1f deg, c %.2f MPa" % (kind, phi, c / 1e6))
    ax.set_xlabel("confining stress sigma3 (MPa)")
    ax.set_ylabel("peak axial stress sigma1 (MPa)")
    ax.set_xlim(left=0.0)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("Triaxial envelopes: the same rock, rigid box vs membrane cylinder")
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print("wrote", out)


def specimen_picture(path, out, title="Membrane cylinder after failure"):
    grains, cracks = [], {"tension": [], "shear": []}
    with open(path) as f:
        for row in csv.DictReader(f):
            xyz = (float(row["x"]), float(row["y"]), float(row["z"]))
            if row["kind"] == "particle":
                if "dx" in row:
                    grains.append(xyz + (float(row["radius"]), float(row["dx"]), float(row["dy"]), float(row["dz"])))
                else:  # an older dump: the displacement magnitude since the pack was built
                    grains.append(xyz + (float(row["radius"]), float(row["displacement"]), None, None))
            elif row["kind"] in cracks:
                cracks[row["kind"]].append(xyz)
            elif row["kind"] == "broken":  # an older dump: no crack kinds
                cracks.setdefault("broken", []).append(xyz)
    if not grains:
        sys.exit("no particles in " + path)
    cx = sum(g[0] for g in grains) / len(grains)
    cy = sum(g[1] for g in grains) / len(grains)
    diameter = 2.0 * sum(g[3] for g in grains) / len(grains)
    # The slab through the axis (the XZ plane through the centroid), one mean diameter thick
    # on either side; colour: the radial displacement during the test (outward positive).
    slab = [g for g in grains if abs(g[1] - cy) <= diameter]

    vectors = slab[0][5] is not None

    def radial(g):
        if not vectors:
            return g[4]
        rx, ry = g[0] - cx, g[1] - cy
        r = (rx * rx + ry * ry) ** 0.5 or 1.0
        return (g[4] * rx + g[5] * ry) / r

    fig, ax = plt.subplots(figsize=(4.8, 7.2))
    coll = PatchCollection([Circle((g[0] * 1e3, g[2] * 1e3), g[3] * 1e3) for g in slab],
                           cmap="coolwarm" if vectors else "viridis", edgecolor="none")
    values = [radial(g) * 1e3 for g in slab]
    coll.set_array(values)
    if vectors:
        top = max(abs(v) for v in values) or 1.0
        coll.set_clim(-top, top)
    ax.add_collection(coll)
    for kind, colour in (("tension", "black"), ("shear", "gold"), ("broken", "red")):
        pts = [c for c in cracks.get(kind, []) if abs(c[1] - cy) <= diameter]
        if not pts:
            continue
        ax.plot([c[0] * 1e3 for c in pts], [c[2] * 1e3 for c in pts], ".", color=colour, markersize=2.5,
                label="%s cracks (%d in the slab)" % (kind, len(pts)))
    fig.colorbar(coll, ax=ax, label="radial displacement during the test (mm, outward +)" if vectors
                 else "displacement since the pack was built (mm)")
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("z (mm, axis)")
    ax.legend(loc="upper right", fontsize=7)
    ax.set_title(title + "\n(slab through the axis)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print("wrote", out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("log")
    parser.add_argument("-o", "--output", default="envelopes.png")
    parser.add_argument("--specimen", help="membrane_failed.csv written by rockdem_bench_rock --dump")
    parser.add_argument("--picture", default="membrane_failed.png")
    args = parser.parse_args()
    points, fits = read_log(args.log)
    if not points:
        sys.exit("no 'envelope' lines in " + args.log)
    envelope_chart(points, fits, args.output)
    if "box" in fits and "cylinder" in fits:
        for kind in ("box", "cylinder"):
            a, b, phi, c = fits[kind]
            print("%s: friction angle %.2f deg, cohesion %.4g Pa, peaks %s" % (
                kind, phi, c, ", ".join("%.4g" % p[1] for p in points[kind])))
    if args.specimen:
        specimen_picture(args.specimen, args.picture)


if __name__ == "__main__":
    main()
