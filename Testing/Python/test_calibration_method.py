"""Calibration's numerical method on cheap synthetic models (exact answers known).

Plain Python (no plugin needed): rockdem_calibration's root finder on monotone functions
with a known root (linear, strongly curved, noisy-free log-log), its bracket and its
'unreachable' answer; then the whole calibrate() loop on a synthetic specimen whose
property relations are closed-form (E proportional to the Bond Modulus and falling with
the Bond Stiffness Ratio, nu falling with the ratio, UCS proportional to the bond
strength, UCS / sigma_t falling with the Moment Contribution from 14 to 5.6 and with a
lower Cohesion / Tensile, the friction angle rising with the Bond Range, as
Documentation/Rock.md measured), so the parameters it must find are known: the levers
alone to 1e-9 (LeverChain), then calibrate(); a target it cannot reach (UCS / sigma_t =
60, the issue's example; a friction angle of 27.8 deg) stops within the test budget and
names the unreachable target; bad targets give errors naming key, value and range.
"""
import math
import os
import json
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "Plugin"))
import rockdem_calibration as cal  # noqa: E402


class Checks:
    def __init__(self):
        self.passed = self.failed = 0

    def check(self, ok, what):
        print(("ok   - " if ok else "FAIL - ") + what)
        if ok:
            self.passed += 1
        else:
            self.failed += 1

    def finish(self):
        print("%d passed, %d failed" % (self.passed, self.failed))
        sys.exit(1 if self.failed or not self.passed else 0)


c = Checks()

# --- 1. root finding on monotone functions with known roots -----------------------------
cases = [
    ("linear 3x + 1 = 10", lambda x: 3 * x + 1, 10.0, 0.0, {}, 3.0),
    ("cubic x^3 + x = 30 (root 3)", lambda x: x ** 3 + x, 30.0, 0.5, {}, 3.0),
    ("log-log: log(2.5 e^x) = log 1e9 (x = log 4e8)", lambda x: math.log(2.5) + x, math.log(1e9),
     math.log(1e9), {}, math.log(4e8)),
    ("decreasing, bracketed: 0.3 - 0.1 log(1 + e^x) = 0.22", lambda x: 0.3 - 0.1 * math.log(1 + math.exp(x)),
     0.22, math.log(0.4), {"lo": math.log(0.05), "hi": math.log(20.0), "slope_guess": -0.05},
     math.log(math.exp(0.8) - 1)),
    ("saturating tanh: 5 tanh(x) = 4.9", lambda x: 5 * math.tanh(x), 4.9, 0.2, {"lo": 0.0, "hi": 10.0}, math.atanh(0.98)),
]
for name, f, goal, x0, kw, root in cases:
    x, y, n, ok = cal.solve(f, goal, x0, 1e-9, 40, **kw)
    c.check(ok and abs(x - root) < 1e-6 and n <= 20,
            "%s: x = %.9g (exact %.9g) in %d evaluations" % (name, x, root, n))

# unreachable: 5 tanh(x) = 6 with x in [0, 3]: stops at the bound, not converged, bounded
x, y, n, ok = cal.solve(lambda x: 5 * math.tanh(x), 6.0, 0.5, 1e-6, 40, lo=0.0, hi=3.0)
c.check(not ok and n <= 6 and abs(x - 3.0) < 1e-12,
        "unreachable 5 tanh(x) = 6 on [0, 3]: stops at the bound x = %g after %d evaluations, "
        "closest y = %.4g" % (x, n, y))
# the bracket is kept: every evaluation inside [lo, hi]
seen = []
cal.solve(lambda x: seen.append(x) or x ** 3, 0.001, 0.9, 1e-12, 40, lo=-1.0, hi=1.0)
c.check(all(-1.0 <= s <= 1.0 for s in seen), "every evaluation inside the bracket [-1, 1] (%d)" % len(seen))


# --- 2. the calibration loop on a synthetic specimen -----------------------------------
# Closed-form relations shaped like the measured ones (Rock.md): the friction angle rises
# with the Bond Range (41.7 deg at 1.0, 27 deg per unit) and with the grains' Friction (19
# deg per unit, measured on the Berea file over 0-200 MPa, Calibration.md) and ignores the
# bond Friction Angle; UCS / sigma_t falls with the Moment Contribution (14 at beta 0, 5.6 at beta 1),
# rises with Cohesion / Tensile q about as q^0.9 (measured at beta 0: 14.2 / 32.0 / 61.4 at
# q 4 / 10 / 20, Calibration.md), and rises with the Bond Range; E rises with the
# Bond Range (the coordination), so a new Bond Range moves E and the rounds must re-check it.
def g_range(br):
    return 0.8 + 0.5 * (br - 1.0)           # 1 at Bond Range 1.4


def e_range(br):
    return 0.6 + br / 3.5                    # 1 at Bond Range 1.4


def ratio_of(beta, q, br):
    return (14.0 - 8.4 * beta) * (q / 4.0) ** 0.9 * g_range(br)


def phi_of(br, mu=0.5):
    return 41.7 + 27.0 * (br - 1.0) + 19.0 * (mu - 0.5)


class SyntheticBench:
    """E = 0.6 Eb (1 + 0.5 r) e_range(BR), nu = 0.28 - 0.12 log(1 + r), sigma_t = 0.9 T,
    UCS = sigma_t ratio_of(beta, q, BR), phi = phi_of(BR, GrainFriction) (q = Cohesion /
    Tensile). Like the real bench, each test puts the grains' friction in pack_props."""

    def __init__(self):
        self.tests = 0
        self.coordination = 11.0
        self.porosity = 0.39
        self.elements = 500
        self.pack_props = {"InitialElements": 500}

    @staticmethod
    def props(p):
        r, eb, br = p["BondStiffnessRatio"], p["BondModulus"], p["BondRange"]
        e = 0.6 * eb * (1 + 0.5 * r) * e_range(br)
        nu = 0.28 - 0.12 * math.log(1 + r)
        st = 0.9 * p["TensileStrength"]
        ratio = ratio_of(p["MomentContribution"], p["CohesionRatio"], br)
        return e, nu, st * ratio, st, phi_of(br, p.get("GrainFriction", 0.5))

    def compression(self, p, strain, elastic=False):
        self.tests += 1
        self.pack_props["Friction"] = p.get("GrainFriction", 0.5)
        e, nu, ucs, st, phi = self.props(p)
        self.coordination = 5.9 + 13.5 * (p["BondRange"] - 1.0)
        return {"E": e, "nu": nu, "ucs": ucs, "history": {}}

    def tension(self, p, strain, strain_per_step=None):
        self.tests += 1
        self.pack_props["Friction"] = p.get("GrainFriction", 0.5)
        return {"tensile_strength": self.props(p)[3], "history": {}}

    def triaxial(self, p, confining, strain, strains_per_step=None, known=None):
        self.tests += len(confining) - len(known or {})
        self.pack_props["Friction"] = p.get("GrainFriction", 0.5)
        e, nu, ucs, st, phi = self.props(p)
        a, b = ucs, (1 + math.sin(math.radians(phi))) / (1 - math.sin(math.radians(phi)))
        return [{"confining": s, "peak_axial": known[s][0] if known and s in known else a + b * s}
                for s in confining], 0.0, phi

    def close(self):
        pass


