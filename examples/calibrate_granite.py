"""Calibrate RockDEM's cement to a named rock (pvpython or pvbatch):

    pvpython examples/calibrate_granite.py [--rock lac_du_bonnet_granite] [--elements 600]
        [--max-tests 30] [--only E,nu,UCS,sigma_t,phi] [--verify 2,3,4] [--output results/calibration]
        [--strain-per-step 1e-6] [--tensile-test direct|brazilian] [--start PARAMETERS.json]
        [--envelope-rate uniform|inertial]

Loads the preset Data/rocks/<rock>.json (Lac du Bonnet granite by default; also
berea_sandstone; --tensile-test brazilian takes the preset's Brazilian strength and
calibrates it on a Brazilian disc carved from the cemented specimen; --start starts from an
earlier calibration's parameter file, e.g. after the target changed), runs
rockdem.calibrate on one compacted specimen of the given size and prints every specimen
test as it finishes (parameters tried, properties measured, errors).
Writes in the output folder: iterations.csv, parameters.json (rockdem.load_parameters /
rockdem.build_specimen read it back), ucs_history.csv, tension_history.csv,
stress_strain.png, envelope.png. Documentation/Calibration.md explains the method and what
the model cannot reach (e.g. the granite's UCS / sigma_t of 29).
"""
import argparse
import os
import sys

