"""The DFN of a saved model, at DEM Fractures To DFN's default settings, with a picture.

    scripts/run_with_xvfb.sh pvbatch scripts/render_dfn.py MODEL.rdem [-o PREFIX] [--set K=V ...]

Reads MODEL.rdem (a RockDEM state file: for example DIR/ucs_failed.rdem written by
`rockdem_bench_rock --dump DIR`, the unconfined specimen where its stress has fallen to 70 %
of the peak, or the main job's specimen.rdem), runs DEM Fractures To DFN on it (its default
settings, or a property changed with --set, e.g. --set BandSignificance=0), prints the
export's report and one line of figures (discs, largest radius against the specimen's
width, share of the broken bonds in discs), and writes PREFIX.csv (one row per disc, Save
Data of the Summary port) and PREFIX.png (the discs coloured by set, tensile red and shear blue, inside
the grains drawn translucent grey). PREFIX defaults to MODEL without .rdem, plus _dfn. The plugin
is taken from $ROCKDEM_PLUGIN, or from the default build tree. Documentation/Rock.md, "The DFN reads
the band".
"""
import argparse
import csv
import os
import sys

from paraview.simple import *  # noqa: F401,F403

SOURCE_DIR = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def plugin_path():
    return os.environ.get("ROCKDEM_PLUGIN") or os.path.join(
        SOURCE_DIR, "build", "lib", "paraview-plugins", "RockDEM", "RockDEM.so")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("model", help="a RockDEM state file (.rdem)")
    parser.add_argument("-o", "--output", default=None, help="prefix of the .csv and .png written")
    parser.add_argument("--set", action="append", default=[], metavar="PROPERTY=VALUE",
                        help="a DEM Fractures To DFN property to change (pvpython name)")
    args = parser.parse_args()
    if not os.path.isfile(args.model):
        sys.exit("model = %s: no such file (a RockDEM state file, .rdem)" % args.model)
    prefix = args.output or (args.model[:-5] if args.model.endswith(".rdem") else args.model) + "_dfn"
    LoadPlugin(plugin_path(), remote=False, ns=globals())
    import rockdem

    model = DEMStateReader(FileName=args.model)
    dfn = DEMFracturesToDFN(Input=model)
    for item in args.set:
        name, _, value = item.partition("=")
        if not dfn.GetProperty(name):
            sys.exit("--set %s: DEM Fractures To DFN has no property %r" % (item, name))
        setattr(dfn, name, float(value))
    dfn.UpdatePipeline()
    print(rockdem.read_only(dfn, "LastMessage"), flush=True)
    table = prefix + ".csv"
    SaveData(table, proxy=OutputPort(dfn, 1))
    largest, in_discs, rows = 0.0, 0, 0
    with open(table) as f:
        for row in csv.DictReader(f):
            rows += 1
            largest = max(largest, float(row["Radius"]))
            in_discs += int(float(row["CrackCount"]))
    bounds = model.GetDataInformation().GetBounds()
    width = min(bounds[1] - bounds[0], bounds[3] - bounds[2])
    broken = rockdem.read_only(dfn, "BrokenBonds")
    print("DFN: %d discs; largest radius %.4g m (%.0f %% of the width %.4g m); %.1f %% of the %d broken bonds "
          "in discs (a crack in two discs counted twice); table: %s"
          % (rows, largest, 100.0 * largest / width, width, 100.0 * in_discs / max(broken, 1), broken, table))

    view = rockdem.white_view([1000, 1200])
    grains = rockdem.show_particles(model, view, color_by=None)
    grains.ColorArrayName = [None, ]
    grains.AmbientColor = grains.DiffuseColor = [0.7, 0.7, 0.7]
    grains.Opacity = 0.12
    discs = rockdem.show_fractures(dfn, view)
    centre = [0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5])]
    view.CameraFocalPoint = centre
    if bounds[5] - bounds[4] <= 0.1 * width:  # a 2D section: look down the slab axis, Y up
        view.CameraPosition = [centre[0], centre[1], centre[2] + 1.0]
        view.CameraViewUp = [0, 1, 0]
        discs.SetRepresentationType("Wireframe")  # seen edge-on: the traces, drawn thick
        discs.LineWidth = 3.0
        discs.Opacity = 1.0
    else:
        view.CameraPosition = [0.19, -0.16, 0.14]
        view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    Render(view)
    picture = prefix + ".png"
    SaveScreenshot(picture, view, ImageResolution=[1000, 1200])
    print("picture: %s" % picture)


if __name__ == "__main__":
    main()
