"""pvpython: one small end-to-end calibration (Documentation/Calibration.md).

A tiny specimen (300 grains) is calibrated to a Young's modulus of 500 MPa and a UCS of
1 MPa, which the model reaches (soft moduli keep the steps long, Rock.md; the number of
steps to failure does not depend on the modulus). The starting parameters give about
that E (the Bond Modulus starts at the target E) and 40 % of that UCS, so the strength
secant has to move (and E to be held as it does). Checks: converged; the final errors within the stated tolerances (5 %);
the number of specimen tests bounded (<= 12); one progress record per test; the files
(iterations.csv with a row per record, parameters.json that load_parameters reads back);
the parameter file carries the Bond Range and Moment Contribution (the recipe's here:
no friction angle, no tensile strength in the target) and rebuilds the calibrated
specimen (build_specimen: the same bonded coordination, the same seed); verify() on a
fresh seed measures every target the file names, the friction angle too; a test with
another grain Friction (the envelope's second lever) runs on the same grains with that
friction, and a confined peak falls with it.

    pvpython test_calibration.py [OUTPUT_FOLDER]
"""
import os
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_test_support import Checks, load_rockdem  # noqa: E402

from paraview.simple import *  # noqa: E402,F401,F403

load_rockdem(globals())
import rockdem  # noqa: E402

c = Checks()
t0 = time.time()
TARGET = {"name": "CI rock", "youngs_modulus": 5.0e8, "ucs": 1.0e6}
RECIPE = {"elements": 300, "seed": 3, "max_tests": 12}
records = []
# argv[1]: the folder to write to (ctest's, where Python.MainJobOnCalibratedRock reads
# parameters.json); a temporary one otherwise.
out = sys.argv[1] if len(sys.argv) > 1 else tempfile.mkdtemp(prefix="rockdem_calibration_")
os.makedirs(out, exist_ok=True)
res = rockdem.calibrate(TARGET, RECIPE, progress=records.append, output=out)
for rec in records:
    print("test %d %s: %s -> %s" % (rec["test"], rec["stage"], {k: "%.4g" % v for k, v in rec["parameters"].items()},
                                    {k: "%.4g" % v for k, v in rec["errors"].items()}))
c.check(res["converged"], "converged after %d specimen tests in %.1f s (%d grains, coordination %.2f, %d packs)"
        % (res["tests"], res["seconds"], res["elements"], res["bonded_coordination"], res["packs"]))
for key in ("youngs_modulus", "ucs"):
    err = res["errors"].get(key, float("nan"))
    c.check(abs(err) <= 0.05, "%s: measured %.4g, target %.4g, error %+.4f within 0.05"
            % (key, res["measured"][key], TARGET[key], err))
c.check(res["tests"] <= RECIPE["max_tests"], "%d specimen tests <= %d" % (res["tests"], RECIPE["max_tests"]))
c.check(len(records) == len(res["iterations"]) >= 2 and records[0]["stage"] == "stiffness",
        "progress: %d records, stiffness first" % len(records))
with open(os.path.join(out, "iterations.csv")) as f:
    rows = f.read().splitlines()
c.check(len(rows) == 1 + len(records), "iterations.csv: %d rows for %d records" % (len(rows) - 1, len(records)))
doc = rockdem.load_parameters(os.path.join(out, "parameters.json"))
c.check(doc["cement"] == res["cement"] and doc["converged"], "parameters.json reads back: %s" % doc["cement"])
c.check(doc["cement"]["BondRange"] == res["parameters"]["BondRange"] and
        doc["cement"]["MomentContribution"] == res["parameters"]["MomentContribution"],
        "parameters.json carries the Bond Range %g and Moment Contribution %g (no phi, no sigma_t target: "
        "the recipe's)" % (doc["cement"]["BondRange"], doc["cement"]["MomentContribution"]))
c.check(os.path.exists(os.path.join(out, "ucs_history.csv")), "the final UCS test's curve is written")
# the parameter file rebuilds the same specimen: the same UCS
pack, cement = rockdem.build_specimen(doc)
c.check(rockdem.read_only(cement, "Bonds") > 0 and abs(rockdem.read_only(cement, "BondedCoordination")
                                                     - res["bonded_coordination"]) < 1e-12,
        "build_specimen: the same bonded coordination %.4f" % rockdem.read_only(cement, "BondedCoordination"))
# verify() on a fresh seed checks every target the file names, the friction angle too
# (the envelope stage's triaxial tests at the target's confining stresses)
# (two confining stresses; the target's E and UCS set how far the triaxial tests press,
# envelope_strain, Calibration.md)
doc_phi = dict(doc, target=dict(doc["target"], friction_angle=45.0, confining_stresses=[0.0, 4e5]),
               tolerances=dict(doc["tolerances"], friction_angle=3.0))
t1 = time.time()
row = rockdem.verify(doc_phi, seeds=(4,))[0]
c.check(row["seed"] == 4 and set(row["errors"]) == {"youngs_modulus", "ucs", "friction_angle"} and
        10.0 < row["measured"]["friction_angle"] < 80.0 and row["measured"]["cohesion"] > 0.0 and
        abs(row["errors"]["friction_angle"] - (row["measured"]["friction_angle"] - 45.0)) < 1e-12,
        "verify, seed 4, with a friction angle in the target: phi %.1f deg (error %+.1f), cohesion %.3g Pa (%.1f s)"
        % (row["measured"]["friction_angle"], row["errors"]["friction_angle"], row["measured"]["cohesion"],
           time.time() - t1))
# the envelope's second lever, the grains' Friction (ENVELOPE_LEVERS): a test with another
# GrainFriction re-runs the pack with that DEM Pack Source Friction; the grains stay where
# they were (the compaction is frictionless: the same porosity) and the confined peak falls
# with the friction
import rockdem_calibration  # noqa: E402
bench = rockdem_calibration.bench_for(doc_phi)
peaks, porosities = {}, {}
t1 = time.time()
try:
    for mu in (0.5, 0.0):
        results, _, _ = bench.triaxial(dict(doc["parameters"], GrainFriction=mu), [4e5],
                                       rockdem_calibration.envelope_strain(doc_phi["target"]))
        peaks[mu], porosities[mu] = results[0]["peak_axial"], bench.porosity
        c.check(bench.pack_props["Friction"] == mu and bench.pack.Friction == mu,
                "grain Friction %g: the pack's Friction follows (%g)" % (mu, bench.pack.Friction))
finally:
    bench.close()
c.check(porosities[0.0] == porosities[0.5] and peaks[0.0] < peaks[0.5],
        "grain Friction 0.5 -> 0: the same grains (porosity %.6g), confined peak %.4g -> %.4g Pa (%.1f s)"
        % (porosities[0.0], peaks[0.5], peaks[0.0], time.time() - t1))
print("total %.1f s" % (time.time() - t0))
c.finish()
