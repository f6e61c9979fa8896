"""RockDEM's side of the bonded-rock comparison with YADE JCFpm (scripts/benchmark_yade_jcfpm.sh).

  pvpython scripts/yade_rockdem.py specimen OUT.csv --particles N
  pvpython scripts/yade_rockdem.py probe SPECIMEN.csv PARAMS.json
  pvpython scripts/yade_rockdem.py run SPECIMEN.csv PARAMS.json --threads T --history OUT.csv [--repeat R]

specimen: the grains both codes load. DEM Pack Source places N grains loose in a W x W x 2W
  box (W = 50 mm x (N / 10000)^(1/3), radii 0.78-1.56 mm before growth, seed 1, as
  examples/main_job.py) and Compact Elements packs them (Target Porosity 0.36); the
  centres and radii are written as a CSV "x,y,z,Radius" (m, full precision).
probe: cements the specimen as "run" does and runs one short Mode Off frame to read the
  timestep RockDEM would choose (Timestep Safety of PARAMS); writes "dt" into PARAMS
  (0.9 x that, rounded down to 3 significant digits): the timestep both codes then use.
run: the user's path. CSV Reader -> Table To Points -> DEM Model From Points (Fit To Input;
  E, nu, density, grain friction of PARAMS; Restitution 1: no contact dashpot, as JCFpm
  has none) -> DEM Cement (PARAMS; Gap Tolerance 0, so that the bonds are exactly the
  pairs within Bond Range x (rA + rB), JCFpm's interactionDetectionFactor rule; Strength
  Scatter 0) -> DEM Load Test (Contact Law of PARAMS), Mode Compression along Z, Requested Timestep dt,
  Strain Rate = strain_per_step / dt, Settling Damping = damping, Gravity 0, Threads T,
  steps steps in 10 frames, History every sample steps. Timed: the UpdatePipeline calls
  of the 10 frames (the compression stage's set-up included; DEM Cement not). Prints
  "run K threads T particles N bonds B steps S seconds X pstep_s Y timestep DT peak P
  path ..."; the history (step, axial strain, axial stress, broken bonds) goes to --history.
ROCKDEM_PLUGIN names the built plugin.
"""
import argparse
import json
import math
import os
import sys
import time

from paraview import servermanager
from paraview.simple import CSVReader, Delete, LoadPlugin, TableToPoints

ap = argparse.ArgumentParser()
ap.add_argument("what", choices=["specimen", "probe", "run"])
ap.add_argument("specimen", help="specimen CSV (x,y,z,Radius)")
ap.add_argument("params", nargs="?", help="parameters JSON (probe, run)")
ap.add_argument("--particles", type=int, default=2000)
ap.add_argument("--threads", type=int, default=1)
ap.add_argument("--repeat", type=int, default=1)
ap.add_argument("--history", help="history CSV to write (run)")
a = ap.parse_args()

plugin = os.environ.get("ROCKDEM_PLUGIN")
if not plugin or not os.path.exists(plugin):
    sys.exit("ROCKDEM_PLUGIN must name the built RockDEM plugin (got %r)" % plugin)
LoadPlugin(plugin, remote=False, ns=globals())
import rockdem  # noqa: E402


def make_specimen():
    from vtk.numpy_interface import dataset_adapter as dsa
    scale = (a.particles / 10000.0) ** (1.0 / 3.0)
    pack = DEMPackSource(XDimension=0.05 * scale, YDimension=0.05 * scale, ZDimension=0.10 * scale,  # noqa: F821
                         InitialElements=a.particles, MinimumSize=0.00078, MaximumSize=0.00156,
                         TargetPorosity=0.36, RandomSeed=1, Density=2650.0, YoungsModulus=1e10,
                         PoissonsRatio=0.25)
    pack.UpdatePipeline()
    pack.InvokeCommand("CompactElements")
    pack.UpdatePipeline()
    n = rockdem.read_only(pack, "NumberOfElements")
    data = servermanager.Fetch(pack)
    it = data.NewIterator()
    it.InitTraversal()
    particles = None
    while not it.IsDoneWithTraversal():
        if it.GetCurrentMetaData().Get(data.NAME()) == "Particles":
            particles = dsa.WrapDataObject(it.GetCurrentDataObject())
        it.GoToNextItem()
    if particles is None or len(particles.Points) != n:
        sys.exit("no Particles block of %d points in the pack: %s" % (n, rockdem.read_only(pack, "LastMessage")))
    xyz, radius = particles.Points, particles.PointData["Radius"]
    tmp = a.specimen + ".tmp"
    with open(tmp, "w") as f:
        f.write("x,y,z,Radius\n")
        for p, r in zip(xyz, radius):
            f.write("%.17g,%.17g,%.17g,%.17g\n" % (p[0], p[1], p[2], r))
    os.replace(tmp, a.specimen)
    print("specimen %d grains, porosity %.4f, locked-in stress %.4g Pa, largest overlap %.3f %%: %s"
          % (n, rockdem.read_only(pack, "CurrentPorosity"), rockdem.read_only(pack, "LockedInStress"),
             100.0 * rockdem.read_only(pack, "LargestOverlap"), a.specimen))