from paraview.simple import *  # noqa: F401,F403

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.dirname(HERE)
KEYS = {"E": "youngs_modulus", "nu": "poissons_ratio", "UCS": "ucs", "sigma_t": "tensile_strength",
        "phi": "friction_angle"}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rock", default="lac_du_bonnet_granite", help="preset name or JSON path")
    parser.add_argument("--elements", type=int, default=600, help="Initial Elements of the specimen")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--max-tests", type=int, default=30, help="specimen tests in all")
    parser.add_argument("--only", default="E,nu,UCS,sigma_t,phi",
                        help="targets to calibrate, comma separated, of E, nu, UCS, sigma_t, phi")
    parser.add_argument("--verify", default="",
                        help="seeds of fresh specimens to test the calibrated parameters on, e.g. 2,3,4")
    parser.add_argument("--output", default=os.path.join(SOURCE_DIR, "results", "calibration"))
    parser.add_argument("--strain-per-step", type=float, default=None,
                        help="platen strain per timestep of every test (the recipe's strain_per_step, "
                             "default 1e-6; Rock.md used 1e-7 in compression, 1e-8 in tension)")
    parser.add_argument("--tensile-test", default=None, choices=("direct", "brazilian"),
                        help="which of the preset's tensile strengths to calibrate, and by which test "
                             "(default: the preset's own, direct for both presets)")
    parser.add_argument("--envelope-rate", default=None, choices=("uniform", "inertial"),
                        help="the triaxial tests' strain per step: uniform (the default), or inertial (each at "
                             "the unconfined test's inertial number, faster under high confinement)")
    parser.add_argument("--start", default=None,
                        help="an earlier calibration's parameters.json to start from (rockdem.calibrate's start)")
    args = parser.parse_args()
    plugin = os.environ.get("ROCKDEM_PLUGIN") or os.path.join(
        SOURCE_DIR, "build", "lib", "paraview-plugins", "RockDEM", "RockDEM.so")
    LoadPlugin(plugin, remote=False, ns=globals())
    os.environ.setdefault("ROCKDEM_SOURCE_DIR", SOURCE_DIR)
    import rockdem

    target = rockdem.load_rock(args.rock, tensile_test=args.tensile_test)
    wanted = set()
    for name in args.only.split(","):
        if name.strip() not in KEYS:
            sys.exit("--only: %r is not one of %s" % (name, ", ".join(KEYS)))
        wanted.add(KEYS[name.strip()])
    drop = {"youngs_modulus", "poissons_ratio", "ucs", "tensile_strength", "friction_angle"} - wanted
    for key in drop:
        target.pop(key, None)
    if "tensile_strength" not in target:
        target.pop("tensile_test", None)
    if "friction_angle" not in target:
        target.pop("confining_stresses", None)
        target.pop("cohesion", None)

    def progress(rec):
        m, e, p = rec["measured"], rec["errors"], rec["parameters"]
        print("test %2d %-9s Eb %.4g Pa, ks/kn %.3g, T %.4g Pa, C %.4g Pa, phi_b %.1f, range %.3f, beta %.3f, "
              "grain friction %.3g, coordination %.2f | %s | errors %s | %.0f s"
              % (rec["test"], rec["stage"], p["BondModulus"], p["BondStiffnessRatio"], p["TensileStrength"],
                 p["Cohesion"], p["FrictionAngle"], p["BondRange"], p["MomentContribution"], p["GrainFriction"],
                 rec["bonded_coordination"],
                 ", ".join("%s %.4g" % (k, v) for k, v in m.items() if isinstance(v, float)),
                 ", ".join("%s %+.3g" % (k, v) for k, v in e.items()), rec["seconds"]), flush=True)

    recipe = {"elements": args.elements, "seed": args.seed, "max_tests": args.max_tests}
    if args.strain_per_step is not None:
        recipe["strain_per_step"] = args.strain_per_step
    if args.envelope_rate is not None:
        recipe["envelope_rate"] = args.envelope_rate
    result = rockdem.calibrate(target, recipe,
                               progress=progress, output=args.output, start=args.start)
    print("specimen: %d grains, porosity %.3f, bonded coordination %.2f"
          % (result["elements"], result["porosity"], result["bonded_coordination"]))
    print("%s: %s after %d specimen tests in %.0f s; unreachable: %s; not within tolerance: %s; "
          "measured with other parameters than the final ones: %s"
          % (target.get("name", args.rock), "CONVERGED" if result["converged"] else "NOT CONVERGED",
             result["tests"], result["seconds"], ", ".join(result["unreachable"]) or "none",
             ", ".join(result["not_within"]) or "none", ", ".join(result["stale"]) or "none"))
    for lever, prop in sorted(result["held_levers"].items()):
        print("  %s was moved for %s and held there (the envelope's next lever, the grains' Friction, "
              "moved instead)" % (lever, prop))
    c = result["cement"]
    print("calibrated: Bond Modulus %.4g Pa, Bond Stiffness Ratio %.4g, Tensile %.4g Pa, Cohesion %.4g Pa, "
          "Bond Range %.4g, Moment Contribution %.4g, grain Friction %.4g"
          % (c["BondModulus"], c["BondStiffnessRatio"], c["TensileStrength"], c["Cohesion"], c["BondRange"],
             c["MomentContribution"], result["parameters"]["GrainFriction"]))
    for key in ("youngs_modulus", "poissons_ratio", "ucs", "tensile_strength", "friction_angle"):
        if key in target:
            print("  %-17s target %-10.4g measured %-10.4g error %+.3g (tolerance %g)"
                  % (key, target[key], result["measured"].get(key, float("nan")),
                     result["errors"].get(key, float("nan")), target["tolerances"][key]))
    print("parameters: %s" % os.path.join(args.output, "parameters.json"))
    if args.verify:
        seeds = [int(x) for x in args.verify.split(",")]
        rows = rockdem.verify(os.path.join(args.output, "parameters.json"), seeds)
        for row in rows:
            print("fresh specimen, seed %d (coordination %.2f): %s" % (
                row["seed"], row["bonded_coordination"],
                ", ".join("%s %.4g (%+.3f)" % (k, row["measured"][k], row["errors"][k]) for k in row["errors"])))
        for key in rows[0]["errors"]:
            errs = [r["errors"][key] for r in rows]
            print("  %-17s error over seeds %s: from %+.3f to %+.3f" % (key, seeds, min(errs), max(errs)))


if __name__ == "__main__":
    main()
