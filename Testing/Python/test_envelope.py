"""pvpython: rockdem's analysis helpers (Mohr-Coulomb fit, elastic constants, run_test).

Synthetic data first (exact answers): a line sigma1 = a + b sigma3 built from a chosen
cohesion and friction angle gives them back; a linear stress-strain curve with a chosen
E and nu gives them back; peaks are taken over the shear rows only. Then one small real
pipeline (pack -> cement -> unconfined compression and a triaxial pair through
rockdem.run_test / ucs_test / triaxial_series) checks the helpers on the engine's table.
"""
import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_test_support import Checks, load_rockdem  # noqa: E402

from paraview.simple import *  # noqa: E402,F401,F403

load_rockdem(globals())
import numpy as np  # noqa: E402
import rockdem  # noqa: E402

c = Checks()
T0 = time.time()

# --- Mohr-Coulomb: exact line -> exact c and phi.
for cohesion, phi in ((2e6, 30.0), (0.35e6, 42.5), (10e6, 5.0)):
    a, b = rockdem.mohr_coulomb_line(cohesion, phi)
    s3 = np.array([0.0, 1e5, 5e5, 2e6])
    c_fit, phi_fit = rockdem.fit_mohr_coulomb(s3, a + b * s3)
    c.check(abs(c_fit - cohesion) <= 1e-9 * cohesion and abs(phi_fit - phi) <= 1e-9,
            "Mohr-Coulomb: c %.6g Pa, phi %.6g deg back from the exact line (set %.6g, %.6g)"
            % (c_fit, phi_fit, cohesion, phi))
# phi = 30 deg: b = 3, a = 2 c sqrt(3) -- the textbook numbers.
a, b = rockdem.mohr_coulomb_line(1e6, 30.0)
c.check(abs(b - 3.0) < 1e-12 and abs(a - 2e6 * math.sqrt(3.0)) < 1e-6, "phi 30 deg: b = 3, a = 2 sqrt(3) c")
# least squares: symmetric noise around the line leaves it unchanged
s3 = np.array([1e5, 1e5, 3e5, 3e5])
noise = np.array([1e4, -1e4, 1e4, -1e4])
c_fit, phi_fit = rockdem.fit_mohr_coulomb(s3, 1e6 + 3.0 * s3 + noise)
c.check(abs(phi_fit - 30.0) < 1e-9 and abs(c_fit - 1e6 / (2 * math.sqrt(3))) < 1e-6,
        "least squares through scattered repeats recovers the line")
for bad in (([1e5], [1e6]), ([1e5, 1e5], [1e6, 2e6]), ([0, 1e5], [1e6, 0.9e6])):
    try:
        rockdem.fit_mohr_coulomb(*bad)
        ok = False
    except ValueError:
        ok = True
    c.check(ok, "fit_mohr_coulomb refuses %s" % (bad,))

# --- Elastic constants from a synthetic unconfined curve: linear to the peak, then softening.
E, NU = 2.5e8, 0.2
strain = np.linspace(0.0, 0.02, 201)
peak_strain = 0.008
stress = np.where(strain <= peak_strain, E * strain, E * peak_strain * (1 - 30 * (strain - peak_strain)))
stress = np.maximum(stress, 0.0)
hist = {"Strain Z": strain, "Strain X": -NU * strain * 1.1, "Strain Y": -NU * strain * 0.9,
        "Axial Stress (Pa)": stress, "Deviator Stress (Pa)": stress, "Stage": np.full(strain.size, 2.0)}
e_fit, nu_fit = rockdem.elastic_constants(hist)
c.check(abs(e_fit - E) <= 1e-9 * E and abs(nu_fit - NU) <= 1e-9,
        "elastic_constants: E %.8g Pa, nu %.8g from a linear curve (set %.6g, %.6g)" % (e_fit, nu_fit, E, NU))
# the same curve with an offset start (seating) and consolidation rows that must be ignored
hist2 = {k: np.concatenate([np.zeros(5), v]) for k, v in hist.items()}
hist2["Stage"][:5] = 1.0
hist2["Axial Stress (Pa)"][:5] = 9e9  # a consolidation row far above the peak: not shear
e_fit, nu_fit = rockdem.elastic_constants(hist2)
c.check(abs(e_fit - E) <= 1e-9 * E and abs(nu_fit - NU) <= 1e-9, "only shear-stage rows are used")
hx = {"Strain X": strain, "Strain Y": -NU * strain, "Strain Z": -NU * strain,
      "Axial Stress (Pa)": stress, "Deviator Stress (Pa)": stress}
