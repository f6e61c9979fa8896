"""pvpython: DEM Model From Points turns a hand-built point set into a model."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rockdem_test_support import Checks, load_rockdem  # noqa: E402

from paraview import servermanager  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403

load_rockdem(globals())
import rockdem  # noqa: E402

c = Checks()
# Two spheres about to collide, built with ordinary ParaView tools.
script = """
import vtk
pts = vtk.vtkPoints()
pts.InsertNextPoint(0.0, 0.0, 0.0)
pts.InsertNextPoint(0.025, 0.0, 0.0)
out = self.GetPolyDataOutput()
out.SetPoints(pts)
r = vtk.vtkDoubleArray(); r.SetName('Radius'); r.InsertNextValue(0.01); r.InsertNextValue(0.01)
v = vtk.vtkDoubleArray(); v.SetName('Velocity'); v.SetNumberOfComponents(3)
v.InsertNextTuple3(10.0, 0, 0); v.InsertNextTuple3(-10.0, 0, 0)
out.GetPointData().AddArray(r); out.GetPointData().AddArray(v)
"""
points = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=script)
model = DEMModelFromPoints(Input=points, Density=2800, YoungsModulus=48e9, PoissonsRatio=0.2)
model.UpdatePipeline()
c.check(rockdem.read_only(model, "NumberOfElements") == 2, "two particles")
mb = servermanager.Fetch(model)
p = mb.GetBlock(0)
c.check(p.GetPointData().GetArray("Velocity").GetTuple3(1) == (-10.0, 0.0, 0.0), "velocity carried")
c.check(abs(p.GetPointData().GetArray("Radius").GetValue(0) - 0.01) < 1e-15, "radius carried")

noradius = ProgrammableSource(OutputDataSetType="vtkPolyData",
                              Script="import vtk\npts = vtk.vtkPoints(); pts.InsertNextPoint(0,0,0)\nself.GetPolyDataOutput().SetPoints(pts)")
bad = DEMModelFromPoints(Input=noradius)
bad.UpdatePipeline()
msg = rockdem.read_only(bad, "LastMessage")
print("error reported:", msg)
c.check("Radius" in msg, "points without Radius are rejected by name")
c.check(servermanager.Fetch(bad).GetNumberOfBlocks() == 0, "no output after bad input")
c.finish()
