#!/usr/bin/env python3
"""How strongly the broken bonds of a failed specimen gather in one planar band: the best
strip (2D) or slab (3D) of a given width, over every orientation and offset, and the share
of the cracks it holds against the share of the specimen it covers.

Reads DIR/ucs_failed.csv written by `rockdem_bench_rock --tests ucs --dump DIR` (2D or 3D:
the specimen at the frame where the stress has fallen to 70 % of its peak). For the cracks
of that frame and for those formed after the peak alone it prints

    excess = crack share in the band - area (volume) share of the band

maximised over the band's normal (2D: every degree; 3D: 2,000 directions on a hemisphere)
and its offset (steps of a quarter of the width), the band's crack and area shares, its
concentration (their ratio) and its normal (dip from the loading axis), and the same for a
control: as many points spread uniformly over the specimen's box (seeded, so repeatable).
A band of cracks has an excess well above the control's; diffuse damage has about the
control's. Documentation/Rock.md, "How much the damage localises".

    scripts/localisation_index.py DIR/ucs_failed.csv[:LABEL] ... [--width 4] [--axis y|z]

--width is in mean grain diameters (default 4). --axis is the loading axis (default: y for a
2D section, whose grains all have one z, else z). Needs numpy.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from failed_dump import read_dump  # noqa: E402
import numpy as np  # noqa: E402


def directions(dimension, count=2000):
    """Unit normals: every degree in the plane (2D), or a Fibonacci hemisphere (3D)."""
    if dimension == 2:
        theta = np.radians(np.arange(180.0))
        return np.stack([np.cos(theta), np.sin(theta), np.zeros_like(theta)], axis=1)
    k = np.arange(count) + 0.5
    z = k / count  # upper hemisphere, uniform in z
    phi = np.pi * (1.0 + 5.0 ** 0.5) * k
    r = np.sqrt(1.0 - z * z)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)


def best_band(points, reference, normals, width):
    """The band (normal, offset) of the given width with the largest excess of the points'
    share over the reference points' share. Returns (excess, share, area_share, normal)."""
    step = width / 4.0
    best = (-1.0, 0.0, 0.0, normals[0])
    for n in normals:
        s = points @ n
        r = reference @ n
        lo = min(s.min(), r.min())
        bins = np.arange(lo, max(s.max(), r.max()) + width + step, step)
        hs = np.histogram(s, bins)[0].astype(float) / len(s)
        hr = np.histogram(r, bins)[0].astype(float) / len(r)
        window = np.ones(4)
        cs = np.convolve(hs, window, mode="valid")
        cr = np.convolve(hr, window, mode="valid")
        excess = cs - cr
        i = int(np.argmax(excess))
        if excess[i] > best[0]:
            best = (float(excess[i]), float(cs[i]), float(cr[i]), n)
    return best


def dip(normal, axis):
    """Angle of the band's plane from the loading axis, degrees (0: the band contains the
    loading axis, a split; 90: it is perpendicular to it, a layer under a platen)."""
    return float(np.degrees(np.arcsin(min(1.0, abs(normal[axis])))))


def band_excess(points, box, normals, width, rng):
    """The best band of the points against a uniform spread over box, and the same for a
    control of as many uniform points: ((excess, share, area_share, normal), control)."""
    reference = rng.uniform(box[0], box[1], size=(20000, 3))
    control = rng.uniform(box[0], box[1], size=(len(points), 3))
    if np.all(box[0][2] == box[1][2]):
        reference[:, 2] = control[:, 2] = box[0][2]
    return best_band(points, reference, normals, width), best_band(control, reference, normals, width)


def report(label, what, points, box, normals, width, axis, rng):
    if len(points) < 10:
        print("%-28s %-12s %6d cracks: too few" % (label, what, len(points)))
        return
    (e, share, area, n), (ec, sc, ac, _) = band_excess(points, box, normals, width, rng)
    print("%-28s %-12s %6d cracks: excess %.3f (band holds %.1f %% on %.1f %% of the specimen, "
          "x%.2f; plane %.0f deg from the loading axis) | control excess %.3f (%.1f %% on %.1f %%)"
          % (label, what, len(points), e, 100 * share, 100 * area, share / max(area, 1e-12),
             dip(n, axis), ec, 100 * sc, 100 * ac))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dumps", nargs="+", help="ucs_failed.csv, optionally :LABEL")
    parser.add_argument("--width", type=float, default=4.0, help="band width, mean grain diameters")
    parser.add_argument("--axis", choices=("x", "y", "z"), default=None, help="loading axis")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    for spec in args.dumps:
        path, _, label = spec.partition(":")
        g, b = read_dump(path)
        flat = np.ptp(g[:, 2]) == 0.0
        dimension = 2 if flat else 3
        axis = "xyz".index(args.axis) if args.axis else (1 if flat else 2)
        width = args.width * 2.0 * g[:, 3].mean()
        box = (g[:, 0:3].min(axis=0), g[:, 0:3].max(axis=0))
        normals = directions(dimension)
        rng = np.random.default_rng(args.seed)
        label = label or path
        report(label, "all", b[:, 0:3], box, normals, width, axis, rng)
        report(label, "after peak", b[b[:, 3] == 1][:, 0:3], box, normals, width, axis, rng)


if __name__ == "__main__":
    main()
