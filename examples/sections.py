"""RockDEM example (pvbatch): seeing inside a failed specimen.

    xvfb-run -a pvbatch examples/sections.py [--output DIR] [--elements N] [--side M]
                                             [--save-model FILE.rdem | --model FILE.rdem]

pack -> isotropic consolidation -> cement -> unconfined compression until the axial
stress has fallen to 60 % of the peak, then (Documentation/Sections.md):
- section_stress.png: DEM Section XZ through the middle, the cut grains coloured by their
  von Mises stress, the traces of the broken bonds within half a mean diameter coloured by
  failure mode (red tension, blue shear);
- voxel_damage.png: DEM Voxelize, the damage (broken / installed bonds per voxel) volume
  rendered inside the outline of the voxel grid;
- spheres_closeup.png: a close-up of a corner of the specimen as true spheres;
- spheres_shadows.png: the specimen as true spheres casting shadows on each other and on
  the floor it stands on;
- voxels.vti: the voxel model (Save Data).
--save-model keeps the failed specimen as a state file; --model starts from one instead of
running the test again.
The plugin is taken from $ROCKDEM_PLUGIN, or from the default build tree.
"""
import argparse
import os
import time

from paraview.simple import *  # noqa: F401,F403

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.dirname(HERE)


def titled_bar(lut, view, title):
    """The colour legend of a transfer function in a view, with a title."""
    bar = GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    return bar


