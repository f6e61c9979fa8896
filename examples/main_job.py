"""RockDEM main job (pvbatch): build the default specimen's particle pack, densify it,
print its porosity and render it with particles drawn as spheres.

    xvfb-run -a pvbatch examples/main_job.py [--elements N] [--output DIR]

The plugin is taken from $ROCKDEM_PLUGIN, or from the default build tree.
Writes DIR/pack.png (the pack as spheres coloured by radius, with the domain box) and
DIR/pack_summary.csv (one row per stage: elements, porosity).
"""
import argparse
import os
import sys

from paraview.simple import *  # noqa: F401,F403

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.dirname(HERE)


def plugin_path():
    env = os.environ.get("ROCKDEM_PLUGIN")
    if env:
        return env
    return os.path.join(SOURCE_DIR, "build", "lib", "paraview-plugins", "RockDEM", "RockDEM.so")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--elements", type=int, default=12000,
                        help="Initial Elements of the default specimen (count)")
    parser.add_argument("--output", default=os.path.join(SOURCE_DIR, "results"),
                        help="folder for the picture and the summary")
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)

    LoadPlugin(plugin_path(), remote=False, ns=globals())
    import rockdem

    # Default laboratory specimen: a 50 x 50 x 100 mm box of 0.75-1.5 mm radius grains.
    pack = DEMPackSource(XDimension=0.05, YDimension=0.05, ZDimension=0.10,
                         InitialElements=args.elements, MinimumSize=0.00075, MaximumSize=0.0015,
                         TargetPorosity=0.35, RandomSeed=1,
                         Density=2650.0, YoungsModulus=10e9, PoissonsRatio=0.25)
    rows = []

    def record(stage):
        pack.UpdatePipeline()
        n = rockdem.read_only(pack, "NumberOfElements")
        porosity = rockdem.read_only(pack, "CurrentPorosity")
        rows.append((stage, n, porosity))
        print("%-14s elements: %7d   Current Porosity: %.4f   (%s)"
              % (stage, n, porosity, rockdem.read_only(pack, "LastMessage")))
        return n

    if record("built") == 0:
        sys.exit("the pack could not be built: " + rockdem.read_only(pack, "LastMessage"))
    pack.InvokeCommand("AddElements")
    record("add elements")
    pack.InvokeCommand("GrowElements")
    record("grow elements")
    pack.InvokeCommand("AddElements")
    record("add elements")
    pack.InvokeCommand("GrowElements")
    record("grow elements")

    summary = os.path.join(args.output, "pack_summary.csv")
    with open(summary + ".tmp", "w") as f:
        f.write("stage,elements,porosity\n")
        for stage, n, porosity in rows:
            f.write("%s,%d,%.6f\n" % (stage, n, porosity))
    os.replace(summary + ".tmp", summary)

    view = CreateView("RenderView")
    view.ViewSize = [1000, 1200]
    view.OrientationAxesVisibility = 1
    view.Background = [1.0, 1.0, 1.0]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    display = rockdem.show_particles(pack, view)
    bar = GetScalarBar(GetColorTransferFunction("Radius"), view)
    bar.Title = "Radius (m)"
    bar.ComponentTitle = ""
    bar.TitleColor = [0, 0, 0]
    bar.LabelColor = [0, 0, 0]
    display.SetScalarBarVisibility(view, True)
    rockdem.show_domain_box(pack, view)
    view.CameraPosition = [0.19, -0.16, 0.14]
    view.CameraFocalPoint = [0.025, 0.025, 0.05]
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    Render(view)
    picture = os.path.join(args.output, "pack.png")
    SaveScreenshot(picture, view, ImageResolution=[1000, 1200])
    final = rows[-1]
    print("Current Porosity: %.4f with %d elements; picture: %s; summary: %s"
          % (final[2], final[1], picture, summary))


if __name__ == "__main__":
    main()
