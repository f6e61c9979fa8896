#!/usr/bin/env python3
"""Localisation after the peak in a failed cylinder (Documentation/Specimens.md, "After
failure"): the deformation after the peak rather than the cumulative cracks.

    scripts/plot_localisation.py DIR/membrane_failed.csv -o PREFIX [--title TEXT]

Reads the dump of `rockdem_bench_rock --tests envelopes --specimen cylinder --dump DIR`
(or, with --outer-layer, DIR/ucs_failed_cylinder.csv of `--tests ucs --specimen cylinder`: the
outer grain layer then stands for the membrane's surface grains)
(one line per grain: position at the end, displacement during the test d, to the start of
the shear stage s, to the peak p, to the fall to 90 % of the peak f, membrane surface flags;
one line per broken bond with `after_peak`) and writes

- PREFIX_increment.png: two slabs through the axis (the XZ and YZ planes through it, one
  mean grain diameter either side), grains coloured by the axial component of their
  displacement increment from the peak to the end, and by the lateral component of its
  non-affine part (the increment less the
  best linear field u = A x + b fitted to all grains), with the bonds broken after the peak;
- PREFIX_surface.png: the lateral surface seen from outside, unrolled (angle about the
  axis against height): the surface grains at the end coloured by the non-affine increment,
  and the bonds broken after the peak within one mean diameter of the surface;
- PREFIX_radius.png: the membrane's radius profile along the axis (the surface grains'
  outer radius, centre distance + radius, averaged in slices) at the start of the shear
  stage (after the consolidation), the peak and the end, and the change since the start,
  also followed on the same grains (the start's surface grains' radial displacement):
  barrelling shows as a middle that grows more than the ends.

and prints the numbers the pictures are read with: the increment statistics (mean, affine
and non-affine parts, the share of the non-affine increment carried by the top 10 % of the
grains), where along the axis the shortening after the peak happens (the mean axial
increment in slices of the height), the after-peak breaks' spread, the boundary on the
surface of the part that moves with the platen and the plane whose trace fits it, and the
radius profile. Needs matplotlib and numpy (Debian:
python3-matplotlib, python3-numpy).
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_plotting import pyplot  # noqa: E402

plt = pyplot()
import numpy as np  # noqa: E402
from failed_dump import read_dump  # noqa: E402,F401 (the dump reader, shared)
from matplotlib.collections import PatchCollection  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402


def affine_fit(x, u):
    """Least-squares u = A x + b over the grains; returns the fitted field."""
    design = np.hstack([x, np.ones((len(x), 1))])
    coef, *_ = np.linalg.lstsq(design, u, rcond=None)
    return design @ coef


def radius_profile(xy_centre, pos, radius, on_surface, z0, z1, slices):
    rel = pos[:, :2] - xy_centre
    outer = np.sqrt(np.sum(rel ** 2, axis=1)) + radius
    edges = np.linspace(z0, z1, slices + 1)
    mids, means = [], []
    for k in range(slices):
        sel = on_surface & (pos[:, 2] >= edges[k]) & (pos[:, 2] < edges[k + 1])
        if sel.sum():
            mids.append(0.5 * (edges[k] + edges[k + 1]))
            means.append(float(outer[sel].mean()))
    return np.array(mids), np.array(means)


def slab_panel(ax, g, values, bonds_after, centre, diameter, plane, label, cmap, symmetric):
    other = 1 if plane == 0 else 0  # plane 0: XZ (slab across y), 1: YZ (slab across x)
    sel = np.abs(g[:, other] - centre[other]) <= diameter
    horizontal = 0 if plane == 0 else 1
    coll = PatchCollection([Circle(((p[horizontal] - centre[horizontal]) * 1e3, p[2] * 1e3), p[3] * 1e3)
                            for p in g[sel]], cmap=cmap, edgecolor="none")
    v = values[sel] * 1e3
    coll.set_array(v)
    if symmetric:
        top = float(np.percentile(np.abs(v), 98)) or 1.0
        coll.set_clim(-top, top)
    else:
        coll.set_clim(0.0, float(np.percentile(v, 98)) or 1.0)
    ax.add_collection(coll)
    bsel = np.abs(bonds_after[:, other] - centre[other]) <= diameter
    ax.plot((bonds_after[bsel, horizontal] - centre[horizontal]) * 1e3, bonds_after[bsel, 2] * 1e3, ".",
            color="black", markersize=2.0, label="broken after the peak (%d)" % int(bsel.sum()))
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlabel(("x" if plane == 0 else "y") + " from the axis (mm)")
    ax.set_ylabel("z (mm)")
    ax.set_title(label, fontsize=8)
    ax.legend(loc="lower right", fontsize=6)
    plt.colorbar(coll, ax=ax, shrink=0.6, label="mm")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dump")
    parser.add_argument("-o", "--prefix", default="membrane")
    parser.add_argument("--title", default="Membrane cylinder after the peak")
    parser.add_argument("--from", dest="start", choices=("peak", "fall"), default="peak",
                        help="the increment from the peak (default) or from the fall to 90 %% of it, to the end")
    parser.add_argument("--outer-layer", action="store_true",
                        help="a cylinder without a membrane (rockdem_bench_rock --tests ucs --specimen cylinder): "
                             "take its outer grain layer (centre at the start within one mean diameter of the "
                             "outermost, about the axis) as the surface grains")
    args = parser.parse_args()
    g, b = read_dump(args.dump)
    pos = g[:, 0:3]
    radius = g[:, 3]
    d, p, f = g[:, 4:7], g[:, 7:10], g[:, 10:13]
    flags = g[:, 13].astype(int)
    if args.outer_layer:
        start = pos - d  # where the grains were at the start of the test
        axis = 0.5 * (start[:, 0:2].min(axis=0) + start[:, 0:2].max(axis=0))
        r0 = np.hypot(start[:, 0] - axis[0], start[:, 1] - axis[1])
        flags = np.where(r0.max() - r0 < 2.0 * float(radius.mean()), 7, 0)
    shear = g[:, 14:17]  # zeros in a dump without the frame: the start of the test then
    diameter = 2.0 * float(radius.mean())
    centre = pos.mean(axis=0)
    inc = d - (p if args.start == "peak" else f)
    fitted = affine_fit(pos, inc)
    residual = inc - fitted
    mag = np.linalg.norm(inc, axis=1)
    res = np.linalg.norm(residual, axis=1)
    order = np.sort(res)[::-1]
    top10 = float(order[: max(1, len(order) // 10)].sum() / order.sum()) if order.sum() > 0 else 0.0
    after = b[b[:, 3] == 1] if len(b) else b
    print("grains %d, mean diameter %.4g m; bonds broken %d, after the peak %d (%.1f %% of the broken)" % (
        len(g), diameter, len(b), len(after), 100.0 * len(after) / max(1, len(b))))
    print("increment %s->end: mean |u| %.4g m (%.3f diameters), affine part mean %.4g m, non-affine mean %.4g m "
          "(%.2f of the affine), RMS %.4g m; top 10 %% of grains carry %.1f %% of the non-affine increment" % (
              args.start, mag.mean(), mag.mean() / diameter, np.linalg.norm(fitted, axis=1).mean(), res.mean(),
              res.mean() / max(1e-300, np.linalg.norm(fitted, axis=1).mean()), math.sqrt(float((res ** 2).mean())),
              100.0 * top10))
    if len(after):
        rel = after[:, :3] - after[:, :3].mean(axis=0)
        w = np.sort(np.linalg.eigvalsh(rel.T @ rel / len(rel)))
        print("after-peak breaks: spread (std) along their principal axes %.3g, %.3g, %.3g m "
              "(thinnest / thickest %.2f; a plane would be << 1); %.1f %% in tension" % (
                  math.sqrt(w[0]), math.sqrt(w[1]), math.sqrt(w[2]), math.sqrt(w[0] / w[2]),
                  100.0 * after[:, 4].mean()))

    # Slabs through the axis.
    fig, axes = plt.subplots(1, 4, figsize=(13, 5.2))
    for k, (plane, values, label, cmap, sym) in enumerate((
            (0, inc[:, 2], "axial increment (z), XZ slab", "PuOr", True),
            (0, residual[:, 0], "non-affine increment, x component, XZ slab", "coolwarm", True),
            (1, inc[:, 2], "axial increment (z), YZ slab", "PuOr", True),
            (1, residual[:, 1], "non-affine increment, y component, YZ slab", "coolwarm", True))):
        slab_panel(axes[k], g, values, after, centre, diameter, plane, label, cmap, sym)
    fig.suptitle(args.title + " (increment from the %s to the end)" % args.start, fontsize=10)
    fig.tight_layout()
    fig.savefig(args.prefix + "_increment.png", dpi=100)
    print("wrote", args.prefix + "_increment.png")

    # The surface seen from outside, unrolled.
    end_surface = (flags & 4) > 0
    if not end_surface.any():
        sys.exit("no membrane surface grains in " + args.dump + " (the surface pictures need a Confinement = "
                 "Membrane test; the slabs above are written)")
    theta = np.degrees(np.arctan2(pos[:, 1] - centre[1], pos[:, 0] - centre[0]))
    fig, axes = plt.subplots(1, 2, figsize=(11, 6))
    top = float(np.percentile(np.abs(inc[end_surface, 2]) * 1e3, 98)) or 1.0
    sc = axes[0].scatter(theta[end_surface], pos[end_surface, 2] * 1e3, c=inc[end_surface, 2] * 1e3, s=28,
                         cmap="PuOr", vmin=-top, vmax=top)
    plt.colorbar(sc, ax=axes[0], label="axial increment %s->end (mm)" % args.start)
    axes[0].set_title("surface grains at the end (%d), unrolled" % int(end_surface.sum()), fontsize=9)
    # The boundary of the part that moves down with the top platen after the peak, on the
    # surface: grains whose axial increment is below the midpoint of the surface's 10th and
    # 90th percentiles move with the platen; in each of 12 sectors the height that best splits
    # them from the rest (fewest grains on the wrong side), and the plane whose trace on the
    # cylinder fits those heights best (z = z0 + a cos theta + b sin theta).
    uz = inc[end_surface, 2]
    threshold = 0.5 * (np.percentile(uz, 10) + np.percentile(uz, 90))
    moving = uz < threshold
    ts, zsurf = theta[end_surface], pos[end_surface, 2]
    cuts, angles, wrong = [], [], 0
    for k in range(12):
        sel = (ts >= -180 + 30 * k) & (ts < -150 + 30 * k)
        if sel.sum() < 4:
            continue
        zk, mk = zsurf[sel], moving[sel]
        candidates = np.concatenate([[zk.min() - 1e-9], np.sort(zk)])
        errors = [int(np.sum((zk > c) & ~mk) + np.sum((zk <= c) & mk)) for c in candidates]
        best = int(np.argmin(errors))
        cuts.append(candidates[best])
        angles.append(math.radians(-165 + 30 * k))
        wrong += errors[best]
    cuts, angles = np.array(cuts), np.array(angles)
    if len(cuts) < 3:
        sys.exit("too few surface grains (%d sectors with 4 or more) to find the boundary" % len(cuts))
    design = np.column_stack([np.ones_like(angles), np.cos(angles), np.sin(angles)])
    coef, *_ = np.linalg.lstsq(design, cuts, rcond=None)
    explained = 1.0 - float(np.sum((cuts - design @ coef) ** 2)) / max(1e-300, float(np.sum((cuts - cuts.mean()) ** 2)))
    amplitude = math.hypot(coef[1], coef[2])
    outer_r = float(np.percentile(np.sqrt((pos[:, 0] - centre[0]) ** 2 + (pos[:, 1] - centre[1]) ** 2) + radius, 95))
    print("surface: %d of %d surface grains move down with the top platen (axial increment below %.4g mm); "
          "the boundary's "
          "height in 12 sectors from theta -180 deg (mm): %s; %d grains (%.1f %%) on the wrong side of it; the best "
          "plane's trace z = %.1f mm + %.1f mm cos(theta - %.0f deg) (%.0f %% of the boundary's spread): a plane "
          "dipping %.0f deg (0: the boundary is level, an end zone)" % (
              int(moving.sum()), len(moving), threshold * 1e3, " ".join("%.1f" % (c * 1e3) for c in cuts), wrong,
              100.0 * wrong / len(moving), coef[0] * 1e3, amplitude * 1e3, math.degrees(math.atan2(coef[2], coef[1])),
              100.0 * explained, math.degrees(math.atan2(amplitude, outer_r))))
    axes[0].plot(np.degrees(angles), cuts * 1e3, "k+", markersize=10, label="boundary in each sector")
    tt = np.linspace(-math.pi, math.pi, 181)
    axes[0].plot(np.degrees(tt), (coef[0] + coef[1] * np.cos(tt) + coef[2] * np.sin(tt)) * 1e3, "-", color="C3",
                 label="best plane's trace: dip %.0f deg" % math.degrees(math.atan2(amplitude, outer_r)))
    axes[0].legend(fontsize=7, loc="lower left")
    rb = np.sqrt((after[:, 0] - centre[0]) ** 2 + (after[:, 1] - centre[1]) ** 2) if len(after) else np.zeros(0)
    outer = float(np.percentile(np.sqrt((pos[:, 0] - centre[0]) ** 2 + (pos[:, 1] - centre[1]) ** 2), 95))
    near = rb >= outer - diameter
    tb = np.degrees(np.arctan2(after[near, 1] - centre[1], after[near, 0] - centre[0])) if len(after) else []
    axes[1].plot(tb, after[near, 2] * 1e3 if len(after) else [], ".", color="black", markersize=2.5)
    if int(near.sum()) >= 10:
        # The trace of an inclined plane on the cylinder: z = z0 + a cos(theta) + b sin(theta),
        # amplitude sqrt(a^2 + b^2) = R tan(dip). A diffuse cloud gives a small share explained.
        t = np.radians(np.asarray(tb))
        zb = after[near, 2]
        design = np.column_stack([np.ones_like(t), np.cos(t), np.sin(t)])
        coef, *_ = np.linalg.lstsq(design, zb, rcond=None)
        explained = 1.0 - float(np.sum((zb - design @ coef) ** 2)) / float(np.sum((zb - zb.mean()) ** 2))
        amplitude = math.hypot(coef[1], coef[2])
        dip = math.degrees(math.atan2(amplitude, outer))
        lowest = math.degrees(math.atan2(-coef[2], -coef[1]))
        print("after-peak breaks near the surface (%d): the best plane's trace z = %.1f mm + %.1f mm cos(theta - "
              "theta_high), highest at theta %.0f deg, explains %.1f %% of their spread in height (a plane dipping "
              "%.0f deg; their height: mean %.1f mm, std %.1f mm)" % (
                  int(near.sum()), coef[0] * 1e3, amplitude * 1e3, (lowest + 360.0) % 360.0 - 180.0,
                  100.0 * explained, dip, zb.mean() * 1e3, zb.std() * 1e3))
        tt = np.linspace(-math.pi, math.pi, 181)
        axes[1].plot(np.degrees(tt), (coef[0] + coef[1] * np.cos(tt) + coef[2] * np.sin(tt)) * 1e3, "-", color="C3",
                     label="best plane's trace: dip %.0f deg, %.0f %% of the spread" % (dip, 100.0 * explained))
        axes[1].legend(fontsize=7, loc="lower left")
    axes[1].set_title("bonds broken after the peak within a diameter of the surface (%d)" % int(near.sum()),
                      fontsize=9)
    for ax in axes:
        ax.set_xlabel("angle about the axis (deg)")
        ax.set_ylabel("z (mm)")
        ax.set_xlim(-180, 180)
    fig.suptitle(args.title + ": the lateral surface seen from outside", fontsize=10)
    fig.tight_layout()
    fig.savefig(args.prefix + "_surface.png", dpi=100)
    print("wrote", args.prefix + "_surface.png")

    # Where the shortening after the peak happens: the mean axial increment of the grains in
    # each slice of the height; a homogeneous specimen gives a straight line, a zone that takes
    # the shortening a steep stretch.
    zs = pos[:, 2]
    edges_z = np.linspace(zs.min(), zs.max() + 1e-12, max(4, int(round((zs.max() - zs.min()) / (1.25 * diameter)))) + 1)
    axial = []
    for k in range(len(edges_z) - 1):
        sel = (zs >= edges_z[k]) & (zs < edges_z[k + 1])
        axial.append(float(inc[sel, 2].mean()) if sel.sum() else float("nan"))
    axial = np.array(axial)
    zmid = 0.5 * (edges_z[:-1] + edges_z[1:])
    total = axial[-1] - axial[0]
    thirds = np.array_split(np.arange(len(axial)), 3)
    shares = []
    for part in thirds:
        lo, hi = max(0, part[0] - 1), part[-1]
        # the shortening across this third: from the slice below it (or its first) to its last
        shares.append((axial[hi] - axial[lo]) / total if total else float("nan"))
    print("axial increment %s->end per slice (mm, bottom to top): %s; shortening %.4g mm, of it bottom / middle / "
          "top third: %.0f %% / %.0f %% / %.0f %% (homogeneous: about a third each)" % (
              args.start, " ".join("%.3f" % (v * 1e3) for v in axial), -total * 1e3, 100 * shares[0], 100 * shares[1],
              100 * shares[2]))

    # Barrelling: the radius profile at the start, the peak and the end.
    start = pos - d + shear
    frames = (("start", start, 1), ("peak", pos - d + p, 2), ("end", pos, 4))
    z0 = float(start[:, 2].min())
    z1 = float(start[:, 2].max())
    slices = max(4, int(round((z1 - z0) / (1.25 * diameter))))
    fig, (ax, ax2, ax3) = plt.subplots(1, 3, figsize=(13, 6), sharey=True)
    zfrac = (zmid - zs.min()) / (zs.max() - zs.min())
    ax3.plot(axial * 1e3, zfrac, "o-", markersize=3, color="C4", label="mean axial increment %s->end" % args.start)
    ax3.plot([axial[0] * 1e3, axial[-1] * 1e3], [zfrac[0], zfrac[-1]], ":", color="grey", label="homogeneous")
    ax3.set_xlabel("axial displacement increment (mm)")
    ax3.grid(True, alpha=0.3)
    ax3.legend(fontsize=8)
    profiles = {}
    for name, x, bit in frames:
        on = (flags & bit) > 0
        zc = x[:, 2]
        mids, means = radius_profile(x[:, :2].mean(axis=0), x, radius, on, zc.min(), zc.max() + 1e-12, slices)
        frac = (mids - zc.min()) / (zc.max() - zc.min())
        profiles[name] = (frac, means)
        ax.plot(means * 1e3, frac, "o-", markersize=3, label="%s: mean %.3f mm" % (name, means.mean() * 1e3))
    for name in ("peak", "end"):
        n = min(len(profiles["start"][1]), len(profiles[name][1]))
        ax2.plot((profiles[name][1][:n] - profiles["start"][1][:n]) * 1e3, profiles["start"][0][:n], "o-",
                 markersize=3, color="C1" if name == "peak" else "C2", label=name + " - start")
    # The same grains followed (no re-selection of the surface): the start's surface grains'
    # radial displacement to the end, averaged in the start's slices.
    x0 = start
    c0 = x0[:, :2].mean(axis=0)
    c1 = pos[:, :2].mean(axis=0)
    r0 = np.linalg.norm(x0[:, :2] - c0, axis=1)
    r1 = np.linalg.norm(pos[:, :2] - c1, axis=1)
    on0 = (flags & 1) > 0
    edges = np.linspace(z0, z1 + 1e-12, slices + 1)
    followed = []
    for k in range(slices):
        sel = on0 & (x0[:, 2] >= edges[k]) & (x0[:, 2] < edges[k + 1])
        followed.append(float((r1[sel] - r0[sel]).mean()) if sel.sum() else float("nan"))
    followed = np.array(followed)
    ax2.plot(followed * 1e3, (0.5 * (edges[:-1] + edges[1:]) - z0) / (z1 - z0), "s--", markersize=3, color="C3",
             label="start's surface grains,\nradial displacement to the end")
    ax2.axvline(0.0, color="grey", lw=0.8)
    ax.set_xlabel("radius: surface grains' mean outer radius (mm)")
    ax2.set_xlabel("radius change since the start (mm)\n(mean grain diameter %.2f mm)" % (diameter * 1e3))
    ax.set_ylabel("height / specimen length")
    for a in (ax, ax2):
        a.grid(True, alpha=0.3)
        a.legend(fontsize=8)
    fig.suptitle(args.title + ": the membrane's radius along the axis", fontsize=10)
    fig.tight_layout()
    fig.savefig(args.prefix + "_radius.png", dpi=110)
    print("wrote", args.prefix + "_radius.png")
    for name in ("start", "peak", "end"):
        frac, means = profiles[name]
        print("radius profile %s (mm, bottom to top): %s" % (name, " ".join("%.3f" % (v * 1e3) for v in means)))
    n = len(followed)
    fmid = np.nanmean(followed[n // 3: n - n // 3])
    fend = np.nanmean(np.concatenate([followed[: max(1, n // 6)], followed[n - max(1, n // 6):]]))
    print("start's surface grains, radial displacement to the end per slice (mm, bottom to top): %s; middle third "
          "%.3f mm, end sixths %.3f mm, barrel (middle - ends) %.3f mm = %.3f diameters" % (
              " ".join("%.3f" % (v * 1e3) for v in followed), fmid * 1e3, fend * 1e3, (fmid - fend) * 1e3,
              (fmid - fend) / diameter))
    fs, ms = profiles["start"]
    fe, me = profiles["end"]
    n = min(len(ms), len(me))
    growth = (me[:n] - ms[:n]) / diameter
    middle = growth[n // 3: n - n // 3].mean()
    ends = np.concatenate([growth[: max(1, n // 6)], growth[n - max(1, n // 6):]]).mean()
    print("radius change start->end, in mean diameters per slice: %s; middle third %.3f, end sixths %.3f, "
          "barrel (middle - ends) %.3f diameters = %.3f mm" % (
              " ".join("%.2f" % v for v in growth), middle, ends, middle - ends, (middle - ends) * diameter * 1e3))


if __name__ == "__main__":
    main()