e_fit, nu_fit = rockdem.elastic_constants(hx, axis="X")
c.check(abs(e_fit - E) <= 1e-9 * E and abs(nu_fit - NU) <= 1e-9, "Axis X, no Stage column")
pa, pd = rockdem.peak_values(hist2)
c.check(abs(pa - E * peak_strain) < 1e-6 and abs(pd - E * peak_strain) < 1e-6,
        "peak_values over the shear rows: %.6g Pa" % pa)
c.check(abs(rockdem.compressive_to_tensile_ratio(2e6, -2e5) - 10.0) < 1e-12, "compressive/tensile ratio 10")
try:
    rockdem.elastic_constants({k: v[:3] for k, v in hist.items()})
    ok = False
except ValueError:
    ok = True
c.check(ok, "elastic_constants refuses a curve with too few rows in the window")

# --- A small real pipeline: pack -> cement -> compression, triaxial pair.
pack = DEMPackSource(InitialElements=500, XDimension=0.02, YDimension=0.02, ZDimension=0.03,
                     MinimumSize=0.0008, MaximumSize=0.0012, YoungsModulus=1e8, RandomSeed=1)
pack.InvokeCommand("GrowElements")
iso = DEMLoadTest(Input=pack, Gravity=[0, 0, 0], Mode="Isotropic", ConfiningStress=5e4,
                  FrameInterval=0.002, NumberOfFrames=30, TimestepSafety=0.3)
iso.UpdatePipeline(0.06)
cement = DEMCement(Input=iso, BondModulus=1e8, TensileStrength=3e5, Cohesion=6e5, StrengthScatter=0.2)
relax = DEMLoadTest(Input=cement, Gravity=[0, 0, 0], FrameInterval=0.002, NumberOfFrames=2, TimestepSafety=0.3)
relax.UpdatePipeline(0.004)
print("pipeline built in %.1f s" % (time.time() - T0))
u = rockdem.ucs_test(relax, StrainRate=2.0, MaxStrain=0.015, SampleInterval=20, TimestepSafety=0.3)
h = u["history"]
c.check("Axial Stress (Pa)" in h and isinstance(h["Axial Stress (Pa)"], np.ndarray) and len(h["Step"]) > 10,
        "run_test fetched the History into numpy arrays (%d rows)" % len(h["Step"]))
c.check(u["proxy"].GetXMLName() == "DEMLoadTest" and rockdem.read_only(u["proxy"], "Stage") == "done",
        "run_test ran the compression to stage done")
c.check(abs(u["ucs"] - rockdem.peak_values(h)[0]) <= 1e-9 * u["ucs"] and u["ucs"] > 0,
        "UCS (Peak Stress) %.4g Pa equals the history's peak" % u["ucs"])
c.check(u["E"] > 0 and math.isfinite(u["E"]), "E %.4g Pa from the real curve" % u["E"])
c.check(math.isfinite(u["nu"]), "nu %.3g from the lateral spread of the centres (a weak 500-grain specimen: dilatant)" % u["nu"])
c.check(u["broken_bonds"] > 0, "bonds broke (%d of %d)" % (u["broken_bonds"], u["bonds"]))
results, (coh, phi) = rockdem.triaxial_series(relax, [2e4, 1e5], StrainRate=2.0, MaxStrain=0.015,
                                              SampleInterval=20, TimestepSafety=0.3,
                                              FrameInterval=0.0015, NumberOfFrames=30)
for r in results:
    print("triaxial sigma3 %.3g Pa: sigma1 peak %.4g Pa, deviator peak %.4g Pa, stage %s"
          % (r["confining"], r["peak_axial"], r["peak_deviator"], r["stage"]))
c.check(len(results) == 2 and all(r["peak_deviator"] > 0 for r in results), "triaxial series ran both tests")
c.check(results[1]["peak_axial"] > results[0]["peak_axial"], "strength grows with confinement")
c.check(math.isfinite(coh) and 0.0 < phi < 90.0, "envelope: c %.4g Pa, phi %.3g deg" % (coh, phi))
print("elapsed %.1f s" % (time.time() - T0))
c.finish()
