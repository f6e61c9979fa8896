"""scripts/localisation_index.py, the band statistic of Rock.md ("The DFN reads the band"),
on planted point sets whose answer is known (no plugin, numpy only):
- 2,000 points uniform in a 1 x 2 rectangle: the best 0.1-wide strip's excess stays near
  the control's (below 0.05);
- the same with 600 of them moved into a strip 0.1 wide through the centre, 20 deg from the
  long (loading) axis Y: the excess is about the planted share above uniform (0.3 x (1 -
  area share) ~ 0.28, at least 0.2), the band's plane is within 3 deg of 20 deg from the
  axis, and the control's excess stays below 0.05;
- 3D: a planted slab dipping 70 deg (20 deg from the Z axis) in a 1 x 1 x 2 box, likewise.
"""
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
import localisation_index as li  # noqa: E402

failures = []


def check(name, ok, detail):
    print("%s: %s (%s)" % (name, "ok" if ok else "FAILED", detail))
    if not ok:
        failures.append(name)


def planted(dimension, rng, count=2000, share=0.3, width=0.1, degrees=20.0):
    size = np.array([1.0, 2.0, 0.0]) if dimension == 2 else np.array([1.0, 1.0, 2.0])
    axis = 1 if dimension == 2 else 2
    pts = rng.uniform(0, 1, size=(count, 3)) * size
    a = np.radians(degrees)
    # the band's in-plane direction, `degrees` from the loading axis, and its normal
    along = np.zeros(3)
    along[axis] = np.cos(a)
    along[0] = np.sin(a)
    normal = np.zeros(3)
    normal[axis] = -np.sin(a)
    normal[0] = np.cos(a)
    centre = 0.5 * size
    k = int(share * count)
    t = rng.uniform(-0.8, 0.8, size=k)
    u = rng.uniform(-0.5, 0.5, size=k) * width
    band = centre + t[:, None] * along + u[:, None] * normal
    if dimension == 3:
        band[:, 1] = rng.uniform(0, 1, size=k)
    pts[:k] = band
    return pts, (np.zeros(3), size), axis


for dimension in (2, 3):
    rng = np.random.default_rng(5)
    normals = li.directions(dimension, 600)
    pts, box, axis = planted(dimension, rng, share=0.0)
    (e, share, area, n), (ec, _, _, _) = li.band_excess(pts, box, normals, 0.1, rng)
    check("%dD uniform" % dimension, e < 0.05 and ec < 0.05, "excess %.3f, control %.3f" % (e, ec))
    pts, box, axis = planted(dimension, rng)
    (e, share, area, n), (ec, _, _, _) = li.band_excess(pts, box, normals, 0.1, rng)
    angle = li.dip(n, axis)
    check("%dD planted band" % dimension, e > 0.2 and abs(angle - 20.0) < 3.0 and ec < 0.05,
          "excess %.3f (band %.1f %% on %.1f %%), %.1f deg from the axis, control %.3f"
          % (e, 100 * share, 100 * area, angle, ec))

if failures:
    sys.exit("FAILED: " + ", ".join(failures))
print("all band-statistic checks passed")
