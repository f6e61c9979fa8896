"""pvpython: load the plugin, build a pack, add and grow it, read Current Porosity.

Also checks the names users type (DESIGN.md "Names users type"), the embedded helper
module, and that bad input is reported without output while ParaView keeps running.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_test_support import Checks, load_rockdem  # noqa: E402

from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403

load_rockdem(globals())
import rockdem  # noqa: E402  (embedded in the plugin)

c = Checks()
pack = DEMPackSource(InitialElements=1500, MinimumSize=0.002, MaximumSize=0.004,
                     XDimension=0.08, YDimension=0.08, ZDimension=0.08,
                     TargetPorosity=0.35, RandomSeed=3)
# Estimated Memory before the pack is built: 1500 particles x (180 + 550) B
# (Documentation/SpeedAccuracy.md "Memory"; measured in Testing/Solver/TestMemoryEstimate.cpp).
pack.UpdatePipelineInformation()
c.check(rockdem.read_only(pack, "EstimatedMemory") == 1500 * 730.0,
        "Estimated Memory before the build: %.6g B" % pack.EstimatedMemory)
pack.UpdatePipeline()
n0 = rockdem.read_only(pack, "NumberOfElements")
p0 = rockdem.read_only(pack, "CurrentPorosity")
c.check(n0 == 1500, "Initial Elements placed: %s" % n0)
c.check(0.0 < p0 < 1.0, "Current Porosity in (0, 1): %.4f" % p0)
c.check(abs(pack.CurrentPorosity - p0) < 1e-15, "proxy.CurrentPorosity reads the same value")

# Independent porosity from the fetched particles (occupied height up to the pack top).
data = servermanager.Fetch(pack)
particles = data.GetBlock(0)
radius = particles.GetPointData().GetArray("Radius")
solid = sum(4.0 / 3.0 * math.pi * radius.GetValue(i) ** 3 for i in range(radius.GetNumberOfTuples()))
top = max(particles.GetPoint(i)[2] + radius.GetValue(i) for i in range(radius.GetNumberOfTuples()))
top = min(top, 0.08)
independent = 1.0 - solid / (0.08 * 0.08 * top)
c.check(abs(independent - p0) < 1e-12, "porosity equals the independent value %.6f" % independent)

pack.InvokeCommand("AddElements")
pack.UpdatePipelineInformation()
ahead = rockdem.read_only(pack, "EstimatedMemory")
pack.UpdatePipeline()
n1 = rockdem.read_only(pack, "NumberOfElements")
c.check(ahead >= n1 * 730.0 and rockdem.read_only(pack, "EstimatedMemory") == n1 * 730.0,
        "Add Elements: Estimated Memory %.4g B ahead (to Target Porosity, an upper bound), %.4g B for the %d made"
        % (ahead, pack.EstimatedMemory, n1))
p1 = rockdem.read_only(pack, "CurrentPorosity")
report = rockdem.read_only(pack, "LastMessage")
print("Add Elements:", report)
c.check(n1 > n0, "Add Elements inserted particles (%d -> %d)" % (n0, n1))
c.check(p1 < p0, "Add Elements lowered porosity (%.4f -> %.4f)" % (p0, p1))
c.check(("reached" in report) or ("saturated" in report), "Add Elements says whether target was reached or placement saturated")

pack.InvokeCommand("GrowElements")
pack.UpdatePipeline()
p2 = rockdem.read_only(pack, "CurrentPorosity")
c.check(p2 < p1, "Grow Elements lowered porosity (%.4f -> %.4f)" % (p1, p2))
c.check(rockdem.read_only(pack, "NumberOfElements") == n1, "Grow Elements kept the particle count")
c.check(rockdem.read_only(pack, "ContactStiffness") > 0, "Contact Stiffness is derived")

# Names users type.
for name in ["OriginX", "XDimension", "PeriodicX", "a2DSectionXY", "FitToInput", "ShowDomainBox",
             "InitialElements", "MinimumSize", "MaximumSize", "TargetPorosity", "RandomSeed",
             "Density", "YoungsModulus", "PoissonsRatio", "Restitution", "Friction",
             "RollingFriction", "FineZone", "FineZoneMinimumSize", "FineZoneMaximumSize"]:
    c.check(pack.GetProperty(name) is not None or hasattr(pack, name), "property %s exists" % name)

# Bad input: error, no output, ParaView keeps running; fixing it recovers.
bad = DEMPackSource(MinimumSize=0.005, MaximumSize=0.003)
bad.UpdatePipeline()
message = rockdem.read_only(bad, "LastMessage")
print("error reported:", message)
c.check("Minimum Size" in message and "0.005" in message, "bad sizes named with their value")
c.check(servermanager.Fetch(bad).GetNumberOfBlocks() == 0, "no output after bad input")
bad.MinimumSize = 0.001
bad.UpdatePipeline()
c.check(rockdem.read_only(bad, "NumberOfElements") > 0, "fixing the input recovers")

# 2D packs are discs at mid-plane.
disc = DEMPackSource(a2DSectionXY=1, ZDimension=0.01, InitialElements=300)
disc.UpdatePipeline()
pts = servermanager.Fetch(disc).GetBlock(0)
zs = set(pts.GetPoint(i)[2] for i in range(pts.GetNumberOfPoints()))
c.check(pts.GetNumberOfPoints() > 0 and zs == {0.005}, "2D discs all at the mid-plane z = 0.005 m (z values: %s)" % sorted(zs)[:4])

c.finish()
