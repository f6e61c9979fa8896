"""pvpython: DEM Specimen and the laboratory's modes (issue "The laboratory's specimens").

Documentation/Specimens.md, Documentation/Press.md ("Brazilian test", "Direct tension
with gripped ends"). On a small grown pack without gravity:
(a) rockdem.specimen carves a cylinder and a disc: fewer particles, a box shrunk to them,
    read-only Number Of Particles / Removed Particles / Specimen Porosity;
(b) bad input (a cylinder that does not fit, a disc thicker than its diameter) gives no
    output and Last Message names the parameter, its value and the valid range;
(c) the cemented disc runs Mode Brazilian: Brazilian Strength = 2 P / (pi D t) at the peak
    equals Peak Stress, Disc Diameter / Thickness are set, and rockdem.brazilian_test
    returns load and displacement; Grip Length 0 in Tension is refused by name;
(d) the carved specimen written by DEM State Writer is read back and runs (reader -> load test).
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_test_support import Checks, load_rockdem  # noqa: E402

from paraview.simple import *  # noqa: E402,F401,F403

load_rockdem(globals())
import rockdem  # noqa: E402

c = Checks()
pack = DEMPackSource(InitialElements=1500, XDimension=0.03, YDimension=0.03, ZDimension=0.03,
                     MinimumSize=0.0008, MaximumSize=0.0012, YoungsModulus=1e8, RandomSeed=4)
pack.GrowElements()
pack.UpdatePipeline()
n_pack = rockdem.read_only(pack, "NumberOfElements")

# (a) a cylinder along Z and a disc along Z
cyl = rockdem.specimen(pack, "Cylinder", axis="Z", diameter=0.02, length=0.028)
n_cyl = rockdem.read_only(cyl, "NumberOfParticles")
removed = rockdem.read_only(cyl, "RemovedParticles")
print("cylinder:", rockdem.read_only(cyl, "LastMessage"))
c.check(0 < n_cyl < n_pack and n_cyl + removed == n_pack,
        "the cylinder keeps %d of %d particles (%d removed)" % (n_cyl, n_pack, removed))
b = cyl.GetDataInformation().GetBounds()
c.check(b[1] - b[0] < 0.025 and b[3] - b[2] < 0.025 and b[5] - b[4] > 0.028,
        "the cylinder's bounds are its diameter (and length) plus a grain: %s" % (b,))
por = rockdem.read_only(cyl, "SpecimenPorosity")
c.check(0.0 < por < 1.0, "Specimen Porosity %.3f" % por)
disc = rockdem.specimen(pack, "Disc", axis="Z", diameter=0.026, length=0.013)
c.check(rockdem.read_only(disc, "NumberOfParticles") > 0, "the disc keeps particles")

# (b) bad input
bad = rockdem.specimen(pack, "Cylinder", axis="Z", diameter=0.05, length=0.02)
msg = rockdem.read_only(bad, "LastMessage")
c.check(bad.GetDataInformation().GetNumberOfPoints() == 0 and "Diameter = 0.05 m is out of range" in msg
        and "valid range is (0, 0.03] m" in msg, "a cylinder that does not fit is refused: %s" % msg)
thick = rockdem.specimen(pack, "Disc", axis="Z", diameter=0.01, length=0.02)
msg = rockdem.read_only(thick, "LastMessage")
c.check("Length = 0.02 m is out of range for Shape = Disc" in msg, "a thick disc is refused: %s" % msg)
Delete(bad)
Delete(thick)

# (c) Brazilian test of the cemented disc
cemented = DEMCement(Input=disc, BondModulus=1e9, TensileStrength=2e5, Cohesion=4e5)
result = rockdem.brazilian_test(cemented, axis="Y", StrainRate=4.0, MaxStrain=0.01, TimestepSafety=0.3)
test = result["proxy"]
print("Brazilian: strength %.4g Pa, D %.4g m, t %.4g m, %d broken bonds" % (
    result["brazilian_strength"], result["diameter"], result["thickness"], result["broken_bonds"]))
c.check(result["brazilian_strength"] > 0 and
        result["brazilian_strength"] == rockdem.read_only(test, "PeakStress"),
        "Brazilian Strength is the Peak Stress (%.4g Pa)" % result["brazilian_strength"])
c.check(0.02 < result["diameter"] < 0.03 and 0.010 < result["thickness"] < 0.016,
        "Disc Diameter %.4g m, Disc Thickness %.4g m" % (result["diameter"], result["thickness"]))
load = result["load"]
c.check(len(load) > 0 and max(load) > 0 and max(result["displacement"]) > 0,
        "load (max %.4g N) against platen displacement (max %.4g m)" % (max(load), max(result["displacement"])))
c.check(rockdem.read_only(test, "TensileStrength") == 0.0, "Tensile Strength is 0 outside Mode Tension")
tension = DEMLoadTest(Input=cemented, Mode="Tension", GripLength=0.0, Gravity=[0, 0, 0],
                      FrameInterval=1e-4, NumberOfFrames=1)
tension.UpdatePipeline(1e-4)
status = rockdem.read_only(tension, "Status")
c.check("Grip Length = 0 largest particle diameters is out of range" in status,
        "Grip Length 0 is refused by name: %s" % status)
Delete(tension)

# (d) every state the project writes runs: the carved specimen, written and read back
d = tempfile.mkdtemp()
path = os.path.join(d, "specimen.rdem")
SaveData(path, proxy=cyl)
reader = DEMStateReader(FileName=path)
run = DEMLoadTest(Input=reader, Mode="Compression", Gravity=[0, 0, 0], StrainRate=1.0,
                  FrameInterval=2e-4, NumberOfFrames=2)
run.UpdatePipeline(4e-4)
c.check(run.GetDataInformation().GetNumberOfPoints() > n_cyl and rockdem.read_only(run, "Stage") == "shear"
        and rockdem.read_only(run, "AxialStrain") > 0,
        "the carved specimen read back runs a Compression test: %s" % rockdem.read_only(run, "Status"))
c.finish()
