"""pvpython: DEM Fractures To DFN on a real failure, and DEM Seed Fractures.

Reference guide "Exporting fractures to a DFN" and "Current limitations" (seeding from
a DFN); issue "Fractures to DFN"; Documentation/Fractures.md. A small cemented specimen
(about 380 particles) is loaded in unconfined compression past its peak (until the axial
stress has fallen to 60 % of it):
(a) the export reports its counts (read-only values and the report); with the defaults
    the specimen's damage is one connected non-planar cluster (reported as rejected), and
    with Cluster Distance one mean diameter it emits at least one disc, whose cell arrays
    are the documented ones;
(b) the export follows time: it is stamped with the load test's frame time;
(c) the summary table (port 1) written as CSV by Save Data round-trips;
(d) DEM Seed Fractures seeds the cemented specimen with any polygonal DFN (a Plane
    source, and the discs just exported): Seeded Bonds > 0 and exactly that many bonds
    of the output have FailureMode 3 (inherited);
(e) bad input is named and gives no output.
"""
import csv
import os
import shutil
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_test_support import Checks, load_rockdem  # noqa: E402

from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403

load_rockdem(globals())
import rockdem  # noqa: E402

T0 = time.time()
c = Checks()
tmp = tempfile.mkdtemp(prefix="rockdem_fractures_")


def block(data, name):
    for k in range(data.GetNumberOfBlocks()):
        if data.HasMetaData(k) and data.GetMetaData(k).Get(data.NAME()) == name:
            return data.GetBlock(k)
    return None


# The specimen: grown pack, closed by an isotropic consolidation to 20 kPa, cemented
# (as Testing/Solver/TestLoadTest.cpp's unconfined compression test).
pack = DEMPackSource(InitialElements=1000, XDimension=0.02, YDimension=0.02, ZDimension=0.02,
                     MinimumSize=0.0008, MaximumSize=0.0012, YoungsModulus=1e8, RandomSeed=3)
pack.InvokeCommand("GrowElements")
iso = DEMLoadTest(Input=pack, Gravity=[0, 0, 0], Mode="Isotropic", ConfiningStress=2e4,
                  FrameInterval=0.002, NumberOfFrames=6, SampleInterval=200)
cement = DEMCement(Input=iso, BondModulus=2e7, TensileStrength=2e5, Cohesion=4e5, StrengthScatter=0.2,
                   GapTolerance=0.1)
cement.UpdatePipeline()
print("cement:", rockdem.read_only(cement, "LastMessage"), "(%.1f s)" % (time.time() - T0))
c.check(rockdem.read_only(iso, "Stage") == "done", "the isotropic consolidation settles")

press = DEMLoadTest(Input=cement, Gravity=[0, 0, 0], Mode="Compression", StrainRate=1.0, MaxStrain=0.04,
                    FrameInterval=0.0005, NumberOfFrames=80, SampleInterval=200)
t_stop = None
for t in list(press.TimestepValues)[1:]:
    press.UpdatePipeline(t)
    axial = rockdem.read_only(press, "AxialStress")
    peak = rockdem.read_only(press, "PeakStress")
    if peak > 0 and axial < 0.6 * peak:
        t_stop = t
        break
c.check(t_stop is not None, "unconfined compression goes past the peak (stopped at t = %s s)" % t_stop)
t_stop = t_stop if t_stop is not None else press.TimestepValues[-1]
broken = rockdem.read_only(press, "BrokenBonds")
print("press at t = %.4g s: peak %.4g Pa, axial %.4g Pa, %d broken bonds (%.1f s)" % (
    t_stop, press.PeakStress, press.AxialStress, broken, time.time() - T0))

