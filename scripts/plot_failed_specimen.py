#!/usr/bin/env python3
"""A picture of a failed specimen written by `rockdem_bench_rock --tests ucs --dump DIR`
(DIR/ucs_failed.csv, the unconfined specimen at the frame where the stress has fallen to
70 % of its peak; Documentation/Rock.md, "Localisation"): the slab through the axis, grains
coloured by their radial displacement during the test, broken bonds as dots (tension black,
shear gold). The drawing is scripts/plot_envelopes.py's specimen picture.

    scripts/plot_failed_specimen.py DIR/ucs_failed.csv -o failed.png [--title TEXT]

Needs matplotlib (Debian: python3-matplotlib).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_envelopes import specimen_picture  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("specimen", help="ucs_failed.csv written by rockdem_bench_rock --dump")
    parser.add_argument("-o", "--output", default="ucs_failed.png")
    parser.add_argument("--title", default="Unconfined compression, 70 % of the peak")
    args = parser.parse_args()
    specimen_picture(args.specimen, args.output, args.title)


if __name__ == "__main__":
    main()
