"""RockDEM main job (pvbatch): the complete workflow on the default specimen.

    xvfb-run -a pvbatch examples/main_job.py [--elements N] [--output DIR]

pack (Add/Grow) -> settle under gravity (Mode Off) -> isotropic consolidation (densify)
-> cement (DEM Cement) -> relax (Mode Off, no gravity) -> unconfined compression (Mode
Compression, Axis Z) -> fracture discs (DEM Fractures To DFN). Prints the porosity, UCS (Peak Stress), Young's modulus, Poisson's
ratio, broken bonds and the timing of each stage. See Documentation/Workflow.md.

The plugin is taken from $ROCKDEM_PLUGIN, or from the default build tree. Writes, in DIR:
pack.png (the pack as spheres coloured by radius, with the domain box), pack_summary.csv
(one row per pack stage: elements, porosity), history.csv (the compression test's
History table), stress_strain.png (the DEM Test chart), broken.png (the specimen after the
test, spheres coloured by displacement, broken bonds in red), dfn.csv and dfn.png (the
fracture discs exported by DEM Fractures To DFN just past the peak, one row per disc, and
a picture of them inside the grains), specimen.rdem and specimen.history.csv (the state
file of the tested specimen and its history: the compression's checkpoint),
settle.rdem, consolidate.rdem, relax.rdem (the checkpoints of the other stepping stages),
main_job.pvsm (the ParaView state: the whole pipeline in a layout of the 3D view and the
test chart, at the end of the test; File > Load State reopens it in seconds, every stage
taking its frames from its checkpoint), results.csv (one row: the measured values and
timings).
"""
import argparse
import os
import sys
import time

from paraview.simple import *  # noqa: F401,F403

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.dirname(HERE)


# Material and test settings (Documentation/Workflow.md says why).
MODULUS = 1e8          # Pa: grain Young's modulus and Bond Modulus (soft: a long timestep)
TENSILE = 5e5          # Pa: bond tensile strength
COHESION = 1e6         # Pa: bond cohesion
CONFINING = 1e4        # Pa: isotropic consolidation before cementing (low: released at relax)
RATE_FACTOR = 16.0     # x the Suggested Strain Rate (Press.md: E within 0.3 % at 16x)
MAX_STRAIN = 0.025     # past the peak (about 1.5 %)


def plugin_path():
    env = os.environ.get("ROCKDEM_PLUGIN")
    if env:
        return env
    return os.path.join(SOURCE_DIR, "build", "lib", "paraview-plugins", "RockDEM", "RockDEM.so")


def checkpoint(args, stage):
    """The checkpoint file of a stepping stage, in the output folder."""
    return os.path.join(args.output, stage + ".rdem")


def save_state(path, view, chart, t_end):
    """Saves the ParaView state with a layout (the 3D view beside the test chart, as
    File > Load State shows it) at t_end, the end of the compression test."""
    layout = CreateLayout("Main job")
    AssignViewToLayout(view=view, layout=layout, hint=0)
    layout.SplitHorizontal(0, 0.62)
    AssignViewToLayout(view=chart, layout=layout, hint=2)
    # The time the state opens at: the end of the test, the frame its checkpoint holds.
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = t_end
    for v in (view, chart):
        v.ViewTime = t_end
    SaveState(path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--elements", type=int, default=16000,
                        help="Initial Elements of the default specimen (count); below 16000 the "
                             "box is shrunk in proportion so the grains stay 0.68-1.36 mm")
    parser.add_argument("--output", default=os.path.join(SOURCE_DIR, "results"),
                        help="folder for the picture and the summary")
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)

    LoadPlugin(plugin_path(), remote=False, ns=globals())
    import rockdem

    # Default laboratory specimen: a 50 x 50 x 100 mm box of 0.68-1.36 mm radius grains;
    # Add and Grow fill it with about 20k (16,000 placed, then Add/Grow twice).
    # Fewer elements (the smoke test's 800) shrink the box by (N / 16000)^(1/3).
    scale = min(1.0, (args.elements / 16000.0) ** (1.0 / 3.0))
    size = [0.05 * scale, 0.05 * scale, 0.10 * scale]
    timings = []
    clock = [time.time()]

    def lap(stage):
        now = time.time()
        timings.append((stage, now - clock[0]))
        print("[%s: %.1f s]" % (stage, now - clock[0]), flush=True)
        clock[0] = now

    # Soft grains (E 1e8 Pa) keep the timestep long; see Documentation/Workflow.md.
    pack = DEMPackSource(XDimension=size[0], YDimension=size[1], ZDimension=size[2],
                         InitialElements=args.elements, MinimumSize=0.00068, MaximumSize=0.00136,
                         TargetPorosity=0.35, RandomSeed=1,
                         Density=2650.0, YoungsModulus=MODULUS, PoissonsRatio=0.25)
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

    lap("pack")
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
          % (final[2], final[1], picture, summary), flush=True)
    lap("pack picture")
    test_workflow(args, pack, rockdem, lap, timings, view)


