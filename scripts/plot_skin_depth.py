#!/usr/bin/env python3
"""Does the failure sit in the skin? Broken bonds against depth below the side surface, for
failed box and cylinder specimens written by `rockdem_bench_rock --tests ucs --dump DIR`
(DIR/ucs_failed.csv, DIR/ucs_failed_cylinder.csv; Documentation/Rock.md, "Carved
cylinders: does the failure leave the skin?").

    scripts/plot_skin_depth.py LABEL:box:DIR/ucs_failed.csv LABEL:cylinder:DIR/ucs_failed_cylinder.csv \
        -o PREFIX

Depth is measured, in mean grain diameters, from the outermost grain centres at the start of
the test (box: the nearest of the four side faces of their bounding box; cylinder about Z:
the largest centre distance from the axis), as rockdem_bench_rock's "outer grain layer"
(depth < 1) is; grains are placed where they were at the start, cracks where they broke. Writes

- PREFIX_depth.png: broken bonds per grain in shells one mean diameter thick (grain centres
  and crack positions binned by their depth), over the specimen's mean (1: the damage is
  uniform across the section; a skin failure is a peak in the first shell);
- PREFIX_plan.png: the broken bonds of the middle half of the height seen along the axis
  (a skin failure is a ring or frame, a failure through the middle fills the section);

and prints each specimen's shell values and the share of its broken bonds within one mean
diameter of the side surface against that shell's share of the grains. Needs matplotlib
and numpy (Debian: python3-matplotlib, python3-numpy).
"""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_plotting import pyplot  # noqa: E402

plt = pyplot()
import numpy as np  # noqa: E402


def read(path):
    grains, cracks = [], []
    with open(path) as f:
        for row in csv.DictReader(f):
            xyz = (float(row["x"]), float(row["y"]), float(row["z"]))
            if row["kind"] == "particle":  # where the grain was at the start of the test
                grains.append((xyz[0] - float(row["dx"]), xyz[1] - float(row["dy"]), xyz[2] - float(row["dz"]),
                               float(row["radius"])))
            elif row["kind"] in ("tension", "shear"):
                cracks.append(xyz)
    return np.array(grains), np.array(cracks).reshape(-1, 3)


def depth_function(grains, shape):
    x, y = grains[:, 0], grains[:, 1]
    lo_x, hi_x, lo_y, hi_y = x.min(), x.max(), y.min(), y.max()
    if shape == "cylinder":
        cx, cy = 0.5 * (lo_x + hi_x), 0.5 * (lo_y + hi_y)
        outer = np.max(np.hypot(x - cx, y - cy))
        return lambda p: outer - np.hypot(p[:, 0] - cx, p[:, 1] - cy), (cx, cy)
    return (lambda p: np.minimum.reduce([p[:, 0] - lo_x, hi_x - p[:, 0], p[:, 1] - lo_y, hi_y - p[:, 1]]),
            (0.5 * (lo_x + hi_x), 0.5 * (lo_y + hi_y)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dumps", nargs="+", help="LABEL:box|cylinder:PATH")
    parser.add_argument("-o", "--prefix", default="skin")
    args = parser.parse_args()
    specs = []
    for spec in args.dumps:
        label, shape, path = spec.split(":", 2)
        if shape not in ("box", "cylinder"):
            sys.exit("shape must be box or cylinder: " + spec)
        specs.append((label, shape, path))
    fig, ax = plt.subplots(figsize=(6.0, 4.0))
    pfig, paxes = plt.subplots(1, len(specs), figsize=(3.2 * len(specs), 3.6), squeeze=False)
    for n, (label, shape, path) in enumerate(specs):
        grains, cracks = read(path)
        d = 2.0 * grains[:, 3].mean()
        depth, centre = depth_function(grains, shape)
        gd, cd = depth(grains) / d, depth(cracks) / d
        edges = np.concatenate(([-1.0], np.arange(1.0, gd.max() + 1.0, 1.0)))  # cracks can lie outside the centres
        g_count, _ = np.histogram(gd, edges)
        c_count, _ = np.histogram(cd, edges)
        mean = len(cracks) / len(grains)
        ok = g_count >= 10
        per = np.where(ok, c_count / np.maximum(g_count, 1) / mean, np.nan)
        mid = np.arange(len(g_count)) + 0.5
        ax.plot(mid[ok], per[ok], "o-", label="%s (%d cracks)" % (label, len(cracks)))
        skin_g = np.mean(gd < 1.0)
        skin_c = np.mean(cd < 1.0) if len(cracks) else 0.0
        print("%s: %d grains, %d broken bonds; within one diameter of the side surface: %.1f %% of the broken "
              "bonds, %.1f %% of the grains (ratio %.2f)" % (label, len(grains), len(cracks), 100 * skin_c,
                                                            100 * skin_g, skin_c / skin_g if skin_g else 0.0))
        print("  broken bonds per grain over the mean, shells of one diameter from the surface: " +
              " ".join("%.2f" % v for v in per[ok]))
        z0, z1 = grains[:, 2].min(), grains[:, 2].max()
        middle = (cracks[:, 2] > z0 + 0.25 * (z1 - z0)) & (cracks[:, 2] < z1 - 0.25 * (z1 - z0))
        pax = paxes[0][n]
        pax.plot((cracks[middle, 0] - centre[0]) * 1e3, (cracks[middle, 1] - centre[1]) * 1e3, ".", color="black",
                 markersize=1.5)
        pax.set_aspect("equal")
        pax.set_title("%s\n%d cracks, middle half of the height" % (label, int(middle.sum())), fontsize=8)
        pax.set_xlabel("x (mm)")
        pax.set_ylabel("y (mm)")
    ax.axhline(1.0, color="grey", lw=0.8)
    ax.set_xlabel("depth below the side surface (mean grain diameters)")
    ax.set_ylabel("broken bonds per grain / specimen mean")
    ax.legend(fontsize=7)
    ax.set_title("Where the broken bonds lie across the section", fontsize=9)
    fig.tight_layout()
    fig.savefig(args.prefix + "_depth.png", dpi=100)
    pfig.tight_layout()
    pfig.savefig(args.prefix + "_plan.png", dpi=100)
    print("wrote", args.prefix + "_depth.png", args.prefix + "_plan.png")


if __name__ == "__main__":
    main()