# (a) The export. With the defaults (Cluster Distance two mean diameters) the damage of
# this small specimen (about 10 diameters across) is one connected cluster, and it is not
# planar: reported, nothing emitted. One mean diameter resolves the axial splitting
# fractures inside it (Documentation/Fractures.md, "Measured results").
dfn = DEMFracturesToDFN(Input=press)
dfn.UpdatePipeline(t_stop)
report = rockdem.read_only(dfn, "LastMessage")
print("DFN with the defaults:", report)
default_clusters = rockdem.read_only(dfn, "Clusters")
default_emitted = rockdem.read_only(dfn, "DiscsEmitted")
c.check(default_clusters >= 1 and rockdem.read_only(dfn, "BrokenBonds") == broken,
        "defaults: %d broken bonds in %d clusters, %d discs, %d rejected too small, %d non-planar" % (
            dfn.BrokenBonds, default_clusters, default_emitted, dfn.RejectedTooSmall, dfn.RejectedNonPlanar))
c.check(default_emitted > 0 or ("Nothing emitted" in report and "rejected" in report),
        "when nothing is emitted the report says why")
diameter = 0.5 * rockdem.read_only(dfn, "UsedClusterDistance")
dfn.ClusterDistance = diameter
dfn.UpdatePipeline(t_stop)
report = rockdem.read_only(dfn, "LastMessage")
print("DFN with Cluster Distance = one mean diameter (%.4g m):" % diameter, report)
emitted = rockdem.read_only(dfn, "DiscsEmitted")
c.check(emitted >= 1, "the export emits at least one disc (%d)" % emitted)
c.check(rockdem.read_only(dfn, "BrokenBonds") == broken,
        "Broken Bonds %d is the load test's" % rockdem.read_only(dfn, "BrokenBonds"))
clusters = rockdem.read_only(dfn, "Clusters")
small = rockdem.read_only(dfn, "RejectedTooSmall")
flat = rockdem.read_only(dfn, "RejectedNonPlanar")
c.check(clusters >= 1 and small + flat + dfn.RejectedSparse < clusters,
        "Clusters %d, Rejected Too Small %d, Rejected Non Planar %d" % (clusters, small, flat))
c.check(emitted == dfn.TensileDiscs + dfn.ShearDiscs + dfn.InheritedDiscs,
        "Discs Emitted = tensile %d + shear %d + inherited %d" % (dfn.TensileDiscs, dfn.ShearDiscs, dfn.InheritedDiscs))
c.check(("%d broken bonds" % broken) in report and "disc" in report and "rejected as too small" in report,
        "the report names broken bonds, discs and rejections")
c.check(abs(rockdem.read_only(dfn, "UsedClusterDistance") - diameter) < 1e-12, "Used Cluster Distance %.4g m" % dfn.UsedClusterDistance)
discs = servermanager.Fetch(dfn)
c.check(discs.IsA("vtkPolyData") and discs.GetNumberOfPolys() == emitted, "port 0: one polygon per disc")
cd = discs.GetCellData()
for name in ("Dip", "Azimuth", "Set", "SetName", "Radius", "Area", "Normal", "Center", "CrackCount", "Planarity",
             "Fill"):
    c.check(cd.GetAbstractArray(name) is not None, "disc cell array %s" % name)
ok = True
for k in range(discs.GetNumberOfCells()):
    dip, az = cd.GetArray("Dip").GetValue(k), cd.GetArray("Azimuth").GetValue(k)
    ok = ok and 0.0 <= dip <= 90.0 and 0.0 <= az < 360.0 and cd.GetArray("Planarity").GetValue(k) >= 0.8 \
        and cd.GetArray("CrackCount").GetValue(k) >= 10
    print("  disc %d: %s dip %.1f az %.1f radius %.4f m, %d cracks, planarity %.3f, fill %.2f" % (
        k, cd.GetAbstractArray("SetName").GetValue(k), dip, az, cd.GetArray("Radius").GetValue(k),
        cd.GetArray("CrackCount").GetValue(k), cd.GetArray("Planarity").GetValue(k), cd.GetArray("Fill").GetValue(k)))
c.check(ok, "dip in [0, 90], azimuth in [0, 360), planarity and crack count above the minimums")