def test_workflow(args, pack, rockdem, lap, timings, view):
    """Settle, consolidate, cement, relax, compress; write the history, chart, picture."""
    from paraview import servermanager
    safety = 0.3
    # 1. settle under gravity (Mode Off): the grains drop onto the floor and each other.
    # Every stepping stage keeps its end in a checkpoint (.rdem): main_job.pvsm reopens the
    # whole pipeline from them without computing the run again (Documentation/StateFile.md).
    settle = DEMLoadTest(Input=pack, FrameInterval=0.002, NumberOfFrames=5, TimestepSafety=safety,
                         CheckpointFile=checkpoint(args, "settle"))
    settle.UpdatePipeline(settle.TimestepValues[-1])
    print("settled:      porosity %.4f, contacts %d, %s" % (
        rockdem.read_only(settle, "CurrentPorosity"), rockdem.read_only(settle, "NumberOfContacts"),
        rockdem.read_only(settle, "SolverPath")), flush=True)
    lap("settle")
    # 2. isotropic consolidation: the random pack is loose (porosity ~0.6); the servo walls
    # squeeze it to CONFINING so the cement finds a dense contact network.
    consolidate = DEMLoadTest(Input=settle, Gravity=[0, 0, 0], Mode="Isotropic", ConfiningStress=CONFINING,
                              FrameInterval=0.002, NumberOfFrames=40, TimestepSafety=safety,
                              SampleInterval=200, CheckpointFile=checkpoint(args, "consolidate"))
    for t in list(consolidate.TimestepValues)[1:]:
        consolidate.UpdatePipeline(t)
        if rockdem.read_only(consolidate, "Stage") == "done":
            break
    suggested = rockdem.read_only(consolidate, "SuggestedStrainRate")
    print("consolidated: stage %s at t = %.4g s, mean stress %.4g Pa, Suggested Strain Rate %.3g 1/s"
          % (rockdem.read_only(consolidate, "Stage"), t, rockdem.read_only(consolidate, "AxialStress"), suggested),
          flush=True)
    lap("consolidate")
    # 3. cement: parallel bonds between touching / nearly touching grains.
    cement = DEMCement(Input=consolidate, BondModulus=MODULUS, TensileStrength=TENSILE, Cohesion=COHESION,
                       StrengthScatter=0.2)
    cement.UpdatePipeline()
    bonds = rockdem.read_only(cement, "Bonds")
    print("cemented:     %s" % rockdem.read_only(cement, "LastMessage"), flush=True)
    # 4. relax: walls back at the box, no gravity, so the stress locked in at cementing
    # is released before the test (Press.md).
    relax = DEMLoadTest(Input=cement, Gravity=[0, 0, 0], FrameInterval=0.001, NumberOfFrames=2,
                        TimestepSafety=safety, CheckpointFile=checkpoint(args, "relax"))
    relax.UpdatePipeline(relax.TimestepValues[-1])
    print("relaxed:      broken bonds %d of %d" % (rockdem.read_only(relax, "BrokenBonds"), bonds), flush=True)
    lap("cement + relax")
    # 5. unconfined compression along Z at RATE_FACTOR x the Suggested Strain Rate.
    rate = RATE_FACTOR * suggested
    frames = 20 if args.elements >= 4000 else 10
    history_file = os.path.join(args.output, "history.csv")

    def progress(k, lt):
        print("compression frame %2d: axial strain %.4f, axial stress %.4g Pa, peak %.4g Pa, broken %d"
              % (k, rockdem.read_only(lt, "AxialStrain"), rockdem.read_only(lt, "AxialStress"),
                 rockdem.read_only(lt, "PeakStress"), rockdem.read_only(lt, "BrokenBonds")), flush=True)

    duration = 1.02 * MAX_STRAIN / rate
    result = rockdem.ucs_test(relax, StrainRate=rate, MaxStrain=MAX_STRAIN, TimestepSafety=safety,
                              FrameInterval=duration / frames, NumberOfFrames=frames,
                              SampleInterval=50, HistoryFile=history_file, progress=progress,
                              CheckpointFile=checkpoint(args, "specimen"))
    press = result["proxy"]
    lap("compression")
    # The tested specimen as a state file (Documentation/StateFile.md): the compression's
    # checkpoint, the exact model at the end of the test (DEM State Reader reopens it), its
    # history beside it.
    state_file = checkpoint(args, "specimen")
    t_end = press.GetDataInformation().DataInformation.GetTime()  # the frame where it finished
    print("state file: %s (%.1f MB)" % (state_file, os.path.getsize(state_file) / 1e6), flush=True)
    ucs, e_mod, nu = result["ucs"], result["E"], result["nu"]
    broken = result["broken_bonds"]
    print("UCS (Peak Stress): %.4g Pa; Young's modulus: %.4g Pa; Poisson's ratio: %.3f; "
          "broken bonds: %d of %d (%d tension, %d shear); strain rate %.3g 1/s (%g x suggested)"
          % (ucs, e_mod, nu, broken, bonds, rockdem.read_only(press, "BrokenInTension"),
             rockdem.read_only(press, "BrokenInShear"), rate, RATE_FACTOR), flush=True)

    # Stress-strain chart (ParaView's DEM Test chart).
    chart = rockdem.show_test_chart(press)
    chart.ViewSize = [900, 600]
    chart_png = os.path.join(args.output, "stress_strain.png")
    SaveScreenshot(chart_png, chart, ImageResolution=[900, 600])
    print("chart: %s; history: %s" % (chart_png, history_file))

    # The broken specimen: grains as spheres, broken bonds as red lines.
    Hide(pack, view)
    for proxy in list(GetSources().values()):
        try:
            Hide(proxy, view)
        except Exception:
            pass
    # The view shows its own time: the specimen at the end of the test.
    view.ViewTime = list(press.TimestepValues)[-1]
    particles = rockdem.show_particles(press, view, color_by="Radius")
    particles.Opacity = 0.25  # see the broken bonds inside the specimen
    rockdem.show_broken_bonds(press, view)
    view.ResetCamera()
    Render(view)
    broken_png = os.path.join(args.output, "broken.png")
    SaveScreenshot(broken_png, view, ImageResolution=[1000, 1200])
    print("broken specimen picture: %s" % broken_png)
    lap("pictures")

    # 6. The fracture network (DEM Fractures To DFN, Documentation/Fractures.md), taken at
    # the first frame past the peak: by the end of the test the specimen is crushed into
    # one connected damage zone. History times are model time; frames count from the
    # test's start.
    h = result["history"]
    stress, times = h["Axial Stress (Pa)"], h["Time (s)"]
    ipeak = int(stress.argmax())
    after = [i for i in range(ipeak, len(stress)) if stress[i] < 0.95 * stress[ipeak]]
    frame_times = list(press.TimestepValues)
    t_dfn = frame_times[0] + (times[after[0]] if after else times[-1]) - times[0]
    t_dfn = min([t for t in frame_times if t >= t_dfn - 1e-12] or [frame_times[-1]])
    dfn = DEMFracturesToDFN(Input=press)
    dfn.UpdatePipeline(t_dfn)
    print("DFN at t = %.4g s: %s" % (t_dfn, rockdem.read_only(dfn, "LastMessage")), flush=True)
    if rockdem.read_only(dfn, "DiscsEmitted") == 0:
        # The damage zones at the two rigid platens join into a few large non-planar
        # clusters at the default distance (two mean diameters); one mean diameter keeps the
        # fractures apart (Documentation/Fractures.md, Workflow.md).
        dfn.ClusterDistance = 0.5 * rockdem.read_only(dfn, "UsedClusterDistance")
        dfn.UpdatePipeline(t_dfn)
        print("DFN with Cluster Distance %.4g m (one mean diameter): %s"
              % (dfn.ClusterDistance, rockdem.read_only(dfn, "LastMessage")), flush=True)
    dfn_csv = os.path.join(args.output, "dfn.csv")
    SaveData(dfn_csv, proxy=OutputPort(dfn, 1))
    for proxy in list(GetSources().values()):
        try:
            Hide(proxy, view)
        except Exception:
            pass
    view.ViewTime = t_dfn
    rockdem.show_fractures(dfn, view, model=press)
    Render(view)
    dfn_png = os.path.join(args.output, "dfn.png")
    SaveScreenshot(dfn_png, view, ImageResolution=[1000, 1200])
    discs = rockdem.read_only(dfn, "DiscsEmitted")
    print("DFN: %d discs (%d tensile, %d shear); picture: %s; table: %s" % (
        discs, rockdem.read_only(dfn, "TensileDiscs"),
        rockdem.read_only(dfn, "ShearDiscs"), dfn_png, dfn_csv), flush=True)
    lap("DFN")
    # The ParaView state: File > Load State (or LoadState in pvpython) rebuilds the pipeline,
    # the 3D view beside the test chart, at the end of the test: the frame the compression's
    # checkpoint holds, so nothing is computed again.
    save_state(os.path.join(args.output, "main_job.pvsm"), view, chart, t_end)

    results = os.path.join(args.output, "results.csv")
    with open(results, "w") as f:
        f.write("elements,bonds,ucs_Pa,youngs_modulus_Pa,poissons_ratio,broken_bonds,strain_rate_per_s,dfn_discs,"
                + ",".join("time_%s_s" % n.replace(" ", "_").replace("+", "and") for n, _ in timings) + "\n")
        f.write("%d,%d,%.6g,%.6g,%.4f,%d,%.4g,%d," % (pack.GetDataInformation().GetNumberOfPoints(),
                                                      bonds, ucs, e_mod, nu, broken, rate, discs)
                + ",".join("%.1f" % t for _, t in timings) + "\n")
    print("total %.1f s; results: %s" % (sum(t for _, t in timings), results))


if __name__ == "__main__":
    main()
