"""RockDEM example (pvbatch/pvpython): a triaxial series on one cemented specimen, the
Mohr-Coulomb failure envelope, and UCS, Young's modulus, Poisson's ratio and the ratio
of compressive to tensile strength.

    pvpython examples/triaxial_series.py [--elements N] [--confining 2e4,5e4,1e5,2e5] [--output DIR]
    xvfb-run -a pvbatch examples/triaxial_series.py --pictures     # also the pictures below

Writes DIR/envelope.csv (one row per test, then the fitted cohesion and friction angle),
DIR/envelope.png (peak sigma1 against sigma3 with the fitted line; needs matplotlib, else
skipped with a message) and prints the figures. With --pictures (needs a display: run it
under xvfb-run) it also writes DIR/specimen.png (the cemented specimen), DIR/triaxial_chart.png
(the DEM Test chart of the test at the highest confining stress) and DIR/triaxial_broken.png
(that specimen after the test, broken bonds in red); Documentation/Triaxial-HowTo.md shows them. The plugin comes from $ROCKDEM_PLUGIN or
the default build tree.
"""
import argparse
import os
import sys
import time

from paraview.simple import *  # noqa: F401,F403

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.dirname(HERE)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--elements", type=int, default=600, help="Initial Elements of the specimen")
    parser.add_argument("--confining", default="2e4,5e4,1e5,2e5", help="confining stresses, Pa")
    parser.add_argument("--output", default=os.path.join(SOURCE_DIR, "results", "triaxial"))
    parser.add_argument("--pictures", action="store_true",
                        help="also write specimen.png, triaxial_chart.png and triaxial_broken.png")
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)
    plugin = os.environ.get("ROCKDEM_PLUGIN") or os.path.join(
        SOURCE_DIR, "build", "lib", "paraview-plugins", "RockDEM", "RockDEM.so")
    LoadPlugin(plugin, remote=False, ns=globals())
    import rockdem

    start = time.time()
    # A small laboratory specimen (20 x 20 x 30 mm), consolidated, cemented and relaxed.
    pack = DEMPackSource(InitialElements=args.elements, XDimension=0.02, YDimension=0.02,
                         ZDimension=0.03, MinimumSize=0.0008, MaximumSize=0.0012,
                         YoungsModulus=1e8, RandomSeed=1)
    pack.InvokeCommand("GrowElements")
    iso = DEMLoadTest(Input=pack, Gravity=[0, 0, 0], Mode="Isotropic", ConfiningStress=2e4,
                      FrameInterval=0.002, NumberOfFrames=30, TimestepSafety=0.3)
    cement = DEMCement(Input=iso, BondModulus=1e8, TensileStrength=3e5, Cohesion=6e5,
                       StrengthScatter=0.2)
    relax = DEMLoadTest(Input=cement, Gravity=[0, 0, 0], FrameInterval=0.002, NumberOfFrames=2,
                        TimestepSafety=0.3)
    relax.UpdatePipeline(list(relax.TimestepValues)[-1])
    print("specimen: %d particles, %d bonds (%.0f s)" % (
        rockdem.read_only(pack, "NumberOfElements"), rockdem.read_only(cement, "Bonds"), time.time() - start))

    view = None
    if args.pictures:
        view = rockdem.white_view([800, 1000], time=list(relax.TimestepValues)[-1])
        rockdem.show_particles(relax, view)
        view.CameraPosition = [0.09, -0.07, 0.06]
        view.CameraFocalPoint = [0.01, 0.01, 0.015]
        view.CameraViewUp = [0, 0, 1]
        view.ResetCamera()
        Render(view)
        SaveScreenshot(os.path.join(args.output, "specimen.png"), view, ImageResolution=[800, 1000])
        Hide(relax, view)

    test = dict(StrainRate=2.0, MaxStrain=0.02, SampleInterval=20, TimestepSafety=0.3)
    ucs = rockdem.ucs_test(relax, **test)
    print("UCS %.4g Pa, Young's modulus %.4g Pa, Poisson's ratio %.3f" % (ucs["ucs"], ucs["E"], ucs["nu"]))
    tension = rockdem.tension_test(relax, **test)
    ratio = rockdem.compressive_to_tensile_ratio(ucs["ucs"], tension["tensile_strength"])
    print("tensile strength %.4g Pa; compressive / tensile = %.2f" % (tension["tensile_strength"], ratio))

    confining = [float(v) for v in args.confining.split(",")]
    results, (cohesion, friction) = rockdem.triaxial_series(
        relax, confining, delete=not args.pictures, FrameInterval=0.002, NumberOfFrames=40, **test)
    if args.pictures:
        last = results[-1]["proxy"]  # the test at the highest confining stress
        chart = rockdem.show_test_chart(last)
        chart.ViewSize = [900, 600]
        SaveScreenshot(os.path.join(args.output, "triaxial_chart.png"), chart, ImageResolution=[900, 600])
        # The frame at which the test stopped (the series stops each test once it is done).
        ended = float(results[-1]["history"]["Time (s)"][-1])
        view.ViewTime = min([t for t in last.TimestepValues if t >= ended - 1e-12] or [last.TimestepValues[-1]])
        particles = rockdem.show_particles(last, view, color_by="Radius")
        particles.Opacity = 0.25
        rockdem.show_broken_bonds(last, view)
        view.ResetCamera()
        Render(view)
        SaveScreenshot(os.path.join(args.output, "triaxial_broken.png"), view, ImageResolution=[800, 1000])
        print("pictures: specimen.png, triaxial_chart.png, triaxial_broken.png in %s" % args.output)
    for r in results:
        print("sigma3 %.3g Pa: peak sigma1 %.4g Pa, peak deviator %.4g Pa, stage %s, %d bonds broken" % (
            r["confining"], r["peak_axial"], r["peak_deviator"], r["stage"], r["broken_bonds"]))
    print("Mohr-Coulomb envelope: cohesion %.4g Pa, friction angle %.1f degrees" % (cohesion, friction))

    table = os.path.join(args.output, "envelope.csv")
    with open(table + ".tmp", "w") as f:
        f.write("confining_Pa,peak_axial_Pa,peak_deviator_Pa,broken_bonds\n")
        for r in results:
            f.write("%.9g,%.9g,%.9g,%d\n" % (r["confining"], r["peak_axial"], r["peak_deviator"], r["broken_bonds"]))
        f.write("# cohesion_Pa,%.9g\n# friction_angle_deg,%.6g\n" % (cohesion, friction))
        f.write("# ucs_Pa,%.9g\n# youngs_modulus_Pa,%.9g\n# poissons_ratio,%.6g\n" % (ucs["ucs"], ucs["E"], ucs["nu"]))
        f.write("# tensile_strength_Pa,%.9g\n# compressive_to_tensile,%.6g\n" % (tension["tensile_strength"], ratio))
    os.replace(table + ".tmp", table)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        a, b = rockdem.mohr_coulomb_line(cohesion, friction)
        s3 = [r["confining"] for r in results]
        s1 = [r["peak_axial"] for r in results]
        fig, ax = plt.subplots(figsize=(6, 4.5))
        ax.plot([v / 1e6 for v in s3], [v / 1e6 for v in s1], "o", label="peak sigma1")
        xs = [0.0, max(s3) * 1.1]
        ax.plot([v / 1e6 for v in xs], [(a + b * v) / 1e6 for v in xs], "-",
                label="c = %.3g MPa, phi = %.1f deg" % (cohesion / 1e6, friction))
        ax.set_xlabel("confining stress sigma3 (MPa)")
        ax.set_ylabel("peak axial stress sigma1 (MPa)")
        ax.legend()
        ax.grid(True, alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(args.output, "envelope.png"), dpi=120)
        print("envelope plot: %s" % os.path.join(args.output, "envelope.png"))
    except ImportError:
        print("matplotlib is not available: envelope.png skipped (envelope.csv has the figures)")
    print("table: %s (%.0f s in all)" % (table, time.time() - start))


if __name__ == "__main__":
    sys.exit(main())
