"""RockDEM main job (pvbatch): the complete workflow on the default specimen.

    scripts/run_with_xvfb.sh pvbatch examples/main_job.py [--elements N] [--output DIR]
    scripts/run_with_xvfb.sh pvbatch examples/main_job.py --parameters FILE [--output DIR]

--parameters runs the same workflow on a calibrated rock: the pack and the cement come from
a calibration's parameter file (rockdem.calibrate, Documentation/Calibration.md; e.g.
Data/calibrated/lac_du_bonnet_granite_5000.json, the granite calibrated on E, nu, UCS, sigma_t and phi), the tests run at the platen strain per step
and to the Max Strains the calibration used, and the job prints its measurements beside
the calibration's target.

pack (placed loose, then Compact Elements: radius expansion with relaxation to the Target
Porosity) -> cement over an interaction range (DEM Cement, Bond Range) -> relax (Mode Off,
no gravity) -> unconfined compression (Mode Compression, Axis Z) and, on a twin of the
same cemented specimen, direct tension (Mode Tension) -> fracture discs (DEM Fractures To
DFN, default settings). Prints the porosity, the bonded coordination, UCS (Peak Stress),
Young's modulus, Poisson's ratio, the direct tensile strength, UCS / tensile strength, the
DFN (discs, largest radius, share of the broken bonds in discs) and the timing of each
stage. See Documentation/Workflow.md and Documentation/Rock.md.

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

ELEMENTS = 5000        # default specimen: 5,000 grains, 13 mean diameters across
HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.dirname(HERE)


# Material and test settings (Documentation/Workflow.md and Rock.md say why).
MODULUS = 1e10         # Pa: grain Young's modulus and Bond Modulus (bond strength / modulus 1e-4, as in rock)
TARGET_POROSITY = 0.37  # Compact Elements' target (a walled specimen this small jams near 0.39)
BOND_RANGE = 1.4       # x (rA + rB): bonded coordination about 11 (Scholtes & Donze 2013)
MOMENT_CONTRIBUTION = 0.5  # beta: half the bond moments in the failure stresses (Rock.md: UCS / sigma_t > 10)
TENSILE = 1e6          # Pa: bond tensile strength
COHESION = 4e6         # Pa: bond cohesion
STRAIN_PER_STEP = 1e-7  # platen strain per timestep in compression (sets the strain rate; Rock.md)
TENSION_STRAIN_PER_STEP = 1e-8  # direct tension, slower: its peak comes at about 7e-5 strain (Rock.md)
MAX_STRAIN = 0.004     # compression: past the peak (about 0.24 %) and its fall to 70 % (0.27 %)
TENSION_MAX_STRAIN = 0.0003  # direct tension: stops once fallen to half


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
    parser.add_argument("--elements", type=int, default=None,
                        help="Initial Elements of the default specimen (count, default %d); the box is "
                             "scaled with the count so the grains stay 1-2 mm after compaction" % ELEMENTS)
    parser.add_argument("--parameters", default=None,
                        help="a calibration's parameter file (JSON, rockdem.calibrate): the specimen "
                             "(pack and cement) and the test rate come from it")
    parser.add_argument("--output", default=os.path.join(SOURCE_DIR, "results"),
                        help="folder for the picture and the summary")
    args = parser.parse_args()
    if args.parameters and args.elements is not None:
        parser.error("--elements = %d: not with --parameters (the specimen is the parameter file's)" % args.elements)
    os.makedirs(args.output, exist_ok=True)

    LoadPlugin(plugin_path(), remote=False, ns=globals())
    import rockdem
    calibrated = None
    if args.parameters:
        calibrated = rockdem.load_parameters(args.parameters)
        args.elements = int(calibrated["pack"]["InitialElements"])
        target = calibrated["target"]
        print("calibrated rock: %s (%s; converged: %s%s)" % (
            target.get("name", "?"), args.parameters, calibrated["converged"],
            "; unreachable: " + ", ".join(calibrated["unreachable"]) if calibrated["unreachable"] else ""), flush=True)
    elif args.elements is None:
        args.elements = ELEMENTS

    # Default laboratory specimen: a W x W x 2W box (W = 50 mm for 10,000 grains, scaled
    # by (N / 10000)^(1/3): 39.7 mm for the default 5,000). The grains are placed loose
    # (radii 0.78-1.56 mm, porosity about 0.70) and Compact Elements grows them (to about
    # 1-2 mm) until the Target Porosity or the Maximum Locked-In Stress.
    scale = (args.elements / 10000.0) ** (1.0 / 3.0)
    size = [0.05 * scale, 0.05 * scale, 0.10 * scale]
    timings = []
    clock = [time.time()]

    def lap(stage):
        now = time.time()
        timings.append((stage, now - clock[0]))
        print("[%s: %.1f s]" % (stage, now - clock[0]), flush=True)
        clock[0] = now

    # Rock-like stiffness (E 1e10 Pa, bond strength / modulus 1e-4); see Documentation/Rock.md.
    if calibrated:
        pack = DEMPackSource(**calibrated["pack"])
        size = [pack.XDimension, pack.YDimension, pack.ZDimension]
    else:
        pack = DEMPackSource(XDimension=size[0], YDimension=size[1], ZDimension=size[2],
                             InitialElements=args.elements, MinimumSize=0.00078, MaximumSize=0.00156,
                             TargetPorosity=TARGET_POROSITY, RandomSeed=1,
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
    pack.InvokeCommand("CompactElements")
    record("compact")
    print("Compact Elements: Locked-In Stress %.4g Pa, Largest Overlap %.3f %% of the smaller radius"
          % (rockdem.read_only(pack, "LockedInStress"), 100.0 * rockdem.read_only(pack, "LargestOverlap")),
          flush=True)

    lap("pack")
    summary = os.path.join(args.output, "pack_summary.csv")
    with open(summary + ".tmp", "w") as f:
        f.write("stage,elements,porosity\n")
        for stage, n, porosity in rows:
            f.write("%s,%d,%.6f\n" % (stage, n, porosity))
    os.replace(summary + ".tmp", summary)

    view = rockdem.white_view([1000, 1200])
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
    test_workflow(args, pack, rockdem, lap, timings, view, calibrated)


def test_workflow(args, pack, rockdem, lap, timings, view, calibrated=None):
    """Cement, relax, compress (and pull a twin); write the history, chart, pictures.
    calibrated: a loaded parameter file (rockdem.load_parameters): its cement, its rate and
    the Max Strains of its target instead of the built-in rock's."""
    safety = 0.3
    strain_per_step, tension_strain_per_step = STRAIN_PER_STEP, TENSION_STRAIN_PER_STEP
    max_strain, tension_max_strain = MAX_STRAIN, TENSION_MAX_STRAIN
    porosity = rockdem.read_only(pack, "CurrentPorosity")
    # 1. cement: parallel bonds between every pair within the Bond Range (Cement.md).
    if calibrated:
        cement = DEMCement(Input=pack, **calibrated["cement"])
        safety = calibrated["test"]["timestep_safety"]
        strain_per_step = calibrated["test"]["strain_per_step"]
        # the calibration's tensile test ran slower when its peak came within a few hundred
        # steps (rockdem_calibration.tension_strain_per_step; older files have no key)
        tension_strain_per_step = calibrated["test"].get("tension_strain_per_step", strain_per_step)
        strains = rockdem.test_strains(calibrated["target"])
        max_strain, tension_max_strain = strains["ucs"], strains["tension"]
        target = calibrated["target"]
        if "ucs" in target and "youngs_modulus" in target:
            # The calibration's Max Strain (6 x UCS / E) is generous because it stops each
            # test once the stress has fallen to 70 % of the peak; the main job runs its
            # test to the end (the stage's checkpoint is the state file it writes), so it
            # stops at 3 x UCS / E: past the fall on the calibrated granite (peak at 1.7 x,
            # 70 % at 2.2 x UCS / E of platen strain, Calibration.md).
            max_strain = min(max_strain, max(0.005, 3.0 * target["ucs"] / target["youngs_modulus"]))
    else:
        cement = DEMCement(Input=pack, BondModulus=MODULUS, TensileStrength=TENSILE, Cohesion=COHESION,
                           BondRange=BOND_RANGE, MomentContribution=MOMENT_CONTRIBUTION, StrengthScatter=0.2)
    cement.UpdatePipeline()
    bonds = rockdem.read_only(cement, "Bonds")
    coordination = rockdem.read_only(cement, "BondedCoordination")
    print("cemented:     %s" % rockdem.read_only(cement, "LastMessage"), flush=True)
    print("Bonded Coordination: %.2f (%d bonds, Bond Range %g)" % (coordination, bonds, cement.BondRange), flush=True)
    # 2. relax: walls at the box, no gravity: the stress Compact Elements locked in is
    # released before the tests (Press.md), and the timestep of the cemented model is known.
    # Every stepping stage keeps its end in a checkpoint (.rdem): main_job.pvsm reopens the
    # whole pipeline from them without computing the run again (Documentation/StateFile.md).
    relax = DEMLoadTest(Input=cement, Gravity=[0, 0, 0], FrameInterval=2e-4, NumberOfFrames=1,
                        TimestepSafety=safety, CheckpointFile=checkpoint(args, "relax"))
    relax.UpdatePipeline(relax.TimestepValues[-1])
    timestep = rockdem.read_only(relax, "Timestep")
    print("relaxed:      broken bonds %d of %d; timestep %.4g s" % (
        rockdem.read_only(relax, "BrokenBonds"), bonds, timestep), flush=True)
    lap("cement + relax")
    # 3. unconfined compression along Z at STRAIN_PER_STEP per timestep.
    rate = strain_per_step / timestep
    frames = 30 if args.elements >= 4000 else 10
    history_file = os.path.join(args.output, "history.csv")

    def progress(k, lt):
        print("%s frame %2d: axial strain %.5f, axial stress %.4g Pa, peak %.4g Pa, broken %d"
              % (str(lt.Mode).strip("'"), k, rockdem.read_only(lt, "AxialStrain"),
                 rockdem.read_only(lt, "AxialStress"), rockdem.read_only(lt, "PeakStress"),
                 rockdem.read_only(lt, "BrokenBonds")), flush=True)

    duration = 1.02 * max_strain / rate
    result = rockdem.ucs_test(relax, StrainRate=rate, MaxStrain=max_strain, TimestepSafety=safety,
                              FrameInterval=duration / frames, NumberOfFrames=frames,
                              SampleInterval=50, HistoryFile=history_file, progress=progress,
                              CheckpointFile=checkpoint(args, "specimen"))
    press = result["proxy"]
    lap("compression")
    # 4. direct tension of a twin: the same cemented, relaxed specimen pulled along Z.
    tension_rate = tension_strain_per_step / timestep
    tduration = 1.02 * tension_max_strain / tension_rate
    tension = rockdem.tension_test(relax, StrainRate=tension_rate, MaxStrain=tension_max_strain, TimestepSafety=safety,
                                   FrameInterval=tduration / 20, NumberOfFrames=20, SampleInterval=20,
                                   progress=progress, stop_below=0.5,
                                   CheckpointFile=checkpoint(args, "tension"))
    sigma_t = tension["tensile_strength"]
    lap("tension")
    # The tested specimen as a state file (Documentation/StateFile.md): the compression's
    # checkpoint, the exact model at the end of the test (DEM State Reader reopens it), its
    # history beside it.
    state_file = checkpoint(args, "specimen")
    t_end = press.GetDataInformation().DataInformation.GetTime()  # the frame where it finished
    print("state file: %s (%.1f MB)" % (state_file, os.path.getsize(state_file) / 1e6), flush=True)
    ucs, e_mod, nu = result["ucs"], result["E"], result["nu"]
    broken = result["broken_bonds"]
    ratio = rockdem.compressive_to_tensile_ratio(ucs, sigma_t) if sigma_t > 0 else float("nan")
    print("Porosity: %.4f; Bonded Coordination: %.2f" % (porosity, coordination))
    print("UCS (Peak Stress): %.4g Pa; Young's modulus: %.4g Pa; Poisson's ratio: %.3f; "
          "broken bonds: %d of %d (%d tension, %d shear); strain rate %.4g 1/s (%g per step)"
          % (ucs, e_mod, nu, broken, bonds, rockdem.read_only(press, "BrokenInTension"),
             rockdem.read_only(press, "BrokenInShear"), rate, strain_per_step), flush=True)
    print("Direct tensile strength (twin): %.4g Pa; UCS / tensile strength: %.2f" % (sigma_t, ratio), flush=True)
    if calibrated:
        target = calibrated["target"]
        here = {"youngs_modulus": e_mod, "ucs": ucs}
        if target.get("tensile_test", "direct") == "direct":
            here["tensile_strength"] = sigma_t
        for key, value in here.items():
            if key in target:
                print("against the calibration's target: %s %.4g here, %.4g in the target (%+.1f %%), %.4g when "
                      "calibrated" % (key, value, target[key], 100.0 * (value / target[key] - 1.0),
                                      calibrated["measured"].get(key, float("nan"))), flush=True)

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

    # 5. The fracture network (DEM Fractures To DFN at its default settings,
    # Documentation/Fractures.md), taken at the first frame where the stress has fallen
    # to 70 % of the peak (the last frame if it never does). History times are model
    # time; frames count from the test's start.
    h = result["history"]
    stress, times = h["Axial Stress (Pa)"], h["Time (s)"]
    ipeak = int(stress.argmax())
    after = [i for i in range(ipeak, len(stress)) if stress[i] < 0.7 * stress[ipeak]]
    frame_times = list(press.TimestepValues)
    t_dfn = frame_times[0] + (times[after[0]] if after else times[-1]) - times[0]
    t_dfn = min([t for t in frame_times if t >= t_dfn - 1e-12] or [frame_times[-1]])
    dfn = DEMFracturesToDFN(Input=press)
    dfn.UpdatePipeline(t_dfn)
    print("DFN at t = %.4g s (%s): %s" % (t_dfn, "stress fallen to 70 % of the peak" if after else "end of the test",
                                       rockdem.read_only(dfn, "LastMessage")), flush=True)
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
    largest, in_discs = 0.0, 0
    with open(dfn_csv) as f:
        header = f.readline().strip().split(",")
        header = [c.strip('"') for c in header]
        for line in f:
            row = dict(zip(header, line.strip().split(",")))
            largest = max(largest, float(row["Radius"]))
            in_discs += int(float(row["CrackCount"]))
    dfn_broken = rockdem.read_only(dfn, "BrokenBonds")
    share = in_discs / dfn_broken if dfn_broken else 0.0
    print("DFN: %d discs (%d tensile, %d shear); largest radius %.4g m (%.0f %% of the width); "
          "%.1f %% of the %d broken bonds in discs; picture: %s; table: %s" % (
              discs, rockdem.read_only(dfn, "TensileDiscs"), rockdem.read_only(dfn, "ShearDiscs"),
              largest, 100.0 * largest / pack.XDimension, 100.0 * share, dfn_broken, dfn_png, dfn_csv), flush=True)
    lap("DFN")
    # The ParaView state: File > Load State (or LoadState in pvpython) rebuilds the pipeline,
    # the 3D view beside the test chart, at the end of the test: the frame the compression's
    # checkpoint holds, so nothing is computed again.
    save_state(os.path.join(args.output, "main_job.pvsm"), view, chart, t_end)

    results = os.path.join(args.output, "results.csv")
    with open(results, "w") as f:
        f.write("elements,porosity,bonds,bonded_coordination,ucs_Pa,youngs_modulus_Pa,poissons_ratio,"
                "tensile_strength_Pa,ucs_over_tensile,broken_bonds,strain_rate_per_s,dfn_discs,"
                "dfn_largest_radius_m,dfn_share_in_discs,"
                + ",".join("time_%s_s" % n.replace(" ", "_").replace("+", "and") for n, _ in timings) + "\n")
        f.write("%d,%.6f,%d,%.4f,%.6g,%.6g,%.4f,%.6g,%.4f,%d,%.4g,%d,%.6g,%.4f," % (
            pack.GetDataInformation().GetNumberOfPoints(), porosity, bonds, coordination, ucs, e_mod, nu,
            sigma_t, ratio, broken, rate, discs, largest, share)
                + ",".join("%.1f" % t for _, t in timings) + "\n")
    print("total %.1f s; results: %s" % (sum(t for _, t in timings), results))


if __name__ == "__main__":
    main()