# (b) Follows time.
# The load test stamps its frame with the model's time (a whole number of steps, within
# half a step per frame of the k x Frame Interval asked for); the discs carry that time.
frame_time = press.GetDataInformation().DataInformation.GetTime()
c.check(abs(frame_time - t_stop) <= 0.5 * rockdem.read_only(press, "Timestep") * round(t_stop / 0.0005) and
        dfn.GetDataInformation().DataInformation.GetTime() == frame_time,
        "the discs are stamped with the load test's frame time %.6g s (asked for %.4g s)" % (frame_time, t_stop))

# (c) The summary table as CSV.
table = servermanager.Fetch(dfn, idx=1)
c.check(table.IsA("vtkTable") and table.GetNumberOfRows() == emitted, "port 1: one summary row per disc")
names = [table.GetColumnName(k) for k in range(table.GetNumberOfColumns())]
expected = ["CenterX", "CenterY", "CenterZ", "NormalX", "NormalY", "NormalZ", "Dip", "Azimuth", "Radius", "Area",
            "Set", "SetName", "CrackCount", "Planarity", "Fill"]
c.check(names == expected, "summary columns %s" % names)
saved = os.path.join(tmp, "dfn.csv")
SaveData(saved, proxy=OutputPort(dfn, 1))
with open(saved, newline="") as f:
    rows = list(csv.reader(f))
c.check(rows and rows[0] == names, "Save Data CSV header equals the column names")
c.check(len(rows) - 1 == emitted, "Save Data CSV has one line per disc (%d)" % (len(rows) - 1))


def same(text, column, r):
    value = table.GetColumnByName(column).GetVariantValue(r)
    if column == "SetName":
        return text == value.ToString()
    v = value.ToDouble()
    return abs(float(text) - v) <= 1e-4 * abs(v) + 1e-9


c.check(all(same(v, n, r - 1) for r in range(1, len(rows)) for n, v in zip(rows[0], rows[r])),
        "Save Data CSV values round-trip within the printed precision")
print("elapsed %.1f s" % (time.time() - T0))

# (d) Seeding the cemented specimen with a mapped DFN: a Plane source (a quad) and the
# discs just exported.
plane = Plane(Origin=[0.0, 0.0, 0.0101], Point1=[0.03, 0.0, 0.0101], Point2=[0.0, 0.03, 0.0101])
for name, fractures in (("a Plane source", plane), ("the exported discs", dfn)):
    seed = DEMSeedFractures(Input=cement, Fractures=fractures)
    seed.UpdatePipeline(t_stop)
    seeded = rockdem.read_only(seed, "SeededBonds")
    bonds = block(servermanager.Fetch(seed), "Bonds")
    mode = bonds.GetCellData().GetArray("FailureMode") if bonds else None
    inherited = sum(1 for k in range(mode.GetNumberOfTuples()) if mode.GetValue(k) == 3) if mode else -1
    c.check(seeded > 0 and inherited == seeded,
            "DEM Seed Fractures with %s: Seeded Bonds %d, %d bonds with FailureMode 3 (%s)" % (
                name, seeded, inherited, rockdem.read_only(seed, "LastMessage")))
    if name == "a Plane source":
        again = DEMFracturesToDFN(Input=seed)
        again.UpdatePipeline()
        c.check(rockdem.read_only(again, "InheritedDiscs") == 1 and
                servermanager.Fetch(again).GetCellData().GetArray("Dip").GetValue(0) < 2.0,
                "the seeded plane exports as one horizontal inherited disc")
        Delete(again)
    Delete(seed)

# (e) Bad input: named, no output.
dfn.MinimumPlanarity = 1.5
dfn.UpdatePipeline(t_stop)
message = rockdem.read_only(dfn, "LastMessage")
c.check("Minimum Planarity" in message, "a bad Minimum Planarity is named: %s" % message)
c.check(dfn.GetDataInformation().GetNumberOfCells() == 0 and rockdem.read_only(dfn, "DiscsEmitted") == 0,
        "and there is no output")
print("elapsed %.1f s" % (time.time() - T0))
shutil.rmtree(tmp, ignore_errors=True)
c.finish()