# 2a. the levers alone, to a tight tolerance: LeverChain on the exact relations
def chain_solve(levers, goal, p, y_of, tolerance=1e-9, n_max=40):
    spent = set()
    chain = cal.LeverChain(levers, goal, p, spent)
    for n in range(1, n_max + 1):
        y = y_of(p)
        if abs(y - goal) <= tolerance:
            return True, n, spent
        if not chain.update(y):
            return False, n, spent
    return False, n_max, spent


p = {"BondRange": 1.4, "MomentContribution": 1.0, "CohesionRatio": 4.0, "GrainFriction": 0.5}
ok, n, spent = chain_solve(cal.ENVELOPE_LEVERS, 50.0, p, lambda q: phi_of(q["BondRange"], q["GrainFriction"]))
c.check(ok and abs(p["BondRange"] - (1 + 8.3 / 27.0)) < 1e-9 and p["GrainFriction"] == 0.5,
        "phi = 50 deg on Bond Range: %.9g (exact %.9g) in %d evaluations" % (p["BondRange"], 1 + 8.3 / 27.0, n))
ok, n, spent = chain_solve(cal.ENVELOPE_LEVERS, 35.0, p, lambda q: phi_of(q["BondRange"], q["GrainFriction"]))
mu_35 = 0.5 + (35.0 - 41.7) / 19.0
c.check(ok and p["BondRange"] == 1.0 and spent == {"BondRange"} and abs(p["GrainFriction"] - mu_35) < 1e-9,
        "phi = 35 deg (below Bond Range 1's 41.7): Bond Range spent at its bound, then grain Friction %.9g "
        "(exact %.9g), %d evaluations" % (p["GrainFriction"], mu_35, n))
ok, n, spent = chain_solve(cal.ENVELOPE_LEVERS, 27.8, p, lambda q: phi_of(q["BondRange"], q["GrainFriction"]))
c.check(not ok and p["BondRange"] == 1.0 and p["GrainFriction"] == 0.0 and spent == {"BondRange", "GrainFriction"}
        and n <= 6,
        "phi = 27.8 deg: both levers spent at their bounds (Bond Range %g, grain Friction %g) after %d "
        "evaluations (closest %.1f deg)" % (p["BondRange"], p["GrainFriction"], n, phi_of(1.0, 0.0)))
p = {"BondRange": 1.4, "MomentContribution": 1.0, "CohesionRatio": 4.0}
ok, n, spent = chain_solve(cal.RATIO_LEVERS, math.log(9.0), p,
                           lambda q: math.log(ratio_of(q["MomentContribution"], q["CohesionRatio"], 1.4)))
c.check(ok and abs(p["MomentContribution"] - 5.0 / 8.4) < 1e-9 and p["CohesionRatio"] == 4.0 and not spent,
        "UCS / sigma_t = 9 on Moment Contribution: beta %.9g (exact %.9g) in %d evaluations, Cohesion / Tensile "
        "untouched" % (p["MomentContribution"], 5.0 / 8.4, n))
p = {"BondRange": 1.4, "MomentContribution": 1.0, "CohesionRatio": 4.0}
ok, n, spent = chain_solve(cal.RATIO_LEVERS, math.log(4.0), p,
                           lambda q: math.log(ratio_of(q["MomentContribution"], q["CohesionRatio"], 1.4)))
q_low = 4.0 * (4.0 / 5.6) ** (1.0 / 0.9)
c.check(ok and p["MomentContribution"] == 1.0 and abs(p["CohesionRatio"] - q_low) < 1e-7 and
        spent == {"MomentContribution"},
        "UCS / sigma_t = 4 (below beta 1's 5.6): beta spent at 1, then Cohesion / Tensile %.9g (exact %.9g), "
        "%d evaluations" % (p["CohesionRatio"], q_low, n))

# 2b. the whole calibrate() loop
target = {"name": "synthetic", "youngs_modulus": 20e9, "poissons_ratio": 0.18, "ucs": 50e6,
          "tensile_strength": 6e6, "friction_angle": 46.0, "confining_stresses": [0, 5e6, 10e6]}
log = []
res = cal.calibrate(target, {"max_tests": 60}, progress=log.append, bench=SyntheticBench())
p = res["parameters"]
# the exact answer
br_exact = 1.0 + (46.0 - 41.7) / 27.0
r_exact = math.exp((0.28 - 0.18) / 0.12) - 1
eb_exact = 20e9 / (0.6 * (1 + 0.5 * r_exact) * e_range(br_exact))
beta_exact = (14.0 - (50.0 / 6.0) / g_range(br_exact)) / 8.4
t_exact = 6e6 / 0.9
c.check(res["converged"] and not res["stale"],
        "synthetic rock: converged (%d tests, unreachable %s, stale %s)" % (res["tests"], res["unreachable"],
                                                                          res["stale"]))
for key, tolerance in cal.DEFAULT_TOLERANCES.items():
    err = res["errors"].get(key)
    c.check(err is not None and abs(err) <= tolerance, "synthetic %s: error %.4g within %g" % (key, err, tolerance))
c.check(res["tests"] <= 40, "synthetic: %d specimen tests (<= 40)" % res["tests"])
# an envelope right after a compression to failure on the same specimen (at the recipe's
# rate: 'uniform') takes its unconfined peak from it instead of running it again
pairs = [(a, b) for a, b in zip(log, log[1:]) if b["stage"] == "envelope" and "ucs" in a["measured"] and
         a["parameters"] == b["parameters"]]
c.check(pairs and all(b["measured"]["triaxial_peaks"][0] == a["measured"]["ucs"] and b["test"] - a["test"] == 2 and
                      "unconfined peak" in b["kind"] for a, b in pairs),
        "%d envelope(s) after a compression on the same specimen: the unconfined peak reused, 2 tests for 3 "
        "confining stresses (%s)" % (len(pairs), pairs[0][1]["kind"] if pairs else "-"))
c.check(cal.reused_ucs([0.0, 5e6], None, 1e-7, (5e7, None)) == {0.0: (5e7, None)} and
        cal.reused_ucs([0.0, 5e6], [1e-7, 2e-7], 1e-7, (5e7, None)) == {0.0: (5e7, None)} and
        cal.reused_ucs([0.0, 5e6], [2e-7, 2e-7], 1e-7, (5e7, None)) is None and
        cal.reused_ucs([1e6, 5e6], None, 1e-7, (5e7, None)) is None and
        cal.reused_ucs([0.0, 5e6], None, 1e-7, None) is None,
        "reused_ucs: only for a confining stress of 0 run at the compression's own rate")
