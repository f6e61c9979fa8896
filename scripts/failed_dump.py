"""Reads the failed-specimen dump of `rockdem_bench_rock --dump DIR` (DIR/ucs_failed.csv,
membrane_failed.csv): the grains and the broken bonds, as numpy arrays. Shared by the
localisation scripts (plot_localisation.py, plot_section2d.py, localisation_index.py);
needs numpy only.
"""
import csv
import sys

import numpy as np


def read_dump(path):
    grains, bonds = [], []
    with open(path) as f:
        reader = csv.DictReader(f)
        if "px" not in reader.fieldnames:
            sys.exit(path + " has no peak frame (px, py, pz): rerun rockdem_bench_rock --dump with this version")
        for row in reader:
            if row["kind"] == "particle":
                shear = [float(row[k]) for k in ("sx", "sy", "sz")] if "sx" in row else [0.0, 0.0, 0.0]
                grains.append([float(row[k]) for k in ("x", "y", "z", "radius", "dx", "dy", "dz", "px", "py", "pz",
                                                        "fx", "fy", "fz")] + [int(row["surface"])] + shear)
            else:
                bonds.append([float(row["x"]), float(row["y"]), float(row["z"]), int(row["after_peak"]),
                              1 if row["kind"] == "tension" else 0])
    g = np.array(grains)
    b = np.array(bonds) if bonds else np.zeros((0, 5))
    return g, b
