"""The calibration's tensile test on a parameter file at a chosen platen strain per step.

    pvpython scripts/tension_rate.py PARAMETER_FILE STRAIN_PER_STEP

Rebuilds the file's specimen (its recipe, seed and cement) as rockdem.calibrate does,
pulls it with the file's tensile test type at STRAIN_PER_STEP (-, platen strain per
timestep; to the calibration's Max Strain, tension_max_strain) and prints the tensile strength (Pa) it reads. Documentation/Calibration.md,
"The tensile test's rate", has the granite's series.
"""
import sys
import time

from load_calibration import load_calibration

cal = load_calibration(globals())


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    path, rate = sys.argv[1], float(sys.argv[2])
    if not rate > 0:
        sys.exit("STRAIN_PER_STEP = %r: must be > 0" % rate)
    doc = cal.load_parameters(path)
    target = cal.validate_target(dict(doc["target"], tolerances=doc["tolerances"]))
    if "tensile_strength" not in target:
        # a file calibrated without sigma_t: the preset's value sets only the Max Strain
        target = cal.validate_target(dict(target, tensile_strength=cal.preset_of(doc).get("tensile_strength", 1e6)))
    bench = cal.bench_for(doc, target)
    t0 = time.time()
    try:
        r = bench.tension(doc["parameters"], cal.tension_max_strain(target, rate), strain_per_step=rate)
    finally:
        bench.close()
    print("strain per step %g: %s tensile strength %.4g Pa (%.0f s)"
          % (rate, target.get("tensile_test", "direct"), r["tensile_strength"], time.time() - t0))


if __name__ == "__main__":
    main()