def dark_text(view):
    """Scalar bars readable on white."""
    for rep in view.Representations:
        if rep.GetXMLName() == "ScalarBarWidgetRepresentation":
            rep.TitleColor = [0.1, 0.1, 0.1]
            rep.LabelColor = [0.1, 0.1, 0.1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default=os.path.join(SOURCE_DIR, "results"), help="folder for the pictures")
    parser.add_argument("--elements", type=int, default=6000, help="Initial Elements of the pack")
    parser.add_argument("--side", type=float, default=0.03, help="edge of the cubic specimen, m")
    parser.add_argument("--save-model", help="write the failed specimen to this state file (.rdem)")
    parser.add_argument("--model", help="start from this state file (.rdem) instead of running the test")
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)
    plugin = os.environ.get("ROCKDEM_PLUGIN") or os.path.join(
        SOURCE_DIR, "build", "lib", "paraview-plugins", "RockDEM", "RockDEM.so")
    LoadPlugin(plugin, remote=False, ns=globals())
    import rockdem

    start = time.time()
    side = args.side
    if args.model:
        press = DEMStateReader(FileName=args.model)
        press.UpdatePipeline()
        t = rockdem.read_only(press, "ModelTime")
    else:
        pack = DEMPackSource(InitialElements=args.elements, XDimension=side, YDimension=side, ZDimension=side,
                             MinimumSize=0.0008, MaximumSize=0.0012, YoungsModulus=1e8, RandomSeed=3)
        pack.InvokeCommand("GrowElements")
        iso = DEMLoadTest(Input=pack, Gravity=[0, 0, 0], Mode="Isotropic", ConfiningStress=2e4,
                          FrameInterval=0.002, NumberOfFrames=8, SampleInterval=200)
        rock = DEMCement(Input=iso, BondModulus=2e7, TensileStrength=2e5, Cohesion=4e5, StrengthScatter=0.2,
                         GapTolerance=0.1)
        press, t = rockdem.compress_until_failure(rock, StrainRate=1.0, MaxStrain=0.05, FrameInterval=0.0005,
                                                  NumberOfFrames=100, SampleInterval=200)
        t = t if t is not None else press.TimestepValues[-1]
        print("compression stopped at t = %.4g s: peak %.4g Pa, axial %.4g Pa, %d broken bonds (%.0f s)" % (
            t, press.PeakStress, press.AxialStress, rockdem.read_only(press, "BrokenBonds"), time.time() - start),
            flush=True)
        if args.save_model:
            SaveData(args.save_model, proxy=press)
    middle = [0.5 * side] * 3

    # The section, coloured by stress, with the broken-bond traces.
    section = rockdem.section(press, "XZ", origin=middle)
    section.UpdatePipeline(t)
    print("section: %s" % rockdem.read_only(section, "LastMessage"), flush=True)
    view = rockdem.white_view([1000, 1000], time=t, axes=False)
    circles = rockdem.show_section(section, view, color_by="VonMisesStress", trace_width=2.0)
    lut = GetColorTransferFunction("VonMisesStress")
    lut.ApplyPreset("Viridis (matplotlib)", True)
    circles.RescaleTransferFunctionToDataRange(False, True)
    titled_bar(lut, view, "von Mises stress (Pa)")
    dark_text(view)
    view.CameraPosition = [middle[0], -4 * side, middle[2]]
    view.CameraFocalPoint = middle
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    Render(view)
    picture = os.path.join(args.output, "section_stress.png")
    SaveScreenshot(picture, view, ImageResolution=[1000, 1000])
    print("picture: %s" % picture, flush=True)

    # The voxel model: damage, volume rendered.
    voxels = rockdem.voxelize(press, number_of_voxels=24)
    voxels.UpdatePipeline(t)
    print("voxels: %s" % rockdem.read_only(voxels, "LastMessage"), flush=True)
    # Data Mode Binary: readable with Debian 12's updated expat (Sections.md, "Saving a voxel model")
    SaveData(os.path.join(args.output, "voxels.vti"), proxy=voxels, DataMode="Binary")
    view2 = rockdem.white_view([1000, 1000], time=t, axes=False)
    rockdem.show_voxels(voxels, view2, "Damage", opacity=[0.0, 0.0, 0.1, 0.0, 0.3, 0.35, 1.0, 0.9])
    outline = Show(Outline(Input=voxels), view2)  # the grid's box
    outline.ColorArrayName = ["POINTS", ""]
    outline.AmbientColor = outline.DiffuseColor = [0.2, 0.2, 0.2]
    titled_bar(GetColorTransferFunction("Damage"), view2, "Damage (broken / installed bonds)")
    dark_text(view2)
    view2.CameraPosition = [middle[0] + 3 * side, middle[1] - 2.2 * side, middle[2] + 1.6 * side]
    view2.CameraFocalPoint = middle
    view2.CameraViewUp = [0, 0, 1]
    view2.ResetCamera()
    Render(view2)
    picture = os.path.join(args.output, "voxel_damage.png")
    SaveScreenshot(picture, view2, ImageResolution=[1000, 1000])
    print("picture: %s" % picture, flush=True)

    # Close-up: true spheres, correct at any zoom (a corner of the specimen).
    view3 = rockdem.white_view([1000, 1000], time=t, axes=False)
    spheres = rockdem.show_as_sphere_glyphs(press, view3, color_by="VonMisesStress", resolution=32)
    spheres.RescaleTransferFunctionToDataRange(False, True)
    view3.CameraPosition = [side * 1.35, -side * 0.55, side * 1.3]
    view3.CameraFocalPoint = [side * 0.8, side * 0.2, side * 0.75]
    view3.CameraViewUp = [0, 0, 1]
    view3.CameraViewAngle = 30
    Render(view3)
    picture = os.path.join(args.output, "spheres_closeup.png")
    SaveScreenshot(picture, view3, ImageResolution=[1000, 1000])
    print("picture: %s" % picture, flush=True)

    # Shadows: the specimen on a floor, true spheres (a surface mesh) and a shadow-map light.
    view4 = rockdem.white_view([1000, 1000], time=t, axes=False)
    floor = Plane(Origin=[-side, -side, 0.0], Point1=[2 * side, -side, 0.0], Point2=[-side, 2 * side, 0.0])
    floor_display = Show(floor, view4)
    floor_display.ColorArrayName = ["POINTS", ""]
    floor_display.AmbientColor = floor_display.DiffuseColor = [0.85, 0.85, 0.82]
    spheres = rockdem.show_as_sphere_glyphs(press, view4, color_by="VonMisesStress", resolution=16, shadows=True)
    spheres.RescaleTransferFunctionToDataRange(False, True)
    view4.CameraPosition = [middle[0] - 1.6 * side, middle[1] - 2.6 * side, middle[2] + 1.9 * side]
    view4.CameraFocalPoint = [middle[0], middle[1] + 0.2 * side, 0.35 * side]
    view4.CameraViewUp = [0, 0, 1]
    view4.CameraViewAngle = 30
    Render(view4)
    picture = os.path.join(args.output, "spheres_shadows.png")
    SaveScreenshot(picture, view4, ImageResolution=[1000, 1000])
    print("picture: %s; total %.0f s" % (picture, time.time() - start), flush=True)


if __name__ == "__main__":
    main()