# The parameters are set only as closely as the tolerances on the properties allow: E
# within 5 % and nu within 0.03 leave Eb and r that far (E depends on both); phi within
# 3 deg leaves the Bond Range within 3 / 27; UCS and sigma_t within 5 % leave the ratio
# within about 10 %, beta within about 0.1.
c.check(abs(p["BondStiffnessRatio"] / r_exact - 1) < 0.3 and abs(p["BondModulus"] / eb_exact - 1) < 0.15 and
        abs(p["MomentContribution"] - beta_exact) < 0.12 and abs(p["TensileStrength"] / t_exact - 1) < 0.1 and
        abs(p["BondRange"] - br_exact) < 3.0 / 27.0 and p["CohesionRatio"] == 4.0,
        "synthetic parameters near the exact answer: Eb %.4g (%.4g), r %.3g (%.3g), T %.4g (%.4g), "
        "beta %.3g (%.3g), Bond Range %.3g (%.3g), Cohesion / Tensile %g (4)"
        % (p["BondModulus"], eb_exact, p["BondStiffnessRatio"], r_exact, p["TensileStrength"], t_exact,
           p["MomentContribution"], beta_exact, p["BondRange"], br_exact, p["CohesionRatio"]))
c.check(res["cement"]["BondRange"] == p["BondRange"] and res["cement"]["MomentContribution"] == p["MomentContribution"],
        "the cement properties carry the calibrated Bond Range %.4g and Moment Contribution %.4g"
        % (res["cement"]["BondRange"], res["cement"]["MomentContribution"]))
stages = [rec["stage"] for rec in log]
c.check("envelope" in stages and any(s in ("stiffness", "strength") for s in stages[stages.index("envelope"):]),
        "a new Bond Range is followed by a re-check of E and nu (stages %s)" % " ".join(s[:3] for s in stages))
c.check(len(log) == len(res["iterations"]) and all(
    set(("test", "stage", "parameters", "measured", "errors")) <= set(rec) for rec in log),
    "progress called once per test record with parameters, measured, errors (%d calls)" % len(log))
c.check([rec["stage"] for rec in log][0] == "stiffness" and "strength" in [rec["stage"] for rec in log]
        and "envelope" in [rec["stage"] for rec in log], "stages in the laboratory's order: stiffness first")
rows = cal.iteration_rows(res["iterations"])
i_br, i_beta = cal.ITERATION_COLUMNS.index("BondRange"), cal.ITERATION_COLUMNS.index("MomentContribution")
c.check(len(set(r[i_br] for r in rows)) > 1 and len(set(r[i_beta] for r in rows)) > 1,
        "the iteration table shows the Bond Range and the Moment Contribution moving")

# the ratio below what beta 1 gives: beta spent at 1, Cohesion / Tensile lowered instead
res = cal.calibrate({"youngs_modulus": 20e9, "ucs": 40e6, "tensile_strength": 10e6}, {"max_tests": 40},
                    bench=SyntheticBench())
c.check(res["converged"] and res["parameters"]["MomentContribution"] == 1.0 and
        abs(res["parameters"]["CohesionRatio"] / q_low - 1) < 0.15,
        "UCS / sigma_t = 4: converged in %d tests, beta %g, Cohesion / Tensile %.3g (exact %.3g)"
        % (res["tests"], res["parameters"]["MomentContribution"], res["parameters"]["CohesionRatio"], q_low))

# a Brazilian target: the strength stage runs the bench's tension with the target's type
res = cal.calibrate({"youngs_modulus": 20e9, "ucs": 50e6, "tensile_strength": 6e6, "tensile_test": "brazilian"},
                    {"max_tests": 40}, bench=SyntheticBench())
kinds = sorted(set(rec["kind"] for rec in res["iterations"] if rec["stage"] == "strength"))
c.check(res["converged"] and kinds == ["compression + brazilian test"],
        "Brazilian target on the synthetic specimen: converged in %d tests, strength records %s"
        % (res["tests"], kinds))

# the ratio also depending on the bond strength relative to the modulus (as measured:
# weaker bonds against the same modulus give a higher UCS / sigma_t, Calibration.md): a
# ratio point means something only where UCS and E are matched; with the points taken
# on the way there, beta was found spent at 0 too early
class StrengthModulusBench(SyntheticBench):
    """UCS / sigma_t = ratio_of(beta, q, BR) sqrt(1e-3 Eb / T)."""

    @staticmethod
    def props(p):
        e, nu, ucs, st, phi = SyntheticBench.props(p)
        return e, nu, ucs * math.sqrt(1e-3 * p["BondModulus"] / p["TensileStrength"]), st, phi


# (started at beta 1, q 4, as the recipe says, so that beta is the lever: a start from
# the target's ratio, 15, would be beta 0 and solve it on q instead)
res = cal.calibrate({"youngs_modulus": 20e9, "ucs": 150e6, "tensile_strength": 10e6},
                    {"max_tests": 40, "moment_contribution": 1.0}, bench=StrengthModulusBench())
eb_sm = 20e9 / (0.6 * 1.2)
beta_sm = (14.0 - 15.0 / math.sqrt(1e-3 * eb_sm / (10e6 / 0.9))) / 8.4
c.check(res["converged"] and abs(res["parameters"]["MomentContribution"] - beta_sm) < 0.12,
        "ratio depending on Tensile / Bond Modulus: converged in %d tests, beta %.3g (exact %.3g)"
        % (res["tests"], res["parameters"]["MomentContribution"], beta_sm))

# Poisson's ratio from the elastic test only. Measured (Calibration.md, granite at 1e-7
# per step): the compression to failure's window below the peak read nu 0.97-1.24 where
# the elastic test read 0.236, and the strength stage, matching nu on it, drove the Bond
# Stiffness Ratio to its bracket end 2. Here the failure test reads such a nu (falling
# with the ratio, so a secant on it pushes the ratio up to 2); the elastic test reads the
# model's nu. The calibration must match nu on the elastic test alone and leave the Bond
# Stiffness Ratio where the stiffness stage put it in every strength test.
class FailureWindowNuBench(SyntheticBench):
    """SyntheticBench whose compression to failure reads nu = 1.1 - 0.1 log(1 + r) (not
    elastic); the elastic compression reads nu = 0.28 - 0.12 log(1 + r)."""

    failure_nus = []

    def compression(self, p, strain, elastic=False):
        r = SyntheticBench.compression(self, p, strain, elastic)
        if not elastic:
            r["nu"] = 1.1 - 0.1 * math.log(1 + p["BondStiffnessRatio"])
            self.failure_nus.append(r["nu"])
        return r


nu_target = {"youngs_modulus": 20e9, "poissons_ratio": 0.18, "ucs": 50e6, "tensile_strength": 6e6}
log = []
nu_bench = FailureWindowNuBench()
res = cal.calibrate(nu_target, {"max_tests": 40}, progress=log.append, bench=nu_bench)
ratio_moves = []
last_stiffness_ratio = None
for rec in log:
    r = rec["parameters"]["BondStiffnessRatio"]
    if rec["stage"] == "stiffness":
        last_stiffness_ratio = r
    elif rec["stage"] == "strength" and r != last_stiffness_ratio:
        ratio_moves.append((rec["test"], last_stiffness_ratio, r))
