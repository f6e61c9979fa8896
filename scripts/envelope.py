"""The calibration's triaxial envelope on a parameter file: the friction angle and cohesion.

    pvpython scripts/envelope.py PARAMETER_FILE [--seed N] [--confining S1,S2,...]

Rebuilds the file's specimen (its recipe and cement; --seed another Random Seed for a
fresh specimen of the same recipe), runs the calibration's envelope stage once on it
(rockdem.calibrate's triaxial tests: an unconfined compression for a confining stress of
0, DEM Load Test's Triaxial mode for the others, each on the same cemented pack, at the
file's strain per step) and fits the Mohr-Coulomb line through the peaks. The confining
stresses (Pa) default to the file's target, or to its rock preset's when the file was
calibrated without a friction angle; the friction angle is compared with the preset's.
Prints one line per test and the fit. Documentation/Calibration.md has the granite's.
"""
import argparse
import os
import sys
import time

from load_calibration import load_calibration

cal = load_calibration(globals())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("parameters", help="a parameter file (format rockdem-calibration)")
    parser.add_argument("--seed", type=int, default=None, help="Random Seed of the pack (default: the file's)")
    parser.add_argument("--confining", default=None,
                        help="confining stresses, Pa, comma separated (default: the target's or the preset's)")
    args = parser.parse_args()
    if not os.path.isfile(args.parameters):
        sys.exit("PARAMETER_FILE = %r: no such file (a parameter file written by rockdem.calibrate, "
                 "e.g. Data/calibrated/lac_du_bonnet_granite_5000.json)" % args.parameters)
    doc = cal.load_parameters(args.parameters)
    rock = cal.preset_of(doc)
    target = dict(doc["target"], tolerances=doc["tolerances"])
    for key in ("friction_angle", "confining_stresses", "ucs", "youngs_modulus"):
        if key not in target and key in rock:
            target[key] = rock[key]
    if args.confining is not None:
        try:
            target["confining_stresses"] = [float(s) for s in args.confining.split(",")]
        except ValueError:
            sys.exit("--confining = %r: a comma-separated list of stresses in Pa" % args.confining)
    if "confining_stresses" not in target:
        sys.exit("%s: no confining stresses in the file's target or its rock; give --confining" % args.parameters)
    target = cal.validate_target(target)
    bench = cal.bench_for(doc, target, args.seed)
    t0 = time.time()
    try:
        # the file's own rates for its own confining stresses (envelope_rate 'inertial')
        rates = doc["test"].get("envelope_strain_per_step") if args.confining is None else None
        results, cohesion, phi = bench.triaxial(doc["parameters"], target["confining_stresses"],
                                                cal.envelope_strain(target), rates)
    finally:
        bench.close()
    for r in results:
        print("confining %.4g Pa: peak axial stress %.4g Pa" % (r["confining"], r["peak_axial"]))
    goal = target.get("friction_angle")
    print("seed %d, %d grains: friction angle %.2f deg%s, cohesion %.4g Pa (%d tests, %.0f s)"
          % (bench.recipe["seed"], bench.elements, phi,
             " (target %.1f deg: %+.2f deg)" % (goal, phi - goal) if goal is not None else "",
             cohesion, len(results), time.time() - t0))


if __name__ == "__main__":
    main()
