#!/usr/bin/env python3
"""Plots the Timestep Safety sweep of rockdem_bench_solver --sweep.

    rockdem_bench_solver --sweep --csv sweep.csv
    scripts/plot_accuracy.py sweep.csv [-o Documentation/images/timestep_accuracy.png]

Top: errors against Timestep Safety (log-log): restitution error of a sphere-wall impact
(e = 0.5 requested), restitution error of the elastic impact (e = 1), its peak-force error
against the Hertz closed form, worst relative energy drift of an undamped elastic system. Middle: cost in steps (steps in
contact per collision; steps of the fixed-model-time energy and settling runs). Bottom: wall
seconds. A red line marks the smallest safety at which a run went unstable
(dem::InstabilityError); the grey dotted lines mark the default (0.1) and the cap without
the test-only unsafe switch (1.0). Needs matplotlib (Debian: python3-matplotlib).
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_plotting import pyplot  # noqa: E402

plt = pyplot()


def read(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(f)]
    if not rows:
        sys.exit(f"{path}: no rows")
    return rows


def num(row, key):
    try:
        return float(row[key])
    except (KeyError, ValueError):
        return math.nan


FLOOR = 1e-7  # errors below this are drawn at the floor (log scale)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default_out = os.path.join(here, "..", "Documentation", "images", "timestep_accuracy.png")
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv", help="CSV written by rockdem_bench_solver --sweep --csv FILE")
    ap.add_argument("-o", "--output", default=default_out)
    args = ap.parse_args()

    rows = sorted(read(args.csv), key=lambda r: num(r, "safety"))
    s = [num(r, "safety") for r in rows]
    # "energy-gain" (the elastic impact came back faster than it went in) is drawn as a
    # point of its own, like an unstable one.
    impact_ok = [r["impact_status"] == "ok" for r in rows]
    energy_ok = [r["energy_status"] == "ok" for r in rows]
    settle_ok = [r["settle_status"] == "ok" for r in rows]
    unstable = [x for x, r in zip(s, rows) if r["stable"].strip() != "1"]
    first_unstable = min(unstable) if unstable else None

    fig, axes = plt.subplots(3, 1, figsize=(8.5, 11), sharex=True,
                             gridspec_kw={"height_ratios": [1.4, 1, 1]})
    ax_err, ax_steps, ax_sec = axes

    def series(ax, key, ok, label, style, scale=1.0, floor=None):
        xs, ys, bad_x, bad_y = [], [], [], []
        for x, r, good in zip(s, rows, ok):
            y = num(r, key) * scale
            if math.isnan(y):
                continue
            if floor is not None:
                y = max(y, floor)
            (xs if good else bad_x).append(x)
            (ys if good else bad_y).append(y)
        line, = ax.plot(xs, ys, style, label=label, lw=1.6, ms=5)
        if bad_x:
            ax.plot(bad_x, bad_y, "x", color=line.get_color(), ms=8, mew=2)
        return line

    series(ax_err, "restitution_error", impact_ok, "restitution error |e - 0.5| (impact, 1 m/s)", "o-", floor=FLOOR)
    if "restitution_elastic" in rows[0]:
        for r in rows:
            r["elastic_error"] = str(abs(num(r, "restitution_elastic") - 1.0))
        series(ax_err, "elastic_error", impact_ok, "elastic impact |e - 1| (e = 1 requested)", "v--", floor=FLOOR)
    series(ax_err, "peak_force_error", impact_ok, "peak-force error vs Hertz (elastic impact)", "s-", floor=FLOOR)
    series(ax_err, "energy_drift", energy_ok, "relative energy drift (40 elastic spheres)", "^-", floor=FLOOR)
    ax_err.axhline(0.005, color="tab:blue", ls=":", lw=1)
    ax_err.text(s[0], 0.0055, "restitution bar ±0.005 (PHYSICS.md)", fontsize=8, color="tab:blue", va="bottom")
    ax_err.set_yscale("log")
    ax_err.set_ylabel("error (relative; restitution absolute)")
    ax_err.set_title("RockDEM: accuracy and cost against Timestep Safety\n"
                     "(x = that run went unstable, or the impact gained energy)")

    series(ax_steps, "steps_per_collision", impact_ok, "steps in contact per collision (impact)", "o-")
    series(ax_steps, "energy_steps", energy_ok, "steps, energy run (fixed model time)", "^-")
    series(ax_steps, "settle_steps", settle_ok, "steps, settling run (0.1 s model time)", "d-")
    ax_steps.set_yscale("log")
    ax_steps.set_ylabel("steps")

    series(ax_sec, "impact_seconds", impact_ok, "impact (e = 0.5 and e = 1)", "o-")
    series(ax_sec, "energy_seconds", energy_ok, "energy run", "^-")
    n_settle = rows[0].get("settle_particles", "?")
    series(ax_sec, "settle_seconds", settle_ok, f"settling, {n_settle} particles", "d-")
    ax_sec.set_yscale("log")
    ax_sec.set_ylabel("wall seconds")
    ax_sec.set_xlabel("Timestep Safety (timestep / Rayleigh critical timestep)")

    for ax in axes:
        ax.set_xscale("log")
        ax.grid(True, which="both", alpha=0.25)
        ax.axvline(0.1, color="grey", ls=":", lw=1.2)
        ax.axvline(1.0, color="grey", ls=":", lw=1.2)
        if first_unstable is not None:
            ax.axvline(first_unstable, color="red", lw=1.8)
            ax.axvspan(first_unstable, max(s) * 1.15, color="red", alpha=0.07)
        ax.legend(fontsize=8, loc="best")
    tr = ax_err.get_xaxis_transform()  # x in data, y in axes fraction
    ax_err.text(0.1, 0.02, " default 0.1", fontsize=8, color="grey", va="bottom", transform=tr)
    ax_err.text(1.0, 0.02, " cap 1.0", fontsize=8, color="grey", va="bottom", transform=tr)
    if first_unstable is not None:
        ax_steps.text(first_unstable, 0.97, f" unstable from {first_unstable:g}", fontsize=9,
                      color="red", va="top", transform=ax_steps.get_xaxis_transform())
    ax_sec.set_xlim(min(s) / 1.15, max(s) * 1.15)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    fig.savefig(args.output, dpi=110)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
