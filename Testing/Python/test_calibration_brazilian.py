"""pvpython: the calibration's Brazilian tensile test (Documentation/Calibration.md).

A target with tensile_test 'brazilian' makes the strength stage's tensile test
(_Bench.tension, the one place a tensile test is run) carve a disc out of the cemented
pack (DEM Specimen, Shape Disc, axis Z, diameter the box's smaller width, thickness half
of it), relax it and squeeze it along Y in DEM Load Test's Mode Brazilian. On a tiny
specimen (300 grains, soft moduli as in test_calibration.py, Bond Modulus 1e9 Pa) this
checks:
- the strength the calibration returns is the Brazilian strength 2 P / (pi D t): equal,
  to the bit, to what rockdem.brazilian_test reports on the same disc carved by hand
  from the same cemented pack, and to that test's Peak Stress; positive and finite;
- the disc is a disc: fewer grains than the box, its D and t near the carved ones, bonds
  broken by the test;
- calibrate() with a Brazilian target: its strength records name the Brazilian test and
  their measured tensile strength is a Brazilian strength (one scale step on the bond
  strength brings it within 5 %).
"""
import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_test_support import Checks, load_rockdem  # noqa: E402

from paraview.simple import *  # noqa: E402,F401,F403

load_rockdem(globals())
import rockdem  # noqa: E402
import rockdem_calibration as cal  # noqa: E402

c = Checks()
t0 = time.time()
TARGET = cal.validate_target({"name": "CI rock (Brazilian)", "tensile_strength": 1.5e5, "tensile_test": "brazilian"})
RECIPE = cal.validate_recipe({"elements": 300, "seed": 3, "max_tests": 6})
# calibrate()'s start for this target (no E: Bond Modulus 1e9 Pa; Tensile Strength = the target)
P = {"BondModulus": 1.0e9, "BondStiffnessRatio": 0.4, "TensileStrength": 1.5e5, "CohesionRatio": 4.0,
     "FrictionAngle": 30.0, "BondRange": 1.4, "MomentContribution": 1.0}
strain = cal._tension_strain(TARGET)

bench = cal._Bench(TARGET, RECIPE, None)
r = bench.tension(P, strain)
diameter, thickness = bench.disc_size()
print("calibration's Brazilian test: %.6g Pa, disc of %d grains (box %d), D %.4g m, t %.4g m (carved %.4g, %.4g), "
      "%d of %d bonds broken, %.1f s" % (r["tensile_strength"], r["disc_particles"], bench.elements, r["diameter"],
                                         r["thickness"], diameter, thickness, r["broken_bonds"], r["bonds"],
                                         time.time() - t0))
c.check(bench.tests == 1, "one specimen test counted (%d)" % bench.tests)
c.check(math.isfinite(r["tensile_strength"]) and r["tensile_strength"] > 0 and
        r["tensile_strength"] == r["brazilian_strength"],
        "the tensile strength returned is the Brazilian strength, positive and finite: %.6g Pa" % r["tensile_strength"])
c.check(0 < r["disc_particles"] < bench.elements and r["bonds"] > 0,
        "a disc carved from the cemented box: %d of %d grains, %d bonds" % (r["disc_particles"], bench.elements,
                                                                           r["bonds"]))
c.check(abs(r["diameter"] / diameter - 1) < 0.3 and abs(r["thickness"] / thickness - 1) < 0.6 and
        r["thickness"] < r["diameter"],
        "its Disc Diameter %.4g m and Disc Thickness %.4g m are near the carved %.4g m and %.4g m"
        % (r["diameter"], r["thickness"], diameter, thickness))
c.check(r["failed"] and r["broken_bonds"] > 0,
        "the disc failed (the load fell below half its peak by Max Strain %.4g): %d bonds broken"
        % (r["max_strain"], r["broken_bonds"]))

# The same disc by hand: the same cemented pack, carved, relaxed and tested with
# rockdem.brazilian_test at the same rate. The solver is deterministic: bit for bit.
model = bench._cemented(P)
disc = rockdem.specimen(model, shape="Disc", axis="Z", diameter=diameter, length=thickness)
relax = bench._relaxed(disc, P)
ref = rockdem.brazilian_test(relax, axis="Y", **bench._press("Brazilian", r["max_strain"], 0.5))
peak = rockdem.read_only(ref["proxy"], "PeakStress")
print("by hand: brazilian_test %.6g Pa, Peak Stress %.6g Pa, D %.4g m, t %.4g m, %d grains"
      % (ref["brazilian_strength"], peak, ref["diameter"], ref["thickness"],
         rockdem.read_only(disc, "NumberOfParticles")))
c.check(r["tensile_strength"] == ref["brazilian_strength"] == peak,
        "equal to rockdem.brazilian_test on the same disc (%.9g Pa) and to its Peak Stress (%.9g Pa)"
        % (ref["brazilian_strength"], peak))
c.check(r["diameter"] == ref["diameter"] and r["thickness"] == ref["thickness"] and
        rockdem.read_only(disc, "NumberOfParticles") == r["disc_particles"],
        "the same disc: D, t and grain count equal")
for proxy in (ref["proxy"], relax, disc):
    Delete(proxy)
bench.close()

# calibrate() with the Brazilian target (tensile strength alone: a proportional step on the
# bond strength per test): the strength records name the Brazilian test
records = []
res = cal.calibrate(TARGET, RECIPE, progress=records.append)
for rec in records:
    print("test %d %s (%s): Tensile %.4g Pa -> %s" % (rec["test"], rec["stage"], rec["kind"],
                                                     rec["parameters"]["TensileStrength"],
                                                     {k: "%.4g" % v for k, v in rec["errors"].items()}))
kinds = set(rec["kind"] for rec in records if rec["stage"] == "strength")
c.check(kinds == {"brazilian test"}, "calibrate(): strength records run the Brazilian test (%s)" % sorted(kinds))
first = [rec for rec in records if rec["stage"] == "strength"][0]
c.check(first["measured"]["tensile_strength"] == r["tensile_strength"],
        "its first Brazilian strength, at the same start parameters, is the one above (%.9g Pa)"
        % first["measured"]["tensile_strength"])
c.check(res["converged"] and abs(res["errors"]["tensile_strength"]) <= 0.05 and res["tests"] <= RECIPE["max_tests"],
        "calibrate(): Brazilian strength %.4g Pa against the target %.4g Pa (error %+.3f) in %d tests"
        % (res["measured"]["tensile_strength"], TARGET["tensile_strength"], res["errors"]["tensile_strength"],
           res["tests"]))
print("total %.1f s" % (time.time() - t0))
c.finish()
