"""pvpython: DEM Load Test's Confinement = Membrane (Documentation/Specimens.md, "The
flexible membrane").

On a small grown pack without gravity: (a) a cylinder carved by rockdem.specimen,
consolidated isotropically in the membrane, reads Lateral Stress and Axial Stress near the
Confining Stress, with no side faces; (b) the membrane on the uncarved (box) pack gives no
output and Last Message names Confinement, its value and what is valid; (c) Membrane in
Mode Compression is refused by name; (d) the membrane test written with SaveData, read back
by DEM State Reader, continues.
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
pack = DEMPackSource(InitialElements=900, XDimension=0.02, YDimension=0.02, ZDimension=0.03,
                     MinimumSize=0.0008, MaximumSize=0.0012, YoungsModulus=1e8, RandomSeed=4)
pack.GrowElements()
pack.UpdatePipeline()
cyl = rockdem.specimen(pack, "Cylinder", axis="Z", diameter=0.019, length=0.028)

# (a) isotropic consolidation in the membrane
iso = DEMLoadTest(Input=cyl, Mode="Isotropic", Confinement="Membrane", ConfiningStress=2e4,
                  Gravity=[0, 0, 0], FrameInterval=0.002, NumberOfFrames=6)
iso.UpdatePipeline(list(iso.TimestepValues)[-1])
lateral = rockdem.read_only(iso, "LateralStress")
axial = rockdem.read_only(iso, "AxialStress")
print("membrane: lateral %.5g Pa, axial %.5g Pa, stage %s; %s" % (
    lateral, axial, rockdem.read_only(iso, "Stage"), rockdem.read_only(iso, "Status")))
c.check(abs(lateral - 2e4) < 0.02 * 2e4, "Lateral Stress (membrane force / lateral area) %.5g Pa" % lateral)
c.check(abs(axial - 2e4) < 0.05 * 2e4, "Axial Stress (platens over pi R^2) %.5g Pa" % axial)

# (b) a box is refused
box = DEMLoadTest(Input=pack, Mode="Triaxial", Confinement="Membrane", ConfiningStress=2e4,
                  Gravity=[0, 0, 0], FrameInterval=1e-4, NumberOfFrames=1)
box.UpdatePipeline(1e-4)
msg = rockdem.read_only(box, "LastMessage")
c.check(box.GetDataInformation().GetNumberOfPoints() == 0 and
        "Confinement = Membrane needs a cylindrical specimen along Axis = Z" in msg and "Rigid Walls" in msg,
        "the membrane on a box is refused: %s" % msg)
Delete(box)

# (c) Membrane in Compression
comp = DEMLoadTest(Input=cyl, Mode="Compression", Confinement="Membrane", Gravity=[0, 0, 0],
                   FrameInterval=1e-4, NumberOfFrames=1)
comp.UpdatePipeline(1e-4)
msg = rockdem.read_only(comp, "LastMessage")
c.check("Confinement = Membrane is out of range for Mode = Compression" in msg,
        "Membrane in Compression is refused: %s" % msg)
Delete(comp)

# (d) the membrane test, written and read back, continues
d = tempfile.mkdtemp()
path = os.path.join(d, "membrane.rdem")
SaveData(path, proxy=iso)
reader = DEMStateReader(FileName=path)
more = DEMLoadTest(Input=reader, Mode="Isotropic", Confinement="Membrane", ConfiningStress=2e4,
                   Gravity=[0, 0, 0], FrameInterval=0.001, NumberOfFrames=1)
more.UpdatePipeline(list(more.TimestepValues)[-1])
lateral = rockdem.read_only(more, "LateralStress")
c.check(abs(lateral - 2e4) < 0.02 * 2e4, "the membrane test read back runs: lateral %.5g Pa (%s)" % (
    lateral, rockdem.read_only(more, "Status")))
c.finish()