def cemented(p):
    """The specimen loaded through the user's path and cemented: (proxies, cement, N)."""
    table = CSVReader(FileName=[a.specimen])
    points = TableToPoints(Input=table, XColumn="x", YColumn="y", ZColumn="z")
    model = DEMModelFromPoints(Input=points, Density=p["density"], YoungsModulus=p["grain_modulus"],  # noqa: F821
                               PoissonsRatio=p["grain_poisson"], Restitution=1.0, Friction=p["grain_friction"])
    model.UpdatePipeline()
    n = rockdem.read_only(model, "NumberOfElements")
    with open(a.specimen) as f:
        rows = sum(1 for _ in f) - 1
    if n != rows:
        sys.exit("DEM Model From Points made %d elements of %d: %s" % (n, rows, rockdem.read_only(model, "LastMessage")))
    cement = DEMCement(Input=model, BondModulus=p["bond_modulus"], BondStiffnessRatio=p["bond_stiffness_ratio"],  # noqa: F821
                       TensileStrength=p["tensile_strength"], Cohesion=p["cohesion"],
                       FrictionAngle=p["friction_angle"], BondRange=p["bond_range"], GapTolerance=0.0,
                       BondRadiusMultiplier=1.0, MomentContribution=p["moment_contribution"],
                       StrengthScatter=0.0)
    cement.UpdatePipeline()
    bonds = rockdem.read_only(cement, "Bonds")
    if bonds <= 0:
        sys.exit("DEM Cement installed no bonds: %s" % rockdem.read_only(cement, "LastMessage"))
    return [cement, model, points, table], cement, n


def probe():
    with open(a.params) as f:
        p = json.load(f)
    proxies, cement, n = cemented(p)
    test = DEMLoadTest(Input=cement, Mode="Off", Gravity=[0.0, 0.0, 0.0], ContactLaw=p["contact_law"],  # noqa: F821
                       TimestepSafety=p["timestep_safety"], NumberOfFrames=1, FrameInterval=0)
    test.UpdatePipeline(list(test.TimestepValues)[-1])
    used = rockdem.read_only(test, "Timestep")
    if not used > 0:
        sys.exit("DEM Load Test chose no timestep: %s" % rockdem.read_only(test, "Status"))
    digits = 10 ** (math.floor(math.log10(0.9 * used)) - 2)
    p["dt"] = math.floor(0.9 * used / digits) * digits
    p["rockdem_bonds"] = int(rockdem.read_only(cement, "Bonds"))
    p["particles"] = int(n)
    tmp = a.params + ".tmp"
    with open(tmp, "w") as f:
        json.dump(p, f, indent=1)
    os.replace(tmp, a.params)
    print("probe: %d grains, %d bonds (bonded coordination %.2f), RockDEM timestep %.6g s at safety %g, "
          "critical %.6g s; dt for both codes %.4g s"
          % (n, p["rockdem_bonds"], rockdem.read_only(cement, "BondedCoordination"), used,
             p["timestep_safety"], rockdem.read_only(test, "CriticalTimestep"), p["dt"]))
    for proxy in [test] + proxies:
        Delete(proxy)


def run():
    with open(a.params) as f:
        p = json.load(f)
    dt, steps, frames = p["dt"], int(p["steps"]), 10
    if steps % frames:
        sys.exit("steps (%d) must be a multiple of %d" % (steps, frames))
    for k in range(a.repeat):
        proxies, cement, n = cemented(p)
        # Max Strain a little beyond the steps, so that the frames, not the test's end, stop it.
        test = DEMLoadTest(Input=cement, Mode="Compression", Axis="Z", Gravity=[0.0, 0.0, 0.0],  # noqa: F821
                           StrainRate=p["strain_per_step"] / dt, MaxStrain=1.05 * steps * p["strain_per_step"],
                           RequestedTimestep=dt, TimestepSafety=p["timestep_safety"],
                           SettlingDamping=p["damping"], Threads=a.threads, PlatenFriction=0.0,
                           FrameInterval=steps // frames * dt, NumberOfFrames=frames,
                           SampleInterval=p["sample"], ContactLaw=p["contact_law"])
        times = list(test.TimestepValues)
        seconds = 0.0
        for t in times:
            start = time.perf_counter()
            test.UpdatePipeline(t)
            seconds += time.perf_counter() - start
        used = rockdem.read_only(test, "Timestep")
        if abs(used - dt) > 1e-12 * dt:
            sys.exit("DEM Load Test ran at %g s, not %g s: %s" % (used, dt, rockdem.read_only(test, "Status")))
        h = rockdem.fetch_history(test)
        step = h["Step"]  # the model's step count: the specimen starts at step 0
        if int(step[-1]) != steps:
            print("warning: the history ends at step %d, not %d" % (int(step[-1]), steps))
        peak = rockdem.read_only(test, "PeakStress")
        print("run %d threads %d particles %d bonds %d steps %d seconds %.6f pstep_s %.6g timestep %.6g "
              "peak %.6g broken %d tension %d shear %d path %s"
              % (k, a.threads, n, rockdem.read_only(cement, "Bonds"), steps, seconds, n * steps / seconds, used,
                 peak, rockdem.read_only(test, "BrokenBonds"), rockdem.read_only(test, "BrokenInTension"),
                 rockdem.read_only(test, "BrokenInShear"), rockdem.read_only(test, "SolverPath")))
        sys.stdout.flush()
        if a.history and k == 0:
            tmp = a.history + ".tmp"
            with open(tmp, "w") as f:
                f.write("step,axial_strain,axial_stress_pa,broken_tension,broken_shear\n")
                f.write("0,0,0,0,0\n")  # the start of the test (the first sample is at step `sample`)
                for i in range(len(step)):
                    f.write("%d,%.9g,%.9g,%d,%d\n" % (step[i], h["Strain Z"][i], h["Axial Stress (Pa)"][i],
                                                      h["Broken In Tension"][i], h["Broken In Shear"][i]))
            os.replace(tmp, a.history)
        for proxy in [test] + proxies:
            Delete(proxy)


{"specimen": make_specimen, "probe": probe, "run": run}[a.what]()
