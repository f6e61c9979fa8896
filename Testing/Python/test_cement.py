"""pvpython: pack -> DEM Load Test (settle) -> DEM Cement -> DEM Load Test (gravity only).

The reference guide's "Settle before cementing", "Cementing the model" and "Reading
damage": cementing installs bonds (read-only Bonds > 0, one line per bond in the Bonds
block), nothing is broken (Damage 0, Broken Bonds 0), and a model cemented with strengths
far above the gravity stresses stays intact when it is run under gravity. A Threshold on
the cell array Broken selects the broken bonds (none here) out of the multiblock.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_test_support import Checks, load_rockdem  # noqa: E402

from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403

load_rockdem(globals())
import rockdem  # noqa: E402


def block(data, name):
    """The block of a fetched multiblock with the given name (None if absent)."""
    for k in range(data.GetNumberOfBlocks()):
        if data.HasMetaData(k) and data.GetMetaData(k).Get(data.NAME()) == name:
            return data.GetBlock(k)
    return None


def cells(data):
    """Cells in all leaves of a fetched composite dataset (or in a dataset)."""
    if data is None:
        return 0
    if data.IsA("vtkCompositeDataSet"):
        total = 0
        it = data.NewIterator()
        it.InitTraversal()
        while not it.IsDoneWithTraversal():
            total += it.GetCurrentDataObject().GetNumberOfCells()
            it.GoToNextItem()
        return total
    return data.GetNumberOfCells()


c = Checks()
pack = DEMPackSource(InitialElements=600, XDimension=0.06, YDimension=0.06, ZDimension=0.12,
                     MinimumSize=0.002, MaximumSize=0.004, YoungsModulus=1e7, RandomSeed=2)
settle = DEMLoadTest(Input=pack, FrameInterval=0.1, NumberOfFrames=4)

cement = DEMCement(Input=settle, BondModulus=1e7, TensileStrength=1e6, Cohesion=2e6)
cement.UpdatePipeline()
bonds = rockdem.read_only(cement, "Bonds")
print("cement:", rockdem.read_only(cement, "LastMessage"))
c.check(bonds > 0, "cementing the settled pack installs bonds (%d)" % bonds)
c.check(rockdem.read_only(cement, "Damage") == 0.0, "Damage is 0 after cementing")
c.check(rockdem.read_only(cement, "BrokenBonds") == 0, "Broken Bonds is 0 after cementing")
c.check(rockdem.read_only(cement, "BondStiffness") > 0.0,
        "Bond Stiffness %.4g N/m^3" % rockdem.read_only(cement, "BondStiffness"))
c.check(cement.Bonds == bonds, "read-only values work as attributes too (cement.Bonds)")

data = servermanager.Fetch(cement)
bond_block = block(data, "Bonds")
c.check(bond_block is not None, "the output has a block named Bonds")
c.check(bond_block is not None and bond_block.GetNumberOfLines() == bonds,
        "one line per bond (%s lines)" % (bond_block.GetNumberOfLines() if bond_block else None))
for name in ("IdA", "IdB", "Broken", "FailureMode", "NormalForce", "ShearForce", "BendingMoment",
             "TensileStrength", "Cohesion", "FrictionAngle"):
    c.check(bond_block is not None and bond_block.GetCellData().GetArray(name) is not None,
            "Bonds cell array %s" % name)
settled_time = data.GetFieldData().GetArray("Time").GetValue(0)
c.check(abs(settled_time - 0.4) < 0.01, "the settle is read at its last frame (t = %.4f s)" % settled_time)
c.check(len(cement.TimestepValues) == 0, "cementing publishes no time steps")

# Threshold on Broken: an ordinary Threshold works on the whole model.
broken = Threshold(Input=cement, Scalars=["CELLS", "Broken"], LowerThreshold=1, UpperThreshold=1,
                   ThresholdMethod="Between")
broken.UpdatePipeline()
c.check(cells(servermanager.Fetch(broken)) == 0, "Threshold Broken in [1, 1] keeps no cells")
intact = Threshold(Input=cement, Scalars=["CELLS", "Broken"], LowerThreshold=0, UpperThreshold=0,
                   ThresholdMethod="Between")
intact.UpdatePipeline()
c.check(cells(servermanager.Fetch(intact)) == bonds, "Threshold Broken in [0, 0] keeps every bond")

# Run the cemented model under gravity alone: far below the strengths, nothing breaks.
run = DEMLoadTest(Input=cement, FrameInterval=0.005, NumberOfFrames=2)
run.UpdatePipeline(0.01)
c.check(rockdem.read_only(run, "Bonds") == bonds, "the load test downstream sees the bonds")
c.check(rockdem.read_only(run, "Damage") == 0.0, "Damage stays 0 under gravity")
c.check(rockdem.read_only(run, "BrokenBonds") == 0, "Broken Bonds stays 0 under gravity")
c.check(rockdem.read_only(run, "BrokenInTension") == 0 and rockdem.read_only(run, "BrokenInShear") == 0,
        "none broken in tension or shear")
print("run:", rockdem.read_only(run, "Status"))

# Re-cementing replaces the bond set; a bad value is named and gives no output.
cement.StrengthScatter = 0.2
cement.UpdatePipeline()
c.check(rockdem.read_only(cement, "Bonds") == bonds, "re-cementing with scatter replaces the same bonds")
# Softening Ratio (tension softening, Cement.md): every bond carries it, damage starts at 0;
# out of [0, 100] it is named.
cement.SofteningRatio = 2.5
cement.UpdatePipeline()
softened = block(servermanager.Fetch(cement), "Bonds").GetCellData()
ratios = softened.GetArray("SofteningRatio")
damage = softened.GetArray("SofteningDamage")
c.check(ratios is not None and ratios.GetRange() == (2.5, 2.5), "every bond's SofteningRatio is 2.5")
c.check(damage is not None and damage.GetRange() == (0.0, 0.0), "SofteningDamage is 0 after cementing")
cement.SofteningRatio = 101.0
cement.UpdatePipeline()
message = rockdem.read_only(cement, "LastMessage")
c.check("Softening Ratio" in message and "100" in message, "a bad Softening Ratio is named: %s" % message)
cement.SofteningRatio = 0.0
cement.BondRadiusMultiplier = 2.0
cement.UpdatePipeline()
message = rockdem.read_only(cement, "LastMessage")
c.check("Bond Radius Multiplier" in message, "a bad Bond Radius Multiplier is named: %s" % message)
c.check(rockdem.read_only(cement, "Bonds") == 0, "and no bonds are reported")
c.finish()