failure_nus = nu_bench.failure_nus
c.check(failure_nus and min(failure_nus) > 0.9 and
        [rec["measured"].get("failure_poissons_ratio") for rec in log if rec["stage"] == "strength"] == failure_nus,
        "the failure tests read nu %.3g-%.3g (not elastic), kept in the records as failure_poissons_ratio"
        % (min(failure_nus), max(failure_nus)))
c.check(res["converged"] and "poissons_ratio" not in res["unreachable"] and
        abs(res["errors"]["poissons_ratio"]) <= 0.03 and abs(res["measured"]["poissons_ratio"] - 0.18) <= 0.03,
        "nu matched on the elastic test: converged in %d tests, nu %.4f (target 0.18), unreachable %s"
        % (res["tests"], res["measured"]["poissons_ratio"], res["unreachable"]))
c.check(not ratio_moves and abs(res["parameters"]["BondStiffnessRatio"] / r_exact - 1) < 0.3 and
        res["parameters"]["BondStiffnessRatio"] < cal.BRACKETS["BondStiffnessRatio"][1],
        "the strength stage never moved the Bond Stiffness Ratio (%s); final %.3g (exact %.3g, bracket end %g)"
        % (ratio_moves or "no move", res["parameters"]["BondStiffnessRatio"], r_exact,
           cal.BRACKETS["BondStiffnessRatio"][1]))
last = {}
for rec in log:
    for k in rec["errors"]:
        last[k] = rec
c.check(last["poissons_ratio"]["stage"] == "stiffness" and
        last["poissons_ratio"]["parameters"] == dict(res["cement"], GrainFriction=0.5),
        "the final nu is an elastic test's, measured with the final parameters (test %d)"
        % last["poissons_ratio"]["test"])

# a granite's UCS / sigma_t = 29 (direct): above what beta 0 gives at Cohesion / Tensile 4,
# so it starts at beta 0 and the q of the measured relation, and solves q
res = cal.calibrate({"youngs_modulus": 20e9, "ucs": 58e6, "tensile_strength": 2e6}, {"max_tests": 30},
                    bench=SyntheticBench())
q_exact = 4.0 * (29.0 / 14.0) ** (1.0 / 0.9)
c.check(res["converged"] and res["parameters"]["MomentContribution"] == 0.0 and
        abs(res["parameters"]["CohesionRatio"] / q_exact - 1) < 0.1 and res["tests"] <= 16,
        "UCS / sigma_t = 29: converged in %d tests at beta %g, Cohesion / Tensile %.3g (exact %.3g), "
        "errors %s" % (res["tests"], res["parameters"]["MomentContribution"], res["parameters"]["CohesionRatio"],
                       q_exact, {k: round(v, 4) for k, v in res["errors"].items()}))


class OffRatioBench(SyntheticBench):
    """UCS 1.55 x the synthetic one at every q: the start relation (RATIO_AT_BETA0) is off
    the way it was on the 5,000-grain Berea (ratio 98 measured where 63 was aimed at)."""
    @staticmethod
    def props(p):
        e, nu, ucs, st, phi = SyntheticBench.props(p)
        return e, nu, 1.55 * ucs, st, phi


# a step of Cohesion / Tensile holds UCS: the Tensile Strength moves by the inverse of the
# step's UCS factor (q^0.9), so the step lands on sigma_t and UCS stays in its band (with
# q alone it took 10 tests, UCS leaving its band on the q step)
res = cal.calibrate({"youngs_modulus": 20e9, "ucs": 73.8e6, "tensile_strength": 1.17e6}, {"max_tests": 30},
                    bench=OffRatioBench())
q_steps = [(a, b) for a, b in zip(res["iterations"], res["iterations"][1:])
           if a["stage"] == b["stage"] == "strength" and
           abs(b["parameters"]["Cohesion"] / b["parameters"]["TensileStrength"] /
               (a["parameters"]["Cohesion"] / a["parameters"]["TensileStrength"]) - 1) > 1e-9]
c.check(res["converged"] and res["tests"] <= 8 and q_steps and
        all(abs(b["errors"]["ucs"]) <= 0.05 for a, b in q_steps),
        "ratio 1.55 x the start relation's: converged in %d tests (at most 8); UCS after each of the %d "
        "Cohesion / Tensile steps: %s" % (res["tests"], len(q_steps),
                                           ["%+.1f %%" % (100 * b["errors"]["ucs"]) for a, b in q_steps]))


class DamagedBench(SyntheticBench):
    """The granite at beta 0 and high Cohesion / Tensile (5,000 grains, Calibration.md): the
    failure test's E is 0.27 x the elastic one (damage long before the peak), and UCS
    rises with the Bond Modulus (182 -> 246 MPa for 6.9e10 -> 2.5e11 Pa: exponent 0.23), from
    15 % below the start's estimate, so that the first strength test misses UCS (as there).
    Before the scale secant restarted on a new modulus, this took more than 40 tests."""

    def compression(self, p, strain, elastic=False):
        r = SyntheticBench.compression(self, p, strain, elastic)
        if not elastic:
            r["E"] *= 0.27
            r["ucs"] *= 0.85 * (p["BondModulus"] / 2e10) ** 0.23
        return r


res = cal.calibrate({"youngs_modulus": 20e9, "poissons_ratio": 0.22, "ucs": 58e6, "tensile_strength": 2e6},
                    {"max_tests": 40}, bench=DamagedBench())
c.check(res["converged"] and res["tests"] <= 20,
        "UCS moving with the Bond Modulus, failure E 0.27 x elastic: converged in %d tests (the scale "
        "secant restarts when the E secant moves the modulus), errors %s"
        % (res["tests"], {k: round(v, 4) for k, v in res["errors"].items()}))
class RoughBench(DamagedBench):
    """DamagedBench whose UCS is 1.4 x the start's estimate (the 5,000-grain granite's
    ratio relation is not the 2,000-grain one start_levers uses) and rough: +-4 % that
    changes with every Tensile Strength and Cohesion / Tensile tried, the way another
    parameter set breaks other bonds first. The 5,000-grain granite rerun stalled here
    (Calibration.md): UCS inside its band, sigma_t 5 % high, the ratio right, and the
    ratio's lever moved q while the common scale was what was off; and q, solved
    linearly, stepped 8.8 -> 3.0 where halving the ratio needed 4.1. With the strengths'
    geometric middle and q in log, 30 phases of the roughness all converge within 16
    tests (before: 16-40 tests, one not converged in 40)."""

    phase = 0.0

    def compression(self, p, strain, elastic=False):
        r = DamagedBench.compression(self, p, strain, elastic)
        if not elastic:
            r["ucs"] *= (1.4 / 0.85) * (1 + 0.04 * math.sin(self.phase + 400 * math.log(p["CohesionRatio"]) +
                                                          300 * math.log(p["TensileStrength"])))
        return r


