#!/usr/bin/env python3
"""Pictures of a failed 2D section written by `rockdem_bench_rock --dimension 2 --tests ucs
--dump DIR` (DIR/ucs_failed.csv: the section at the frame where the stress has fallen to
70 % of its peak; Documentation/Rock.md, "Damping during the test"). One column per dump:
top, the discs coloured by the non-affine part of their displacement from the peak to
that frame (the least-squares affine field taken out: where the section slides or opens),
the bonds broken before the peak as grey dots and after it as red dots; bottom, the bonds
broken after the peak alone (a shear band or a split shows as a strip of them).

    scripts/plot_section2d.py DIR1/ucs_failed.csv[:LABEL] [DIR2/ucs_failed.csv[:LABEL] ...] -o out.png \
        [--dfn DFN1.csv,DFN2.csv,...]

--dfn draws the traces of the discs of DEM Fractures To DFN's Summary table (Save Data of
its second port; one per dump, in order, empty to skip one) on both rows, in blue.

Needs matplotlib (Debian: python3-matplotlib).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_localisation import affine_fit, plt, read_dump  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PatchCollection  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402


def read_traces(path):
    """The disc traces of a 2D DFN summary table: a segment of length 2 x Radius through
    the centre, perpendicular to the normal, in the XY plane."""
    import csv
    traces = []
    with open(path) as f:
        for row in csv.DictReader(f):
            c = np.array([float(row["CenterX"]), float(row["CenterY"])])
            n = np.array([float(row["NormalX"]), float(row["NormalY"])])
            t = np.array([-n[1], n[0]]) / np.linalg.norm(n)
            r = float(row["Radius"])
            traces.append((tuple(c - r * t), tuple(c + r * t)))
    return traces


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dumps", nargs="+", help="ucs_failed.csv of a 2D run, optionally :LABEL")
    parser.add_argument("-o", "--output", default="section2d.png")
    parser.add_argument("--dfn", default="", help="DFN summary CSVs, comma-separated, one per dump")
    args = parser.parse_args()
    dfns = args.dfn.split(",") if args.dfn else []
    columns = len(args.dumps)
    fig, axes = plt.subplots(2, columns, figsize=(3.4 * columns, 11.5), squeeze=False)
    for k, spec in enumerate(args.dumps):
        path, _, label = spec.partition(":")
        g, b = read_dump(path)
        xy, radius = g[:, 0:2], g[:, 3]
        increment = g[:, 4:6] - g[:, 7:9]  # displacement from the peak to the end
        residual = np.linalg.norm(increment - affine_fit(xy, increment), axis=1)
        before, after = b[b[:, 3] == 0], b[b[:, 3] == 1]
        top, bottom = axes[0, k], axes[1, k]
        discs = PatchCollection([Circle(c, r) for c, r in zip(xy, radius)], cmap="viridis")
        discs.set_array(residual)
        discs.set_clim(0.0, np.percentile(residual, 98))
        top.add_collection(discs)
        top.plot(before[:, 0], before[:, 1], ".", color="0.55", ms=1.2)
        top.plot(after[:, 0], after[:, 1], ".", color="red", ms=1.6)
        top.set_title("%s\nnon-affine motion after the peak;\ncracks before (grey, %d) / after (red, %d)"
                      % (label or path, len(before), len(after)), fontsize=8)
        bottom.plot(after[:, 0], after[:, 1], ".", color="red", ms=1.6)
        bottom.set_title("%s: the %d bonds broken after the peak" % (label or "", len(after)), fontsize=8)
        traces = read_traces(dfns[k]) if k < len(dfns) and dfns[k] else []
        for ax in (top, bottom):
            for (x0, y0), (x1, y1) in traces:
                ax.plot([x0, x1], [y0, y1], "-", color="blue", lw=1.2)
        if traces:
            bottom.set_title(bottom.get_title() + "\nblue: the %d DFN discs' traces" % len(traces), fontsize=8)
        for ax in (top, bottom):
            ax.set_xlim(xy[:, 0].min() - radius.max(), xy[:, 0].max() + radius.max())
            ax.set_ylim(xy[:, 1].min() - radius.max(), xy[:, 1].max() + radius.max())
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
    fig.tight_layout()
    fig.savefig(args.output, dpi=64)
    print("wrote", args.output)


if __name__ == "__main__":
    main()
