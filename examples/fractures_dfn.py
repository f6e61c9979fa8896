"""RockDEM example (pvbatch): a specimen loaded past its peak, its fractures as a DFN.

    xvfb-run -a pvbatch examples/fractures_dfn.py [--output DIR]

pack -> isotropic consolidation -> cement -> unconfined compression until the axial
stress has fallen to 60 % of the peak -> DEM Fractures To DFN (Cluster Distance one mean
grain diameter; Documentation/Fractures.md says why) -> dfn.csv (the Summary table, one
row per disc) and dfn.png (the discs, coloured by set, inside the translucent grains).
The plugin is taken from $ROCKDEM_PLUGIN, or from the default build tree.
"""
import argparse
import os

from paraview.simple import *  # noqa: F401,F403

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.dirname(HERE)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default=os.path.join(SOURCE_DIR, "results"), help="folder for dfn.csv and dfn.png")
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)
    plugin = os.environ.get("ROCKDEM_PLUGIN") or os.path.join(
        SOURCE_DIR, "build", "lib", "paraview-plugins", "RockDEM", "RockDEM.so")
    LoadPlugin(plugin, remote=False, ns=globals())
    import rockdem

    pack = DEMPackSource(InitialElements=1000, XDimension=0.02, YDimension=0.02, ZDimension=0.02,
                         MinimumSize=0.0008, MaximumSize=0.0012, YoungsModulus=1e8, RandomSeed=3)
    pack.InvokeCommand("GrowElements")
    iso = DEMLoadTest(Input=pack, Gravity=[0, 0, 0], Mode="Isotropic", ConfiningStress=2e4,
                      FrameInterval=0.002, NumberOfFrames=6, SampleInterval=200)
    rock = DEMCement(Input=iso, BondModulus=2e7, TensileStrength=2e5, Cohesion=4e5, StrengthScatter=0.2,
                     GapTolerance=0.1)
    press = DEMLoadTest(Input=rock, Gravity=[0, 0, 0], Mode="Compression", StrainRate=1.0, MaxStrain=0.04,
                        FrameInterval=0.0005, NumberOfFrames=80, SampleInterval=200)
    t = press.TimestepValues[-1]
    for t in list(press.TimestepValues)[1:]:
        press.UpdatePipeline(t)
        if rockdem.read_only(press, "AxialStress") < 0.6 * rockdem.read_only(press, "PeakStress"):
            break
    print("compression stopped at t = %.4g s: peak %.4g Pa, axial %.4g Pa, %d broken bonds" % (
        t, press.PeakStress, press.AxialStress, rockdem.read_only(press, "BrokenBonds")), flush=True)

    dfn = DEMFracturesToDFN(Input=press)
    dfn.UpdatePipeline(t)
    dfn.ClusterDistance = 0.5 * rockdem.read_only(dfn, "UsedClusterDistance")  # one mean diameter
    dfn.UpdatePipeline(t)
    print("DFN: %s" % rockdem.read_only(dfn, "LastMessage"), flush=True)
    table = os.path.join(args.output, "dfn.csv")
    SaveData(table, proxy=OutputPort(dfn, 1))

    view = rockdem.white_view([1000, 1000], time=t)
    rockdem.show_fractures(dfn, view, model=press)
    view.CameraPosition = [0.07, -0.05, 0.05]
    view.CameraFocalPoint = [0.01, 0.01, 0.01]
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    Render(view)
    picture = os.path.join(args.output, "dfn.png")
    SaveScreenshot(picture, view, ImageResolution=[1000, 1000])
    print("DFN: %d discs; picture: %s; table: %s" % (rockdem.read_only(dfn, "DiscsEmitted"), picture, table))


if __name__ == "__main__":
    main()