rough = []
for k in range(30):
    bench = RoughBench()
    bench.phase = 0.7 * k
    r = cal.calibrate({"youngs_modulus": 20e9, "ucs": 58e6, "tensile_strength": 2e6}, {"max_tests": 40}, bench=bench)
    rough.append((r["converged"], r["tests"]))
c.check(all(ok and n <= 16 for ok, n in rough),
        "rough UCS (+-4 %%), start 1.4 x off: %d of 30 converged, %d-%d tests"
        % (sum(ok for ok, n in rough), min(n for ok, n in rough), max(n for ok, n in rough)))


# Poisson's ratio above what the Bond Stiffness Ratio can give: a pack held by normal and
# shear springs stays below about 0.26 at a high bonded coordination whatever the ratio,
# and rises towards the rigidity threshold (coordination 6) as the Bond Range falls
# (measured on 2,000 grains at ratio 0.01: 0.256 at Bond Range 1.4, 0.411 at 1.0;
# Calibration.md, "Poisson's ratio above 0.25"). The ratio is spent at its bracket end,
# the Bond Range takes over, and the envelope stage leaves the Bond Range that nu needed.
class LowCoordinationBench(SyntheticBench):
    """SyntheticBench with nu = 0.26 - 0.12 log(1 + r) + 0.4 (1.4 - BR)."""

    @staticmethod
    def props(p):
        e, nu, ucs, st, phi = SyntheticBench.props(p)
        nu = 0.26 - 0.12 * math.log(1 + p["BondStiffnessRatio"]) + 0.4 * (1.4 - p["BondRange"])
        return e, nu, ucs, st, phi


r_lo = cal.BRACKETS["BondStiffnessRatio"][0]
br_nu = 1.4 - (0.38 - (0.26 - 0.12 * math.log(1 + r_lo))) / 0.4
nu_high = {"youngs_modulus": 20e9, "poissons_ratio": 0.38, "ucs": 50e6, "tensile_strength": 6e6}
res = cal.calibrate(nu_high, {"max_tests": 40}, bench=LowCoordinationBench())
c.check(res["converged"] and res["parameters"]["BondStiffnessRatio"] == r_lo and
        abs(res["parameters"]["BondRange"] - br_nu) < 0.03 / 0.4 and
        res["held_levers"] == {"BondRange": "poissons_ratio"} and res["tests"] <= 30,
        "nu = 0.38 (beyond the ratio's reach): converged in %d tests, ratio %g (its bracket end), Bond Range "
        "%.4g (exact %.4g), held %s, errors %s"
        % (res["tests"], res["parameters"]["BondStiffnessRatio"], res["parameters"]["BondRange"], br_nu,
           res["held_levers"], {k: round(v, 4) for k, v in res["errors"].items()}))
# ... with a friction angle: the Bond Range is nu's, so the envelope moves the grains'
# Friction, up (50 deg) or down (38 deg, below what Bond Range 1.1 gives at Friction 0.5,
# as Berea's over 0-200 MPa); 60 deg is beyond Friction 1 (the bracket's end): unreachable
for phi_t in (50.0, 38.0, 60.0):
    env = dict(nu_high, friction_angle=phi_t, confining_stresses=[0.0, 5e6, 1e7])
    res = cal.calibrate(env, {"max_tests": 60}, bench=LowCoordinationBench())
    br, mu = res["parameters"]["BondRange"], res["parameters"]["GrainFriction"]
    mu_exact = 0.5 + (phi_t - phi_of(br)) / 19.0
    doc_dir = tempfile.mkdtemp()
    cal.write_outputs(res, doc_dir)
    doc = cal.load_parameters(os.path.join(doc_dir, "parameters.json"))
    kept = abs(res["errors"]["poissons_ratio"]) <= 0.03 and abs(br - br_nu) < 0.03 / 0.4 and \
        res["held_levers"] == {"BondRange": "poissons_ratio"} and doc["pack"]["Friction"] == mu
    if phi_t < 55.0:
        c.check(res["converged"] and kept and abs(mu - mu_exact) < 3.0 / 19.0 and res["tests"] <= 60,
                "nu = 0.38 with phi = %g deg: converged in %d tests, nu error %+.3g at Bond Range %.4g (nu's), "
                "grain Friction %.4g (exact %.4g), in the parameter file's pack"
                % (phi_t, res["tests"], res["errors"]["poissons_ratio"], br, mu, mu_exact))
    else:
        c.check(not res["converged"] and res["unreachable"] == ["friction_angle"] and kept and mu == 1.0 and
                abs(res["measured"]["friction_angle"] - phi_of(br, 1.0)) < 1e-9,
                "nu = 0.38 with phi = %g deg: nu kept at Bond Range %.4g, grain Friction at its bracket end %g, "
                "phi %.2f deg reported unreachable after %d tests"
                % (phi_t, br, mu, res["measured"]["friction_angle"], res["tests"]))

# the triaxial tests' Max Strain: 8 x UCS / E, or 3 x the target envelope's peak deviator at
# the largest confining stress over E when more (Berea over 0-200 MPa); the granite's as before
granite_env = cal.load_rock("lac_du_bonnet_granite")
berea_env = cal.load_rock("berea_sandstone")
b_berea = (1 + math.sin(math.radians(27.8))) / (1 - math.sin(math.radians(27.8)))
c.check(abs(cal.envelope_strain(granite_env) - 8 * 200e6 / 69e9) < 1e-15 and
        berea_env["confining_stresses"] == [0.0, 50e6, 100e6, 200e6] and
        abs(cal.envelope_strain(berea_env) - 3 * (73.8e6 + (b_berea - 1) * 200e6) / 19.3e9) < 1e-15 and
        cal.envelope_strain({"friction_angle": 30.0, "confining_stresses": [0.0, 1e6]}) == 0.005,
        "envelope Max Strain: granite %.4g (8 UCS / E), Berea over 0-200 MPa %.4g (3 x its deviator at 200 MPa / E)"
        % (cal.envelope_strain(granite_env), cal.envelope_strain(berea_env)))

# the triaxial tests' rates: uniform by default; 'inertial' keeps the inertial number of the
# unconfined test, sqrt of the target envelope's mean stress at the peak (Berea at 200 MPa:
# sigma1 = 73.8 + 2.75 x 200 = 623.8 MPa, p = 341 MPa against 24.6: 3.72 x)
uniform = cal.envelope_strains_per_step(berea_env, cal.validate_recipe({"strain_per_step": 1e-7}))
inertial = cal.envelope_strains_per_step(berea_env, cal.validate_recipe({"strain_per_step": 1e-7,
                                                                         "envelope_rate": "inertial"}))
