"""pvpython: bad input and faults (issue 18) as a ParaView user meets them.

Each case ends in a message naming the parameter (or the file) and what is wrong, read
from the proxy's Last Message / Status, never in a Python exception or "No reader found".
Documentation/Faults.md lists every case and the test that covers it.
"""
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_test_support import Checks, load_rockdem  # noqa: E402

from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403

load_rockdem(globals())
import rockdem  # noqa: E402

c = Checks()
work = tempfile.mkdtemp(prefix="rockdem-faults-")

# Item 15: a count beyond 32 bits reaches the engine, which names the property.
try:
    huge = DEMPackSource(InitialElements=2 ** 31)
    huge.UpdatePipeline()
    message = rockdem.read_only(huge, "LastMessage")
    c.check("Initial Elements = 2147483648 needs about" in message and "GiB" in message,
            "InitialElements = 2**31 is refused by name: %s" % message)
except OverflowError as e:
    c.check(False, "InitialElements = 2**31 raised OverflowError: %s" % e)

# Item 17: a damaged .rdem opens with DEM State Reader, which says what is wrong.
pack = DEMPackSource(InitialElements=60, XDimension=0.02, YDimension=0.02, ZDimension=0.02,
                     MinimumSize=0.001, MaximumSize=0.0015)
pack.UpdatePipeline()
good = os.path.join(work, "good.rdem")
SaveData(good, proxy=pack)
data = open(good, "rb").read()
cases = {
    "magic.rdem": (b"X" + data[1:], "is not a RockDEM state file"),
    "cut.rdem": (data[:len(data) // 2], "truncated"),
    "flipped.rdem": (data[:16] + bytes([data[16] ^ 0x10]) + data[17:], "is corrupt"),
    "empty.rdem": (b"", "is empty (0 bytes)"),
}
for name, (content, expected) in cases.items():
    path = os.path.join(work, name)
    with open(path, "wb") as f:
        f.write(content)
    reader = OpenDataFile(path)
    c.check(reader is not None and reader.GetXMLName() == "DEMStateReader",
            "OpenDataFile(%s) gives DEM State Reader, not 'No reader found'" % name)
    if reader is not None:
        reader.UpdatePipeline()
        message = rockdem.read_only(reader, "LastMessage")
        c.check(expected in message, "%s: %s" % (name, message))
        Delete(reader)

# Item 11: an absurd thread count is refused by name; the path says why it is serial.
settle = DEMLoadTest(Input=pack, FrameInterval=0.001, NumberOfFrames=1, Threads=100000)
settle.UpdatePipeline(0.001)
message = rockdem.read_only(settle, "LastMessage")
c.check("Threads = 100000 is out of range on this machine" in message, "Threads = 100000: %s" % message)
settle.Threads = 4
settle.UpdatePipeline(0.001)
path = rockdem.read_only(settle, "SolverPath")
c.check(path.startswith("CPU serial (") and "below the parallel threshold" in path, "Solver Path: %s" % path)

# Item 13: Fit To Input (the default) replacing a box the user set says so.
script = """
import vtk
pts = vtk.vtkPoints(); pts.InsertNextPoint(0.05, 0.05, 0.01)
out = self.GetPolyDataOutput(); out.SetPoints(pts)
r = vtk.vtkDoubleArray(); r.SetName('Radius'); r.InsertNextValue(0.01)
out.GetPointData().AddArray(r)
"""
ball = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=script)
dropped = DEMModelFromPoints(Input=ball, OriginZ=0.0, ZDimension=0.5)
dropped.UpdatePipeline()
message = rockdem.read_only(dropped, "LastMessage")
c.check("Fit To Input is on: the box you set" in message, "box replaced: %s" % message)
shutil.rmtree(work)
c.finish()