p200 = (73.8e6 + (b_berea + 2) * 200e6) / 3
c.check(uniform == [1e-7] * 4 and inertial[0] == 1e-7 and
        abs(inertial[3] / 1e-7 - math.sqrt(p200 / (73.8e6 / 3))) < 1e-12 and inertial == sorted(inertial) and
        cal.envelope_strains_per_step({"friction_angle": 30.0, "confining_stresses": [0.0, 1e6]},
                                      cal.validate_recipe({"envelope_rate": "inertial"})) == [1e-6, 1e-6],
        "envelope rates for Berea at 1e-7: uniform %s; inertial %s" % (uniform, ["%.3g" % x for x in inertial]))
try:
    cal.validate_recipe({"envelope_rate": "fast"})
    c.check(False, "envelope_rate 'fast' accepted")
except cal.CalibrationError as e:
    c.check("envelope_rate" in str(e) and "'fast'" in str(e) and "'inertial'" in str(e), "bad envelope_rate: %s" % e)

# a start from an earlier calibration (start=, its parameter file): the target's friction
# angle changed from 50 to 38 deg; the start's nu, E and strengths are within tolerance, so
# each stage measures once and the envelope moves the grain Friction alone; the Bond Range
# stays nu's (the file's held_levers)
first = cal.calibrate(dict(nu_high, friction_angle=50.0, confining_stresses=[0.0, 5e6, 1e7]), {"max_tests": 60},
                      bench=LowCoordinationBench())
first_dir = tempfile.mkdtemp()
cal.write_outputs(first, first_dir)
res = cal.calibrate(dict(nu_high, friction_angle=38.0, confining_stresses=[0.0, 5e6, 1e7]), {"max_tests": 60},
                    bench=LowCoordinationBench(), start=os.path.join(first_dir, "parameters.json"))
c.check(first["converged"] and res["converged"] and res["tests"] < first["tests"] and
        res["parameters"]["BondRange"] == first["parameters"]["BondRange"] and
        res["held_levers"] == {"BondRange": "poissons_ratio"} and res["iterations"][0]["parameters"] ==
        cal.specimen_properties(first["parameters"], cal.validate_recipe({})) and
        res["start"] == os.path.join(first_dir, "parameters.json"),
        "start from an earlier calibration (phi 50 -> 38 deg): converged in %d tests (from scratch %d), first test "
        "on the file's parameters, Bond Range %.4g kept (held for nu), grain Friction %.3g -> %.3g"
        % (res["tests"], first["tests"], res["parameters"]["BondRange"], first["parameters"]["GrainFriction"],
           res["parameters"]["GrainFriction"]))
for bad_start, words in (({"BondRange": 2.5}, ("start.parameters.BondRange", "2.5", "[1, 2]")),
                         ({"GrainFriction": -0.1}, ("start.parameters.GrainFriction", "-0.1", "[0, 1]"))):
    doc = json.load(open(os.path.join(first_dir, "parameters.json")))
    doc["parameters"].update(bad_start)
    try:
        cal.calibrate(nu_high, {}, bench=LowCoordinationBench(), start=doc)
        c.check(False, "start %s accepted" % bad_start)
    except cal.CalibrationError as e:
        c.check(all(w in str(e) for w in words), "bad start %s: %s" % (bad_start, e))

# the tensile test's rate: TENSION_STEPS_TO_PEAK steps to the expected peak (sigma_t / Bond
# Modulus; 30 x for a Brazilian disc), never faster than the recipe's strain per step
rec = cal.validate_recipe({"strain_per_step": 1e-7})
sps = cal.tension_strain_per_step({"tensile_strength": 6.9e6}, rec, 2.5e11)
sps_b = cal.tension_strain_per_step({"tensile_strength": 9.3e6, "tensile_test": "brazilian"}, rec, 2.5e11)
c.check(abs(sps - 6.9e6 / 2.5e11 / cal.TENSION_STEPS_TO_PEAK) < 1e-20 and sps < 1e-8 and
        sps_b == min(1e-7, 30 * 9.3e6 / 2.5e11 / cal.TENSION_STEPS_TO_PEAK) and
        abs(cal.tension_strain_per_step({"tensile_strength": 9.3e6, "tensile_test": "brazilian"}, rec, 1e12)
            - 30 * 9.3e6 / 1e12 / cal.TENSION_STEPS_TO_PEAK) < 1e-20 and
        cal.tension_strain_per_step({"tensile_strength": 1e6}, rec, 1e9) == 1e-7 and
        cal.tension_strain_per_step({}, rec, 2.5e11) == 1e-7,
        "tensile test rate: granite direct %.3g, Brazilian %.3g per step; capped at the recipe's 1e-7" % (sps, sps_b))
# ... and at most TENSION_MAX_STEPS steps: Berea at Bond Modulus 4.429e11 Pa pulls at 6.6e-10 per
# step to a Max Strain cut from 0.002 to 6.6e-5
sps_berea = cal.tension_strain_per_step({"tensile_strength": 1.17e6}, rec, 4.429e11)
berea_st = {"tensile_strength": 1.17e6, "youngs_modulus": 19.3e9}
c.check(abs(cal.tension_max_strain(berea_st, sps_berea) - cal.TENSION_MAX_STEPS * sps_berea) < 1e-18 and
        cal.tension_max_strain(berea_st, sps_berea) < 1e-4 and cal.tension_max_strain(berea_st, 1e-7) == 0.002,
        "tensile test's Max Strain: Berea at 4.429e11 Pa, %.3g per step, Max Strain %.3g (%d steps)"
        % (sps_berea, cal.tension_max_strain(berea_st, sps_berea), cal.TENSION_MAX_STEPS))
# the pack's locked-in stress: DEM Pack Source's default (2e-6 x the grains' modulus) unless it
# passes LOCKED_IN_FRACTION of the target's smallest strength (Berea at Bond Modulus 9.7e11 Pa
# held 1.5 MPa against sigma_t 1.17 MPa); the shipped files' packs keep the default
granite_t = {"ucs": 200e6, "tensile_strength": 6.9e6}
berea_t = {"ucs": 73.8e6, "tensile_strength": 1.17e6}
c.check(cal.locked_in_ceiling(granite_t, 2.5157e11) == 0.0 and cal.locked_in_ceiling(berea_t, 6.919e10) == 0.0 and
        cal.locked_in_ceiling(berea_t, 9.704e11) == cal.LOCKED_IN_FRACTION * 1.17e6 and
        cal.locked_in_ceiling({"ucs": 73.8e6}, 1e13) == cal.LOCKED_IN_FRACTION * 73.8e6 and
        cal.locked_in_ceiling({}, 1e13) == 0.0,
        "locked-in stress ceiling: the default for the granite and Berea files' moduli, %.4g Pa for Berea at 9.7e11 Pa"
        % cal.locked_in_ceiling(berea_t, 9.704e11))
c.check(cal.start_levers({"ucs": 58e6, "tensile_strength": 2e6}, cal.validate_recipe({"moment_contribution": 0.5}))
        == (0.5, 4.0) and cal.start_levers({"ucs": 58e6, "tensile_strength": 8e6}, cal.validate_recipe({})) == (1.0, 4.0),
        "start levers: the recipe's Moment Contribution when set; beta 1, q 4 below the beta-0 ratio")
# unreachable: UCS / sigma_t = 200 on a model that tops out at 14 (30 / 4)^0.9 = 85 (the
# issue's example of 60 is reached by this model at beta 0, Cohesion / Tensile about 20;
# measured 61.4 on 2,000 grains, Calibration.md)
bad = {"youngs_modulus": 20e9, "ucs": 200e6, "tensile_strength": 1e6}
res = cal.calibrate(bad, {"max_tests": 30}, bench=SyntheticBench())
c.check(not res["converged"] and res["unreachable"] == ["tensile_strength"] and res["tests"] <= 30,
        "UCS / sigma_t = 200: not converged, unreachable %s after %d tests; closest sigma_t error %+.3g, UCS error %+.3g"
        % (res["unreachable"], res["tests"], res["errors"]["tensile_strength"], res["errors"]["ucs"]))
c.check(abs(res["errors"]["ucs"]) <= 0.05 and res["parameters"]["MomentContribution"] == 0.0 and
        res["parameters"]["CohesionRatio"] == cal.BRACKETS["CohesionRatio"][1],
        "unreachable ratio: UCS still matched, beta %g and Cohesion / Tensile %g at their brackets' ends"
        % (res["parameters"]["MomentContribution"], res["parameters"]["CohesionRatio"]))
# unreachable friction angle: 27.8 deg on a model whose lowest is 32.2 at Bond Range 1 and
# grain Friction 0 (both levers at their brackets' ends)
res = cal.calibrate({"friction_angle": 27.8, "confining_stresses": [0.0, 5e6, 1e7]}, {"max_tests": 30},
                    bench=SyntheticBench())
c.check(not res["converged"] and res["unreachable"] == ["friction_angle"] and res["tests"] <= 18 and
        res["parameters"]["BondRange"] == 1.0 and res["parameters"]["GrainFriction"] == 0.0 and
        abs(res["measured"]["friction_angle"] - phi_of(1.0, 0.0)) < 1e-9,
        "phi = 27.8 deg: unreachable after %d tests, Bond Range %g, grain Friction %g, closest phi %.2f deg "
        "(exact %.2f)" % (res["tests"], res["parameters"]["BondRange"], res["parameters"]["GrainFriction"],
                          res["measured"]["friction_angle"], phi_of(1.0, 0.0)))
# the grains' Friction a calibration starts at (start_grain_friction): the recipe's; else
# 0.5, less by the second lever's slope (19 deg per unit) below the 36 deg that Bond Range
# 1.0 reaches at 0.5, within [0, 1]; calibrate() records it in the recipe it returns
sgf = cal.start_grain_friction
berea_mu = 0.5 - (36.0 - 27.8) / 19.0
c.check(abs(sgf({"friction_angle": 27.8}, {"grain_friction": None}) - berea_mu) < 1e-12 and
        sgf({"friction_angle": 59.0}, {"grain_friction": None}) == 0.5 and sgf({}, {"grain_friction": None}) == 0.5 and
        sgf({"friction_angle": 27.8}, {"grain_friction": 0.3}) == 0.3 and
        sgf({"friction_angle": 20.0}, {"grain_friction": None}) == 0.0 and
        cal.validate_recipe({})["grain_friction"] is None,
        "start grain Friction: %.4f for phi 27.8 deg (Berea), 0.5 for 59 deg and without phi, the recipe's when set, "
        "0 (the bracket's end) for 20 deg" % berea_mu)
res = cal.calibrate({"friction_angle": 30.0, "confining_stresses": [0.0, 5e6, 1e7]}, {"max_tests": 30},
                    bench=SyntheticBench())
c.check(abs(res["recipe"]["grain_friction"] - (0.5 - 6.0 / 19.0)) < 1e-12 and
        res["iterations"][0]["parameters"]["GrainFriction"] == res["recipe"]["grain_friction"],
        "phi = 30 deg: the first test ran at the start grain Friction %.4f, which the result's recipe records"
        % res["recipe"]["grain_friction"])
# a friction angle alone (no E, no UCS) is calibrated too
res = cal.calibrate({"friction_angle": 40.0, "confining_stresses": [0.0, 5e6, 1e7]}, {}, bench=SyntheticBench())
c.check(res["converged"] and abs(res["errors"]["friction_angle"]) <= 3.0,
        "friction angle alone: converged, error %+.3g deg after %d tests" % (res["errors"]["friction_angle"], res["tests"]))
# a test budget that is too small stops and says so
res = cal.calibrate(target, {"max_tests": 3}, bench=SyntheticBench())
for budget in (11, 12):
    r = cal.calibrate(target, {"max_tests": budget}, bench=SyntheticBench())
    c.check(r["tests"] <= budget, "budget of %d tests: %d run" % (budget, r["tests"]))
c.check(not res["converged"] and res["tests"] <= 3 and res["not_within"],
        "budget of 3 tests: stops after %d, not within %s" % (res["tests"], res["not_within"]))
c.check(dict(res["cement"], GrainFriction=res["parameters"]["GrainFriction"]) == res["iterations"][-1]["parameters"],
        "budget spent: the result keeps the parameters of the latest test (measured), not an untried step")

# --- 3. bad targets: key, value and range in the message --------------------------------
bad_cases = [
    ({"youngs_modulus": -5e9}, ("youngs_modulus", "-5000000000", "> 0")),
    ({"poissons_ratio": 0.5}, ("poissons_ratio", "0.5", "(0, 0.5)")),
    ({"poissons_ratio": -0.1}, ("poissons_ratio", "-0.1", "(0, 0.5)")),
    ({"ucs": 1e6, "tensile_strength": 1e5, "tensile_test": "splitting"},
     ("tensile_test", "'splitting'", "'direct', 'brazilian'")),
    ({"ucs": 1e6, "friction_angle": 95.0, "confining_stresses": [0, 1e6]}, ("friction_angle", "95", "(0, 90)")),
    ({"ucs": 1e6, "friction_angle": 40.0}, ("confining_stresses", "None", ">= 2 distinct")),
    ({"UCS": 1e6}, ("UCS", "1000000", "valid keys")),
    ({}, ("nothing to calibrate",)),
]
for bad_target, words in bad_cases:
    try:
        cal.validate_target(bad_target)
        c.check(False, "bad target %r raised nothing" % bad_target)
    except cal.CalibrationError as e:
        c.check(all(w in str(e) for w in words), "bad target %r: %s" % (bad_target, e))
# the tensile test types: 'brazilian' is valid; the preset names the one it uses
c.check(cal.TENSILE_TESTS == ("direct", "brazilian") and
        cal.validate_target({"tensile_strength": 9.3e6, "tensile_test": "brazilian"})["tensile_test"] == "brazilian",
        "TENSILE_TESTS %s: a Brazilian target validates" % (cal.TENSILE_TESTS,))
granite = cal.load_rock("lac_du_bonnet_granite")
granite_b = cal.load_rock("lac_du_bonnet_granite", tensile_test="brazilian")
c.check(granite["tensile_test"] == "direct" and granite["tensile_strength"] == 6.9e6 and
        granite_b["tensile_test"] == "brazilian" and granite_b["tensile_strength"] == 9.3e6 and
        {k: v for k, v in granite_b.items() if k not in ("tensile_test", "tensile_strength")} ==
        {k: v for k, v in granite.items() if k not in ("tensile_test", "tensile_strength")},
        "Lac du Bonnet preset: direct 6.9 MPa by default, Brazilian 9.3 MPa with tensile_test='brazilian' "
        "(the rest the same)")
for args, words in (((("lac_du_bonnet_granite",), {"tensile_test": "splitting"}),
                     ("tensile_test", "'splitting'", "'direct', 'brazilian'")),
                    ((("berea_sandstone",), {"tensile_test": "brazilian"}),
                     ("tensile_test", "'brazilian'", "Berea sandstone", "'direct'"))):
    try:
        cal.load_rock(*args[0], **args[1])
        c.check(False, "load_rock%r accepted" % (args,))
    except cal.CalibrationError as e:
        c.check(all(w in str(e) for w in words), "load_rock(%s, %s): %s" % (args[0][0], args[1], e))
try:
    cal.validate_recipe({"elements": 3})
    c.check(False, "recipe elements 3 accepted")
except cal.CalibrationError as e:
    c.check("elements" in str(e) and "3" in str(e) and "[10, 200000]" in str(e), "bad recipe: %s" % e)

# --- 4. parameter file round trip and its errors -----------------------------------------

folder = tempfile.mkdtemp()
res = cal.calibrate({"youngs_modulus": 20e9, "ucs": 50e6, "tensile_strength": 12e6}, {}, bench=SyntheticBench())
cal.write_outputs(res, folder)
doc = cal.load_parameters(os.path.join(folder, "parameters.json"))
c.check(doc["cement"] == res["cement"] and doc["converged"] == res["converged"],
        "parameters.json reads back the cement properties: %s" % doc["cement"])
res = cal.calibrate(target, {"max_tests": 60}, bench=SyntheticBench())
cal.write_outputs(res, folder)
doc = cal.load_parameters(os.path.join(folder, "parameters.json"))
c.check(doc["cement"]["BondRange"] == res["parameters"]["BondRange"] != 1.4 and
        doc["cement"]["MomentContribution"] == res["parameters"]["MomentContribution"] != 1.0,
        "parameters.json carries the calibrated Bond Range %.4g and Moment Contribution %.4g (what DEM Cement "
        "and build_specimen load)" % (doc["cement"]["BondRange"], doc["cement"]["MomentContribution"]))
with open(os.path.join(folder, "iterations.csv")) as f:
    lines = f.read().splitlines()
c.check(len(lines) == 1 + res["tests"] - 0 or len(lines) == 1 + len(res["iterations"]),
        "iterations.csv: a header and one row per test record (%d rows)" % (len(lines) - 1))
# the final triaxial tests' curves are written and charted with the others (run under
# pvpython, which has numpy and matplotlib, as ctest does)
try:
    import numpy as np
except ImportError:
    np = None
if np is not None:
    strain = np.linspace(0.0, 0.01, 11)
    res["histories"]["triaxial"] = [
        {"confining": s3, "peak_axial": 1e8 + 4 * s3,
         "history": {"Strain Z": strain, "Axial Stress (Pa)": (1e8 + 4 * s3) * np.sin(strain * 150)}}
        for s3 in (0.0, 5e6, 1e7)]
    tri_folder = tempfile.mkdtemp()
    cal.write_outputs(res, tri_folder)
    with open(os.path.join(tri_folder, "triaxial_5MPa_history.csv")) as f:
        tri_rows = f.read().splitlines()
    c.check(len(tri_rows) == 12 and tri_rows[0] == '"Strain Z","Axial Stress (Pa)"' and
            os.path.exists(os.path.join(tri_folder, "triaxial_0MPa_history.csv")) and
            os.path.exists(os.path.join(tri_folder, "triaxial_10MPa_history.csv")) and
            os.path.getsize(os.path.join(tri_folder, "stress_strain.png")) > 0,
            "the final triaxial tests' curves: triaxial_<confining>MPa_history.csv (%d rows at 5 MPa) and "
            "the stress-strain chart" % (len(tri_rows) - 1))
broken = dict(doc)
broken["cement"] = dict(doc["cement"], BondModulos=1e9)
path = os.path.join(folder, "broken.json")
with open(path, "w") as f:
    json.dump(broken, f)
try:
    cal.load_parameters(path)
    c.check(False, "an unknown property in the parameter file was accepted")
except cal.CalibrationError as e:
    c.check("cement.BondModulos" in str(e) and "BondModulus" in str(e), "unknown property named: %s" % e)

# the rock a parameter file names (its 'rock' is the preset's name) is found in Data/rocks/
c.check(cal.preset_of({"rock": "Lac du Bonnet granite"}) == cal.load_rock("lac_du_bonnet_granite") and
        cal.preset_of({"rock": "Berea sandstone"})["tensile_strength"] == 1.17e6 and cal.preset_of({"rock": ""}) == {},
        "preset_of: a parameter file's rock name finds its preset (granite, Berea); no name, no preset")

# --- 5. the shipped parameter files (Data/calibrated/) -----------------------------------
# every one loads (format, version, property names), is listed in that folder's README,
# and a file calibrated on its tensile strength carries the rate its tensile test ran at
# (the rate tension_strain_per_step gives for its target, recipe and Bond Modulus) and is
# either converged or says unreachable for exactly the targets it misses
data = os.path.join(os.path.dirname(os.path.dirname(HERE)), "Data", "calibrated")
with open(os.path.join(data, "README.md")) as f:
    listing = f.read()
for name in sorted(n for n in os.listdir(data) if n.endswith(".json")):
    doc = cal.load_parameters(os.path.join(data, name))
    ok = "`%s`" % name in listing
    what = "listed in the README"
    if "tension_strain_per_step" in doc["test"]:
        t = cal.validate_target(dict(doc["target"], tolerances=doc["tolerances"]))
        rate = cal.tension_strain_per_step(t, cal.validate_recipe(doc["recipe"]), doc["parameters"]["BondModulus"])
        outside = sorted(k for k in t if k in doc["tolerances"] and k in doc["errors"]
                         and abs(doc["errors"][k]) > doc["tolerances"][k])
        ok = ok and rate == doc["test"]["tension_strain_per_step"] and \
            (doc["converged"] if not outside else (not doc["converged"] and outside == sorted(doc["unreachable"])))
        what += ", tensile test at %.3g per step, %s" % (
            rate, "converged within its tolerances" if not outside else
            "not converged, outside its tolerances only on what it reports unreachable (%s)" % ", ".join(outside))
    c.check(ok, "Data/calibrated/%s: loads (cement %s), %s" % (name, sorted(doc["cement"]), what))
c.finish()
